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
Small plane-geometry truths used across the package, written once.

Angles follow REP 103: counter-clockwise positive about z, radians.
"""

import math

_TWO_PI = 2.0 * math.pi


def yaw_from_quaternion(qx, qy, qz, qw):
    """
    Return the heading of a unit quaternion: its rotation about z [rad], in (-pi, pi].

    The yaw of the z-y-x (yaw, pitch, roll) decomposition,
    ``atan2(2 (w z + x y), 1 - 2 (y² + z²))``; for a pure rotation about z by θ
    (q = (0, 0, sin θ/2, cos θ/2)) it is θ.

    :param qx: quaternion x.
    :param qy: quaternion y.
    :param qz: quaternion z.
    :param qw: quaternion w (scalar part).
    :return: yaw [rad].
    """
    return math.atan2(2.0 * (qw * qz + qx * qy), 1.0 - 2.0 * (qy * qy + qz * qz))


def wrap_angle_rad(angle_rad):
    """
    Return an angle wrapped into (-pi, pi] [rad]: the package's one angle wrap.

    The interval of ROS's ``angles::normalize_angle``: a half turn either way is +pi. The IEEE
    remainder by 2 pi is exact: an angle already in the interval comes back unchanged.

    :param angle_rad: any finite angle [rad].
    """
    wrapped = math.remainder(angle_rad, _TWO_PI)
    return math.pi if wrapped == -math.pi else wrapped
