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
``/map/lanes``' fast serializer (ros/lane_cdr.py) gives its builder's message's bytes.

Equal to cyclonedds-python's and rosbags' CDR of the MarkerArray that ``lane_markers_builder``
makes of the same graph, for every alignment the frame id gives: roads with dashed lines, a
crossing with stop lines, lamps, a crosswalk and an area, the shipped Lanelet2 and SUMO maps,
and markers of no point and of one.
"""

from pathlib import Path

from lane_helpers import signal_crossing
import numpy as np
import pytest

from vehicle_msgs_py import message_type, to_rosbags, typestore
from vehicle_sim.config import load_world
from vehicle_sim.core.map.road_segments import lane_graph_from_roads, roads_from_list
from vehicle_sim.maps.lane_maps import load_lane_graph
from vehicle_sim.ros import lane_cdr, lane_messages
from vehicle_sim.ros.lane_messages import (
    lane_markers_builder,
    LINE_STRIP,
    MARKER_ARRAY,
    MarkerPart,
    TRIANGLE_LIST,
)

FRAME_IDS = ['', 'm', 'map', 'world', 'abcdefg', 'framed/ego/odom']
WORLDS = Path(__file__).resolve().parents[1] / 'config' / 'worlds'


def stamp(sec=12, nanosec=345_678_901):
    return message_type('builtin_interfaces/msg/Time')(sec=sec, nanosec=nanosec)


def rosbags_bytes(obj):
    return bytes(typestore().serialize_cdr(to_rosbags(obj), type(obj).__ros_type__))


def roads():
    return lane_graph_from_roads(roads_from_list(
        [{'lanes': 2, 'backward_lanes': 1, 'segments': [
            {'type': 'straight', 'length': 30.0}, {'type': 'arc', 'radius': 40.0,
                                                  'angle': 0.5}]}], 'roads'), 'roads')


@pytest.mark.parametrize('frame_id', FRAME_IDS)
def test_lane_markers_bytes_equal_the_builders_message_for_every_alignment(frame_id):
    serialize = lane_cdr.lane_markers_serializer(frame_id)
    build = lane_markers_builder(message_type, frame_id)
    for graph in (roads(), signal_crossing(), signal_crossing(areas=False)):
        for t in (stamp(), stamp(0, 0), stamp(-3, 7)):
            message = build(t, graph)
            data = serialize(t, graph)
            assert data == message.serialize() == rosbags_bytes(message)
    # every kind of marker was in there
    namespaces = {m.ns for m in build(stamp(), signal_crossing()).markers}
    assert namespaces == {'road_surface', 'lane_boundaries', 'centrelines', 'stop_lines',
                          'traffic_lights', 'crosswalks', 'areas'}


def test_the_decoded_bytes_hold_the_graphs_points_in_order():
    graph = roads()
    data = lane_cdr.lane_markers_serializer('map')(stamp(), graph)
    decoded = typestore().deserialize_cdr(data, MARKER_ARRAY)
    parts = lane_messages.lane_marker_parts(graph)
    assert len(decoded.markers) == len(parts)
    for marker, part in zip(decoded.markers, parts):
        assert (marker.ns, marker.id, marker.type) == (part.ns, part.marker_id, part.kind)
        assert marker.header.frame_id == 'map' and marker.header.stamp.sec == 12
        got = np.array([(p.x, p.y, p.z) for p in marker.points]).reshape(-1, 3)
        assert np.array_equal(got, part.points)
    centre = [m for m in decoded.markers if m.ns == 'centrelines'][0]
    assert centre.type == LINE_STRIP and centre.points[0].z == 0.02


@pytest.mark.parametrize('frame_id', FRAME_IDS[:4])
def test_markers_of_no_point_and_of_one_point_serialize_as_the_builders(monkeypatch, frame_id):
    parts = [MarkerPart('empty', 1, LINE_STRIP, np.empty((0, 3)), (1.0, 0.5, 0.25, 1.0),
                        (0.1, 0.0, 0.0)),
             MarkerPart('one', 2, TRIANGLE_LIST, np.array([[1.5, -2.0, 0.25]]),
                        (0.0, 0.0, 0.0, 0.5), (1.0, 1.0, 1.0)),
             MarkerPart('ñandú', 3, LINE_STRIP, np.empty((0, 3)), (0.2, 0.2, 0.2, 0.2),
                        (0.05, 0.0, 0.0))]
    for module in (lane_messages, lane_cdr):
        monkeypatch.setattr(module, 'lane_marker_parts', lambda graph: parts)
    message = lane_markers_builder(message_type, frame_id)(stamp(), None)
    assert [len(m.points) for m in message.markers] == [0, 1, 0]
    data = lane_cdr.lane_markers_serializer(frame_id)(stamp(), None)
    assert data == message.serialize() == rosbags_bytes(message)


@pytest.mark.parametrize('world, extra', [('urban.yaml', 'lanelet2'),
                                          ('city_sumo.yaml', 'sumolib')])
def test_the_shipped_lane_maps_serialize_as_the_builders(world, extra):
    pytest.importorskip(extra, reason=f'{extra} is not installed (its map kind needs it)')
    graph = load_lane_graph(load_world(WORLDS / world))
    message = lane_markers_builder(message_type, 'map')(stamp(), graph)
    assert sum(len(m.points) for m in message.markers) > 3000
    assert lane_cdr.lane_markers_serializer('map')(stamp(), graph) == message.serialize()


def test_the_map_lanes_row_publishes_the_fast_bytes_where_the_transport_takes_them():
    from vehicle_sim.ros.endpoints import MessageKit
    from vehicle_sim.ros.map_interfaces import MAP_LANES
    from vehicle_sim.transport import fast_cdr

    class Wiring:
        lanes_frame = 'map'

    convert = MAP_LANES.converter(MessageKit(message_type, fast_cdr.SERIALIZERS.get), Wiring())
    assert convert.serialized
    # a transport without serializers gets the message
    assert not MAP_LANES.converter(MessageKit(message_type), Wiring()).serialized
