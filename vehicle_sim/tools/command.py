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

"""What every ``vehicle-sim`` command shares: exit statuses, the error it reports, signals."""

import signal
import threading

EXIT_OK = 0
EXIT_FAILURE = 1
EXIT_USAGE = 2


class CliError(Exception):
    """A failure reported to the user as one message and a non-zero exit status."""

    def __init__(self, message: str, status: int = EXIT_FAILURE):
        super().__init__(message)
        self.status = status


# The signals that end a command cleanly: Ctrl-C, kill, and a closed terminal (SIGHUP, POSIX
# only), so that the helper node leaves the graph and a recording is finished.
STOP_SIGNALS = tuple(getattr(signal, name) for name in ('SIGINT', 'SIGTERM', 'SIGHUP')
                     if hasattr(signal, name))


def install_stop_handlers() -> threading.Event:
    """Turn SIGINT/SIGTERM/SIGHUP into an event, so that the command ends cleanly."""
    stop = threading.Event()
    if threading.current_thread() is threading.main_thread():
        for signum in STOP_SIGNALS:
            signal.signal(signum, lambda *_: stop.set())
    return stop
