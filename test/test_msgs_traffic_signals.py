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
The signals' message: autoware_perception_msgs/TrafficLightGroupArray, built and hand-packed.

The definitions in vehicle_msgs_py are copies of autoware_msgs' (1.9.0, the same fields in
1.12.0): their type hashes are the ones ROS 2 Jazzy's rosidl writes for the real package. The
bytes of a two-group array are computed here by hand and equal what the builder's message
serializes to, what the fast serializer packs and what rosbags writes; they decode to the same
ids, colours and shapes, and, on a machine with ROS 2 and autoware_msgs sourced, through the
real package's own type support (rclpy).
"""

import struct
import sys

import pytest

from vehicle_msgs_py import message_type, to_rosbags, type_hash, typestore
from vehicle_sim.core.map.lane_rules import Bulb, TrafficLightGroup
from vehicle_sim.ros import traffic_cdr
from vehicle_sim.ros.traffic_messages import (
    DARK,
    signal_elements,
    signal_groups_reader,
    traffic_signals_builder,
)

pytestmark = pytest.mark.skipif(sys.byteorder != 'little', reason='examples are little-endian')

PKG = 'autoware_perception_msgs/msg/'
ARRAY = PKG + 'TrafficLightGroupArray'


@pytest.mark.parametrize('name, fields', [
    ('TrafficLightGroupArray', ['stamp', 'traffic_light_groups']),
    ('TrafficLightGroup', ['traffic_light_group_id', 'elements', 'predictions']),
    ('TrafficLightElement', ['color', 'shape', 'status', 'confidence']),
    ('PredictedTrafficLightState', ['predicted_stamp', 'simultaneous_elements', 'reliability',
                                    'information_source']),
])
def test_fields_are_the_real_packages(name, fields):
    assert list(message_type(PKG + name).__dataclass_fields__) == fields


def test_element_constants_are_the_real_packages():
    element = message_type(PKG + 'TrafficLightElement')
    assert (element.UNKNOWN, element.RED, element.AMBER, element.GREEN, element.WHITE) == \
        (0, 1, 2, 3, 4)
    assert (element.CIRCLE, element.LEFT_ARROW, element.RIGHT_ARROW, element.UP_ARROW,
            element.DOWN_ARROW, element.CROSS) == (1, 2, 3, 4, 7, 10)
    assert (element.SOLID_OFF, element.SOLID_ON, element.FLASHING) == (1, 2, 3)


@pytest.mark.parametrize('name, digest', [
    # as ROS 2 Jazzy's rosidl writes them for autoware_msgs 1.12.0's autoware_perception_msgs
    # (share/autoware_perception_msgs/msg/<Name>.json)
    ('TrafficLightGroupArray', '6f6bf892681a43836041dabdac5e95dc3125f1f785d7455c77d09a8b4645fc90'),
    ('TrafficLightGroup', '39af6118b864b40141456dd74caefe615739b465e136ef0b806d0b50329347cb'),
    ('TrafficLightElement', '825dec7c3da93f4cb3653006dbeef30f7d1ca92f1d1091e01e79d7d6b84086e9'),
    ('PredictedTrafficLightState',
     '2681f28132320e5fba12197070f0f06a956f5a991823034eb5b1bf298243e4be'),
])
def test_type_hash_is_the_real_packages(name, digest):
    assert type_hash(PKG + name) == 'RIHS01_' + digest


def bulb(color, shape='circle'):
    return Bulb(color, 0.0, 0.0, 5.0, shape)


def group(group_id, *bulbs):
    return TrafficLightGroup(group_id, (1,), (), tuple(bulbs))


THREE = (bulb('red'), bulb('yellow'), bulb('green'))


def test_a_group_shows_one_element_per_shape_of_its_lit_colour():
    with_arrow = group(7, *THREE, bulb('green', 'left_arrow'))
    assert signal_elements(with_arrow, 'green') == ((3, 1, 2), (3, 2, 2))   # GREEN CIRCLE+LEFT
    assert signal_elements(with_arrow, 'red') == ((1, 1, 2),)                # RED CIRCLE ON
    assert signal_elements(with_arrow, 'yellow') == ((2, 1, 2),)             # AMBER
    assert signal_elements(with_arrow, 'off') == DARK == ((0, 0, 1),)        # SOLID_OFF
    # a group without bulbs (no camera sees it) shows a circle of its state's colour
    assert signal_elements(group(8), 'green') == ((3, 1, 2),)
    # an arrow-only group: the arrow alone
    assert signal_elements(group(9, bulb('green', 'right_arrow')), 'green') == ((3, 3, 2),)


def test_the_reader_gives_every_group_in_the_maps_order():
    class Rules:
        groups = (group(20, *THREE), group(10))
    read = signal_groups_reader(Rules())
    assert read({10: 'red', 20: 'green'}) == ((20, ((3, 1, 2),)), (10, ((1, 1, 2),)))
    assert read({10: 'off', 20: 'yellow'}) == ((20, ((2, 1, 2),)), (10, DARK))


def stamp():
    return message_type('builtin_interfaces/msg/Time')(sec=12, nanosec=500_000_000)


# Two groups: 1001 green with a left arrow (two elements), 2**40 + 3 red (one element).
GROUPS = ((1001, ((3, 1, 2), (3, 2, 2))), (2**40 + 3, ((1, 1, 2),)))
HAND_BYTES = (
    bytes.fromhex('00010000')                       # CDR, little endian
    + struct.pack('<iI', 12, 500_000_000)           # stamp: 0 .. 8
    + struct.pack('<I', 2)                          # two groups: 8 .. 12
    + bytes(4)                                      # pad to 16 for the int64 id
    + struct.pack('<q', 1001) + struct.pack('<I', 2)            # id, two elements: .. 28
    + bytes([3, 1, 2, 0]) + struct.pack('<f', 1.0)  # GREEN CIRCLE SOLID_ON, pad, 1.0: .. 36
    + bytes([3, 2, 2, 0]) + struct.pack('<f', 1.0)  # GREEN LEFT_ARROW SOLID_ON: .. 44
    + struct.pack('<I', 0)                          # no predictions: .. 48 (8-aligned)
    + struct.pack('<q', 2**40 + 3) + struct.pack('<I', 1)       # .. 60
    + bytes([1, 1, 2, 0]) + struct.pack('<f', 1.0)  # RED CIRCLE SOLID_ON: .. 68
    + struct.pack('<I', 0))                         # .. 72


def test_two_groups_serialize_to_the_hand_computed_bytes():
    message = traffic_signals_builder(message_type)(stamp(), GROUPS)
    assert message.serialize() == HAND_BYTES
    assert traffic_cdr.traffic_signals_serializer()(stamp(), GROUPS) == HAND_BYTES
    assert bytes(typestore().serialize_cdr(to_rosbags(message), ARRAY)) == HAND_BYTES


def test_the_hand_computed_bytes_decode_to_the_groups():
    message = message_type(ARRAY).deserialize(HAND_BYTES)
    assert (message.stamp.sec, message.stamp.nanosec) == (12, 500_000_000)
    assert [(g.traffic_light_group_id, [(e.color, e.shape, e.status, e.confidence)
                                        for e in g.elements], list(g.predictions))
            for g in message.traffic_light_groups] == [
        (1001, [(3, 1, 2, 1.0), (3, 2, 2, 1.0)], []), (2**40 + 3, [(1, 1, 2, 1.0)], [])]
    decoded = typestore().deserialize_cdr(HAND_BYTES, ARRAY)
    assert [g.traffic_light_group_id for g in decoded.traffic_light_groups] == [1001, 2**40 + 3]
    assert [e.color for e in decoded.traffic_light_groups[0].elements] == [3, 3]


@pytest.mark.parametrize('groups', [
    (), GROUPS[:1], GROUPS[1:], GROUPS, ((5, DARK),) * 3,
    tuple((i, ((1 + i % 3, 1, 2),) * (i % 4 + 1)) for i in range(-3, 9))])
def test_the_serializer_gives_the_builders_bytes_for_any_groups(groups):
    t = stamp()
    message = traffic_signals_builder(message_type)(t, groups)
    data = traffic_cdr.traffic_signals_serializer()(t, groups)
    assert data == message.serialize() == bytes(
        typestore().serialize_cdr(to_rosbags(message), ARRAY))


def test_the_real_packages_type_support_reads_the_bytes():
    pytest.importorskip('rclpy', reason='rclpy not importable: ROS 2 Jazzy is not sourced')
    msgs = pytest.importorskip('autoware_perception_msgs.msg',
                               reason='autoware_msgs is not sourced on this machine')
    from rclpy.serialization import deserialize_message, serialize_message
    message = deserialize_message(HAND_BYTES, msgs.TrafficLightGroupArray)
    assert [(g.traffic_light_group_id, [(e.color, e.shape, e.status, e.confidence)
                                        for e in g.elements])
            for g in message.traffic_light_groups] == [
        (1001, [(3, 1, 2, 1.0), (3, 2, 2, 1.0)]), (2**40 + 3, [(1, 1, 2, 1.0)])]
    assert msgs.TrafficLightElement.AMBER == 2
    assert serialize_message(message) == HAND_BYTES
