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
vehicle_msgs/LaneState and LaneInvasion: fields, type hashes, CDR bytes, and their builders.

The generic checks of test_msgs_vehicle_msgs_py (both serializers agree, round trips) run for
these types too, since they cover every shipped definition; here the bytes are computed by hand.
"""

import math
import struct
import sys

import pytest

from vehicle_msgs_py import message_definition, message_type, type_hash, typestore
from vehicle_sim.core.map.lane_invasion import LaneInvasion
from vehicle_sim.core.map.lane_state import LaneState, OFF_LANE
from vehicle_sim.ros.lane_messages import (
    lane_invasion_builder,
    lane_markers_builder,
    lane_state_builder,
)

pytestmark = pytest.mark.skipif(sys.byteorder != 'little', reason='examples are little-endian')

LE_HEADER = bytes.fromhex('00010000')


def _stamp():
    return message_type('builtin_interfaces/msg/Time')(sec=12, nanosec=500_000_000)


def test_fields_are_in_the_definitions_order():
    assert list(message_type('vehicle_msgs/msg/LaneState').__dataclass_fields__) == [
        'header', 'on_lane', 'lane_id', 's', 'offset', 'heading_error', 'width', 'speed_limit',
        'stop_line_ahead', 'stop_line_id', 'stop_line_kind', 'stop_line_distance',
        'traffic_light_group_id', 'signal_state']
    assert list(message_type('vehicle_msgs/msg/LaneInvasion').__dataclass_fields__) == [
        'header', 'boundary_id', 'line_type', 'position']
    assert list(message_type('vehicle_msgs/srv/SetLanePose_Request').__dataclass_fields__) == [
        'lanelet', 's', 'offset']
    assert list(message_type('vehicle_msgs/srv/SetLanePose_Response').__dataclass_fields__) == [
        'success', 'message']


@pytest.mark.parametrize('ros_type, digest', [
    # regression values (REP 2011 over the definitions in vehicle_msgs_py)
    # (LaneState's: also what ROS 2 Jazzy's rosidl wrote for the exported vehicle_msgs)
    ('vehicle_msgs/msg/LaneState',
     '38eb5bcb8dff1b864f3610eef459eeafd659fc9467ad9116d63ff781b9208be8'),
    ('vehicle_msgs/msg/LaneInvasion',
     '536182fd7b69061433861ddfa523cab04c997eac600fa56ed53317ce7eabeea5'),
    ('vehicle_msgs/srv/SetLanePose',
     '2c795a5dbb0b5089d6e7807059c11b16188933e566a7abc4ae085675e81c65bd'),
])
def test_type_hash_is_the_pinned_value(ros_type, digest):
    assert type_hash(ros_type) == 'RIHS01_' + digest


def test_lane_state_bytes_are_the_hand_computed_cdr():
    state = LaneState(True, 2001, 10.0, -0.25, 0.05, 3.5, 50.0 / 3.6,
                      True, 9001, 'traffic_light', 40.0, 7001, 'red')
    message = lane_state_builder(message_type, 'map')(_stamp(), state)
    expected = (LE_HEADER + struct.pack('<iI', 12, 500_000_000)
                + struct.pack('<I', 4) + b'map\x00'              # header ends at 16
                + b'\x01' + bytes(7)                             # bool, pad to 24 for int64
                + struct.pack('<q', 2001)
                + struct.pack('<5d', 10.0, -0.25, 0.05, 3.5, 50.0 / 3.6)      # .. 72
                + b'\x01' + bytes(7)                             # stop_line_ahead, pad to 80
                + struct.pack('<q', 9001)                        # stop_line_id: .. 88
                + struct.pack('<I', 14) + b'traffic_light\x00'   # kind: .. 106
                + bytes(6) + struct.pack('<d', 40.0)             # pad to 112, distance: .. 120
                + struct.pack('<q', 7001)                        # group: .. 128
                + struct.pack('<I', 4) + b'red\x00')             # signal_state: .. 136
    data = message.serialize()
    assert data == expected
    assert bytes(typestore().serialize_cdr(_rosbags(message), 'vehicle_msgs/msg/LaneState')) \
        == expected
    assert type(message).deserialize(data) == message


def test_lane_invasion_bytes_are_the_hand_computed_cdr():
    event = LaneInvasion(12.5, 1002, 'dashed', 27.5, 3.5)
    message = lane_invasion_builder(message_type, 'map')(_stamp(), event)
    expected = (LE_HEADER + struct.pack('<iI', 12, 500_000_000)
                + struct.pack('<I', 4) + b'map\x00'              # 16
                + struct.pack('<q', 1002)                        # 24
                + struct.pack('<I', 7) + b'dashed\x00' + bytes(5)   # 35 -> pad to 40
                + struct.pack('<3d', 27.5, 3.5, 0.0))
    assert message.serialize() == expected
    assert type(message).deserialize(expected) == message


def test_off_lane_state_is_all_zero_but_the_header():
    message = lane_state_builder(message_type, 'map')(_stamp(), OFF_LANE)
    assert (message.on_lane, message.lane_id, message.s, message.offset, message.width,
            message.speed_limit) == (False, 0, 0.0, 0.0, 0.0, 0.0)
    assert (message.stop_line_ahead, message.stop_line_id, message.stop_line_kind,
            message.stop_line_distance, message.traffic_light_group_id,
            message.signal_state) == (False, 0, '', 0.0, 0, '')
    assert not math.isnan(message.heading_error)


def test_message_definition_carries_the_header_and_point():
    text = message_definition('vehicle_msgs/msg/LaneInvasion')
    assert text.startswith('std_msgs/Header header\nint64 boundary_id\nstring line_type\n'
                           'geometry_msgs/Point position\n')
    assert 'MSG: geometry_msgs/Point\nfloat64 x\nfloat64 y\nfloat64 z' in text


def _rosbags(message):
    from vehicle_msgs_py import to_rosbags
    return to_rosbags(message)


def test_lane_markers_draw_the_surface_every_boundary_and_every_centreline():
    from vehicle_sim.core.map.road_segments import lane_graph_from_roads, roads_from_list
    from vehicle_sim.ros.lane_messages import LINE_LIST, LINE_STRIP, TRIANGLE_LIST
    graph = lane_graph_from_roads(roads_from_list(
        [{'lanes': 2, 'backward_lanes': 1, 'segments': [{'type': 'straight', 'length': 30.0}]}],
        'roads'), 'roads')
    array = lane_markers_builder(message_type, 'map')(_stamp(), graph)
    by_ns = {}
    for marker in array.markers:
        by_ns.setdefault(marker.ns, []).append(marker)
    (surface,) = by_ns['road_surface']
    assert surface.type == TRIANGLE_LIST and len(surface.points) == 3 * 2 * 3   # 3 lanes
    boundaries = {m.id: m for m in by_ns['lane_boundaries']}
    assert sorted(boundaries) == [100028, 100029, 100030, 100031]
    dashed = boundaries[100029]              # between the forward lanes, y = -3.5
    # dashes at 0, 9, 18, 27 m: four (start, end) pairs
    assert dashed.type == LINE_LIST
    assert [(p.x, p.y) for p in dashed.points] == [
        (0.0, -3.5), (3.0, -3.5), (9.0, -3.5), (12.0, -3.5), (18.0, -3.5), (21.0, -3.5),
        (27.0, -3.5), (30.0, -3.5)]
    assert boundaries[100030].type == LINE_STRIP and len(by_ns['centrelines']) == 3
    assert all(m.header.frame_id == 'map' for m in array.markers)
    data = array.serialize()       # (colours are float32: compare bytes, not values)
    assert type(array).deserialize(data).serialize() == data


def test_set_lane_pose_request_bytes_are_the_hand_computed_cdr():
    request = message_type('vehicle_msgs/srv/SetLanePose_Request')(lanelet=-2005, s=12.5,
                                                                   offset=-0.25)
    expected = LE_HEADER + struct.pack('<q2d', -2005, 12.5, -0.25)
    assert request.serialize() == expected
    assert type(request).deserialize(expected) == request
