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
Rigid-body frames: mount poses, quaternions (x, y, z, w) and rotation matrices.

Conventions (REP 103): right-handed, x forward, y left, z up; roll, pitch and yaw are the URDF
``rpy`` (fixed axes x, y, z: R = Rz(yaw) · Ry(pitch) · Rx(roll)). A camera's optical frame
(REP 103 ``_optical`` suffix) has z forward, x right and y down.
"""

from dataclasses import dataclass
import math
from typing import Tuple

import numpy as np

from vehicle_sim.core.geometry.angles import yaw_from_quaternion
from vehicle_sim.core.specs.value_kinds import ParamRefused, register_kind
from vehicle_sim.core.specs.value_text import brief

Quaternion = Tuple[float, float, float, float]
Vector = Tuple[float, float, float]


def quaternion_from_rpy(roll_rad, pitch_rad, yaw_rad):
    """
    Return the quaternion of URDF-style roll, pitch, yaw angles.

    :param roll_rad: rotation about the fixed x axis [rad].
    :param pitch_rad: rotation about the fixed y axis [rad].
    :param yaw_rad: rotation about the fixed z axis [rad].
    :return: (x, y, z, w), unit norm.
    """
    cr, sr = math.cos(roll_rad / 2.0), math.sin(roll_rad / 2.0)
    cp, sp = math.cos(pitch_rad / 2.0), math.sin(pitch_rad / 2.0)
    cy, sy = math.cos(yaw_rad / 2.0), math.sin(yaw_rad / 2.0)
    return (sr * cp * cy - cr * sp * sy,
            cr * sp * cy + sr * cp * sy,
            cr * cp * sy - sr * sp * cy,
            cr * cp * cy + sr * sp * sy)


def rpy_from_quaternion(q):
    """
    Return the roll, pitch, yaw angles of a quaternion (inverse of quaternion_from_rpy).

    :param q: (x, y, z, w).
    :return: (roll, pitch, yaw) [rad]; pitch in [-pi/2, pi/2].
    """
    x, y, z, w = q
    roll = math.atan2(2.0 * (w * x + y * z), 1.0 - 2.0 * (x * x + y * y))
    sin_pitch = max(-1.0, min(1.0, 2.0 * (w * y - z * x)))
    pitch = math.asin(sin_pitch)
    yaw = yaw_from_quaternion(x, y, z, w)
    return roll, pitch, yaw


def rotation_matrix(q):
    """
    Return the 3x3 rotation matrix of a unit quaternion.

    Its columns are the rotated frame's axes expressed in the reference frame.

    :param q: (x, y, z, w).
    :return: numpy array of shape (3, 3).
    """
    x, y, z, w = q
    return np.array([
        [1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - z * w), 2.0 * (x * z + y * w)],
        [2.0 * (x * y + z * w), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - x * w)],
        [2.0 * (x * z - y * w), 2.0 * (y * z + x * w), 1.0 - 2.0 * (x * x + y * y)],
    ])


# base frame -> optical frame of a camera: rpy (-pi/2, 0, -pi/2), as in REP 103's examples.
OPTICAL_RPY = (-math.pi / 2.0, 0.0, -math.pi / 2.0)
OPTICAL_QUATERNION = quaternion_from_rpy(*OPTICAL_RPY)


@dataclass(frozen=True)
class Pose:
    """A mount pose relative to a parent frame: translation [m] and URDF rpy angles [rad]."""

    x_m: float = 0.0
    y_m: float = 0.0
    z_m: float = 0.0
    roll_rad: float = 0.0
    pitch_rad: float = 0.0
    yaw_rad: float = 0.0

    @property
    def xyz(self) -> Vector:
        return (self.x_m, self.y_m, self.z_m)

    @property
    def rpy(self) -> Vector:
        return (self.roll_rad, self.pitch_rad, self.yaw_rad)

    @property
    def quaternion(self) -> Quaternion:
        return quaternion_from_rpy(self.roll_rad, self.pitch_rad, self.yaw_rad)

    def as_dict(self):
        """Return the pose as its configuration mapping (keys x, y, z, roll, pitch, yaw)."""
        return {'x': self.x_m, 'y': self.y_m, 'z': self.z_m, 'roll': self.roll_rad,
                'pitch': self.pitch_rad, 'yaw': self.yaw_rad}


POSE_KEYS = ('x', 'y', 'z', 'roll', 'pitch', 'yaw')


def _check_pose(spec, value):
    """Return a Pose from a mapping of POSE_KEYS (``spec.choices``: the keys it may hold)."""
    if isinstance(value, Pose):
        return value
    keys = spec.choices or POSE_KEYS
    if not isinstance(value, dict):
        raise ParamRefused(f'must be a mapping of {", ".join(keys)}')
    unknown = sorted(set(value) - set(keys))
    if unknown:
        raise ParamRefused(f'unknown key(s) {brief(unknown)}; valid: {", ".join(keys)}')
    numbers = {}
    for key in POSE_KEYS:
        item = value.get(key, 0.0)
        if not isinstance(item, (int, float)) or isinstance(item, bool) or \
                not math.isfinite(float(item)):
            raise ParamRefused('must be a finite number', item, key)
        numbers[key] = float(item)
    return Pose(numbers['x'], numbers['y'], numbers['z'], numbers['roll'], numbers['pitch'],
                numbers['yaw'])


# The ParamSpec kind of a pose (a mapping of POSE_KEYS, or a Pose); importing Pose registers it.
POSE_KIND = register_kind('pose', 'pose', _check_pose)


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


def pose_from_frame(frame_xyz: Vector, frame_q: Quaternion, xyz: Vector,
                    q: Quaternion) -> Tuple[Vector, Quaternion]:
    """
    Express in the world a pose given in another frame (the inverse of :func:`pose_in_frame`).

    :param frame_xyz: frame origin in the world [m].
    :param frame_q: frame orientation in the world.
    :param xyz: pose position in the frame [m].
    :param q: pose orientation in the frame.
    :return: (position, orientation) in the world.
    """
    offset = rotate(frame_q, xyz)
    return ((frame_xyz[0] + offset[0], frame_xyz[1] + offset[1], frame_xyz[2] + offset[2]),
            quaternion_multiply(frame_q, q))


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
