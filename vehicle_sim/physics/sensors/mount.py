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
Where a sensor is: its mount on a vehicle body, as a world pose and a point velocity.

The body is a CarBody or a DiffRobotBody: ``pose()`` gives base_link in the world (x, y, z, qx,
qy, qz, qw), ``velocity()`` its linear and angular velocity in the world frame.
"""

import numpy as np
import pybullet


class Mount:
    """
    A sensor frame fixed to a body's base_link at a mount Pose.

    :param body: the vehicle body (CarBody or DiffRobotBody).
    :param pose: core.frames.Pose of the sensor frame in base_link.
    """

    def __init__(self, body, pose):
        self.body = body
        self._xyz = tuple(pose.xyz)
        self._quaternion = tuple(pose.quaternion)

    def world_frame(self):
        """
        Return the sensor frame in the world.

        :return: (position (3,) [m], rotation (3, 3) whose columns are the sensor axes,
            quaternion (x, y, z, w)).
        """
        base = self.body.pose()
        position, quaternion = pybullet.multiplyTransforms(base[:3], base[3:], self._xyz,
                                                           self._quaternion)
        rotation = np.array(pybullet.getMatrixFromQuaternion(quaternion)).reshape(3, 3)
        return np.array(position), rotation, tuple(quaternion)

    def world_pose(self):
        """
        Return the sensor frame in the world as plain tuples (no arrays: a reader of few values).

        :return: (position (x, y, z) [m], quaternion (x, y, z, w), rotation: the 9 values of
            the 3 x 3 matrix row by row, its columns the sensor axes).
        """
        base = self.body.pose()
        position, quaternion = pybullet.multiplyTransforms(base[:3], base[3:], self._xyz,
                                                           self._quaternion)
        return position, quaternion, pybullet.getMatrixFromQuaternion(quaternion)

    def point_velocity(self, position):
        """
        Return the world velocity of the sensor point and the body's angular velocity.

        v = v_base + w x (p - p_base).

        :param position: the sensor position in the world [m].
        :return: (v (3,) [m/s], w (3,) [rad/s]) in the world frame.
        """
        linear, angular = self.body.velocity()
        base = np.array(self.body.pose()[:3])
        angular = np.array(angular)
        return np.array(linear) + np.cross(angular, np.asarray(position) - base), angular
