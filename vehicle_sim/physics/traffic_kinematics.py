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
The traffic bodies' motion as arrays: where each body on the map is now and how it moves.

Both traffic engines place their bodies (never moved by Bullet) at each update and let them go
on straight at their speed until the next: each keeps, per body on the map, its pose and
velocity at the last update (``(x, y, z, qz, qw, vx, vy)``). :class:`MotionTable` turns those
into arrays once per update and gives the bodies' positions now from them, so a reader of many
bodies (the radar, physics/sensors/radar.py) pays a few array operations, not a PyBullet call
per body. The velocities are the engines' own (speed along the heading), exact for the motion
the bodies have between updates.
"""

import numpy as np


class MotionTable:
    """The arrays of the traffic bodies' motion at the last update (the traffic-body contract)."""

    def __init__(self):
        self._table = None

    def invalidate(self):
        """Forget the arrays: an update placed the bodies again (or one stopped)."""
        self._table = None

    def now(self, since_s, rows):
        """
        Return the bodies on the map now.

        :param since_s: time since the last update [s].
        :param rows: ``rows()`` -> [(body id, (x, y, z, qz, qw, vx, vy), (length, width,
            height))] of the bodies on the map, called once per update.
        :return: (body ids (n,) int64, positions (n, 3) [m], velocities (n, 3) [m/s], extents
            (n, 3) [m]: length, width, height, yaw (n,) [rad]).
        """
        if self._table is None:
            found = rows()
            ids = np.array([row[0] for row in found], dtype=np.int64)
            motion = np.array([row[1] for row in found], dtype=float).reshape(-1, 7)
            extents = np.array([row[2] for row in found], dtype=float).reshape(-1, 3)
            velocity = np.zeros((len(found), 3))
            velocity[:, :2] = motion[:, 5:7]
            yaw = 2.0 * np.arctan2(motion[:, 3], motion[:, 4])
            self._table = (ids, motion[:, :3].copy(), velocity, extents, yaw)
        ids, positions, velocity, extents, yaw = self._table
        return ids, positions + velocity * since_s, velocity, extents, yaw
