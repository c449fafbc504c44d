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
The shipped road worlds (config/worlds/highway.yaml, city_block.yaml) load into lane graphs.

Road lane ids: road r (1-based), segment j, forward lane i: r * 100000 + j * 100 + 1 + i
(core/map/road_segments.py).
"""

import math

import numpy as np
import pytest

from vehicle_sim.config import load_world
from vehicle_sim.core.map.lane_invasion import LaneInvasionDetector
from vehicle_sim.core.map.lane_state import LaneTracker
from vehicle_sim.core.map.road_intersections import CONNECTOR_ID
from vehicle_sim.core.map.road_segments import lane_graph_from_roads


def _graph(name):
    world = load_world(name)
    return world, lane_graph_from_roads(world.roads, world.source)


def _chain(graph, first):
    """Return the lanes from ``first`` along the (single) successors to the end or back."""
    chain = [first]
    while graph.lanes[chain[-1]].successors and graph.lanes[chain[-1]].successors[0] != first:
        chain.append(graph.lanes[chain[-1]].successors[0])
    return chain


def test_highway_is_a_three_lane_carriageway_over_two_km_with_gentle_bends():
    world, graph = _graph('highway')
    (road,) = world.roads
    assert (road.lanes, road.backward_lanes) == (3, 3)
    assert min(s.radius_m for s in road.segments if s.type == 'arc') >= 1000.0
    for lane in range(3):
        chain = _chain(graph, 100001 + lane)
        assert len(chain) == 5
        assert sum(graph.lanes[i].length_m for i in chain) >= 2000.0
    assert graph.lanes[100001].right_change and not graph.lanes[100001].left_lane
    car = world.vehicles[0]
    found = graph.locate(car.x_m, car.y_m, car.yaw_rad)
    assert found.lane_id == 100002 and found.offset_m == pytest.approx(0.0, abs=1e-9)
    assert found.speed_limit_mps == pytest.approx(33.3)


def test_city_block_ring_is_closed_and_a_car_driven_round_it_sees_each_lane_once():
    world, graph = _graph('city_block')
    ring = _chain(graph, 100001)
    assert len(ring) == 16 and graph.lanes[ring[-1]].successors == (100001,)
    # ring length: 4 x (79 + 12 + 79) m of straights + 4 quarter circles of r = 15 + 1.75 m
    assert sum(graph.lanes[i].length_m for i in ring) == pytest.approx(
        4 * 170.0 + 2 * math.pi * 16.75, abs=0.05)
    tracker = LaneTracker(graph)
    seen = []
    for lane_id in ring + [100001]:
        lane = graph.lanes[lane_id]
        for step in range(1, 10):
            state = tracker.update(*graph.pose_at(lane_id, lane.length_m * step / 10.0))
            if not seen or seen[-1] != state.lane_id:
                seen.append(state.lane_id)
    assert seen == ring + [100001]      # through the four intersections, the cross streets'
    car = world.vehicles[0]             # lanes overlapping there
    assert graph.locate(car.x_m, car.y_m, car.yaw_rad).lane_id == 100001


@pytest.mark.parametrize('x, y, yaw, road', [
    (0.0 + 1.75, -100.0, math.pi / 2, 2),     # north_south crossing the ring's south side
    (0.0 + 1.75, 0.0, math.pi / 2, 2),        # the middle
    (-100.0, 0.0 - 1.75, 0.0, 3),             # east_west crossing the ring's west side
    (100.0, -1.75, 0.0, 3),
    (-1.75, 100.0, -math.pi / 2, 2),          # north_south's other direction, north side
])
def test_city_block_cross_streets_run_through_five_intersections(x, y, yaw, road):
    _, graph = _graph('city_block')
    found = graph.locate(x, y, yaw)
    assert found.lane_id // 100000 == road and found.offset_m == pytest.approx(0.0, abs=1e-9)
    assert abs(found.heading_error_rad) < 1e-9
    # driving straight through: every line crossed inside the intersection is virtual
    detector = LaneInvasionDetector(graph)
    dx, dy = math.cos(yaw), math.sin(yaw)
    events = [e for step in range(-6, 7) for e in
              detector.update(x + dx * step, y + dy * step, step + 6.0)]
    assert events == []


def test_city_block_intersections_have_a_right_and_a_left_turn_from_every_approach():
    _, graph = _graph('city_block')
    turns = [lane for lane in graph.lanes.values() if lane.id >= CONNECTOR_ID]
    assert len(turns) == 5 * 4 * 2        # 5 crossings x 4 approaches x (right, left)
    assert all(lane.left.line_type == lane.right.line_type == 'virtual' for lane in turns)
    # right from east_west eastbound (road 3, segment 2, lane 0: ends at (-6, -1.75)) onto
    # north_south southbound (road 2, segment 2, backward lane 0: starts at (-1.75, -6)): a
    # quarter circle of radius 4.25 m about (-6, -6), as a Bezier within 0.03 % of it
    (right,) = [graph.lanes[i] for i in graph.lanes[300201].successors if i >= CONNECTOR_ID
                and graph.lanes[i].successors == (200251,)]
    radii = np.hypot(right.centerline[:, 0] + 6.0, right.centerline[:, 1] + 6.0)
    assert radii == pytest.approx(np.full(len(radii), 4.25), abs=0.002)
    assert right.length_m == pytest.approx(math.pi / 2 * 4.25, abs=0.01)
    assert right.speed_limit_mps == pytest.approx(8.3)


def test_a_car_turning_right_is_on_the_turn_lane_then_on_the_street_it_turned_into():
    _, graph = _graph('city_block')
    (right,) = [i for i in graph.lanes[300201].successors if i >= CONNECTOR_ID
                and graph.lanes[i].successors == (200251,)]
    tracker = LaneTracker(graph)
    seen = []
    for lane_id, start in ((300201, 80.0), (right, 0.0), (200251, 0.0)):
        lane = graph.lanes[lane_id]
        for step in range(20):
            s_m = start + (min(lane.length_m, start + 20.0) - start) * step / 20.0
            state = tracker.update(*graph.pose_at(lane_id, s_m))
            if not seen or seen[-1] != state.lane_id:
                seen.append(state.lane_id)
    assert seen == [300201, right, 200251]
