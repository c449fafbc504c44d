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
Teleport requests: a pose in a known frame turned into a place on the ground (x, y, heading).

A vehicle is teleported onto the ground: x, y and the heading come from the request, the height,
roll and pitch from the ground (the physics layer places the body). The request is checked first,
as every command is: non-finite values, places outside the world (|x| or |y| above
WORLD_EXTENT_M) and quaternions whose norm is not within QUATERNION_NORM_TOLERANCE of 1 raise
InvalidPoseError, naming the value.
"""

from dataclasses import dataclass
import math
from typing import Sequence

from vehicle_sim.core.geometry.frames import pose_from_frame, rpy_from_quaternion
from vehicle_sim.core.specs.errors import InvalidPoseError

# |‖q‖ − 1| above this is refused rather than normalised: such a quaternion is a bug upstream.
QUATERNION_NORM_TOLERANCE = 1e-3
# The world: |x| and |y| of every place [m] (a teleport, a spawn pose, an obstacle). A thousand
# kilometres is far beyond any map, and keeps doubles exact to ~1e-10 m; beyond ~1e30 m Bullet
# loses a body (it falls through the ground ever after).
WORLD_EXTENT_M = 1.0e6
_AXES = ('x', 'y', 'z')
_COMPONENTS = ('qx', 'qy', 'qz', 'qw')


@dataclass(frozen=True)
class GroundPose:
    """Where a vehicle is put on the ground: base_link's x, y [m] and heading [rad] (REP 103)."""

    x_m: float
    y_m: float
    yaw_rad: float

    @property
    def position(self):
        """The (x [m], y [m], yaw [rad]) form the physics bodies take."""
        return (self.x_m, self.y_m, self.yaw_rad)


def check_pose(xyz: Sequence[float], q: Sequence[float]):
    """
    Check a pose: finite position, finite quaternion of norm within 1e-3 of 1.

    :return: (xyz, q) as float tuples, q normalised.
    :raises InvalidPoseError: naming the offending value.
    """
    xyz = tuple(float(v) for v in xyz)
    q = tuple(float(v) for v in q)
    for name, value in zip(_AXES + _COMPONENTS, xyz + q):
        if not math.isfinite(value):
            raise InvalidPoseError(f'pose {name} = {value!r} is not a finite number')
    norm = math.sqrt(sum(v * v for v in q))
    if not abs(norm - 1.0) <= QUATERNION_NORM_TOLERANCE:
        raise InvalidPoseError(
            f'orientation ({", ".join(f"{v:g}" for v in q)}) has norm {norm:g}: a unit '
            f'quaternion is needed (norm within {QUATERNION_NORM_TOLERANCE:g} of 1)')
    return xyz, tuple(v / norm for v in q)


def ground_pose(xyz: Sequence[float], q: Sequence[float], frame_xyz=(0.0, 0.0, 0.0),
                frame_q=(0.0, 0.0, 0.0, 1.0)) -> GroundPose:
    """
    Turn a requested pose into a place on the ground.

    :param xyz: requested base_link position [m] in the request's frame (z is ignored).
    :param q: requested orientation (x, y, z, w) in that frame; its yaw is kept, its roll and
        pitch are ignored (the ground sets them).
    :param frame_xyz: origin of the request's frame in the world [m] (default: the world).
    :param frame_q: orientation of the request's frame in the world.
    :return: the GroundPose in the world frame.
    :raises InvalidPoseError: for a non-finite value or a non-unit quaternion.
    """
    xyz, q = check_pose(xyz, q)
    world_xyz, world_q = pose_from_frame(frame_xyz, frame_q, xyz, q)
    check_in_world(world_xyz[0], world_xyz[1])
    return GroundPose(world_xyz[0], world_xyz[1], rpy_from_quaternion(world_q)[2])


def check_in_world(x_m: float, y_m: float, what='pose'):
    """
    Check that a place is inside the world: ``|x|, |y| <= WORLD_EXTENT_M``.

    :param what: what is placed, quoted in the error (``'pose'``, ``'position'``).
    :raises InvalidPoseError: naming the coordinate, its value and the extent.
    """
    for name, value in (('x', x_m), ('y', y_m)):
        if not abs(value) <= WORLD_EXTENT_M:
            raise InvalidPoseError(
                f'{what} {name} = {value:g} m is outside the world (|x| and |y| at most '
                f'{WORLD_EXTENT_M:g} m)')
