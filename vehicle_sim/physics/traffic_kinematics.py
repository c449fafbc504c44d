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
into one array once per update, a *body table*, the same object until the next update, so a
reader of many bodies (the radar, physics/sensors/radar.py) may keep what it derived from it,
and takes the positions now as ``X..Z + VX..VZ * since``: no PyBullet call per body. The
velocities are the engines' own (speed along the heading), exact for the motion the bodies have
between updates.
"""

import numpy as np

# The columns of a body table (one row per body): centre, velocity, extents (length, width,
# height along its own axes), heading, bounding-sphere radius (half the extents' diagonal) and
# body id (exact as a float).
X, Y, Z, VX, VY, VZ, LENGTH, WIDTH, HEIGHT, YAW, RADIUS, BODY = range(12)
COLUMNS = 12


def body_table(ids, positions, velocities, extents, yaw):
    """Return the (n, COLUMNS) body table of per-body sequences."""
    count = len(ids)
    table = np.empty((count, COLUMNS))
    if count:
        table[:, X:Z + 1] = positions
        table[:, VX:VZ + 1] = velocities
        table[:, LENGTH:HEIGHT + 1] = extents
        table[:, YAW] = yaw
        table[:, RADIUS] = 0.5 * np.sqrt((table[:, LENGTH:HEIGHT + 1] ** 2).sum(axis=1))
        table[:, BODY] = ids
    return table


class MotionTable:
    """The traffic bodies' body table at the last update (the traffic-body contract)."""

    def __init__(self):
        self._table = None

    def invalidate(self):
        """Forget the table: an update placed the bodies again (or one stopped)."""
        self._table = None

    def now(self, since_s, rows):
        """
        Return the bodies on the map at the last update and the time since.

        :param since_s: time since the last update [s].
        :param rows: ``rows()`` -> [(body id, (x, y, z, qz, qw, vx, vy), (length, width,
            height))] of the bodies on the map, called once per update.
        :return: (body table at the last update (columns X .. BODY above; the same array until
            the next update), ``since_s``): a body is at ``X..Z + VX..VZ * since_s`` now.
        """
        if self._table is None:
            found = rows()
            motion = np.array([row[1] for row in found], dtype=float).reshape(-1, 7)
            velocity = np.zeros((len(found), 3))
            velocity[:, :2] = motion[:, 5:7]
            self._table = body_table([row[0] for row in found], motion[:, :3], velocity,
                                     [row[2] for row in found] or np.zeros((0, 3)),
                                     2.0 * np.arctan2(motion[:, 3], motion[:, 4]))
        return self._table, since_s
