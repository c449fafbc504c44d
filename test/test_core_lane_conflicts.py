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


"""The conflicts of a lane graph from its lanes' geometry (core/map/lane_conflicts.py)."""

import math

import pytest

from vehicle_sim.core.map.lane_conflicts import lane_conflicts
from vehicle_sim.core.map.lane_graph import Boundary, Lane, LaneGraph
from vehicle_sim.core.map.road_segments import lane_graph_from_roads, roads_from_list


def lane(lane_id, points, width=3.5, successors=(), left_lane=None, right_lane=None):
    """Return a lane along ``points`` (its boundaries: virtual lines at half the width)."""
    (x0, y0), (x1, y1) = points[0], points[-1]
    heading = math.atan2(y1 - y0, x1 - x0)
    nx, ny = -math.sin(heading) * width / 2, math.cos(heading) * width / 2
    left = Boundary(10 * lane_id, [(x + nx, y + ny) for x, y in points], 'virtual')
    right = Boundary(10 * lane_id + 1, [(x - nx, y - ny) for x, y in points], 'virtual')
    return Lane(lane_id, points, left, right, 10.0, successors, left_lane, right_lane,
                widths=width)


def test_lanes_crossing_at_a_right_angle_conflict_over_the_other_lanes_width():
    # lane 1 east along y = 0 (3.5 m), lane 2 north along x = 12 (3.0 m), from y = -8
    graph = LaneGraph([lane(1, [(0, 0), (30, 0)]), lane(2, [(12, -8), (12, 20)], width=3.0)])
    (conflict,) = lane_conflicts(graph)
    assert (conflict.lane_id, conflict.other_id, conflict.kind) == (1, 2, 'crossing')
    # on lane 1: lane 2's width (3.0 m) centred on x = 12; on lane 2: 3.5 m centred on s = 8
    assert conflict.s_m == pytest.approx((10.5, 13.5), abs=1e-9)
    assert conflict.other_s_m == pytest.approx((6.25, 9.75), abs=1e-9)
    graph.set_rules(type(graph.rules)(conflicts=(conflict,)))
    assert graph.rules.conflicts_of(2)[0].s_m == pytest.approx((6.25, 9.75))


def test_a_crossing_at_45_degrees_spans_the_widths_over_the_sine():
    # lane 2 crosses lane 1 (y = 0) at (20, 0) heading 45 deg
    graph = LaneGraph([lane(1, [(0, 0), (40, 0)]),
                       lane(2, [(10, -10), (30, 10)], width=3.0)])
    (conflict,) = lane_conflicts(graph)
    # lane 1's cross-section (3.5 m) meets lane 2's strip (3.0 m wide, at 45 deg) over
    # x = 20 +- (1.5 / sin 45 + 1.75 / tan 45)
    half = 1.5 * math.sqrt(2.0) + 1.75
    assert conflict.s_m == pytest.approx((20 - half, 20 + half), abs=1e-9)
    along = 10 * math.sqrt(2.0)                 # lane 2's arc length at the crossing point
    half = 1.75 * math.sqrt(2.0) + 1.5
    assert conflict.other_s_m == pytest.approx((along - half, along + half), abs=1e-9)


def test_neighbours_chained_lanes_and_forks_do_not_conflict_merges_do():
    graph = LaneGraph([
        lane(1, [(0, 0), (20, 0)], successors=(2, 5), left_lane=3),
        lane(2, [(20, 0), (40, 0)], successors=(6,)),
        lane(3, [(0, 3.5), (20, 3.5)], right_lane=1),         # same direction, shares a line
        lane(4, [(20, -3.5), (0, -3.5)]),                     # the other direction
        lane(5, [(20, 0), (30, -1.0), (40, -6)]),             # leaves 1 beside 2: a fork
        lane(6, [(40, 0), (60, 0)]),
        lane(7, [(30, -20), (30, 20)]),                       # crosses 2 and 5
    ])
    pairs = {(c.lane_id, c.other_id): c.kind for c in lane_conflicts(graph)}
    assert pairs == {(2, 7): 'crossing', (5, 7): 'crossing'}
    merged = LaneGraph([
        lane(1, [(0, -10), (18, -1.0), (20, 0)], successors=(3,)),
        lane(2, [(0, 0), (20, 0)], successors=(3,)),
        lane(3, [(20, 0), (40, 0)]),
    ])
    (conflict,) = lane_conflicts(merged)
    assert (conflict.lane_id, conflict.other_id, conflict.kind) == (1, 2, 'merging')
    assert conflict.other_s_m[1] == pytest.approx(20.0)      # up to where they join


def test_every_intersection_of_a_roads_map_has_its_crossings_and_nothing_else_conflicts():
    roads = roads_from_list([
        {'name': 'ew', 'start': {'x': -50, 'y': 0, 'yaw': 0}, 'segments': [
            {'type': 'straight', 'length': 44}, {'type': 'intersection', 'length': 12},
            {'type': 'straight', 'length': 44}]},
        {'name': 'ns', 'start': {'x': 0, 'y': -50, 'yaw': math.pi / 2}, 'segments': [
            {'type': 'straight', 'length': 44}, {'type': 'intersection', 'length': 12},
            {'type': 'straight', 'length': 44}]}], 'roads')
    graph = lane_graph_from_roads(roads, 'roads')
    conflicts = lane_conflicts(graph)
    through = {100101, 100151, 200101, 200151}          # the intersection segments' lanes
    for conflict in conflicts:
        assert {conflict.lane_id, conflict.other_id} <= through | {
            i for i in graph.lanes if i >= 1_000_000_000}
    crossings = {(c.lane_id, c.other_id): c for c in conflicts}
    # east through the middle (100101, y = -1.75) meets north (200101, x = +1.75) at
    # x = 1.75, 7.75 m along the 12 m segment: +- 1.75 m
    assert crossings[(100101, 200101)].s_m == pytest.approx((6.0, 9.5), abs=1e-6)
    assert crossings[(100101, 200101)].other_s_m == pytest.approx((2.5, 6.0), abs=1e-6)
    assert crossings[(100101, 200101)].kind == 'crossing'
    assert 'merging' in {c.kind for c in conflicts}     # a turn joins the lane it leaves onto
