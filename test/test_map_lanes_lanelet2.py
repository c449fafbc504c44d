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
Lanelet2 maps as lane graphs: a map the test writes (OSM XML), read with the lanelet2 package.

The map, its ids and its two kinds of coordinates are drawn in test/lane_helpers.py.
"""

import math
from pathlib import Path
import subprocess
import sys

from lane_helpers import DEFAULT_MPS, local_node, LOCAL_SHIFT, ORIGIN, write_map
import pytest
import yaml

from vehicle_sim.config import load_world
from vehicle_sim.core.geometry.geodesy import GeodeticOrigin
from vehicle_sim.core.map.lane_invasion import LaneInvasionDetector
from vehicle_sim.core.map.lane_state import LaneTracker
from vehicle_sim.core.map.lanelet2_params import lanelet2_map_from_dict
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.maps.lane_maps import with_lanes

pytest.importorskip('lanelet2', reason="lanelet2 is not installed (pip install "
                                       "'vehicle_sim[lanelet2]'; the test extra has it)")

from vehicle_sim.maps.lanelet2_file import MAX_OSM_BYTES  # noqa: E402
from vehicle_sim.maps.lanelet2_map import (  # noqa: E402  (after the skip)
    lane_graph_from_map,
    Lanelet2MapWarning,
    Lanelet2Unavailable,
    line_type_of,
    load_lanelet2,
)


@pytest.fixture(scope='module')
def osm(tmp_path_factory):
    return write_map(tmp_path_factory.mktemp('lanelet2') / 'town.osm')


@pytest.fixture(scope='module')
def loaded(osm):
    return load_lanelet2(str(osm), ORIGIN, 'local_cartesian', DEFAULT_MPS)


def test_a_point_at_s_10_on_a_lanelet_reads_its_id_and_offset_zero(loaded):
    graph = loaded[0]
    found = graph.locate(10.0, 1.75, 0.0)          # lanelet 2001's centreline is y = 1.75
    assert found.lane_id == 2001
    assert found.offset_m == pytest.approx(0.0, abs=0.01)
    assert found.s_m == pytest.approx(10.0, abs=0.01)
    assert found.width_m == pytest.approx(3.5, abs=0.01)
    state = LaneTracker(graph).update(10.0, 1.75, 0.0)
    assert (state.lane_id, round(state.offset_m, 2), round(state.s_m, 2)) == (2001, 0.0, 10.0)
    x, y, _ = graph.pose_at(2001, 10.0, 0.0)
    assert (x, y) == (pytest.approx(10.0, abs=0.01), pytest.approx(1.75, abs=0.01))


def test_successors_and_neighbours_equal_the_routing_graphs(loaded):
    graph, lanelet_map, routing = loaded

    def lane_id(lanelet):
        return -lanelet.id if lanelet.inverted() else lanelet.id

    lanelets = list(lanelet_map.laneletLayer)
    lanelets += [ll.invert() for ll in lanelets if ll.id == 2005]
    assert sorted(graph.lanes) == [-2005, 2001, 2002, 2003, 2004, 2005]
    for lanelet in lanelets:
        lane = graph.lanes[lane_id(lanelet)]
        assert set(lane.successors) == {lane_id(f) for f in routing.following(lanelet)}
        for side in ('left', 'right'):
            change = getattr(routing, side)(lanelet)
            adjacent = getattr(routing, 'adjacent' + side.title())(lanelet)
            expected = change if change is not None else adjacent
            assert getattr(lane, side + '_lane') == (None if expected is None
                                                     else lane_id(expected))
            assert getattr(lane, side + '_change') == (change is not None)
    # the map as drawn: 2001 -> 2003 -> 2005; a change 2001 <-> 2002 across the dashed line;
    # 2003 and 2004 side by side behind a solid line (neighbours, no change)
    lanes = graph.lanes
    assert lanes[2001].successors == (2003,) and lanes[2003].successors == (2005,)
    assert (lanes[2001].left_lane, lanes[2001].left_change) == (2002, True)
    assert (lanes[2003].left_lane, lanes[2003].left_change) == (2004, False)
    assert lanes[-2005].successors == ()


def test_speed_limits_come_from_the_tag_or_the_default(loaded):
    graph = loaded[0]
    assert graph.lanes[2004].speed_limit_mps == pytest.approx(30.0 / 3.6)
    assert graph.lanes[2001].speed_limit_mps == DEFAULT_MPS


def test_line_types_come_from_the_line_strings_tags(loaded):
    graph = loaded[0]
    assert graph.lanes[2001].left.line_type == 'dashed'
    assert graph.lanes[2001].right.line_type == 'solid'
    assert graph.lanes[2005].right.line_type == 'curbstone'
    assert line_type_of({'type': 'line_thick', 'subtype': 'solid_dashed'}) == 'solid_dashed'
    assert line_type_of({'type': 'fence'}) == 'wall'
    assert line_type_of({'type': 'virtual'}) == 'virtual'
    assert line_type_of({}) == 'none'


def test_a_path_across_the_dashed_line_gives_one_invasion_naming_it(loaded):
    detector = LaneInvasionDetector(loaded[0])
    events = []
    for step in range(41):            # from (10, 1.75) on 2001 to (30, 5.75) on 2002
        events += detector.update(10.0 + 0.5 * step, 1.75 + 0.1 * step, 0.05 * step)
    assert [(e.boundary_id, e.line_type) for e in events] == [(1002, 'dashed')]
    assert events[0].y_m == pytest.approx(3.5, abs=0.01)


def test_autoware_local_projector_reads_the_local_tags(osm):
    graph = load_lanelet2(str(osm), ORIGIN, 'autoware_local', DEFAULT_MPS)[0]
    found = graph.locate(10.0 + LOCAL_SHIFT[0], 1.75 + LOCAL_SHIFT[1], 0.0)
    assert found.lane_id == 2001
    assert found.offset_m == pytest.approx(0.0, abs=1e-6)
    assert found.s_m == pytest.approx(10.0, abs=1e-6)
    assert graph.locate(10.0, 1.75, 0.0) is None      # lat/lon are not used


def test_local_cartesian_projector_matches_the_worlds_east_north_up_plane(loaded):
    start = loaded[0].lanes[2002].centerline[0]
    assert start.tolist() == [pytest.approx(0.0, abs=1e-3), pytest.approx(5.25, abs=1e-3)]


def test_utm_projector_turns_the_map_by_the_meridian_convergence(osm):
    # UTM zone 32 (central meridian 9 deg E): at 48.1 N, 11.5 E true east points
    # atan(tan(2.5 deg) sin(48.1 deg)) = 1.861 deg left of grid east; the scale there is
    # 0.9996 (1 + (2.5 deg cos(48.1 deg))^2 / 2) = 1.000025
    graph = load_lanelet2(str(osm), ORIGIN, 'utm', DEFAULT_MPS)[0]
    lane = graph.lanes[2001]
    (x0, y0), (x1, y1) = lane.centerline[0], lane.centerline[-1]
    convergence = math.degrees(math.atan(math.tan(math.radians(2.5))
                                         * math.sin(math.radians(48.1))))
    assert math.degrees(math.atan2(y1 - y0, x1 - x0)) == pytest.approx(convergence, abs=0.01)
    assert lane.length_m == pytest.approx(50.0 * 1.000025, abs=0.002)


def test_a_world_map_entry_loads_relative_to_the_world_file(osm):
    spec = lanelet2_map_from_dict({'type': 'lanelet2', 'file': osm.name,
                                   'projector': 'autoware_local'}, 'w.yaml: map')
    graph = lane_graph_from_map(spec, str(osm.parent / 'w.yaml'), ORIGIN)
    assert 2001 in graph.lanes


@pytest.mark.parametrize('data, match', [
    ({'type': 'lanelet2'}, "w.yaml: map: field 'file' is required"),
    ({'type': 'lanelet2', 'file': 'a.osm', 'projector': 'mgrs'},
     "field 'projector' = 'mgrs': must be one of local_cartesian, utm, autoware_local"),
    ({'type': 'lanelet2', 'file': 'a.osm', 'default_speed_limit': 0.0},
     "field 'default_speed_limit' = 0.0: must be > 0"),
])
def test_bad_map_entries_are_refused_naming_the_field(data, match):
    with pytest.raises(InvalidParameterError, match=match):
        lanelet2_map_from_dict(data, 'w.yaml: map')


def test_bad_files_are_refused_naming_the_file(tmp_path):
    text = tmp_path / 'notes.osm'
    text.write_text('these are not lanes\n', encoding='utf-8')
    gpx = tmp_path / 'track.osm'
    gpx.write_text('<?xml version="1.0"?>\n<gpx version="1.1"></gpx>\n', encoding='utf-8')
    bare = write_map(tmp_path / 'bare.osm', lanelets=False)
    untagged = write_map(tmp_path / 'untagged.osm', local_tags=False)
    cases = [
        (text, 'local_cartesian', r'notes.osm: not an OSM file \(not XML'),
        (gpx, 'local_cartesian', r'track.osm: not an OSM file \(its root element is <gpx>'),
        (bare, 'local_cartesian', 'bare.osm: has no lanelets'),
        (tmp_path / 'missing.osm', 'utm', 'missing.osm: no such file'),
        (untagged, 'autoware_local', r'untagged.osm: node 100 has no local_x/local_y tags'),
    ]
    for path, projector, match in cases:
        with pytest.raises(InvalidParameterError, match='w.yaml: map.file: .*' + match):
            load_lanelet2(str(path), ORIGIN, projector, DEFAULT_MPS, 'w.yaml: map.file')


# What the refusals below tell the user to write.
ORIGIN_HINT = ("set the world file's origin: near the map, e.g. origin: {latitude: 48.1, "
               "longitude: 11.5} (or, its nodes having local_x/local_y tags, the map's "
               'projector: autoware_local)')


def test_a_map_far_from_the_worlds_origin_is_refused_naming_the_origin_key(osm):
    # A world file without origin: (latitude 0, longitude 0) and the map at 48.1 N, 11.5 E:
    # on that origin's east-north-up plane its lanes would lie 4800 km away.
    with pytest.raises(InvalidParameterError) as refused:
        load_lanelet2(str(osm), GeodeticOrigin(), 'local_cartesian', DEFAULT_MPS,
                      'w.yaml: map.file')
    assert str(refused.value) == (
        f"w.yaml: map.file: {osm}: its lanes lie 4,800 km from the world's origin (latitude 0, "
        "longitude 0) with projector 'local_cartesian', which places the map's lat/lon around "
        f'that origin: {ORIGIN_HINT}')


def test_a_map_outside_the_utm_zone_of_the_worlds_origin_is_refused_naming_the_key(osm):
    with pytest.raises(InvalidParameterError) as refused:
        load_lanelet2(str(osm), GeodeticOrigin(), 'utm', DEFAULT_MPS, 'w.yaml: map.file')
    assert str(refused.value) == (
        f"w.yaml: map.file: {osm}: its nodes lie outside the UTM zone of the world's origin "
        "(latitude 0, longitude 0), as lanelet2 says: 'Latitude 48.1, longitude 11.5 out of "
        f"legal range for UTM zone 31': {ORIGIN_HINT}")


def test_a_map_near_the_worlds_origin_is_taken(osm):
    near = GeodeticOrigin(ORIGIN.latitude_deg + 0.5, ORIGIN.longitude_deg, 0.0)   # 56 km north
    graph = load_lanelet2(str(osm), near, 'local_cartesian', DEFAULT_MPS)[0]
    assert graph.lanes[2001].centerline[0][1] == pytest.approx(-55600.0, abs=200.0)


def test_without_lanelet2_the_error_names_the_extra(monkeypatch, osm):
    monkeypatch.setitem(sys.modules, 'lanelet2', None)
    with pytest.raises(Lanelet2Unavailable, match=r"pip install 'vehicle_sim\[lanelet2\]'"):
        load_lanelet2(str(osm), ORIGIN)


# ------------------------------------------------------------- Autoware's maps, bad input

def _way(way_id, nodes, kind, subtype=None, tags=''):
    sub = f'<tag k="subtype" v="{subtype}"/>' if subtype else ''
    refs = ''.join(f'<nd ref="{n}"/>' for n in nodes)
    return f'  <way id="{way_id}">{refs}<tag k="type" v="{kind}"/>{sub}{tags}</way>\n'


def _element(rel_id, subtype, members):
    refs = ''.join(f'<member type="{kind}" ref="{ref}" role="{role}"/>'
                   for kind, ref, role in members)
    return (f'  <relation id="{rel_id}">{refs}<tag k="type" v="regulatory_element"/>'
            f'<tag k="subtype" v="{subtype}"/></relation>\n')


def _refers(*ids):
    return ''.join(f'<member type="relation" ref="{i}" role="regulatory_element"/>' for i in ids)


def _square(first_node, way_id, x, y, size=2.0):
    corners = [(x, y), (x + size, y), (x + size, y + size), (x, y + size)]
    nodes = ''.join(local_node(first_node + i, cx, cy) for i, (cx, cy) in enumerate(corners))
    return nodes + _way(way_id, range(first_node, first_node + 4), 'area_polygon',
                        tags='<tag k="area" v="yes"/>')


# Every regulatory element type of Autoware's format (autoware_lanelet2_extension's
# docs/lanelet2_format_extension.md), none of which the PyPI lanelet2 can construct, and one
# no one knows: lanelets 2001 and 2003 refer to all of them.
AUTOWARE_ELEMENTS = (
    # road marking 3001: stop line 1101 at x = 40 across lanelet 2001
    local_node(5001, 40.0, 0.0) + local_node(5002, 40.0, 3.5)
    + _way(1101, (5001, 5002), 'stop_line')
    + _element(3001, 'road_marking', [('way', 1101, 'refers')])
    # crosswalk 3002: crosswalk lanelet 2101 across lanelet 2003 at x = 70 .. 74, its polygon
    # 1103, its stop line 1104 at x = 68
    + local_node(5003, 70.0, -1.0) + local_node(5004, 70.0, 8.0) + local_node(5005, 74.0, -1.0)
    + local_node(5006, 74.0, 8.0) + local_node(5007, 68.0, 0.0) + local_node(5008, 68.0, 3.5)
    + _way(1102, (5003, 5004), 'line_thin', 'dashed')
    + _way(1105, (5005, 5006), 'line_thin', 'dashed')
    + _way(1103, (5003, 5005, 5006, 5004), 'crosswalk_polygon', tags='<tag k="area" v="yes"/>')
    + _way(1104, (5007, 5008), 'stop_line')
    + '  <relation id="2101"><member type="way" ref="1102" role="left"/><member type="way" '
      'ref="1105" role="right"/><tag k="type" v="lanelet"/><tag k="subtype" v="crosswalk"/>'
      '<tag k="one_way" v="no"/><tag k="participant:pedestrian" v="yes"/></relation>\n'
    + _element(3002, 'crosswalk', [('relation', 2101, 'refers'), ('way', 1103,
                                                                  'crosswalk_polygon'),
                                   ('way', 1104, 'ref_line')])
    # areas: detection area 3003, no stopping 3004, no parking 3005, bus stop 3006, speed
    # bump 3007 (polygons 1111 .. 1115 beside the road)
    + ''.join(_square(5100 + 4 * i, 1111 + i, 10.0 * i, -10.0) for i in range(5))
    + _element(3003, 'detection_area', [('way', 1111, 'refers'), ('way', 1101, 'ref_line')])
    + _element(3004, 'no_stopping_area', [('way', 1112, 'refers')])
    + _element(3005, 'no_parking_area', [('way', 1113, 'refers')])
    + _element(3006, 'bus_stop_area', [('way', 1114, 'refers')])
    + _element(3007, 'speed_bump', [('way', 1115, 'refers')])
    # skipped: a virtual traffic light 3008 (its stop line 1101), a roundabout 3009, and 3010
    + _element(3008, 'virtual_traffic_light', [('way', 1101, 'stop_line')])
    + _element(3009, 'roundabout', [('relation', 2003, 'entry')])
    + _element(3010, 'nobody_knows_this', [('way', 1101, 'refers')]))


def test_a_map_whose_regulatory_elements_all_fail_in_lanelet2_loads_warning_once_per_type(
        tmp_path):
    path = write_map(tmp_path / 'autoware.osm', extra=AUTOWARE_ELEMENTS, members={
        2001: _refers(3001, 3003, 3004, 3005, 3008, 3010),
        2003: _refers(3002, 3006, 3007, 3009)})
    with pytest.warns(Lanelet2MapWarning) as caught:
        graph = load_lanelet2(str(path), ORIGIN, 'autoware_local', DEFAULT_MPS,
                              'w.yaml: map.file')[0]
    messages = sorted(str(w.message).replace(f'w.yaml: map.file: {path}: ', '')
                      for w in caught)
    assert messages == [
        '1 bus_stop_area regulatory element (id 3006) drawn as areas only: the simulator does '
        'not act on them',
        '1 detection_area regulatory element (id 3003) drawn as areas only: the simulator does '
        'not act on them',
        '1 no_parking_area regulatory element (id 3005) drawn as areas only: the simulator '
        'does not act on them',
        '1 no_stopping_area regulatory element (id 3004) drawn as areas only: the simulator '
        'does not act on them',
        '1 nobody_knows_this regulatory element (id 3010) skipped: the simulator does not use '
        'them',
        '1 roundabout regulatory element (id 3009) skipped: the simulator does not use them',
        '1 speed_bump regulatory element (id 3007) drawn as areas only: the simulator does not '
        'act on them',
        '1 virtual_traffic_light regulatory element (id 3008) skipped: the simulator does not '
        'use them']
    assert all(str(w.message).startswith(f'w.yaml: map.file: {path}: ') for w in caught)
    assert sorted(graph.lanes) == [-2005, 2001, 2002, 2003, 2004, 2005]
    rules = graph.rules
    # the road marking's stop line on 2001 at x = 40; the crosswalk's on 2003 at x = 68
    assert [(s.id, s.lane_id, s.kind, round(s.s_m, 6)) for s in rules.stop_lines] == [
        (1101, 2001, 'road_marking', 40.0), (1104, 2003, 'yield', 18.0)]
    areas = {a.kind: a for a in rules.areas}
    assert sorted(areas) == ['bus_stop_area', 'crosswalk', 'detection_area', 'no_parking_area',
                             'no_stopping_area', 'speed_bump']
    crosswalk = areas['crosswalk']
    assert (crosswalk.id, crosswalk.lanes, crosswalk.walkable) == (2101, (2003, 2004), True)
    assert crosswalk.polygon.min(axis=0).tolist() == [70.0 + LOCAL_SHIFT[0],
                                                      -1.0 + LOCAL_SHIFT[1]]
    assert areas['detection_area'].lanes == (2001,)
    assert areas['speed_bump'].polygon.shape == (4, 2)


# A traffic light (3020: light 1120, bulbs 1121, stop line 1122 at x = 45) on lanelets 2001 and
# 2002, a right of way (3021: 2003 before 2004, 2004's stop line 1123 at x = 55) and a stop
# sign (3022: sign 1124, stop line 1125 at x = 120 on 2005).
SIGNALS = (
    local_node(5201, 48.0, -1.0, 5.0) + local_node(5202, 48.0, -1.5, 5.0)
    + _way(1120, (5201, 5202), 'traffic_light', 'red_yellow_green',
           '<tag k="height" v="0.9"/>')
    + local_node(5203, 48.0, -1.25, 5.75, '<tag k="color" v="red"/>')
    + local_node(5204, 48.0, -1.25, 5.45, '<tag k="color" v="yellow"/>')
    + local_node(5205, 48.0, -1.25, 5.15, '<tag k="color" v="green"/>')
    + local_node(5206, 48.0, -1.0, 5.15, '<tag k="color" v="green"/><tag k="arrow" v="left"/>')
    + _way(1121, (5203, 5204, 5205, 5206), 'light_bulbs', tags='<tag k="traffic_light_id" '
                                                               'v="1120"/>')
    + local_node(5207, 45.0, 0.0) + local_node(5208, 45.0, 7.0)
    + _way(1122, (5207, 5208), 'stop_line')
    + _element(3020, 'traffic_light', [('way', 1120, 'refers'), ('way', 1122, 'ref_line'),
                                       ('way', 1121, 'light_bulbs')])
    + local_node(5209, 55.0, 3.5) + local_node(5210, 55.0, 7.0)
    + _way(1123, (5209, 5210), 'stop_line')
    + _element(3021, 'right_of_way', [('relation', 2003, 'right_of_way'),
                                      ('relation', 2004, 'yield'), ('way', 1123, 'ref_line')])
    + local_node(5211, 122.0, -1.0) + local_node(5212, 122.0, -1.5)
    + _way(1124, (5211, 5212), 'traffic_sign', 'stop_sign')
    + local_node(5213, 120.0, 0.0) + local_node(5214, 120.0, 3.5)
    + _way(1125, (5213, 5214), 'stop_line')
    + _element(3022, 'traffic_sign', [('way', 1124, 'refers'), ('way', 1125, 'ref_line')]))


def test_traffic_lights_right_of_way_and_stop_signs_become_the_lane_graphs_rules(tmp_path):
    path = write_map(tmp_path / 'signals.osm', extra=SIGNALS, members={
        2001: _refers(3020), 2002: _refers(3020), 2003: _refers(3021), 2004: _refers(3021),
        2005: _refers(3022)})
    graph = load_lanelet2(str(path), ORIGIN, 'autoware_local', DEFAULT_MPS)[0]
    rules = graph.rules
    group = rules.group(3020)
    assert (group.lanes, len(group.stop_lines)) == ((2001, 2002), 2)
    assert [(b.color, b.shape, round(b.z_m, 3)) for b in group.bulbs] == [
        ('red', 'circle', 5.75), ('yellow', 'circle', 5.45), ('green', 'circle', 5.15),
        ('green', 'left_arrow', 5.15)]
    assert (group.bulbs[0].x_m, group.bulbs[0].y_m) == (48.0 + LOCAL_SHIFT[0],
                                                        -1.25 + LOCAL_SHIFT[1])
    lines = {(s.lane_id, s.kind): s for s in rules.stop_lines}
    assert lines[(2001, 'traffic_light')].id == 1122          # the map's line, then a new id
    assert lines[(2002, 'traffic_light')].id not in (1122, 2001, 2002)
    for lane_id in (2001, 2002):
        line = lines[(lane_id, 'traffic_light')]
        assert (round(line.s_m, 6), line.group_id) == (45.0, 3020)
        assert rules.next_stop_line(graph, lane_id, 10.0, 100.0)[1] == pytest.approx(35.0)
    (rule,) = rules.right_of_way
    assert (rule.id, rule.priority_lanes, rule.yield_lanes) == (3021, (2003,), (2004,))
    assert [s.s_m for s in rules.stop_lines if s.id in rule.stop_lines] == [
        pytest.approx(5.0)]
    assert (round(lines[(2005, 'stop_sign')].s_m, 6), lines[(2005, 'stop_sign')].id) == (
        20.0, 1125)
    assert (-2005, 'stop_sign') not in lines            # the inverted lane: its direction only


def test_speed_limits_of_lanelets_with_regulatory_elements_load(tmp_path):
    # a lanelet referring to any regulatory element crashed the speed limit's lookup
    path = write_map(tmp_path / 'limits.osm', extra=SIGNALS, members={2004: _refers(3021)})
    graph = load_lanelet2(str(path), ORIGIN, 'autoware_local', DEFAULT_MPS)[0]
    assert graph.lanes[2004].speed_limit_mps == pytest.approx(30.0 / 3.6)
    assert graph.lanes[2003].speed_limit_mps == DEFAULT_MPS


def _lanelet_xml(rel_id, left, right, subtype, one_way='yes'):
    return (f'  <relation id="{rel_id}"><member type="way" ref="{left}" role="left"/>'
            f'<member type="way" ref="{right}" role="right"/><tag k="type" v="lanelet"/>'
            f'<tag k="subtype" v="{subtype}"/><tag k="location" v="urban"/>'
            f'<tag k="one_way" v="{one_way}"/></relation>\n')


def _subtypes_map(path):
    # 2201: a road whose left bound meets its right one at x = 30 (a taper); 2202: a road
    # shoulder on its right; rows 10 m apart above: one lanelet of each other subtype
    text = '<?xml version="1.0" encoding="UTF-8"?>\n<osm version="0.6">\n'
    text += (local_node(1, 0.0, 3.5) + local_node(2, 0.0, 0.0) + local_node(3, 30.0, 0.0)
             + local_node(4, 0.0, -3.0) + local_node(5, 30.0, -3.0))
    text += (_way(11, (1, 3), 'line_thin', 'solid') + _way(12, (2, 3), 'line_thin', 'solid')
             + _way(13, (4, 5), 'road_border'))
    text += _lanelet_xml(2201, 11, 12, 'road') + _lanelet_xml(2202, 12, 13, 'road_shoulder')
    subtypes = ('bicycle_lane', 'highway', 'exit', 'play_street', 'crosswalk', 'walkway',
                'rail')
    for i, subtype in enumerate(subtypes):
        y, first = 10.0 * (i + 1), 100 + 4 * i
        text += (local_node(first, 0.0, y + 3.0) + local_node(first + 1, 30.0, y + 3.0)
                 + local_node(first + 2, 0.0, y) + local_node(first + 3, 30.0, y))
        text += (_way(200 + 2 * i, (first, first + 1), 'line_thin', 'solid')
                 + _way(201 + 2 * i, (first + 2, first + 3), 'line_thin', 'solid'))
        text += _lanelet_xml(2203 + i, 200 + 2 * i, 201 + 2 * i, subtype)
    for i, subtype in enumerate(('parking', 'keepout', 'building')):     # multipolygons
        first = 300 + 4 * i
        text += ''.join(local_node(first + k, 40.0 + 10.0 * i + dx, dy) for k, (dx, dy) in
                        enumerate(((0, 0), (5, 0), (5, 5), (0, 5))))
        text += (_way(400 + 2 * i, (first, first + 1, first + 2), 'line_thin', 'solid')
                 + _way(401 + 2 * i, (first + 2, first + 3, first), 'line_thin', 'solid'))
        text += (f'  <relation id="{2401 + i}"><member type="way" ref="{400 + 2 * i}" '
                 f'role="outer"/><member type="way" ref="{401 + 2 * i}" role="outer"/>'
                 f'<tag k="type" v="multipolygon"/><tag k="subtype" v="{subtype}"/>'
                 '</relation>\n')
    path.write_text(text + '</osm>\n', encoding='utf-8')
    return path


def test_tapers_other_subtypes_walking_lanelets_and_areas_load(tmp_path):
    path = _subtypes_map(tmp_path / 'subtypes.osm')
    with pytest.warns(Lanelet2MapWarning) as caught:
        graph = load_lanelet2(str(path), ORIGIN, 'autoware_local', DEFAULT_MPS)[0]
    assert [str(w.message) for w in caught] == [
        f"map: {path}: 1 lanelet of subtype 'rail' (id 2209) skipped: not a lane the simulator "
        'drives']
    assert {i: lane.subtype for i, lane in graph.lanes.items()} == {
        2201: 'road', 2202: 'road_shoulder', 2203: 'bicycle_lane', 2204: 'highway',
        2205: 'exit', 2206: 'play_street'}
    taper = graph.lanes[2201]
    assert taper.widths[-1] == 0.0 and taper.widths[0] == pytest.approx(3.5, abs=0.2)
    end = graph.locate(30.0 + LOCAL_SHIFT[0], LOCAL_SHIFT[1], 0.0)
    assert end is not None and end.width_m == 0.0
    assert {a.id: (a.kind, a.walkable) for a in graph.rules.areas} == {
        2207: ('crosswalk', True), 2208: ('walkway', True), 2401: ('parking', False),
        2402: ('keepout', False), 2403: ('building', False)}


def test_a_wrong_vehicle_lanelet_is_refused_naming_the_world_file_the_map_and_the_lanelet(
        tmp_path):
    text = ('<?xml version="1.0"?>\n<osm version="0.6">\n' + local_node(1, 0.0, 0.0)
            + local_node(2, 30.0, 0.0) + _way(11, (1, 2), 'line_thin', 'solid')
            + _lanelet_xml(2301, 11, 11, 'road') + '</osm>\n')
    path = tmp_path / 'flat.osm'
    path.write_text(text, encoding='utf-8')
    with pytest.raises(InvalidParameterError) as refused:
        load_lanelet2(str(path), ORIGIN, 'autoware_local', DEFAULT_MPS, 'w.yaml: map.file')
    assert str(refused.value) == (f'w.yaml: map.file: {path}: lanelet 2301: lane 2301: its '
                                  'width must be > 0 somewhere (its bounds coincide)')


def test_a_map_with_empty_lat_lon_needs_autoware_local_and_no_origin(tmp_path):
    # Autoware's local and MGRS maps: lat="" lon="", local_x/local_y on every node
    real = Path(__file__).resolve().parent / 'data' / 'lanelet2_maps' / 'autoware_core'
    world = tmp_path / 'w.yaml'
    data = {'vehicles': [{'name': 'Car', 'namespace': '', 'model': 'ToyotaPrius',
                          'pose': {'lanelet': 45, 's': 5.0}}],
            'map': {'type': 'lanelet2', 'file': str(real / 'vm_06_01.osm')}}
    world.write_text(yaml.safe_dump(data), encoding='utf-8')
    with pytest.raises(InvalidParameterError) as refused:
        with_lanes(load_world(str(world), 'ToyotaPrius'))
    assert str(refused.value) == (
        f"{world}: map.file: {real / 'vm_06_01.osm'}: node 1 has lat '', lon '', not numbers: "
        "projector 'local_cartesian' reads them: its local_x/local_y tags are Autoware's map "
        "frame: set the map's projector: autoware_local")
    data['map']['projector'] = 'autoware_local'              # and still no origin:
    world.write_text(yaml.safe_dump(data), encoding='utf-8')
    spec = with_lanes(load_world(str(world), 'ToyotaPrius'))
    car = spec.vehicles[0]
    assert spec.lanes.locate(car.x_m, car.y_m, car.yaw_rad).lane_id == 45


def test_a_file_over_the_size_limit_is_refused_before_parsing(tmp_path):
    path = tmp_path / 'huge.osm'
    with open(path, 'wb') as sparse:          # no disk used: nothing is read
        sparse.truncate(MAX_OSM_BYTES + 1)
    with pytest.raises(InvalidParameterError, match=(
            r'huge.osm: 100 MB is larger than the 100 MB a lanelet2 map may have')):
        load_lanelet2(str(path), ORIGIN, 'autoware_local')


def _write_big_map(path, megabytes):
    # rows of two-lane straight roads, 100 m long, 20 m apart, until the file has ``megabytes``
    rows, size = 0, 0
    with open(path, 'w', encoding='utf-8') as out:
        out.write('<?xml version="1.0"?>\n<osm version="0.6">\n')
        node, way, lanelet = 1, 10_000_000, 20_000_000
        while size < megabytes * 1_000_000:
            text, lines = '', []
            for k in range(3):
                first = node
                for i in range(11):
                    text += local_node(node, 10.0 * i, 20.0 * rows + 3.5 * k)
                    node += 1
                text += _way(way, range(first, node), 'line_thin', 'solid')
                lines.append(way)
                way += 1
            for k in range(2):
                text += _lanelet_xml(lanelet, lines[k + 1], lines[k], 'road')
                lanelet += 1
            out.write(text)
            size += len(text)
            rows += 1
        out.write('</osm>\n')
    return 2 * rows


def test_a_50_mb_map_loads_in_bounded_memory(tmp_path):
    path = tmp_path / 'big.osm'
    lanelets = _write_big_map(path, 50)
    script = ('import resource, sys\n'
              'from vehicle_sim.maps.lanelet2_map import load_lanelet2\n'
              f'graph = load_lanelet2({str(path)!r}, projector="autoware_local")[0]\n'
              'print(len(graph.lanes), resource.getrusage(resource.RUSAGE_SELF).ru_maxrss)\n')
    done = subprocess.run([sys.executable, '-c', script], capture_output=True, text=True,
                          check=True)
    lanes, peak_kb = map(int, done.stdout.split())
    print(f'50 MB map: {lanelets} lanelets, peak RSS {peak_kb / 1024:.0f} MB')
    assert lanes == lanelets
    assert peak_kb < 1_500_000           # about 15 bytes of memory per byte of XML, 0.75 GB


def test_a_lanelet_lanelet2_cannot_make_is_left_out_with_its_error_not_a_crash(tmp_path):
    # lanelet 2302 names two left bounds: lanelet2 reports it and keeps a broken lanelet, whose
    # routing graph ended the process (a segmentation fault)
    text = ('<?xml version="1.0"?>\n<osm version="0.6">\n'
            + ''.join(local_node(i + 1, 30.0 * (i % 2), 3.5 * (i // 2)) for i in range(6))
            + _way(11, (1, 2), 'line_thin', 'solid') + _way(12, (3, 4), 'line_thin', 'dashed')
            + _way(13, (5, 6), 'line_thin', 'solid') + _lanelet_xml(2301, 12, 11, 'road')
            + _lanelet_xml(2302, 13, 12, 'road').replace(
                'role="left"/>', 'role="left"/><member type="way" ref="11" role="left"/>')
            + '</osm>\n')
    path = tmp_path / 'two_lefts.osm'
    path.write_text(text, encoding='utf-8')
    script = ('import warnings\n'
              'from vehicle_sim.maps.lanelet2_map import load_lanelet2\n'
              'with warnings.catch_warnings(record=True) as caught:\n'
              '    warnings.simplefilter("always")\n'
              f'    graph = load_lanelet2({str(path)!r}, projector="autoware_local")[0]\n'
              'print(sorted(graph.lanes))\n'
              'print(*(str(w.message) for w in caught), sep="\\n")\n')
    done = subprocess.run([sys.executable, '-c', script], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr[-2000:]
    lanes, message = done.stdout.splitlines()
    assert lanes == '[2301]'
    assert message == (f'map: {path}: lanelet2 reports 1 error(s), the map is loaded without '
                       'the primitives they name: Error parsing primitive 2302: Lanelet has not '
                       'exactly one left border!')
