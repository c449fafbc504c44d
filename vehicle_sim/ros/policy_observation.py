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
A policy's observation built from ROS messages, as the Gym environment builds it in process.

The keys a driving policy reads (docs/gym.md, docs/learning.md), from the automobile node's
topics (docs/ros_interface.md):

- ``lane`` (6,) float32 from ``<ns>/lane_state`` (vehicle_msgs/LaneState): s, offset, heading
  error, width, speed limit, on_lane, in that order (gym/lanes.py's layout);
- ``twist`` (3,) float32 from ``<ns>/odom``'s twist (in base_link): forward, left, yaw rate;
- ``objects`` (count, 7) float32 from ``/perception/object_recognition/objects``
  (PredictedObjects: each object's pose, heading and twist linear x), by core's
  :func:`~vehicle_sim.core.learning.objects_table.objects_table`, the function the environment
  uses. The objects are in ``world`` (or ``map``), the odometry in the vehicle's ``<p>odom``
  frame (at its spawn pose): the ego's pose is carried into the objects' frame through the
  static transforms of ``/tf_static`` (:class:`StaticFrames`).

No ROS import: the builder reads message attributes, so any object with those fields serves.
"""

import math

import numpy as np

from vehicle_sim.core.geometry.angles import yaw_from_quaternion
from vehicle_sim.core.learning.objects_table import Neighbour, objects_table
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.units import stamp_to_seconds

LANE, TWIST, OBJECTS = 'lane', 'twist', 'objects'
# The keys this builder makes (a policy reading another key cannot drive the node).
KEYS = (LANE, TWIST, OBJECTS)


def stamp_s(msg):
    """Return a stamped message's header stamp [s]."""
    stamp = msg.header.stamp
    return stamp_to_seconds(stamp.sec, stamp.nanosec)


def _compose(a, b):
    # planar poses (x, y, yaw): a then b (b given in a's frame)
    x, y, yaw = a
    c, s = math.cos(yaw), math.sin(yaw)
    return (x + c * b[0] - s * b[1], y + s * b[0] + c * b[1], yaw + b[2])


def _inverse(a):
    x, y, yaw = a
    c, s = math.cos(yaw), math.sin(yaw)
    return (-c * x - s * y, s * x - c * y, -yaw)


class StaticFrames:
    """
    The planar static transforms of ``/tf_static`` (parent -> child): a frame's pose in another.

    Every vehicle's ``<p>odom`` hangs under ``world`` at its spawn pose; a lanelet2 map's
    ``map`` frame is a translation of ``world``.
    """

    def __init__(self):
        self._parent = {}           # child -> (parent, (x, y, yaw))

    def add(self, msg):
        """Take the transforms of one tf2_msgs/TFMessage."""
        for t in msg.transforms:
            tr, q = t.transform.translation, t.transform.rotation
            self._parent[t.child_frame_id] = (
                t.header.frame_id, (tr.x, tr.y, yaw_from_quaternion(q.x, q.y, q.z, q.w)))

    def _root_pose(self, frame):
        pose, seen = (0.0, 0.0, 0.0), {frame}
        while frame in self._parent:
            frame, up = self._parent[frame]
            if frame in seen:
                break
            seen.add(frame)
            pose = _compose(up, pose)
        return frame, pose

    def pose_in(self, frame, target):
        """
        Return the pose (x, y, yaw) of ``frame``'s origin in ``target``, or None if unlinked.

        :param frame: e.g. the odometry's ``odom``.
        :param target: e.g. the objects' ``world``.
        """
        if frame == target:
            return (0.0, 0.0, 0.0)
        root_a, a = self._root_pose(frame)
        root_b, b = self._root_pose(target)
        if root_a != root_b:
            return None
        return _compose(_inverse(b), a)


class ObservationBuilder:
    """
    Build a policy's observation dict from the latest messages.

    :param keys: the observation keys the policy reads (its card's), each one of :data:`KEYS`.
    :param objects_spec: the ObjectsTableSpec of ``objects`` (None when not read).
    :raises InvalidParameterError: naming a key the ROS topics do not give.
    """

    def __init__(self, keys, objects_spec=None):
        unknown = [key for key in keys if key not in KEYS]
        if unknown:
            raise InvalidParameterError(
                f'observation keys {unknown}: the ROS topics give {", ".join(KEYS)} only (a '
                'policy reading other keys cannot drive the node)')
        if OBJECTS in keys and objects_spec is None:
            raise InvalidParameterError("observation key 'objects' needs its table's spec")
        self.keys = tuple(keys)
        self.objects_spec = objects_spec
        self.frames = StaticFrames()

    def build(self, odom, lane_state=None, objects=None):
        """
        Return {key: array} of the policy's keys.

        :param odom: nav_msgs/Odometry of the ego (pose in its odom frame, twist in base_link).
        :param lane_state: vehicle_msgs/LaneState of the ego (``lane``).
        :param objects: autoware_perception_msgs/PredictedObjects (``objects``).
        :raises InvalidParameterError: when the odometry's frame is not linked to the objects'
            by /tf_static.
        """
        out = {}
        twist = odom.twist.twist
        forward, left = twist.linear.x, twist.linear.y
        if TWIST in self.keys:
            out[TWIST] = np.array((forward, left, twist.angular.z), dtype=np.float32)
        if LANE in self.keys:
            s = lane_state
            out[LANE] = np.array((s.s, s.offset, s.heading_error, s.width, s.speed_limit,
                                  float(s.on_lane)), dtype=np.float32)
        if OBJECTS in self.keys:
            out[OBJECTS] = self.objects(odom, objects, forward, left)
        return out

    def objects(self, odom, objects, forward, left):
        """Return the objects table of a PredictedObjects around the ego of ``odom``."""
        frame = objects.header.frame_id
        place = self.frames.pose_in(odom.header.frame_id, frame)
        if place is None:
            raise InvalidParameterError(
                f'the odometry frame {odom.header.frame_id!r} is not linked to the objects '
                f'frame {frame!r} by /tf_static')
        p, q = odom.pose.pose.position, odom.pose.pose.orientation
        x, y, yaw = _compose(place, (p.x, p.y, yaw_from_quaternion(q.x, q.y, q.z, q.w)))
        others = []
        for o in objects.objects:
            kin = o.kinematics
            pose = kin.initial_pose_with_covariance.pose
            oq = pose.orientation
            others.append(Neighbour(pose.position.x, pose.position.y,
                                    yaw_from_quaternion(oq.x, oq.y, oq.z, oq.w),
                                    kin.initial_twist_with_covariance.twist.linear.x))
        return objects_table(self.objects_spec, x, y, yaw, forward, left, others)
