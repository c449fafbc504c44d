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
The lane graph of road segments: geometry against closed forms, lane state, lane invasion.

Roads here run along +x from the origin unless said otherwise; lane width 3.5 m, so forward
lane 0 is centred at y = -1.75, forward lane 1 at y = -5.25, backward lane 0 at y = +1.75.
"""

import math

import numpy as np
import pytest

from vehicle_sim.core.map.lane_graph import Boundary, Lane, LaneGraph, LOCATE_CELL_M
from vehicle_sim.core.map.lane_invasion import LaneInvasionDetector
from vehicle_sim.core.map.lane_state import LaneTracker, OFF_LANE
from vehicle_sim.core.map.road_segments import lane_graph_from_roads, roads_from_list
from vehicle_sim.core.specs.errors import InvalidParameterError

SOURCE = 'w.yaml: roads'


def graph_of(*roads):
    return lane_graph_from_roads(roads_from_list(list(roads), SOURCE), SOURCE)


def straight_then_left(lanes=2):
    # 100 m straight, then a quarter circle of radius 50 m to the left, then 20 m straight north
    return graph_of({'name': 'r', 'lanes': lanes, 'segments': [
        {'type': 'straight', 'length': 100.0},
        {'type': 'arc', 'radius': 50.0, 'angle': 90.0},
        {'type': 'straight', 'length': 20.0}]})


def test_lanes_of_a_two_by_two_road_have_ids_successors_and_neighbours():
    graph = straight_then_left()
    assert sorted(graph.lanes) == [100001, 100002, 100051, 100052, 100101, 100102, 100151,
                                   100152, 100201, 100202, 100251, 100252]
    forward0, forward1 = graph.lanes[100001], graph.lanes[100002]
    assert forward0.successors == (100101,) and graph.lanes[100101].successors == (100201,)
    assert graph.lanes[100201].successors == ()
    # backward lanes run the other way: segment 1's backward lane continues in segment 0's
    assert graph.lanes[100151].successors == (100051,) and graph.lanes[100051].successors == ()
    assert (forward0.left_lane, forward0.right_lane) == (None, 100002)
    assert (forward1.left_lane, forward1.right_lane) == (100001, None)
    # the line between forward lanes is dashed by default: a change is allowed both ways
    assert forward0.right_change and forward1.left_change
    assert graph.predecessors[100101] == (100001,)


def test_a_solid_lane_line_forbids_the_lane_change_but_keeps_the_neighbour():
    graph = graph_of({'lanes': 2, 'lane_line': 'solid',
                      'segments': [{'type': 'straight', 'length': 50.0}]})
    assert graph.lanes[100001].right_lane == 100002 and not graph.lanes[100001].right_change


def test_mixed_line_allows_the_change_from_its_dashed_side_only():
    # dashed_solid seen along the chain: dashed on its left (forward lane 0's side)
    graph = graph_of({'lanes': 2, 'lane_line': 'dashed_solid', 'backward_lanes': 0,
                      'segments': [{'type': 'straight', 'length': 50.0}]})
    assert graph.lanes[100001].right_change and not graph.lanes[100002].left_change


def test_locate_on_a_straight_reads_s_offset_heading_error_width_and_limit():
    graph = graph_of({'lanes': 2, 'speed_limit': 25.0,
                      'segments': [{'type': 'straight', 'length': 100.0}]})
    found = graph.locate(10.0, -1.75 + 0.3, 0.1)
    assert found.lane_id == 100001
    assert found.s_m == pytest.approx(10.0) and found.offset_m == pytest.approx(0.3)
    assert found.heading_error_rad == pytest.approx(0.1)
    assert (found.width_m, found.speed_limit_mps) == (3.5, 25.0)
    other = graph.locate(10.0, 1.75, math.pi)     # backward lane: s counts from x = 100
    assert other.lane_id == 100051 and other.s_m == pytest.approx(90.0)
    assert other.offset_m == pytest.approx(0.0, abs=1e-12)
    assert graph.locate(10.0, -7.1, 0.0) is None         # beyond the outer edge (-7.0)
    assert graph.locate(-0.5, -1.75, 0.0) is None        # before the road's start


def test_locate_on_an_arc_matches_the_circle():
    graph = straight_then_left()
    # the arc's centre is (100, 50); forward lane 0 has radius 51.75 there
    angle = math.radians(30.0)
    x = 100.0 + 51.75 * math.sin(angle) - 0.4 * math.sin(angle)     # 0.4 m left of centre
    y = 50.0 - 51.75 * math.cos(angle) + 0.4 * math.cos(angle)
    found = graph.locate(x, y, angle)
    assert found.lane_id == 100101
    assert found.s_m == pytest.approx(51.75 * angle, abs=0.01)     # polyline within 5 mm
    assert found.offset_m == pytest.approx(0.4, abs=0.006)
    assert found.heading_error_rad == pytest.approx(0.0, abs=0.01)


def test_pose_at_and_locate_are_inverse():
    graph = straight_then_left()
    for lane_id, s_m, offset_m in ((100001, 37.0, -0.8), (100101, 60.0, 1.2), (100152, 5.0, 0.0),
                                   (100201, 19.5, 0.3)):
        x, y, yaw = graph.pose_at(lane_id, s_m, offset_m)
        found = graph.locate(x, y, yaw)
        assert (found.lane_id, round(found.s_m, 6), round(found.offset_m, 6)) == \
            (lane_id, pytest.approx(s_m), pytest.approx(offset_m))


def whole_map_locate(graph, x, y, yaw=None):
    """LaneGraph.locate over every segment of the map (its grid of cells set aside)."""
    cells, graph._cells = graph._cells, None
    try:
        return graph.locate(x, y, yaw)
    finally:
        graph._cells = cells


@pytest.mark.parametrize('make', [straight_then_left, lambda: graph_of(
    {'lanes': 3, 'backward_lanes': 2, 'segments': [
        {'type': 'arc', 'radius': 30.0, 'angle': 270.0}, {'type': 'straight', 'length': 70.0},
        {'type': 'arc', 'radius': 12.0, 'angle': -120.0}]})])
def test_locate_in_its_grid_cell_is_locate_over_the_whole_map_bit_for_bit(make):
    # locate looks only at the segments whose reach meets the point's cell (LOCATE_CELL_M):
    # the same LanePosition, to the last bit, as over every segment, on lanes, between them,
    # at their ends, off them, with and without a heading; points off every cell: None.
    graph = make()
    rng = np.random.default_rng(7)
    xs = np.concatenate([lane.xs for lane in graph.lanes.values()])
    ys = np.concatenate([lane.ys for lane in graph.lanes.values()])
    picked = rng.integers(0, len(xs), 4000)
    points = np.column_stack((xs[picked], ys[picked])) + rng.normal(0.0, 4.0, (4000, 2))
    located = 0
    for index, (x, y) in enumerate(points.tolist()):
        yaw = None if index % 3 == 0 else float(rng.uniform(-4.0, 4.0))
        found = graph.locate(x, y, yaw)
        assert found == whole_map_locate(graph, x, y, yaw), (x, y, yaw)
        located += found is not None
    assert 2000 < located < 4000          # on lanes and off them
    # cell edges: points exactly on the lines of the grid, across the map
    for x in np.arange(-32.0, 160.0, LOCATE_CELL_M):
        for y in np.arange(-48.0, 160.0, LOCATE_CELL_M / 2):
            assert graph.locate(x, y) == whole_map_locate(graph, x, y)
    assert graph.locate(1e6, 1e6) is None and graph.locate(math.nan, 0.0) is None
    assert graph.locate(-math.inf, 3.0) is None and graph.locate(0.0, math.inf, 0.5) is None


def test_centre_pose_is_pose_at_on_the_centreline_bit_for_bit():
    graph = straight_then_left()
    for lane in graph.lanes.values():
        for k in range(101):
            s_m = lane.length_m * k / 100.0
            assert lane.centre_pose(s_m) == graph.pose_at(lane.id, s_m), (lane.id, s_m)


@pytest.mark.parametrize('lane_id, s_m, offset_m, match', [
    (999, 1.0, 0.0, 'lane 999 is not in the map'),
    (100001, 100.5, 0.0, r's = 100.5 m is not on it \(0 .. 100.000 m\)'),
    (100001, -1.0, 0.0, 's = -1.0 m'),
    (100001, 10.0, 1.8, r'offset = 1.8 m is off the lane \(\|offset\| <= 1.750 m'),
    (100001, float('nan'), 0.0, 's = nan'),
])
def test_pose_at_refuses_what_is_not_on_the_lane(lane_id, s_m, offset_m, match):
    graph = straight_then_left()
    with pytest.raises(InvalidParameterError, match=match):
        graph.pose_at(lane_id, s_m, offset_m)


def test_a_closed_road_joins_its_last_lane_to_its_first():
    square = [{'type': 'straight', 'length': 40.0}, {'type': 'arc', 'radius': 10.0,
                                                     'angle': 90.0}] * 4
    graph = graph_of({'lanes': 1, 'closed': True, 'segments': square})
    assert graph.lanes[100701].successors == (100001,)
    assert graph.lanes[100051].successors == (100751,)


def test_a_closed_road_whose_end_misses_its_start_is_refused():
    with pytest.raises(InvalidParameterError, match="road 'ring' is closed but its end .* "
                                                    'misses its start by 10.000 m'):
        graph_of({'name': 'ring', 'closed': True, 'segments': [
            {'type': 'straight', 'length': 10.0}]})


@pytest.mark.parametrize('roads, match', [
    ([], 'must be a non-empty list of roads'),
    ([{'lanes': 1}], r"w.yaml: roads\[0\]: field 'segments' is required"),
    ([{'segments': [{'type': 'loop'}]}],
     r"roads\[0\].segments\[0\]: field 'type' = 'loop': unknown segment type; valid: "
     'straight, arc, intersection'),
    ([{'segments': [{'type': 'straight', 'length': -1.0}]}],
     r"segments\[0\]: field 'length' = -1.0: must be > 0"),
    ([{'segments': [{'type': 'arc', 'radius': 5.0, 'angle': 0.0}]}],
     "field 'angle' = 0.0: must not be 0"),
    ([{'lanes': 3, 'segments': [{'type': 'arc', 'radius': 10.0, 'angle': 90.0}]}],
     r"field 'radius' = 10: must be > 10.5 m"),
    ([{'lanes': 9, 'segments': [{'type': 'straight', 'length': 1.0}]}],
     "field 'lanes' = 9: must be in 1 .. 8"),
    ([{'edge_line': 'zigzag', 'segments': [{'type': 'straight', 'length': 1.0}]}],
     "field 'edge_line' = 'zigzag': must be one of solid, dashed"),
    ([{'name': 'a', 'segments': [{'type': 'straight', 'length': 1.0}]},
      {'name': 'a', 'segments': [{'type': 'straight', 'length': 1.0}]}],
     "two roads are named 'a'"),
    ([{'segments': [{'type': 'straight', 'length': 1.0, 'radius': 3.0}]}],
     "unknown field 'radius'"),
])
def test_bad_roads_are_refused_naming_the_field(roads, match):
    with pytest.raises(InvalidParameterError, match=match):
        roads_from_list(roads, SOURCE)


def test_lane_graph_refuses_inconsistent_lanes():
    edge = Boundary(1, [[0.0, 0.0], [10.0, 0.0]], 'solid')
    other = Boundary(2, [[0.0, 3.0], [10.0, 3.0]], 'solid')
    lane = Lane(5, [[0.0, 1.5], [10.0, 1.5]], other, edge, 10.0, successors=(6,))
    with pytest.raises(InvalidParameterError, match='m.osm: lane 5: successor 6 is not in'):
        LaneGraph([lane], 'm.osm')
    with pytest.raises(InvalidParameterError, match='lane id 5 is used twice'):
        LaneGraph([Lane(5, [[0.0, 1.5], [10.0, 1.5]], other, edge, 10.0)] * 2, 'm.osm')
    with pytest.raises(InvalidParameterError, match='has no lanes'):
        LaneGraph([], 'm.osm')
    with pytest.raises(InvalidParameterError, match="line type 'zigzag'"):
        Boundary(3, [[0.0, 0.0], [1.0, 0.0]], 'zigzag')
    with pytest.raises(InvalidParameterError, match='speed limit'):
        Lane(7, [[0.0, 1.5], [10.0, 1.5]], other, edge, 0.0)


def test_width_between_boundaries_is_measured_when_not_given():
    # a lane widening from 3 m to 4 m: left boundary y = 3 .. 4, right y = 0. At the first
    # centreline point (0, 1.5) the nearest left point is the boundary's start (3.0 m wide); at
    # the last, (10, 2), the perpendicular to the left line: 2 + 20 / sqrt(101) = 3.9901 m.
    lane = Lane(1, [[0.0, 1.5], [10.0, 2.0]], Boundary(2, [[0.0, 3.0], [10.0, 4.0]], 'solid'),
                Boundary(3, [[0.0, 0.0], [10.0, 0.0]], 'solid'), 10.0)
    found = LaneGraph([lane]).locate(5.0, 1.75, 0.0)
    assert found.width_m == pytest.approx(0.5 * (3.0 + 2.0 + 20.0 / math.sqrt(101.0)), abs=1e-3)


def test_tracker_follows_a_vehicle_through_successors_and_a_lane_change():
    graph = straight_then_left()
    tracker = LaneTracker(graph)
    seen = []
    for step in range(0, 1000):           # along forward lane 0, drifting right from x = 40
        s = step * 0.2
        if s <= 100.0:
            x, y, yaw = s, -1.75 - max(0.0, min(s - 40.0, 35.0)) * 0.1, 0.0
        else:
            x, y, yaw = graph.pose_at(100102, min(s - 100.0, graph.lanes[100102].length_m))
        state = tracker.update(x, y, yaw)
        if not seen or seen[-1] != state.lane_id:
            seen.append(state.lane_id)
    assert seen == [100001, 100002, 100102]
    assert tracker.update(500.0, 500.0, 0.0) == OFF_LANE and tracker.state == OFF_LANE


def test_tracker_keeps_a_vehicle_in_the_wedge_where_two_lanes_join_at_a_kink():
    # lane 1 east to (10, 0), lane 2 on from there turning 10 degrees left (as a SUMO
    # network's junction lane meets the lane it leads to): on the kink's outside (right), a
    # point beyond lane 1's end lies before lane 2's start
    turn = math.radians(10.0)
    end = (10.0 + 20.0 * math.cos(turn), 20.0 * math.sin(turn))

    def lane(lane_id, points, successors=()):
        points = np.array(points)
        d = (points[1] - points[0]) / np.hypot(*(points[1] - points[0]))
        n = np.array((-d[1], d[0])) * 1.75
        return Lane(lane_id, points, Boundary(10 * lane_id, points + n, 'virtual'),
                    Boundary(10 * lane_id + 1, points - n, 'virtual'), 10.0, successors,
                    widths=3.5)
    graph = LaneGraph([lane(1, [(0.0, 0.0), (10.0, 0.0)], (2,)),
                       lane(2, [(10.0, 0.0), end])])
    tracker = LaneTracker(graph)
    assert tracker.update(9.9, -1.5, 0.0).lane_id == 1
    wedge = (10.1, -1.5)
    assert graph.locate(*wedge, 0.05) is None                   # on neither lane's area
    state = tracker.update(*wedge, 0.05)
    assert (state.on_lane, state.lane_id, state.s_m) == (True, 2, 0.0)
    assert tracker.update(10.3, -3.0, 0.05) == OFF_LANE         # beside the lanes: off


def test_tracker_agrees_with_locate_everywhere_on_the_road():
    graph = straight_then_left()
    tracker = LaneTracker(graph)
    for step in range(180):     # (exactly at a joint both lanes hold the point: not tested)
        x, y, yaw = graph.pose_at(100001 if step < 100 else 100101, 0.5 + step % 100 * 0.99,
                                  0.5 * math.sin(step / 7.0))
        state = tracker.update(x, y, yaw)
        found = graph.locate(x, y, yaw)
        assert (state.lane_id, state.s_m, state.offset_m) == \
            (found.lane_id, pytest.approx(found.s_m), pytest.approx(found.offset_m))


def test_crossing_a_dashed_line_gives_exactly_one_invasion_naming_it():
    graph = graph_of({'lanes': 2, 'segments': [{'type': 'straight', 'length': 100.0}]})
    detector = LaneInvasionDetector(graph)
    events = []
    for step in range(101):           # diagonal from lane 0's centre to y = -4.75 (lane 1)
        x = 10.0 + step * 0.4
        events += detector.update(x, -1.75 - step * 0.03, step * 0.01)
    assert [(e.boundary_id, e.line_type) for e in events] == [(100029, 'dashed')]
    event = events[0]
    assert event.y_m == pytest.approx(-3.5) and event.x_m == pytest.approx(10.0 + 1.75 / 0.03 *
                                                                         0.4)


def test_a_point_landing_on_the_line_and_going_on_counts_once():
    graph = graph_of({'lanes': 2, 'segments': [{'type': 'straight', 'length': 100.0}]})
    detector = LaneInvasionDetector(graph)
    path = [(5.0, -3.0), (5.0, -3.5), (5.0, -3.5), (5.0, -4.0), (5.0, -3.5), (5.0, -3.0)]
    counts = [len(detector.update(x, y, 0.0)) for x, y in path]
    assert counts == [0, 1, 0, 0, 1, 0]      # onto the line, then back onto it from the other side


def test_crossing_at_a_joint_of_two_segments_counts_once_and_virtual_lines_never():
    graph = graph_of({'lanes': 1, 'segments': [{'type': 'straight', 'length': 50.0},
                                               {'type': 'straight', 'length': 50.0},
                                               {'type': 'intersection', 'length': 20.0}]})
    detector = LaneInvasionDetector(graph)
    detector.update(50.0, -1.0, 0.0)
    crossed = detector.update(50.0, -8.0, 0.1)       # through the edge line exactly at x = 50
    assert [e.line_type for e in crossed] == ['solid']
    detector.reset()
    detector.update(110.0, -1.0, 0.2)
    assert detector.update(110.0, -8.0, 0.3) == ()   # the intersection's lines are virtual


def test_lanes_doc_contains_the_generated_key_tables():
    from pathlib import Path

    from vehicle_sim.core.map.lanelet2_params import LANELET2_SPECS
    from vehicle_sim.core.map.road_segments import roads_markdown
    from vehicle_sim.core.specs.param_spec import parameter_table_markdown
    text = (Path(__file__).resolve().parent.parent / 'docs' / 'lanes.md').read_text('utf-8')
    assert roads_markdown() in text
    assert parameter_table_markdown(LANELET2_SPECS, 'key') in text


def test_a_vehicle_placed_by_lane_gets_the_pose_on_it():
    from vehicle_sim.core.map.lane_placement import is_lane_pose, pose_on_lane
    graph = straight_then_left()
    assert is_lane_pose({'lanelet': 100001}) and not is_lane_pose({'x': 1.0})
    x, y, yaw = pose_on_lane({'lanelet': 100001, 's': 10.0, 'offset': 0.5}, graph, 'w: pose')
    assert (x, y, yaw) == (pytest.approx(10.0), pytest.approx(-1.25), pytest.approx(0.0))


@pytest.mark.parametrize('data, match', [
    ({'lanelet': 5}, 'w.yaml: vehicles.0..pose: lane 5 is not in the map'),
    ({'lanelet': 100001, 's': 100.5}, r'lane 100001: s = 100.5 m is not on it \(0 .. 100.000'),
    ({'lanelet': 100001, 'offset': -2.0}, 'offset = -2.0 m is off the lane'),
    ({'lanelet': 100001, 's': -1.0}, "field 's' = -1.0: must be >= 0"),
    ({'lanelet': 100001, 'yaw': 1.0}, "unknown field 'yaw'"),
])
def test_placing_off_every_lane_is_refused_naming_the_field(data, match):
    from vehicle_sim.core.map.lane_placement import pose_on_lane
    with pytest.raises(InvalidParameterError, match=match):
        pose_on_lane(data, straight_then_left(), 'w.yaml: vehicles[0].pose')


def test_placing_by_lane_in_a_world_without_lanes_is_refused():
    from vehicle_sim.core.map.lane_placement import pose_on_lane
    with pytest.raises(InvalidParameterError, match='placed on lanelet 7, but the world has no '
                                                    'lane map'):
        pose_on_lane({'lanelet': 7}, None, 'w.yaml: vehicles[0].pose')


def test_invasions_found_through_the_grid_equal_a_test_of_every_boundary_segment():
    import random
    graph = straight_then_left(lanes=3)
    segments = [(b.id, b.line_type, a, c) for b in graph.boundaries()
                for a, c in zip(b.points[:-1].tolist(), b.points[1:].tolist())]

    def brute(p, q):
        crossed = set()
        rx, ry = q[0] - p[0], q[1] - p[1]
        for boundary_id, line_type, a, c in segments:
            sx, sy = c[0] - a[0], c[1] - a[1]
            denom = rx * sy - ry * sx
            if denom == 0.0 or line_type in ('virtual', 'none'):
                continue
            qx, qy = a[0] - p[0], a[1] - p[1]
            t, u = (qx * sy - qy * sx) / denom, (qx * ry - qy * rx) / denom
            if 0.0 < t <= 1.0 and 0.0 <= u < 1.0:
                crossed.add(boundary_id)
        return crossed

    rng = random.Random(7)
    detector = LaneInvasionDetector(graph, cell_m=5.0)
    point, total = (50.0, -3.0), 0
    detector.update(*point, 0.0)
    for step in range(3000):      # a random walk over the road and its bend, steps up to 4 m
        nxt = (min(max(point[0] + rng.uniform(-4.0, 4.0), -5.0), 160.0),
               min(max(point[1] + rng.uniform(-4.0, 4.0), -15.0), 80.0))
        found = {e.boundary_id for e in detector.update(*nxt, step * 0.1)}
        assert found == brute(point, nxt)
        total += len(found)
        point = nxt
    assert total > 100


def tapered_lane():
    # a merge taper: 3.5 m wide at x = 0, its bounds meet at x = 30 (zero width there)
    left = Boundary(11, [[0.0, 3.5], [30.0, 0.0]], 'dashed')
    right = Boundary(12, [[0.0, 0.0], [30.0, 0.0]], 'solid')
    return Lane(9, [[0.0, 1.75], [15.0, 0.875], [30.0, 0.0]], left, right, 10.0)


def test_a_tapered_lane_loads_and_its_zero_width_end_is_located_without_division_by_zero():
    lane = tapered_lane()
    assert lane.widths[0] == pytest.approx(3.5, abs=0.02) and lane.widths[-1] == 0.0
    graph = LaneGraph([lane])
    end = graph.locate(30.0, 0.0, 0.0)           # on the point where the bounds meet
    assert (end.lane_id, end.width_m) == (9, 0.0)
    assert end.s_m == pytest.approx(lane.length_m)
    assert graph.locate(30.0, 0.01, 0.0) is None  # beside it: off the lane
    assert graph.pose_at(9, lane.length_m, 0.0)[:2] == (pytest.approx(30.0), pytest.approx(0.0))
    with pytest.raises(InvalidParameterError, match=r'\|offset\| <= 0.000 m there'):
        graph.pose_at(9, lane.length_m, 0.1)
    tracker = LaneTracker(graph)
    states = [tracker.update(x, 1.75 * (1.0 - x / 30.0), lane.headings[0])
              for x in (0.0, 10.0, 20.0, 30.0)]
    assert [s.lane_id for s in states] == [9, 9, 9, 9]
    assert states[-1].width_m == 0.0 and math.isfinite(states[-1].offset_m)


def test_a_lane_of_zero_width_everywhere_is_refused_and_its_subtype_is_kept():
    edge = Boundary(1, [[0.0, 0.0], [10.0, 0.0]], 'solid')
    with pytest.raises(InvalidParameterError, match='lane 5: its width must be > 0 somewhere'):
        Lane(5, [[0.0, 0.0], [10.0, 0.0]], edge, edge, 10.0)
    with pytest.raises(InvalidParameterError, match=r'lane 6: its width must be >= 0 '):
        Lane(6, [[0.0, 0.0], [10.0, 0.0]], edge, edge, 10.0, widths=[3.0, -1.0])
    other = Boundary(2, [[0.0, 3.0], [10.0, 3.0]], 'solid')
    assert Lane(7, [[0.0, 1.5], [10.0, 1.5]], other, edge, 10.0).subtype == 'road'
    shoulder = Lane(8, [[0.0, 1.5], [10.0, 1.5]], other, edge, 10.0, subtype='road_shoulder')
    assert shoulder.subtype == 'road_shoulder'
