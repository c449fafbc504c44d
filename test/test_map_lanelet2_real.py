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
Real Lanelet2 maps (test/data/lanelet2_maps: Lanelet2's example, Autoware's test and sample maps).

Each loads with its traffic lights, stop lines, right of way, crosswalks and areas, warns once
per element type it does not simulate, and a car placed on one of its lanes drives 2 s along it.
Every test prints, per map, its lanelets, signal groups, stop lines, crosswalks and load time.
"""

import collections
import math
from pathlib import Path
import re
import time
import warnings

import pytest
from script_helpers import load_script
import yaml

from vehicle_sim.config import load_world
from vehicle_sim.core.geometry.geodesy import GeodeticOrigin
from vehicle_sim.maps.lane_maps import with_lanes
from vehicle_sim.physics.scene import build_scene

pytest.importorskip('lanelet2', reason="lanelet2 is not installed (pip install "
                                       "'vehicle_sim[lanelet2]'; the test extra has it)")

from vehicle_sim.maps.lanelet2_map import Lanelet2MapWarning, load_lanelet2  # noqa: E402

DATA = Path(__file__).resolve().parent / 'data' / 'lanelet2_maps'
KARLSRUHE = GeodeticOrigin(49.0, 8.42, 0.0)      # near Lanelet2's example map

# file -> (projector, lanelets, lanes, signal groups, bulbs, stop lines by kind, right of way
# rules, crosswalks, the element types warned about)
MAPS = {
    'lanelet2/mapping_example.osm': (
        'local_cartesian', 371, 450, 6, 30, {'traffic_light': 10, 'yield': 2}, 2, 8,
        {"subtype 'rail'", 'stop lines off the lanes'}),
    'autoware_core/vm_03_right_hand.osm': (
        'autoware_local', 68, 63, 16, 136, {'traffic_light': 18}, 4, 5, set()),
    'autoware_core/vm_02.osm': (
        'autoware_local', 10, 10, 0, 0, {'stop_sign': 1, 'road_marking': 1}, 0, 0,
        {'detection_area', 'no_stopping_area'}),
    'autoware_core/vm_01_15-16_pudo.osm': (
        'autoware_local', 40, 40, 0, 0, {}, 0, 0, {'no_parking_area', 'no_stopping_area'}),
    'autoware_core/vm_06_01.osm': ('autoware_local', 3, 3, 0, 0, {}, 0, 0, set()),
    'autoware_lanelet2_extension/mgrs.osm': ('autoware_local', 1, 1, 0, 0, {}, 0, 0, set()),
    'autoware_lanelet2_map_validator/sample_map.osm': (
        'autoware_local', 53, 49, 11, 61, {'traffic_light': 17}, 14, 4,
        {'detection_area', 'no_stopping_area', 'virtual_traffic_light'}),
    'autoware_lanelet2_map_validator/bus_stop_area.osm': (
        'autoware_local', 2, 2, 0, 0, {}, 0, 0, {'bus_stop_area'}),
    'autoware_lanelet2_map_validator/crosswalk_with_regulatory_element.osm': (
        'autoware_local', 3, 2, 0, 0, {'yield': 2}, 0, 1, set()),
}


def _load(name):
    projector = MAPS[name][0]
    start = time.perf_counter()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter('always')
        graph, lanelet_map, _ = load_lanelet2(str(DATA / name), KARLSRUHE, projector)
    seconds = time.perf_counter() - start
    rules = graph.rules
    crosswalks = [a for a in rules.areas if a.kind == 'crosswalk']
    print(f'{name}: {len(lanelet_map.laneletLayer)} lanelets ({len(graph.lanes)} lanes), '
          f'{len(rules.groups)} signal groups, {len(rules.stop_lines)} stop lines, '
          f'{len(crosswalks)} crosswalks, loaded in {seconds:.2f} s')
    return graph, lanelet_map, [str(w.message) for w in caught
                                if issubclass(w.category, Lanelet2MapWarning)]


@pytest.mark.parametrize('name', sorted(MAPS))
def test_a_real_map_loads_with_its_signals_stop_lines_and_crosswalks(name):
    _, lanelets, lanes, groups, bulbs, stops, row, crosswalks, warned = MAPS[name]
    graph, lanelet_map, messages = _load(name)
    rules = graph.rules
    assert (len(lanelet_map.laneletLayer), len(graph.lanes)) == (lanelets, lanes)
    assert (len(rules.groups), sum(len(g.bulbs) for g in rules.groups)) == (groups, bulbs)
    assert dict(collections.Counter(s.kind for s in rules.stop_lines)) == stops
    assert len(rules.right_of_way) == row
    assert sum(a.kind == 'crosswalk' for a in rules.areas) == crosswalks
    # one warning per type not simulated, each naming its ids
    assert len(messages) == len(warned)
    for what in warned:
        assert sum(what in m for m in messages) == 1, (what, messages)
    for message in messages:
        assert str(DATA / name) in message
        assert re.search(r'\(ids? \d|regulatory element \d', message), message
    # every signal's stop lines lie on its lanes; every bulb has a colour and a height
    for group in rules.groups:
        for line_id in group.stop_lines:
            line = next(s for s in rules.stop_lines if s.id == line_id)
            assert line.group_id == group.id
            assert line.lane_id in group.lanes or line.lane_id in {
                p for lane in group.lanes for p in graph.predecessors[lane]}
        assert all(b.z_m > 0.0 for b in group.bulbs)


def test_an_autoware_traffic_light_has_its_maps_bulbs_lanes_and_stop_line():
    # sample_map.osm: traffic light regulatory element 1012 (refers 369, 371, 373; light_bulbs
    # 368, 370, 372; ref_line 367), which lanelets 50 and 51 refer to
    graph, lanelet_map, _ = _load('autoware_lanelet2_map_validator/sample_map.osm')
    group = graph.rules.group(1012)
    assert sorted(group.lanes) == [50, 51]
    points = [p for way in (368, 370, 372) for p in lanelet_map.lineStringLayer[way]]
    assert [(b.color, b.x_m, b.y_m) for b in group.bulbs] == [
        (str(p.attributes['color']), p.x, p.y) for p in points]
    assert {b.shape for b in group.bulbs} <= {'circle', 'left_arrow', 'right_arrow', 'up_arrow'}
    stop = [(p.x, p.y) for p in lanelet_map.lineStringLayer[367]]
    for lane_id in group.lanes:
        (line,) = [s for s in graph.rules.stop_lines_on(lane_id) if s.group_id == 1012]
        assert line.id in group.stop_lines
        # where the map's stop line crosses the lane's centreline
        x, y, _ = graph.lanes[lane_id].centre_pose(line.s_m)
        (ax, ay), (bx, by) = stop[0], stop[-1]
        assert abs((bx - ax) * (y - ay) - (by - ay) * (x - ax)) / math.hypot(
            bx - ax, by - ay) == pytest.approx(0.0, abs=0.01)


def test_conflicts_are_those_of_lanelet2s_routing_graph_with_their_overlap():
    graph, lanelet_map, _ = _load('autoware_core/vm_03_right_hand.osm')
    conflicts = graph.rules.conflicts
    assert conflicts
    for conflict in conflicts:
        lane, other = graph.lanes[conflict.lane_id], graph.lanes[conflict.other_id]
        assert other.id not in lane.successors and lane.id not in other.successors
        first, last = conflict.s_m
        assert 0.0 <= first <= last <= lane.length_m
        x, y, _ = lane.centre_pose(0.5 * (first + last))
        position, _ = graph.locate_on(other.id, x, y)
        assert abs(position.offset_m) <= 0.5 * (position.width_m + max(lane.widths)) + 0.01


def test_the_mgrs_map_is_placed_where_autowares_mgrs_projector_puts_it():
    # Autoware's MGRSProjector gives a node's UTM coordinates minus the corner of its 100 km
    # grid square (54SUE here, as map_projector_info.yaml says); the map's local_x/local_y
    # tags, which projector autoware_local reads, are those coordinates
    import lanelet2.io
    import lanelet2.projection
    name = 'autoware_lanelet2_extension/mgrs.osm'
    assert 'mgrs_grid: 54SUE' in (DATA / name).with_name(
        'mgrs_map_projector_info.yaml').read_text(encoding='utf-8')
    graph, lanelet_map, _ = _load(name)
    utm = lanelet2.projection.UtmProjector(lanelet2.io.Origin(0.0, 141.0, 0.0))   # zone 54
    for point in lanelet_map.pointLayer:
        gps = lanelet2.core.GPSPoint(*_lat_lon(DATA / name, point.id), 0.0)
        east_north = utm.forward(gps)
        assert point.x == pytest.approx((east_north.x + 500_000.0) % 100_000.0, abs=0.01)
        assert point.y == pytest.approx(east_north.y % 100_000.0, abs=0.01)


def _lat_lon(path, node_id):
    import xml.etree.ElementTree as ElementTree
    for node in ElementTree.parse(path).getroot().iter('node'):
        if int(node.get('id')) == node_id:
            return float(node.get('lat')), float(node.get('lon'))
    raise KeyError(node_id)


@pytest.mark.parametrize('name', sorted(MAPS))
def test_a_car_placed_on_a_lane_of_a_real_map_drives_2_s_along_it(name, tmp_path):
    graph, _, _ = _load(name)
    roads = [lane for lane in graph.lanes.values()
             if lane.subtype == 'road' and min(lane.widths) > 2.0]
    lane = max(roads, key=lambda one: one.length_m)          # the longest road lane
    start_m = min(3.0, 0.1 * lane.length_m)
    world = tmp_path / 'world.yaml'
    data = {'origin': {'latitude': KARLSRUHE.latitude_deg, 'longitude': KARLSRUHE.longitude_deg},
            'vehicles': [{'name': 'Car', 'namespace': '', 'model': 'ToyotaPrius',
                          'pose': {'lanelet': lane.id, 's': start_m}}],
            'map': {'type': 'lanelet2', 'file': str(DATA / name), 'projector': MAPS[name][0]}}
    world.write_text(yaml.safe_dump(data), encoding='utf-8')
    with warnings.catch_warnings():
        warnings.simplefilter('ignore', Lanelet2MapWarning)
        scene = build_scene(load_world(str(world), 'ToyotaPrius'))
    try:
        car = scene.cars['Car']
        car.logic.set_cruising_speed_kmh(10.0)
        steps = round(2.0 / scene.world.time_step_s)
        for _ in range(steps):
            scene.world.step()
        x, y, _, qx, qy, qz, qw = car.body.pose()
        found = scene.lanes.locate(x, y, 2.0 * math.atan2(qz, qw))
        assert found is not None and found.lane_id in (lane.id,) + lane.successors
        travelled = found.s_m - start_m if found.lane_id == lane.id else \
            found.s_m + lane.length_m - start_m
        assert travelled > 1.0                      # it drove forwards along the lane
        assert abs(found.offset_m) < 0.5 * found.width_m
    finally:
        scene.world.close()


# ----------------------------------------------------------------- the shipped urban map

REPO = Path(__file__).resolve().parent.parent


def test_the_shipped_urban_map_is_what_its_script_draws():
    script = load_script('config/maps/make_urban_map.py')
    assert script.osm_text() == (REPO / 'config' / 'maps' / 'urban_map.osm').read_text('utf-8')


def test_the_urban_world_has_signals_crosswalks_right_of_way_and_a_taper():
    from vehicle_sim.core.map.signal_plan import default_phases, group_conflicts
    with warnings.catch_warnings():
        warnings.simplefilter('error', Lanelet2MapWarning)          # nothing left out
        spec = with_lanes(load_world(str(REPO / 'config' / 'worlds' / 'urban.yaml'),
                                     'ToyotaPrius'))
    graph = spec.lanes
    rules = graph.rules
    # a traffic light per arm on its incoming lane, its stop line 15 m from the centre, three
    # bulbs (green, yellow, red) 5.25 m up
    assert sorted((g.id, g.lanes) for g in rules.groups) == [
        (400, (100,)), (401, (110,)), (402, (120,)), (403, (130,))]
    for group in rules.groups:
        assert [b.color for b in group.bulbs] == ['green', 'yellow', 'red']
        assert {round(b.z_m, 6) for b in group.bulbs} == {5.25}
        (line,) = [s for s in rules.stop_lines if s.group_id == group.id]
        x, y, _ = graph.lanes[line.lane_id].centre_pose(line.s_m)
        assert math.hypot(x, y) == pytest.approx(math.hypot(15.0, 1.75), abs=1e-6)
    # right of way: each straight movement before the opposite left turn
    assert sorted((r.priority_lanes, r.yield_lanes) for r in rules.right_of_way) == [
        ((200,), (221,)), ((210,), (231,)), ((220,), (201,)), ((230,), (211,))]
    # four crosswalks, each across its arm's lanes
    assert sorted((a.id, a.lanes) for a in rules.areas if a.kind == 'crosswalk') == [
        (300, (100, 101)), (301, (110, 111)), (302, (120, 121, 190)), (303, (130, 131))]
    # the taper: lane 191 narrows to nothing; its neighbour on the left takes its traffic
    taper = graph.lanes[191]
    assert taper.widths[-1] == 0.0 and taper.successors == ()
    assert (taper.left_lane, taper.left_change) == (125, True)
    # every left turn crosses the opposite straight movement; the signal plan's phases
    # never hold two conflicting groups
    pairs = {(c.lane_id, c.other_id) for c in rules.conflicts}
    assert {(200, 221), (201, 220), (210, 231), (211, 230)} <= pairs
    conflicts = group_conflicts(rules, graph)
    for intersection in default_phases(rules, graph):
        for phase in intersection:
            assert not any(conflicts[a] & set(phase) for a in phase)
    # the car is on the west arm's incoming lane, 25 m before its stop line
    car = spec.vehicles[0]
    found = graph.locate(car.x_m, car.y_m, car.yaw_rad)
    assert (found.lane_id, round(found.s_m, 6)) == (100, 30.0)
    assert rules.next_stop_line(graph, 100, 30.0, 100.0)[1] == pytest.approx(25.0)


def test_the_car_of_the_urban_world_drives_towards_its_green_light():
    scene = build_scene(load_world(str(REPO / 'config' / 'worlds' / 'urban.yaml'), 'ToyotaPrius'))
    try:
        car = scene.cars['Car']
        car.logic.set_cruising_speed_kmh(10.0)
        for _ in range(round(2.0 / scene.world.time_step_s)):
            scene.world.step()
        x, y, _, qx, qy, qz, qw = car.body.pose()
        found = scene.lanes.locate(x, y, 2.0 * math.atan2(qz, qw))
        assert found.lane_id == 100 and found.s_m > 31.0
        line, distance = scene.lanes.rules.next_stop_line(scene.lanes, 100, found.s_m, 100.0)
        assert (line.group_id, distance) == (400, pytest.approx(55.0 - found.s_m))
        # the map's groups run the default plan: one phase per arm, the west arm's first
        assert scene.parts['signals'].controller.states() == {
            400: 'green', 401: 'red', 402: 'red', 403: 'red'}
    finally:
        scene.world.close()
