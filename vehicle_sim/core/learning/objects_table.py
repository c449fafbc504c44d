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
The objects around a vehicle as a fixed-size table: what a policy reads of the traffic.

As highway-env's ``Kinematics`` observation (relative, normalised, nearest first): up to
``count`` objects whose centres lie within ``range`` of the ego's base_link, nearest first, one
row each; the rows left over are all zero. Each row, in the ego's frame (x forward, y left,
REP 103):

===========  =================================================================================
``presence``  1.0 for an object, 0.0 for an empty row
``x``, ``y``  the object's centre minus the ego's position, in the ego's axes, over ``range``
              (so in [-1, 1])
``vx``, ``vy``  the object's velocity minus the ego's, in the ego's axes, over ``speed_scale``,
              saturated to [-1, 1] (an encoding: a faster relative speed reads as +-1)
``cos_h``, ``sin_h``  cosine and sine of the object's heading minus the ego's
===========  =================================================================================

The objects are what ``/perception/object_recognition/objects`` carries (the traffic and the
world's obstacles, at rest), so that the same table is built in process (the Gym env's
``objects`` key, gym/objects.py) and from the ROS topics (a policy driving the node): one
function, :func:`objects_table`, for both. Numpy only.
"""

from dataclasses import dataclass
import math
from typing import Iterable, Tuple

import numpy as np

from vehicle_sim.core.specs.param_spec import ParamSpec, validate_table

FEATURES = ('presence', 'x', 'y', 'vx', 'vy', 'cos_h', 'sin_h')

# The keys of the table (the Gym env's ``objects`` option as a mapping).
OBJECTS_TABLE_SPECS = (
    ParamSpec('count', kind='int', default=5, ge=1, le=64,
              doc='rows: the nearest objects kept'),
    ParamSpec('range', kind='float', default=80.0, unit='m', gt=0.0, attr='range_m',
              doc="objects whose centre is farther from the ego's are left out; x and y are "
                  'divided by it'),
    ParamSpec('speed_scale', kind='float', default=40.0, unit='m/s', gt=0.0,
              attr='speed_scale_mps',
              doc='relative velocities are divided by it and saturated to [-1, 1]'),
)


@dataclass(frozen=True)
class ObjectsTableSpec:
    """The table's size and scales (:data:`OBJECTS_TABLE_SPECS`)."""

    count: int = 5
    range_m: float = 80.0
    speed_scale_mps: float = 40.0

    @classmethod
    def from_dict(cls, data, source):
        """Return the spec of a mapping of :data:`OBJECTS_TABLE_SPECS` keys (errors name them)."""
        return cls(**validate_table(OBJECTS_TABLE_SPECS, dict(data), source, what='objects',
                                    key_word='key'))

    def as_dict(self):
        """Return the keys of this spec (what :meth:`from_dict` reads back)."""
        return {'count': self.count, 'range': self.range_m, 'speed_scale': self.speed_scale_mps}

    @property
    def shape(self) -> Tuple[int, int]:
        """The table's shape: (count, len(FEATURES))."""
        return self.count, len(FEATURES)


@dataclass(frozen=True)
class Neighbour:
    """
    One object as the table reads it (world frame).

    :param x_m: its centre x [m].
    :param y_m: its centre y [m].
    :param yaw_rad: its heading [rad].
    :param speed_mps: its speed along its heading [m/s] (0 for an obstacle).
    """

    x_m: float
    y_m: float
    yaw_rad: float
    speed_mps: float = 0.0


def objects_table(spec: ObjectsTableSpec, ego_x_m: float, ego_y_m: float, ego_yaw_rad: float,
                  ego_forward_mps: float, ego_left_mps: float,
                  others: Iterable[Neighbour]) -> np.ndarray:
    """
    Return the table of the objects around the ego: float32 of shape ``spec.shape``.

    :param ego_x_m: the ego's base_link x in the objects' frame [m]; ``ego_y_m`` its y.
    :param ego_yaw_rad: the ego's heading in that frame [rad].
    :param ego_forward_mps: the ego's velocity along its x axis [m/s]; ``ego_left_mps`` along
        its y axis (an odometry's twist).
    :param others: the objects (:class:`Neighbour`), in any order.
    """
    table = np.zeros(spec.shape, dtype=np.float32)
    c, s = math.cos(ego_yaw_rad), math.sin(ego_yaw_rad)
    rows = []
    for other in others:
        dx, dy = other.x_m - ego_x_m, other.y_m - ego_y_m
        distance = math.hypot(dx, dy)
        if distance > spec.range_m:
            continue
        heading = other.yaw_rad - ego_yaw_rad
        vx = other.speed_mps * math.cos(heading) - ego_forward_mps
        vy = other.speed_mps * math.sin(heading) - ego_left_mps
        rows.append((distance, (c * dx + s * dy) / spec.range_m,
                     (-s * dx + c * dy) / spec.range_m, vx, vy, heading))
    rows.sort(key=lambda row: row[0])
    scale = spec.speed_scale_mps
    for i, (_, x, y, vx, vy, heading) in enumerate(rows[:spec.count]):
        table[i] = (1.0, x, y, min(1.0, max(-1.0, vx / scale)),
                    min(1.0, max(-1.0, vy / scale)), math.cos(heading), math.sin(heading))
    return table
