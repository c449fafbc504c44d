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

"""
A synchronous run held to a real-time factor: the world steps, then waits for the wall clock.

Stepping stays synchronous (what a step computes does not depend on the pace); only the wall
time between steps changes, spent serving the nodes (``spin``). Used by the external drivers
(their ``real_time_factor``) and by a scenario watched live (``--real-time-factor``,
``--foxglove``).
"""

import time
from typing import Callable

# The longest wait between two spins while the wall clock catches up [s].
SPIN_SLICE_S = 0.001


class Pacer:
    """
    Hold simulated time to ``factor`` simulated seconds per wall-clock second.

    :param factor: simulated seconds per wall-clock second; 0: as fast as possible.
    :param spin: called while waiting (serves the nodes); must not block.
    """

    def __init__(self, factor: float, spin: Callable[[], None]):
        self.factor = factor
        self._spin = spin
        self._start = None

    def start(self, time_s: float = 0.0) -> None:
        """Anchor the pace: simulated ``time_s`` is now."""
        self._start = time.monotonic() - (time_s / self.factor if self.factor > 0.0 else 0.0)

    def wait(self, time_s: float) -> None:
        """Spin until the wall clock has reached simulated ``time_s`` (anchored at the first)."""
        if self.factor <= 0.0:
            return
        if self._start is None:
            self.start()
        due = self._start + time_s / self.factor
        while time.monotonic() < due:
            self._spin()
            time.sleep(min(SPIN_SLICE_S, max(0.0, due - time.monotonic())))
