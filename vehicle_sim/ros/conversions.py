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
The pose math behind odometry and TF, at the node boundary.

Pure Python on tuples (quaternions ``(x, y, z, w)``, REP 103), so it is cheap in the per-step
loop and testable without ROS. Messages are built by :mod:`.messages`; unit conversions come from
:mod:`vehicle_sim.core.units` only.
"""

import math
from typing import Tuple

Vector = Tuple[float, float, float]
Quaternion = Tuple[float, float, float, float]


def quaternion_from_yaw(yaw_rad: float) -> Quaternion:
    """Return the quaternion (x, y, z, w) of a rotation by ``yaw_rad`` about +z (+ = left)."""
    half = 0.5 * yaw_rad
    return (0.0, 0.0, math.sin(half), math.cos(half))


def quaternion_multiply(a: Quaternion, b: Quaternion) -> Quaternion:
    """Return the Hamilton product a·b (apply b, then a)."""
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw,
            aw * bw - ax * bx - ay * by - az * bz)


def quaternion_conjugate(q: Quaternion) -> Quaternion:
    """Return the inverse of a unit quaternion."""
    return (-q[0], -q[1], -q[2], q[3])


def rotate(q: Quaternion, v: Vector) -> Vector:
    """Return vector ``v`` rotated by the unit quaternion ``q``."""
    qx, qy, qz, qw = q
    vx, vy, vz = v
    # t = 2 q_vec x v; v' = v + w t + q_vec x t
    tx = 2.0 * (qy * vz - qz * vy)
    ty = 2.0 * (qz * vx - qx * vz)
    tz = 2.0 * (qx * vy - qy * vx)
    return (vx + qw * tx + qy * tz - qz * ty,
            vy + qw * ty + qz * tx - qx * tz,
            vz + qw * tz + qx * ty - qy * tx)


def pose_in_frame(frame_xyz: Vector, frame_q: Quaternion, xyz: Vector,
                  q: Quaternion) -> Tuple[Vector, Quaternion]:
    """
    Express a world pose in another frame given by its world pose.

    :param frame_xyz: frame origin in the world [m].
    :param frame_q: frame orientation in the world.
    :param xyz: pose position in the world [m].
    :param q: pose orientation in the world.
    :return: (position, orientation) in the frame.
    """
    inverse = quaternion_conjugate(frame_q)
    delta = (xyz[0] - frame_xyz[0], xyz[1] - frame_xyz[1], xyz[2] - frame_xyz[2])
    return rotate(inverse, delta), quaternion_multiply(inverse, q)


def twist_in_body(q: Quaternion, linear_world: Vector,
                  angular_world: Vector) -> Tuple[Vector, Vector]:
    """
    Express a world-frame twist in the body frame (nav_msgs/Odometry: twist in child_frame_id).

    :param q: body orientation in the world.
    :param linear_world: linear velocity [m/s] in the world frame.
    :param angular_world: angular velocity [rad/s] in the world frame.
    :return: (linear, angular) in the body frame.
    """
    inverse = quaternion_conjugate(q)
    return rotate(inverse, linear_world), rotate(inverse, angular_world)
