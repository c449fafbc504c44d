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
autoware_perception_msgs (autoware_msgs 1.9.0) for traffic ground truth, and their builders.

The definitions are copies of the real package's; the bytes our types write are checked
against rosbags' independent CDR serializer over the same definitions.
"""

import math

import pytest

from vehicle_msgs_py import message_type, to_rosbags, type_hash, typestore
from vehicle_sim.core.traffic.objects import TrafficObject
from vehicle_sim.physics.body_labels import instance_uuid
from vehicle_sim.ros.traffic_messages import (
    DELETE,
    predicted_objects_builder,
    traffic_markers_builder,
)

PKG = 'autoware_perception_msgs/msg/'


@pytest.mark.parametrize('name, fields', [
    ('PredictedObjects', ['header', 'objects']),
    ('PredictedObject', ['object_id', 'existence_probability', 'classification', 'kinematics',
                         'shape']),
    ('ObjectClassification', ['label', 'probability']),
    ('PredictedObjectKinematics', ['initial_pose_with_covariance',
                                   'initial_twist_with_covariance',
                                   'initial_acceleration_with_covariance', 'predicted_paths']),
    ('PredictedPath', ['path', 'time_step', 'confidence']),
    ('Shape', ['type', 'footprint', 'dimensions']),
])
def test_fields_are_the_real_packages(name, fields):
    assert list(message_type(PKG + name).__dataclass_fields__) == fields


def test_constants_are_the_real_packages():
    classification = message_type(PKG + 'ObjectClassification')
    assert (classification.UNKNOWN, classification.CAR, classification.TRUCK,
            classification.PEDESTRIAN, classification.UNDER_DRIVABLE) == (0, 1, 2, 7, 11)
    shape = message_type(PKG + 'Shape')
    assert (shape.BOUNDING_BOX, shape.CYLINDER, shape.POLYGON) == (0, 1, 2)


@pytest.mark.parametrize('name, digest', [
    # regression values (REP 2011 over the definitions in vehicle_msgs_py)
    ('PredictedObjects', 'b63151309c3323bb6e3f09c54b3358aa53a8e66937a1cde15c5d5ede1ef80a08'),
    ('PredictedObject', '07a517a2ed3cfcc961768dbbe769091566e8415177c3e3526a83fb392bcd3717'),
    ('ObjectClassification',
     '38131fef2df46486c20c12c238faf778328309f4c3e9daa6ffd621732e48dd19'),
    ('PredictedObjectKinematics',
     'a7c128b84bbb8de1f927c8475930a99681b67832fe947aa5cb1ac6c5b3e6a80b'),
    ('PredictedPath', 'd7e3250f12551fcc92777897e1ae11d71f355f770b993189eb2053f10531ccd2'),
    ('Shape', '1a32ac3073c17e4822d39b7f4c263eb1c4a2bacbf707d6db96e77e867063562b'),
])
def test_type_hash_is_the_pinned_value(name, digest):
    assert type_hash(PKG + name) == 'RIHS01_' + digest


def objects():
    return (TrafficObject(0, 'traffic_0', 10.0, -5.625, 0.0, 20.0, 4.3, 1.8, 1.5,
                          ((20.0, -5.625, 0.0), (30.0, -5.625, 0.0)), 0.5, instance_id=1),
            TrafficObject(3, 'traffic_3', 50.0, -1.875, 0.1, 0.0, 4.6, 1.9, 1.7, (), 0.5,
                          instance_id=4))


def stamp():
    return message_type('builtin_interfaces/msg/Time')(sec=3, nanosec=250_000_000)


def test_predicted_objects_serialize_as_rosbags_does():
    message = predicted_objects_builder(message_type, 'map')(stamp(), objects())
    data = message.serialize()
    assert bytes(typestore().serialize_cdr(to_rosbags(message), PKG + 'PredictedObjects')) \
        == data
    assert type(message).deserialize(data) == message
    first, second = message.objects
    # the UUID of the instance id: the object's id in every perception output
    assert bytes(first.object_id.uuid) == instance_uuid(1) == bytes(15) + b'\x01'
    assert bytes(second.object_id.uuid) == instance_uuid(4)
    assert first.kinematics.initial_pose_with_covariance.pose.position.z == 0.75   # h / 2
    assert [p.position.x for p in first.kinematics.predicted_paths[0].path] == [20.0, 30.0]
    assert second.kinematics.initial_pose_with_covariance.pose.orientation.z == \
        pytest.approx(math.sin(0.1 / 2), abs=1e-12)
    assert (second.shape.dimensions.x, second.shape.dimensions.y,
            second.shape.dimensions.z) == (4.6, 1.9, 1.7)


def test_markers_delete_the_vehicles_that_left():
    build = traffic_markers_builder(message_type, 'world', ((1.0, 0.0, 0.0, 1.0),))
    both = build(stamp(), objects())
    assert [(m.id, m.action) for m in both.markers] == [(0, 0), (3, 0)]
    assert both.markers[1].scale.z == 1.7 and both.markers[0].color.r == 1.0
    one = build(stamp(), objects()[:1])
    assert [(m.id, m.action) for m in one.markers] == [(0, 0), (3, DELETE)]
    again = build(stamp(), objects()[:1])
    assert [(m.id, m.action) for m in again.markers] == [(0, 0)]


def test_obstacles_follow_the_vehicles_as_unknown_objects_at_rest():
    from vehicle_sim.core.traffic.objects import obstacle_objects
    from vehicle_sim.core.world.params import obstacle_from_dict
    wall = obstacle_from_dict({'name': 'wall', 'shape': 'box', 'size': [1.0, 6.0, 2.0],
                               'position': [20.0, 0.0, 1.0], 'yaw': 0.3}, 'w.yaml')
    pole = obstacle_from_dict({'name': 'pole', 'shape': 'cylinder', 'radius': 0.2,
                               'height': 2.0, 'position': [10.0, 5.0, 1.0], 'mass': 3.0},
                              'w.yaml')
    found = obstacle_objects((wall, pole), pose_of=lambda name: (11.0, 5.5, 1.0, 0.0),
                             instance_of={'wall': 7, 'pole': 8}.get)
    assert [(o.name, o.x_m, o.y_m, o.yaw_rad) for o in found] == [
        ('wall', 20.0, 0.0, 0.3), ('pole', 11.0, 5.5, 0.0)]       # the pole is movable
    message = predicted_objects_builder(message_type, 'map')(stamp(), objects()[:1], found)
    assert len(message.objects) == 3
    first, wall_object, pole_object = message.objects
    assert first.classification[0].label == 1
    assert [c.label for c in wall_object.classification] == [0]          # UNKNOWN
    assert wall_object.kinematics.predicted_paths == []
    assert wall_object.kinematics.initial_twist_with_covariance.twist.linear.x == 0.0
    assert (wall_object.shape.type, wall_object.shape.dimensions.y) == (0, 6.0)  # BOUNDING_BOX
    assert (pole_object.shape.type, pole_object.shape.dimensions.x) == (1, 0.4)  # CYLINDER
    assert bytes(wall_object.object_id.uuid) == instance_uuid(7)
    assert bytes(pole_object.object_id.uuid) == instance_uuid(8)
    data = message.serialize()
    assert bytes(typestore().serialize_cdr(to_rosbags(message), PKG + 'PredictedObjects')) \
        == data
