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
The traffic topics' fast serializers (ros/traffic_cdr.py) give their builders' messages' bytes.

Equal to cyclonedds-python's and rosbags' CDR of the message the builder makes from the same
constants and values, for every alignment the frame id and the paths' lengths give, vehicles and
obstacles, and markers added and deleted over successive calls.
"""

from dataclasses import replace
import math

import pytest

from vehicle_msgs_py import message_type, to_rosbags, typestore
from vehicle_sim.core.traffic.objects import ObstacleObject, TrafficObject
from vehicle_sim.ros import traffic_cdr
from vehicle_sim.ros import traffic_messages as tm

FRAME_IDS = ['', 'm', 'map', 'world', 'abcdefg', 'framed/ego/odom']
STAMPS = [(0, 0), (12, 345_678_901), (-3, 7)]


def rosbags_bytes(obj):
    return bytes(typestore().serialize_cdr(to_rosbags(obj), type(obj).__ros_type__))


def stamp(sec, nanosec):
    return message_type('builtin_interfaces/msg/Time')(sec=sec, nanosec=nanosec)


def vehicle(index, poses, step_s=0.5):
    # a vehicle with a path of ``poses`` poses (0 .. 10: shorter where the lanes end)
    return TrafficObject(index, f'traffic_{index}', 10.0 * index + 0.25, -5.625, 0.1 * index,
                         20.0 + index, 4.5, 1.8, 1.5 - 0.1 * index,
                         tuple((10.0 * index + k, -5.625 + 0.01 * k, 0.1 * index + 0.001 * k)
                               for k in range(1, poses + 1)), step_s)


VEHICLES = [vehicle(i, poses) for i, poses in enumerate((10, 0, 3, 1, 10, 7))] + [
    vehicle(6, 2, step_s=1.25)]
# one of each other class; a pedestrian a cylinder (its diameter the larger of its sides)
CLASSED = [replace(vehicle(7 + i, i % 4), object_class=name, length_m=0.3, width_m=0.6)
           if name == 'pedestrian' else replace(vehicle(7 + i, i % 4), object_class=name)
           for i, name in enumerate(('pedestrian', 'truck', 'bus', 'trailer', 'motorcycle',
                                     'bicycle', 'pedestrian'))]
OBSTACLES = [ObstacleObject('cone', 50.0, -14.0, 0.35, 0.0, 'cylinder', (0.4, 0.4, 0.7)),
             ObstacleObject('wall', 20.0, 0.0, 1.0, math.pi / 3, 'box', (1.0, 6.0, 2.0)),
             ObstacleObject('ball', -1.0, 2.0, 0.5, -0.5, 'sphere', (1.0, 1.0, 1.0))]


@pytest.mark.parametrize('frame_id', FRAME_IDS)
def test_predicted_objects_bytes_equal_the_builders_message_for_every_alignment(frame_id):
    serialize = traffic_cdr.predicted_objects_serializer(frame_id)
    build = tm.predicted_objects_builder(message_type, frame_id)
    for (sec, nanosec), count in zip(STAMPS, (len(VEHICLES), 3, 0)):
        for obstacles in ((), OBSTACLES[:1], OBSTACLES):
            t = stamp(sec, nanosec)
            message = build(t, VEHICLES[:count], obstacles)
            data = serialize(t, VEHICLES[:count], obstacles)
            assert data == message.serialize() == rosbags_bytes(message), (count, obstacles)


@pytest.mark.parametrize('frame_id', FRAME_IDS[:3])
def test_objects_of_every_class_serialize_to_their_labels_and_shapes(frame_id):
    serialize = traffic_cdr.predicted_objects_serializer(frame_id)
    build = tm.predicted_objects_builder(message_type, frame_id)
    objects = VEHICLES[:2] + CLASSED
    t = stamp(12, 345_678_901)
    message = build(t, objects, OBSTACLES[:1])
    data = serialize(t, objects, OBSTACLES[:1])
    assert data == message.serialize() == rosbags_bytes(message)
    decoded = typestore().deserialize_cdr(data, tm.PREDICTED_OBJECTS)
    assert [o.classification[0].label for o in decoded.objects] == [1, 1, 7, 2, 3, 4, 5, 6, 7, 0]
    assert [o.shape.type for o in decoded.objects] == [0, 0, 1, 0, 0, 0, 0, 0, 1, 1]
    walker = decoded.objects[2].shape.dimensions
    assert (walker.x, walker.y, walker.z) == (0.6, 0.6, CLASSED[0].height_m)


@pytest.mark.parametrize('frame_id', FRAME_IDS[:3])
def test_markers_of_pedestrians_are_cylinders_in_both_ways(frame_id):
    serialize = traffic_cdr.traffic_markers_serializer(frame_id)
    build = tm.traffic_markers_builder(message_type, frame_id)
    t = stamp(0, 7)
    objects = VEHICLES[:1] + CLASSED
    message = build(t, objects)
    assert serialize(t, objects) == message.serialize() == rosbags_bytes(message)
    assert [m.type for m in message.markers] == [1, 3, 1, 1, 1, 1, 1, 3]    # CUBE, CYLINDER
    assert (message.markers[1].scale.x, message.markers[1].scale.y) == (0.6, 0.6)


@pytest.mark.parametrize('frame_id', FRAME_IDS)
def test_traffic_markers_bytes_equal_the_builders_through_adds_and_deletes(frame_id):
    colours = ((1.0, 0.0, 0.0, 1.0), (0.0, 0.5, 1.0, 0.75))
    serialize = traffic_cdr.traffic_markers_serializer(frame_id, colours)
    build = tm.traffic_markers_builder(message_type, frame_id, colours)
    grey = traffic_cdr.traffic_markers_serializer(frame_id)
    build_grey = tm.traffic_markers_builder(message_type, frame_id)
    # all, some gone (deleted), back again, none
    for (sec, nanosec), objects in zip(STAMPS * 2, (VEHICLES, VEHICLES[2:5], VEHICLES[:3], ())):
        t = stamp(sec, nanosec)
        message = build(t, objects)
        assert serialize(t, objects) == message.serialize() == rosbags_bytes(message)
        assert grey(t, objects) == build_grey(t, objects).serialize()


def test_the_traffic_rows_publish_the_fast_bytes_on_the_embedded_transport():
    from vehicle_sim.ros.endpoints import MessageKit
    from vehicle_sim.ros.traffic_interfaces import PREDICTED_OBJECTS_TOPIC, TRAFFIC_MARKERS
    from vehicle_sim.transport import fast_cdr

    class Wiring:
        frame = 'world'
        colours = ()

    kit = MessageKit(message_type, fast_cdr.SERIALIZERS.get)
    for row in (PREDICTED_OBJECTS_TOPIC, TRAFFIC_MARKERS):
        assert row.converter(kit, Wiring()).serialized, row.name
        # a transport without serializers gets messages
        assert not row.converter(MessageKit(message_type), Wiring()).serialized, row.name
