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
Message builders of the traffic topics: PredictedObjects (ground truth), markers, signals.

Same form as ros/messages.py's builders: ``<type>_builder(msg, frame_id)`` resolves the classes
once; the ``build(stamp, objects)`` it returns makes one message from a stamp and the core
TrafficObjects (core/traffic/objects.py).

- ``autoware_perception_msgs/PredictedObjects``, as Autoware's planning simulator's dummy
  perception gives them: per object the UUID of its instance id (physics/body_labels.py
  ``instance_uuid``: the id of its instance image pixels, labelled lidar points, recognition
  object and radar target), existence probability 1,
  the classification of its class (:data:`LABEL_OF_CLASS`: CAR, TRUCK, BUS, TRAILER,
  MOTORCYCLE, BICYCLE, PEDESTRIAN; probability 1), the pose of its body's centre, its twist in
  its own frame (x forward), its class's shape (a BOUNDING_BOX of its dimensions; a
  pedestrian's CYLINDER: diameter, diameter, height), and one predicted path (confidence 1):
  constant speed along its lane. After them the world's obstacles: classification UNKNOWN, at
  rest, no predicted path, a BOUNDING_BOX (a box) or CYLINDER (a cylinder, a sphere) shape.
- ``visualization_msgs/MarkerArray``: one CUBE per object (a CYLINDER for a pedestrian;
  namespace ``traffic``, id = the vehicle's index), coloured like its body; objects that left
  the map since the last message are deleted (action DELETE).
- ``autoware_perception_msgs/TrafficLightGroupArray``: the state of every traffic light group
  of the map (its id the map's: a lanelet2 traffic light regulatory element's id), as
  Autoware's planning simulator and scenario_simulator_v2 give them to the planners: per
  group, one element per bulb shape lit in its state (:func:`signal_elements`), confidence 1.
"""

import math
from typing import Dict, Tuple

from vehicle_sim.core.geometry.frames import quaternion_from_yaw
from vehicle_sim.core.map.lane_rules import BULB_SHAPES, SIGNAL_STATES
from vehicle_sim.physics.body_labels import instance_uuid

HEADER = 'std_msgs/msg/Header'
PREDICTED_OBJECTS = 'autoware_perception_msgs/msg/PredictedObjects'
PREDICTED_OBJECT = 'autoware_perception_msgs/msg/PredictedObject'
OBJECT_CLASSIFICATION = 'autoware_perception_msgs/msg/ObjectClassification'
PREDICTED_PATH = 'autoware_perception_msgs/msg/PredictedPath'
SHAPE = 'autoware_perception_msgs/msg/Shape'
UUID = 'unique_identifier_msgs/msg/UUID'
POSE = 'geometry_msgs/msg/Pose'
POINT = 'geometry_msgs/msg/Point'
QUATERNION = 'geometry_msgs/msg/Quaternion'
DURATION = 'builtin_interfaces/msg/Duration'
MARKER = 'visualization_msgs/msg/Marker'
MARKER_ARRAY = 'visualization_msgs/msg/MarkerArray'
COLOR = 'std_msgs/msg/ColorRGBA'
TRAFFIC_LIGHT_GROUP_ARRAY = 'autoware_perception_msgs/msg/TrafficLightGroupArray'
TRAFFIC_LIGHT_GROUP = 'autoware_perception_msgs/msg/TrafficLightGroup'
TRAFFIC_LIGHT_ELEMENT = 'autoware_perception_msgs/msg/TrafficLightElement'
TIME = 'builtin_interfaces/msg/Time'

UNKNOWN = 0             # ObjectClassification
# a traffic object's class (core/traffic/objects.py OBJECT_CLASSES) -> its ObjectClassification
# label (autoware_perception_msgs' CAR, TRUCK, ... of the same name).
LABEL_OF_CLASS = {'car': 1, 'truck': 2, 'bus': 3, 'trailer': 4, 'motorcycle': 5, 'bicycle': 6,
                  'pedestrian': 7}
BOUNDING_BOX, CYLINDER = 0, 1    # Shape
# obstacle shape (core/world/params.py OBSTACLE_SHAPES; a traffic object's shape, core
# CLASS_SHAPES, is one of them) -> its Shape type as an object: a CYLINDER's dimensions x and y
# are its diameter, as Autoware's.
OBJECT_SHAPE_OF_OBSTACLE = {'box': BOUNDING_BOX, 'cylinder': CYLINDER, 'sphere': CYLINDER}
CUBE, CYLINDER_MARKER, ADD, DELETE = 1, 3, 0, 2     # visualization_msgs/Marker
# a traffic object's shape -> the marker type drawing it
MARKER_OF_SHAPE = {'box': CUBE, 'cylinder': CYLINDER_MARKER}
# TrafficLightElement: colour, shape and status values (UNKNOWN = 0 for each).
ELEMENT_UNKNOWN = 0
ELEMENT_COLOR = {'red': 1, 'yellow': 2, 'green': 3}      # RED, AMBER, GREEN
ELEMENT_SHAPE = {'circle': 1, 'left_arrow': 2, 'right_arrow': 3, 'up_arrow': 4,
                 'down_arrow': 7}                         # CIRCLE, *_ARROW (core BULB_SHAPES)
SOLID_OFF, SOLID_ON = 1, 2
# What a dark group ('off') shows: one element, colour and shape UNKNOWN, SOLID_OFF.
DARK = ((ELEMENT_UNKNOWN, ELEMENT_UNKNOWN, SOLID_OFF),)


def object_uuid(o) -> bytes:
    """Return the 16 bytes of an object's id (a TrafficObject's or an ObstacleObject's)."""
    return instance_uuid(o.instance_id)


def predicted_objects_builder(msg, frame_id: str):
    """Return ``build(stamp, objects)``: autoware_perception_msgs/PredictedObjects."""
    objects_type, object_type = msg(PREDICTED_OBJECTS), msg(PREDICTED_OBJECT)
    header_type, classification_type = msg(HEADER), msg(OBJECT_CLASSIFICATION)
    path_type, shape_type, uuid_type = msg(PREDICTED_PATH), msg(SHAPE), msg(UUID)
    pose_type, point_type, quaternion_type = msg(POSE), msg(POINT), msg(QUATERNION)
    duration_type = msg(DURATION)

    def pose(x, y, z, yaw):
        qx, qy, qz, qw = quaternion_from_yaw(yaw)
        return pose_type(position=point_type(x=float(x), y=float(y), z=float(z)),
                         orientation=quaternion_type(x=qx, y=qy, z=qz, w=qw))

    def one(o):
        item = object_type(object_id=uuid_type(uuid=object_uuid(o)),
                           existence_probability=1.0,
                           classification=[classification_type(
                               label=LABEL_OF_CLASS[o.object_class], probability=1.0)])
        z = 0.5 * o.height_m
        kinematics = item.kinematics
        kinematics.initial_pose_with_covariance.pose = pose(o.x_m, o.y_m, z, o.yaw_rad)
        kinematics.initial_twist_with_covariance.twist.linear.x = float(o.speed_mps)
        seconds = math.floor(o.step_s)
        kinematics.predicted_paths = [path_type(
            path=[pose(x, y, z, yaw) for x, y, yaw in o.path],
            time_step=duration_type(sec=int(seconds),
                                    nanosec=int(round((o.step_s - seconds) * 1e9))),
            confidence=1.0)]
        item.shape = shape_type(type=OBJECT_SHAPE_OF_OBSTACLE[o.shape])
        item.shape.dimensions.x, item.shape.dimensions.y, item.shape.dimensions.z = \
            (float(v) for v in o.size_m)
        return item

    def obstacle(o):
        item = object_type(object_id=uuid_type(uuid=object_uuid(o)),
                           existence_probability=1.0,
                           classification=[classification_type(label=UNKNOWN, probability=1.0)])
        item.kinematics.initial_pose_with_covariance.pose = pose(o.x_m, o.y_m, o.z_m, o.yaw_rad)
        item.shape = shape_type(type=OBJECT_SHAPE_OF_OBSTACLE[o.shape])
        item.shape.dimensions.x, item.shape.dimensions.y, item.shape.dimensions.z = \
            (float(v) for v in o.size_m)
        return item

    def build(stamp, objects, obstacles=()):
        return objects_type(header=header_type(stamp=stamp, frame_id=frame_id),
                            objects=[one(o) for o in objects] + [obstacle(o) for o in obstacles])
    return build


def traffic_markers_builder(msg, frame_id: str, colours=()):
    """
    Return ``build(stamp, objects)``: visualization_msgs/MarkerArray of the traffic vehicles.

    :param colours: RGBA per vehicle index, cycled (the bodies' colours); () = grey.
    """
    marker_type, array_type = msg(MARKER), msg(MARKER_ARRAY)
    header_type, color_type = msg(HEADER), msg(COLOR)
    shown = set()

    def build(stamp, objects):
        header = header_type(stamp=stamp, frame_id=frame_id)
        markers = []
        present = set()
        for o in objects:
            r, g, b, a = colours[o.index % len(colours)] if colours else (0.6, 0.6, 0.6, 1.0)
            item = marker_type(header=header, ns='traffic', id=o.index,
                               type=MARKER_OF_SHAPE[o.shape], action=ADD,
                               color=color_type(r=r, g=g, b=b, a=a))
            item.pose.position.x, item.pose.position.y = float(o.x_m), float(o.y_m)
            item.pose.position.z = 0.5 * o.height_m
            qx, qy, qz, qw = quaternion_from_yaw(o.yaw_rad)
            item.pose.orientation.x, item.pose.orientation.y = qx, qy
            item.pose.orientation.z, item.pose.orientation.w = qz, qw
            item.scale.x, item.scale.y, item.scale.z = (float(v) for v in o.size_m)
            markers.append(item)
            present.add(o.index)
        for index in sorted(shown - present):
            markers.append(marker_type(header=header, ns='traffic', id=index, action=DELETE))
        shown.clear()
        shown.update(present)
        return array_type(markers=markers)
    return build


# (colour, shape, status) of each TrafficLightElement of a group in one state.
Elements = Tuple[Tuple[int, int, int], ...]


def signal_elements(group, state: str) -> Elements:
    """
    Return the TrafficLightElements (colour, shape, status) a group shows in a state.

    Lit ('red', 'yellow', 'green'): one SOLID_ON element of the state's colour per shape of the
    group's bulbs of that colour (in the order of core BULB_SHAPES), a CIRCLE when it has none
    (a group without bulbs); 'off': :data:`DARK`.
    """
    if state == 'off':
        return DARK
    shapes = {bulb.shape for bulb in group.bulbs if bulb.color == state} or {'circle'}
    return tuple((ELEMENT_COLOR[state], ELEMENT_SHAPE[shape], SOLID_ON)
                 for shape in BULB_SHAPES if shape in shapes)


def signal_groups_reader(rules):
    """
    Return ``groups(states)`` -> ((group id, Elements), ...) of every group of ``rules``.

    ``states`` is ``{group id: state}`` (SignalController.states()); the groups come in the
    map's order. The elements of each (group, state) are worked out once, here.
    """
    table: Dict[int, Dict[str, Elements]] = {
        group.id: {state: signal_elements(group, state) for state in SIGNAL_STATES}
        for group in rules.groups}

    def groups(states):
        return tuple((group_id, by_state[states[group_id]])
                     for group_id, by_state in table.items())
    return groups


def traffic_signals_builder(msg):
    """
    Return ``build(stamp, groups)``: autoware_perception_msgs/TrafficLightGroupArray.

    ``groups``: ((group id, Elements), ...) as :func:`signal_groups_reader` gives them; every
    element has confidence 1.0 and no group has predictions.
    """
    array_type, group_type = msg(TRAFFIC_LIGHT_GROUP_ARRAY), msg(TRAFFIC_LIGHT_GROUP)
    element_type = msg(TRAFFIC_LIGHT_ELEMENT)

    def build(stamp, groups):
        return array_type(stamp=stamp, traffic_light_groups=[
            group_type(traffic_light_group_id=int(group_id), elements=[
                element_type(color=color, shape=shape, status=status, confidence=1.0)
                for color, shape, status in elements])
            for group_id, elements in groups])
    return build
