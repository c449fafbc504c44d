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
The lane state's next stop line ahead and its signal (core/map/lane_state.py).

On test/signal_helpers.py's road: lane 100001 (x 0 -> 60) has traffic light line 9001 at s 50
(group 7001), lane 100101 (x 60 -> 120) the stop sign line 9003 at s 30 (x = 90).
"""

import pytest
from signal_helpers import EAST, EAST_NEXT, PHASES, PLAN, road_rules, ROADS, WEST, WEST_NEXT

from vehicle_sim.core.map.lane_rules import LaneRules
from vehicle_sim.core.map.lane_state import LaneTracker, OFF_LANE, STOP_LINE_HORIZON_M
from vehicle_sim.core.map.road_segments import lane_graph_from_roads, roads_from_list
from vehicle_sim.core.map.signal_plan import SignalController
from vehicle_sim.core.map.vehicle_lanes import VehicleLanes


def road(rules=True):
    graph = lane_graph_from_roads(roads_from_list(ROADS, 'roads'), 'roads')
    if rules:
        graph.set_rules(road_rules())
    return graph


def ahead(state):
    return (state.stop_line_ahead, state.stop_line_id, state.stop_line_kind,
            state.stop_line_distance_m, state.traffic_light_group_id, state.signal_state)


def test_the_next_traffic_light_line_its_group_and_state_at_a_known_distance():
    graph = road()
    signals = SignalController(graph, PLAN, PHASES)
    tracker = LaneTracker(graph, signals)
    state = tracker.update(20.0, -1.75, 0.0)                  # lane 100001 at s 20
    assert (state.lane_id, state.s_m) == (EAST, pytest.approx(20.0))
    assert ahead(state) == (True, 9001, 'traffic_light', pytest.approx(30.0), 7001, 'green')
    signals.update(0.6)                                        # 7001 yellow from 0.55 s
    assert ahead(tracker.update(35.5, -1.75, 0.0)) == (
        True, 9001, 'traffic_light', pytest.approx(14.5), 7001, 'yellow')
    signals.force(7001, 'off')
    assert tracker.update(50.0, -1.75, 0.0).signal_state == 'off'   # on the line: 0 m
    assert tracker.state.stop_line_distance_m == pytest.approx(0.0, abs=1e-9)


def test_past_the_line_the_next_is_found_on_the_following_lane():
    graph = road()
    tracker = LaneTracker(graph)                              # no controller: no state
    state = tracker.update(50.5, -1.75, 0.0)                  # 0.5 m past 9001
    # to the end of 100001 (9.5 m) then 30 m on 100101 to the stop sign's line
    assert ahead(state) == (True, 9003, 'stop_sign', pytest.approx(39.5), 0, '')
    assert ahead(tracker.update(80.0, -1.75, 0.0)) == (
        True, 9003, 'stop_sign', pytest.approx(10.0), 0, '')
    assert ahead(tracker.update(95.0, -1.75, 0.0)) == (False, 0, '', 0.0, 0, '')   # none left
    # the other way: lane 100151 (x 120 -> 60) has 9002 at s 50 (x = 70); group 7002
    state = tracker.update(100.0, 1.75, 3.14159)
    assert (state.lane_id, ahead(state)) == (
        WEST, (True, 9002, 'traffic_light', pytest.approx(30.0), 7002, ''))
    assert tracker.update(30.0, 1.75, 3.14159).lane_id == WEST_NEXT
    assert not tracker.state.stop_line_ahead


def test_a_line_beyond_the_horizon_is_not_ahead():
    graph = road()
    near = LaneTracker(graph, horizon_m=35.0)
    assert near.update(20.0, -1.75, 0.0).stop_line_id == 9001          # 30 m
    assert not near.update(10.0, -1.75, 0.0).stop_line_ahead          # 40 m
    assert not near.update(52.0, -1.75, 0.0).stop_line_ahead          # 9003 is 38 m ahead
    assert near.update(56.0, -1.75, 0.0).stop_line_id == 9003          # 34 m
    assert STOP_LINE_HORIZON_M == 200.0


def test_the_tracker_agrees_with_lane_rules_next_stop_line_everywhere():
    graph = road()
    tracker = LaneTracker(graph, horizon_m=45.0)
    for lane_id in (EAST, EAST_NEXT, WEST, WEST_NEXT):
        for k in range(121):
            s = k * 0.5
            x, y, yaw = graph.pose_at(lane_id, s)
            state = tracker.update(x, y, yaw)
            if state.lane_id != lane_id:        # at a joint both lanes hold the point
                continue
            found = graph.rules.next_stop_line(graph, lane_id, state.s_m, 45.0)
            expected = (False, 0, 0.0) if found is None else (True, found[0].id, found[1])
            assert (state.stop_line_ahead, state.stop_line_id,
                    state.stop_line_distance_m) == (expected[0], expected[1],
                                                    pytest.approx(expected[2], abs=1e-9))


def test_a_map_without_rules_and_off_lane_have_no_stop_line():
    graph = road(rules=False)
    assert ahead(LaneTracker(graph).update(20.0, -1.75, 0.0)) == (False, 0, '', 0.0, 0, '')
    graph.set_rules(road_rules())                  # rules attached later: seen at once
    lanes = VehicleLanes(graph)
    assert lanes.update(20.0, -1.75, 0.0, 0.0)[0].stop_line_id == 9001
    graph.set_rules(LaneRules())
    assert not lanes.update(21.0, -1.75, 0.0, 0.01)[0].stop_line_ahead
    assert lanes.update(20.0, 40.0, 0.0, 0.02)[0] == OFF_LANE
