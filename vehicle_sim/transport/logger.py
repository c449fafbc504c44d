# Copyright 2026 vehicle_sim contributors
#
# Licensed under the Apache License, Version 2.0 (the "License");
# you may not use this file except in compliance with the License.
# You may obtain a copy of the License at
#
#     http://www.apache.org/licenses/LICENSE-2.0
#
# Unless required by applicable law or agreed to in writing, software
# distributed under the License is distributed on an "AS IS" BASIS,
# WITHOUT WARRANTIES OR CONDITIONS OF ANY KIND, either express or implied.
# See the License for the specific language governing permissions and
# limitations under the License.

"""The port's node logger (rcutils severities) and a wall-time throttle for repeated warnings."""

import abc
import time

# Severity names of rcutils' console output, by level.
LOG_LEVEL_NAMES = {10: 'DEBUG', 20: 'INFO', 30: 'WARN', 40: 'ERROR', 50: 'FATAL'}


class Logger(abc.ABC):
    """A node logger: rcutils-like console output plus /rosout."""

    @abc.abstractmethod
    def log(self, level: int, message: str) -> None:
        """Log ``message`` at ``level`` (10 debug, 20 info, 30 warn, 40 error, 50 fatal)."""

    def debug(self, message: str) -> None:
        self.log(10, message)

    def info(self, message: str) -> None:
        self.log(20, message)

    def warn(self, message: str) -> None:
        self.log(30, message)

    warning = warn

    def error(self, message: str) -> None:
        self.log(40, message)

    def fatal(self, message: str) -> None:
        self.log(50, message)


# Throttle period of repeated warnings [s] (wall time).
WARN_THROTTLE_S = 1.0


class ThrottledWarning:
    """Log a warning at most once per ``period_s`` of wall time, counting what was suppressed."""

    def __init__(self, logger: 'Logger', period_s: float = WARN_THROTTLE_S):
        """
        Create the throttle.

        :param logger: a port Logger.
        :param period_s: minimum wall time between two warnings [s].
        """
        self._logger = logger
        self._period_s = period_s
        self._last_s = None
        self.suppressed = 0
        self.count = 0

    def warn(self, message: str) -> None:
        """Count the event and log it unless one was logged less than period_s ago."""
        self.count += 1
        now_s = time.monotonic()
        if self._last_s is not None and now_s - self._last_s < self._period_s:
            self.suppressed += 1
            return
        if self.suppressed:
            message += f' ({self.suppressed} similar warnings suppressed)'
        self.suppressed = 0
        self._last_s = now_s
        self._logger.warn(message)
