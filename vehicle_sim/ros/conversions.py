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
ROS message construction at the node boundary, and the pose math behind odometry and TF.

Unit conversions come from :mod:`vehicle_sim.core.units` only. The math here is pure Python on
tuples (quaternions ``(x, y, z, w)``, REP 103), so it is cheap in the per-step loop and testable
without ROS. :class:`RosMessages` builds messages with the classes of whichever transport the
node runs on (rclpy or embedded DDS): the code is the same on both.
"""

import math
from typing import Sequence, Tuple

from vehicle_sim.core.units import seconds_to_stamp

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


class RosMessages:
    """
    Builds the node's messages with the active transport's classes.

    :param node: a transport NodePort (``node.msg(ros_type)`` gives the classes).
    """

    def __init__(self, node):
        msg = node.msg
        self.Time = msg('builtin_interfaces/msg/Time')
        self.Header = msg('std_msgs/msg/Header')
        self.String = msg('std_msgs/msg/String')
        self.Float64Stamped = msg('vehicle_msgs/msg/Float64Stamped')
        self.Clock = msg('rosgraph_msgs/msg/Clock')
        self.Odometry = msg('nav_msgs/msg/Odometry')
        self.PoseWithCovariance = msg('geometry_msgs/msg/PoseWithCovariance')
        self.TwistWithCovariance = msg('geometry_msgs/msg/TwistWithCovariance')
        self.Pose = msg('geometry_msgs/msg/Pose')
        self.Twist = msg('geometry_msgs/msg/Twist')
        self.Point = msg('geometry_msgs/msg/Point')
        self.Vector3 = msg('geometry_msgs/msg/Vector3')
        self.Quaternion = msg('geometry_msgs/msg/Quaternion')
        self.Transform = msg('geometry_msgs/msg/Transform')
        self.TransformStamped = msg('geometry_msgs/msg/TransformStamped')
        self.TFMessage = msg('tf2_msgs/msg/TFMessage')
        self.JointState = msg('sensor_msgs/msg/JointState')

    def stamp(self, time_s: float):
        """Return builtin_interfaces/Time for a simulated time [s]."""
        sec, nanosec = seconds_to_stamp(time_s)
        return self.Time(sec=sec, nanosec=nanosec)

    def header(self, stamp, frame_id: str):
        return self.Header(stamp=stamp, frame_id=frame_id)

    def clock(self, stamp):
        return self.Clock(clock=stamp)

    def float64_stamped(self, header, value: float):
        return self.Float64Stamped(header=header, data=float(value))

    def string(self, text: str):
        return self.String(data=text)

    def _quaternion(self, q: Quaternion):
        return self.Quaternion(x=float(q[0]), y=float(q[1]), z=float(q[2]), w=float(q[3]))

    def _vector3(self, v: Vector):
        return self.Vector3(x=float(v[0]), y=float(v[1]), z=float(v[2]))

    def transform_stamped(self, stamp, frame_id: str, child_frame_id: str, xyz: Vector,
                          q: Quaternion):
        """Return geometry_msgs/TransformStamped: ``child_frame_id`` pose in ``frame_id``."""
        return self.TransformStamped(
            header=self.header(stamp, frame_id), child_frame_id=child_frame_id,
            transform=self.Transform(translation=self._vector3(xyz),
                                     rotation=self._quaternion(q)))

    def tf_message(self, transforms: Sequence):
        return self.TFMessage(transforms=list(transforms))

    def odometry(self, header, child_frame_id: str, xyz: Vector, q: Quaternion,
                 linear: Vector, angular: Vector):
        """
        Return nav_msgs/Odometry (ground truth: zero covariances).

        :param header: stamp and the odom frame.
        :param child_frame_id: the base_link frame; the twist is expressed in it.
        """
        return self.Odometry(
            header=header, child_frame_id=child_frame_id,
            pose=self.PoseWithCovariance(pose=self.Pose(
                position=self.Point(x=float(xyz[0]), y=float(xyz[1]), z=float(xyz[2])),
                orientation=self._quaternion(q))),
            twist=self.TwistWithCovariance(twist=self.Twist(
                linear=self._vector3(linear), angular=self._vector3(angular))))

    def joint_state(self, header, names: Sequence[str], positions: Sequence[float],
                    velocities: Sequence[float]):
        return self.JointState(header=header, name=list(names),
                               position=[float(p) for p in positions],
                               velocity=[float(v) for v in velocities], effort=[])
