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
The real-time factor a simulation achieves, and whether it falls behind the one asked.

A node stepping in real time (``real_time_factor`` 1) stays there only while a step and its
publishing take less than the step period; beyond that its timer fires late and simulated time
drifts behind wall time. :class:`RealTimeMeter` measures the achieved factor (simulated time
per wall time) over windows of wall time and says when a window fell short of the target.
Both times are passed in (``update(wall_s, sim_s)``), so a test drives it with any clock.
"""

import math
from typing import Optional

# Wall time one measurement spans [s]: long enough to average a timer's jitter, short enough
# for a live status line.
WINDOW_S = 1.0
# A window counts as behind below (1 - TOLERANCE) x the target: a node that keeps up reads
# within a few per cent of it.
TOLERANCE = 0.1


class RealTimeMeter:
    """
    Simulated time per wall time, over consecutive windows of wall time.

    :param target: the real-time factor asked (``real_time_factor``); 0 = none (as fast as
        possible, or synchronous stepping): the factor is measured, never behind.
    :param window_s: wall time a measurement spans [s], > 0.
    :param tolerance: fraction of the target a window may fall short by, in [0, 1).
    :raises ValueError: for a target, window or tolerance out of range, or not finite.
    """

    def __init__(self, target: float, window_s: float = WINDOW_S, tolerance: float = TOLERANCE):
        for name, value, valid in (('target', target, target >= 0.0),
                                   ('window_s', window_s, window_s > 0.0),
                                   ('tolerance', tolerance, 0.0 <= tolerance < 1.0)):
            if not math.isfinite(value) or not valid:
                raise ValueError(f'{name} = {value!r}: out of range')
        self.target = float(target)
        self.window_s = float(window_s)
        self._floor = self.target * (1.0 - tolerance)
        self._start = None           # (wall_s, sim_s) where the window began
        self.factor: Optional[float] = None     # the last window's factor; None before one
        self.window_wall_s = 0.0                 # the last window's wall time [s]

    def restart(self) -> None:
        """Forget the current window (after a pause: held time is not falling behind)."""
        self._start = None

    @property
    def behind(self) -> bool:
        """True when the last window fell short of the target."""
        return self.factor is not None and self.factor < self._floor

    def update(self, wall_s: float, sim_s: float) -> bool:
        """
        Account for the simulated time reached at a wall time; True when a window closed behind.

        :param wall_s: a monotonic wall clock [s].
        :param sim_s: the simulated time then [s]; a smaller value than the window's start
            (a new world) starts a new window.
        :return: True once per window that closes below the target.
        """
        start = self._start
        if start is None or sim_s < start[1]:
            self._start = (wall_s, sim_s)
            return False
        elapsed_s = wall_s - start[0]
        if elapsed_s < self.window_s:
            return False
        self.factor = (sim_s - start[1]) / elapsed_s
        self.window_wall_s = elapsed_s
        self._start = (wall_s, sim_s)
        return self.behind
