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
Plane geometry shared by every layer (ROS-free).

Conventions (REP 103): right-handed, x forward, y left, z up; yaw is the heading about z,
counter-clockwise from x. Quaternions are (x, y, z, w), as ROS messages and PyBullet order them.
"""

import math


def yaw_from_quaternion(q):
    """
    Return the yaw (heading about z) of a quaternion.

    The closed form ``atan2(2 (w z + x y), 1 - 2 (y^2 + z^2))`` is exact for any rotation,
    including ones with roll and pitch (it is the yaw of the fixed-axes x, y, z decomposition).

    :param q: (x, y, z, w), unit norm.
    :return: yaw [rad] in [-pi, pi].
    """
    x, y, z, w = q
    return math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))
