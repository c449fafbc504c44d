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
The traffic vehicles as objects for ground-truth perception: pose, speed, box, predicted path.

:func:`traffic_objects` reads a TrafficManager: every vehicle on the map becomes a
:class:`TrafficObject` with its centre pose, speed along its heading, box dimensions and a
straight prediction: the poses it reaches at its current speed along its lane and planned
successors every ``step_s`` up to ``horizon_s`` (as Autoware's dummy perception predicts its
objects: constant speed along the lane). :func:`obstacle_objects` gives the world's obstacles
(:class:`ObstacleObject`: pose, shape, extents). The ROS layer turns them into
``autoware_perception_msgs/PredictedObjects`` and markers (ros/traffic_messages.py).
"""

from dataclasses import dataclass
import math
from typing import Mapping, Tuple

PREDICTION_HORIZON_S = 5.0
# The classes of traffic objects (autoware_perception_msgs/ObjectClassification's labels but
# UNKNOWN, lower case; the ROS layer maps each to its label) -> the shape of its body (an
# obstacle shape, core/world/params.py OBSTACLE_SHAPES): a pedestrian an upright cylinder, the
# rest boxes. The ROS objects and markers and the live view draw each object so.
CLASS_SHAPES = {'car': 'box', 'truck': 'box', 'bus': 'box', 'trailer': 'box',
                'motorcycle': 'box', 'bicycle': 'box', 'pedestrian': 'cylinder'}
OBJECT_CLASSES = tuple(CLASS_SHAPES)
PREDICTION_STEP_S = 0.5


@dataclass(frozen=True)
class TrafficObject:
    """
    One traffic vehicle as an object (world frame, base at the box's centre on the ground).

    :param index: the vehicle's index (``traffic_<index>``).
    :param name: its name.
    :param x_m: box centre x [m].
    :param y_m: box centre y [m].
    :param yaw_rad: heading [rad].
    :param speed_mps: speed along its heading [m/s].
    :param length_m: box length [m].
    :param width_m: box width [m].
    :param height_m: box height [m].
    :param path: predicted poses (x, y, yaw), one per ``step_s``, the first at ``step_s``.
    :param step_s: time between the path's poses [s].
    :param object_class: what it is, one of :data:`OBJECT_CLASSES` (Autoware's
        ObjectClassification labels, lower case): the builtin engine's are all cars; SUMO's
        come from their vehicle classes (docs/sumo.md). Its shape is its class's
        (:data:`CLASS_SHAPES`): a box of length, width and height, or an upright cylinder
        whose diameter is the larger of length and width (:attr:`size_m`,
        :func:`shape_extents`).
    :param instance_id: its object id (physics/body_labels.py ``World.labels.instance`` of the
        agent it stands for): the PredictedObjects UUID, the instance image's and labelled
        lidar's id; 0 = none given.
    :raises ValueError: for a class not in :data:`OBJECT_CLASSES`, naming it.
    """

    index: int
    name: str
    x_m: float
    y_m: float
    yaw_rad: float
    speed_mps: float
    length_m: float
    width_m: float
    height_m: float
    path: Tuple[Tuple[float, float, float], ...]
    step_s: float
    object_class: str = 'car'
    instance_id: int = 0

    def __post_init__(self):
        if self.object_class not in CLASS_SHAPES:
            raise ValueError(f'object_class {self.object_class!r} of {self.name!r}: unknown; '
                             f'valid: {", ".join(OBJECT_CLASSES)}')

    @property
    def shape(self) -> str:
        """Its body's shape: 'box' or 'cylinder' (upright), its class's."""
        return CLASS_SHAPES[self.object_class]

    @property
    def size_m(self) -> Tuple[float, float, float]:
        """Its shape's extents (x, y, z) [m] (:func:`shape_extents`)."""
        return shape_extents(self.object_class, self.length_m, self.width_m, self.height_m)


def shape_extents(object_class, length_m, width_m, height_m) -> Tuple[float, float, float]:
    """
    Return the extents (x, y, z) [m] of the shape of a class's body of a given size.

    As an obstacle's (core ObstacleSpec ``size_m``): a box's length, width and height; an
    upright cylinder's diameter (the larger of length and width) twice and its height.
    """
    if CLASS_SHAPES[object_class] == 'cylinder':
        diameter = max(length_m, width_m)
        return diameter, diameter, height_m
    return length_m, width_m, height_m


def _path(manager, v, horizon_s, step_s, since_s):
    """Poses along the lane and its planned successors at constant speed (centreline)."""
    lanes = manager.graph.lanes
    poses = []
    lane_id, s, upcoming = v.lane, v.s_m + v.speed_mps * since_s, [v.next_lane]
    count = int(round(horizon_s / step_s))
    for _ in range(count):
        s += v.speed_mps * step_s
        while s > lanes[lane_id].length_m:
            nxt = upcoming.pop(0) if upcoming else None
            if nxt is None:
                successors = lanes[lane_id].successors
                nxt = successors[0] if successors else None
            if nxt is None:
                return tuple(poses)          # the lane ends: the prediction too
            s -= lanes[lane_id].length_m
            lane_id = nxt
        poses.append(lanes[lane_id].centre_pose(s))     # s is on the lane: no check
    return tuple(poses)


def traffic_objects(manager, heights: Mapping[str, float], horizon_s=PREDICTION_HORIZON_S,
                    step_s=PREDICTION_STEP_S, since_s=0.0,
                    instance_of=None, paths=True) -> Tuple[TrafficObject, ...]:
    """
    Return the vehicles on the map as TrafficObjects, in index order.

    :param manager: the TrafficManager.
    :param heights: {model: box height [m]}.
    :param horizon_s: how far the prediction reaches [s].
    :param step_s: time between predicted poses [s].
    :param since_s: time since the manager's last step [s], >= 0: each vehicle is where it
        is now, gone on straight at its speed (as its body in the physics world), and its
        path starts from there.
    :param instance_of: ``instance_of(name)`` -> a vehicle's instance id (None: 0).
    :param paths: False: no prediction (each path empty), for readers of poses and speeds only
        (the Gym env's objects table and gap reward): the paths are most of the cost.
    """
    if not (math.isfinite(horizon_s) and math.isfinite(step_s) and 0.0 < step_s <= horizon_s):
        raise ValueError(f'horizon_s = {horizon_s!r}, step_s = {step_s!r}: need '
                         f'0 < step_s <= horizon_s')
    if not (math.isfinite(since_s) and since_s >= 0.0):
        raise ValueError(f'since_s = {since_s!r}: must be finite and >= 0')
    found = []
    for v in manager.vehicles:
        if not v.active:
            continue
        x, y, yaw = manager.pose(v)
        gone = v.speed_mps * since_s
        found.append(TrafficObject(v.index, v.name, x + gone * math.cos(yaw),
                                   y + gone * math.sin(yaw), yaw, v.speed_mps, v.length_m,
                                   v.width_m, heights[v.model],
                                   _path(manager, v, horizon_s, step_s, since_s) if paths
                                   else (), step_s,
                                   instance_id=0 if instance_of is None else instance_of(v.name)))
    return tuple(found)


@dataclass(frozen=True)
class ObstacleObject:
    """
    One obstacle as an object: its name, centre (x, y, z) [m], heading [rad], shape, extents.

    :param shape: the ObstacleSpec's shape ('box', 'cylinder', 'sphere').
    :param size_m: full extents along its own x, y, z [m].
    :param instance_id: its object id (``World.labels.instance`` of its name); 0 = none given.
    """

    name: str
    x_m: float
    y_m: float
    z_m: float
    yaw_rad: float
    shape: str
    size_m: Tuple[float, float, float]
    instance_id: int = 0


def obstacle_objects(specs, pose_of=None, instance_of=None) -> Tuple[ObstacleObject, ...]:
    """
    Return the obstacles (core ObstacleSpecs) as ObstacleObjects.

    :param specs: the world's ObstacleSpecs.
    :param pose_of: ``pose_of(name)`` -> (x, y, z, yaw) now of a movable obstacle (mass > 0);
        None = every obstacle where its spec puts it.
    :param instance_of: ``instance_of(name)`` -> an obstacle's instance id (None: 0).
    """
    found = []
    for spec in specs:
        if pose_of is not None and not spec.static:
            x, y, z, yaw = pose_of(spec.name)
        else:
            (x, y, z), yaw = spec.position_m, spec.yaw_rad
        found.append(ObstacleObject(spec.name, x, y, z, yaw, spec.shape, tuple(spec.size_m),
                                    0 if instance_of is None else instance_of(spec.name)))
    return tuple(found)
