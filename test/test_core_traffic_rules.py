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


"""The traffic obeys signals, stop signs, right of way and conflicts (core/traffic/rules.py)."""

import math
import random

from lane_helpers import straight
import pytest

from vehicle_sim.config import load_world
from vehicle_sim.core.map.lane_graph import LaneGraph
from vehicle_sim.core.map.lane_rules import (
    Conflict,
    LaneRules,
    RightOfWay,
    StopLine,
    TrafficLightGroup,
)
from vehicle_sim.core.map.road_segments import lane_graph_from_roads
from vehicle_sim.core.map.signal_plan import FixedTimePlan, SignalController
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.traffic.footprints import footprint_overlaps, overlapping
from vehicle_sim.core.traffic.manager import TrafficManager
from vehicle_sim.core.traffic.params import traffic_from_dict

DT = 0.1
DIMS = {'Car': (4.5, 1.8)}
HALF = 2.25
# lanes 1 -> 2 -> 5 east along y = 0, 3 -> 4 -> 6 north along x = 10; 2 and 4 cross at (10, 0)
EAST_IN, EAST_X, EAST_OUT, NORTH_IN, NORTH_X, NORTH_OUT = 1, 2, 5, 3, 4, 6
EAST_LINE_S, NORTH_LINE_S = 198.0, 188.0     # x = -2 on lane 1, y = -12 on lane 3
ZONE = (8.25, 11.75)                         # the crossing on lanes 2 and 4


def crossing(lines='traffic_light', right_of_way=False):
    """Return the crossing's LaneGraph with its rules: stop lines of ``lines`` kind or none."""
    graph = LaneGraph([straight(1, -200, 0, 0, 0, [2]), straight(2, 0, 0, 20, 0, [5]),
                       straight(5, 20, 0, 200, 0),
                       straight(3, 10, -200, 10, -10, [4]), straight(4, 10, -10, 10, 10, [6]),
                       straight(6, 10, 10, 10, 200)])
    stop_lines, groups = (), ()
    if lines is not None:
        group = (lambda g: g) if lines == 'traffic_light' else (lambda g: None)
        stop_lines = (StopLine(101, EAST_IN, EAST_LINE_S, [(-2, -1.75), (-2, 1.75)], lines,
                               group(11)),
                      StopLine(102, NORTH_IN, NORTH_LINE_S, [(8.25, -12), (11.75, -12)], lines,
                               group(12)))
    if lines == 'traffic_light':
        groups = (TrafficLightGroup(11, (EAST_IN,), (101,)),
                  TrafficLightGroup(12, (NORTH_IN,), (102,)))
    rules = (RightOfWay(1, (EAST_IN, EAST_X), (NORTH_IN, NORTH_X)),) if right_of_way else ()
    graph.set_rules(LaneRules(stop_lines=stop_lines, groups=groups, right_of_way=rules,
                              conflicts=(Conflict(EAST_X, NORTH_X, ZONE, ZONE),)))
    return graph


def manager(graph, placed, signals=None):
    data = {'models': ['Car'], 'placed': [
        {'model': 'Car', 'lanelet': lane, 's': s, 'speed': speed, 'route': route}
        for lane, s, speed, route in placed]}
    return TrafficManager(graph, traffic_from_dict(data, 'w.yaml: traffic'), DIMS,
                          signals=signals)


EAST = (EAST_IN, 100.0, 10.0, [EAST_X, EAST_OUT])
NORTH = (NORTH_IN, 90.0, 10.0, [NORTH_X, NORTH_OUT])


def front_on_approach(v, lane):
    """Return the front's arc length on the approach lane ``lane`` (inf once past it)."""
    return v.s_m + HALF if v.lane == lane else float('inf')


def test_a_vehicle_stops_before_a_red_line_and_goes_at_green():
    graph = crossing()
    signals = SignalController(graph, FixedTimePlan())
    signals.force(11, 'red')
    m = manager(graph, [EAST], signals)
    v = m.vehicles[0]
    for _ in range(int(40.0 / DT)):
        m.step(DT)
        signals.update(m.time_s)
        assert v.lane == EAST_IN and v.s_m + HALF < EAST_LINE_S
    assert v.speed_mps < 0.01
    # the front stands within the model's least gap (2 m) and a half metre before the line
    assert EAST_LINE_S - (v.s_m + HALF) == pytest.approx(m.idm.min_gap_m, abs=0.5)
    signals.force(11, 'green')
    for _ in range(int(10.0 / DT)):
        m.step(DT)
    assert v.lane == EAST_OUT and v.speed_mps > 5.0


def test_a_queue_forms_at_red_and_discharges_at_green():
    graph = crossing()
    signals = SignalController(graph, FixedTimePlan())
    signals.force(11, 'red')
    m = manager(graph, [(EAST_IN, s, 10.0, [EAST_X, EAST_OUT]) for s in (40, 70, 100, 130)],
                signals)
    for _ in range(int(40.0 / DT)):
        m.step(DT)
    fronts = sorted((v.s_m + HALF for v in m.vehicles), reverse=True)
    assert all(v.lane == EAST_IN and v.speed_mps < 0.01 for v in m.vehicles)
    assert fronts[0] < EAST_LINE_S
    # bumper to bumper gaps of about s0 = 2 m: a queue of 4 within 4 x 4.5 + 4 x 2.5 m
    gaps = [a - b - 2 * HALF for a, b in zip(fronts, fronts[1:])]
    assert all(m.idm.min_gap_m - 0.3 < gap < m.idm.min_gap_m + 0.5 for gap in gaps), gaps
    signals.force(11, 'green')
    crossed = {}
    for _ in range(int(20.0 / DT)):
        m.step(DT)
        for v in m.vehicles:
            if v.index not in crossed and front_on_approach(v, EAST_IN) > EAST_LINE_S:
                crossed[v.index] = m.time_s - 40.0
    print('crossed the line after green [s]:', crossed)
    # all four over the line within 12 s of green, the first one first
    assert sorted(crossed, key=crossed.get) == [3, 2, 1, 0]
    assert max(crossed.values()) < 12.0, crossed


def test_a_vehicle_held_at_red_does_not_keep_the_green_crossing_traffic_waiting():
    # the stop lines at the very ends of the approaches, where the crossing's lanes start, and
    # the north lane's side of the zone from its start
    graph = crossing()
    rules = graph.rules
    lines = (StopLine(101, EAST_IN, 200.0, [(0, -1.75), (0, 1.75)], 'traffic_light', 11),
             StopLine(102, NORTH_IN, 190.0, [(8.25, -10), (11.75, -10)], 'traffic_light', 12))
    graph.set_rules(LaneRules(stop_lines=lines, groups=rules.groups,
                              conflicts=(Conflict(EAST_X, NORTH_X, ZONE, (0.0, ZONE[1])),)))
    signals = SignalController(graph, FixedTimePlan())
    signals.force(11, 'green')
    signals.force(12, 'red')
    m = manager(graph, [(NORTH_IN, 150.0, 5.0, [NORTH_X, NORTH_OUT]),
                        (EAST_IN, 20.0, 10.0, [EAST_X, EAST_OUT])], signals)
    north, east = m.vehicles
    for _ in range(int(25.0 / DT)):
        m.step(DT)
        assert m.rules.waiting.get(east.index) is None      # it never waits
    assert east.lane == EAST_OUT and north.lane == NORTH_IN and north.speed_mps < 0.01


def test_on_yellow_a_vehicle_that_can_stop_stops_and_one_too_close_goes_on_through_red():
    graph = crossing()
    signals = SignalController(graph, FixedTimePlan())
    signals.force(11, 'green')
    # at 10 m/s the comfortable stop (b = 2 m/s^2) takes 25 m: 45 m ahead stops, 12 m goes
    far = manager(graph, [(EAST_IN, EAST_LINE_S - HALF - 45.0, 10.0, [EAST_X, EAST_OUT])],
                  signals)
    near = manager(graph, [(EAST_IN, EAST_LINE_S - HALF - 12.0, 10.0, [EAST_X, EAST_OUT])],
                   signals)
    signals.force(11, 'yellow')
    for step in range(int(20.0 / DT)):
        if step == 20:
            signals.force(11, 'red')
        far.step(DT)
        near.step(DT)
        assert front_on_approach(far.vehicles[0], EAST_IN) < EAST_LINE_S
    assert far.vehicles[0].speed_mps < 0.01
    assert near.vehicles[0].lane == EAST_OUT


def zone_holders(m):
    """Return the vehicles whose footprint overlaps the crossing on lanes 2 and 4."""
    inside = set()
    for v in m.vehicles:
        for lane, lo, hi in ((v.lane, v.s_m - HALF, v.s_m + HALF),
                             (v.prev_lane, v.s_m - HALF + 20.0, v.s_m + HALF + 20.0),
                             (v.next_lane, v.s_m - HALF - 20.0, v.s_m + HALF - 20.0)):
            if lane in (EAST_X, NORTH_X) and lo < ZONE[1] and hi > ZONE[0]:
                inside.add((v.index, lane))
    return inside


@pytest.mark.parametrize('lead', [0.0, 0.3, -0.3, 1.0])
def test_two_vehicles_at_an_unsignalled_crossing_are_never_both_inside(lead):
    graph = crossing(lines=None)
    # both reach the zone at the same time (lead = 0) or one a little before the other
    east = (EAST_IN, 100.0 + 10.0 * lead, 10.0, [EAST_X, EAST_OUT])
    m = manager(graph, [east, NORTH])
    both_seen, reached = set(), set()
    for _ in range(int(25.0 / DT)):
        m.step(DT)
        inside = zone_holders(m)
        assert len({lane for _, lane in inside}) < 2, (m.time_s, inside)
        both_seen |= {lane for _, lane in inside}
        reached |= {(v.index, v.lane) for v in m.vehicles}
    assert both_seen == {EAST_X, NORTH_X}
    assert {(0, EAST_OUT), (1, NORTH_OUT)} <= reached


def test_a_yielding_vehicle_lets_the_priority_one_go_first():
    graph = crossing(lines=None, right_of_way=True)
    # the yielding (north) vehicle would arrive a little first
    m = manager(graph, [EAST, (NORTH_IN, 92.0, 10.0, [NORTH_X, NORTH_OUT])])
    entered = {}
    for _ in range(int(40.0 / DT)):
        m.step(DT)
        for index, lane in zone_holders(m):
            entered.setdefault(index, m.time_s)
        assert len({lane for _, lane in zone_holders(m)}) < 2
    assert entered[0] < entered[1]
    reference = manager(crossing(lines=None), [EAST, (NORTH_IN, 92.0, 10.0,
                                                      [NORTH_X, NORTH_OUT])])
    first = {}
    for _ in range(int(40.0 / DT)):
        reference.step(DT)
        for index, _ in zone_holders(reference):
            first.setdefault(index, reference.time_s)
    assert first[1] < first[0]          # without the rule, first come goes first


def test_a_stop_sign_makes_a_vehicle_stand_still_at_the_line_then_go():
    graph = crossing(lines='stop_sign')
    m = manager(graph, [EAST])
    v = m.vehicles[0]
    stood, passed_at = 0.0, None
    for _ in range(int(40.0 / DT)):
        m.step(DT)
        if v.lane == EAST_IN and v.speed_mps < 0.1:
            assert EAST_LINE_S - (v.s_m + HALF) < m.idm.min_gap_m + 1.5
            stood += DT
        if passed_at is None and front_on_approach(v, EAST_IN) > EAST_LINE_S:
            passed_at = m.time_s
            assert stood >= 1.0 - 1e-9
    assert passed_at is not None and v.lane == EAST_OUT


def test_footprints_overlap_where_the_cars_would_touch_and_not_on_parallel_lanes():
    graph = crossing(lines=None)
    found = footprint_overlaps(graph, {EAST_X: (0.0, 20.0), NORTH_X: (0.0, 20.0),
                                       EAST_OUT: (0.0, 20.0)}, 4.5, 1.8,
                               skip=[(EAST_X, EAST_OUT)])
    # a car on lane 2 centred at s touches one at the crossing on lane 4 while
    # |s - 10| < 2.25 + 0.9 + 2 x 0.15 (margins) = 3.45 m; the range is widened by a step
    assert list(found) == [(EAST_X, NORTH_X)]
    (lo, hi), (lo_n, hi_n) = found[(EAST_X, NORTH_X)]
    assert (lo, hi) == pytest.approx((10.0 - 3.45 - 0.5, 10.0 + 3.45 + 0.5), abs=0.5)
    assert (lo_n, hi_n) == pytest.approx((lo, hi))
    parallel = LaneGraph([straight(1, 0, 0, 50, 0), straight(2, 0, 3.5, 50, 3.5)])
    assert footprint_overlaps(parallel, {1: (0.0, 50.0), 2: (0.0, 50.0)}, 4.5, 1.8) == {}


def test_overlapping_names_the_pairs_of_rectangles_that_overlap():
    boxes = [(0.0, 0.0, 0.0, 4.5, 1.8), (4.4, 0.0, 0.0, 4.5, 1.8),      # 0.1 m into each other
             (20.0, 0.0, 0.0, 4.5, 1.8), (20.0, 2.0, 0.0, 4.5, 1.8),    # 0.2 m apart side by side
             (40.0, 0.0, 0.0, 4.5, 1.8), (40.0, 3.5, 1.5708, 4.5, 1.8)]  # a T: 0.35 m apart
    assert overlapping(boxes) == [(0, 1)]
    assert overlapping([(0.0, 0.0, 0.7854, 4.5, 1.8), (2.2, 2.2, -0.7854, 4.5, 1.8)]) == [(0, 1)]
    rng = random.Random(1)
    for _ in range(50):                 # as a plain separating-axis test of each pair
        boxes = [(rng.uniform(0, 30), rng.uniform(0, 30), rng.uniform(-3, 3),
                  rng.uniform(3, 6), rng.uniform(1.5, 2.5)) for _ in range(25)]
        expected = [(i, j) for i in range(25) for j in range(i + 1, 25)
                    if separated(boxes[i], boxes[j]) is False]
        assert overlapping(boxes) == expected


def separated(a, b):
    """Return whether two rectangles (x, y, yaw, length, width) have a separating axis."""
    def corners(x, y, yaw, length, width):
        c, s = math.cos(yaw), math.sin(yaw)
        return [(x + c * u - s * v, y + s * u + c * v)
                for u, v in ((length / 2, width / 2), (-length / 2, width / 2),
                             (-length / 2, -width / 2), (length / 2, -width / 2))]
    pa, pb = corners(*a), corners(*b)
    for poly in (pa, pb):
        for k in range(2):
            ex, ey = poly[k + 1][0] - poly[k][0], poly[k + 1][1] - poly[k][1]
            on_a = [-ey * x + ex * y for x, y in pa]
            on_b = [-ey * x + ex * y for x, y in pb]
            if max(on_a) <= min(on_b) or max(on_b) <= min(on_a):
                return True
    return False


def test_traffic_drives_road_and_highway_lanes_only():
    # lane 1 forks into a road (2) and a bicycle lane (3); lane 4, a shoulder, enters nowhere
    lanes = [straight(1, -200, 0, 0, 0, [2, 3]), straight(2, 0, 0, 200, 0),
             straight(3, 0, 0, 0, 200), straight(4, -200, 10, 0, 10)]
    lanes[2].subtype, lanes[3].subtype = 'bicycle_lane', 'road_shoulder'
    graph = LaneGraph(lanes)
    data = {'vehicles': 5, 'seed': 2, 'models': ['Car'], 'spawn': {'spacing': 30.0}}
    m = TrafficManager(graph, traffic_from_dict(data, 'w.yaml: traffic'), DIMS)
    seen = set()
    for _ in range(int(120.0 / DT)):
        m.step(DT)
        seen |= {v.lane for v in m.vehicles if v.active}
    assert seen == {1, 2}
    with pytest.raises(InvalidParameterError, match=r"w\.yaml: traffic: spawn: field 'lanes': "
                                                    r"lane 4 is a 'road_shoulder' lane"):
        TrafficManager(graph, traffic_from_dict({**data, 'spawn': {'lanes': [1, 4]}},
                                                'w.yaml: traffic'), DIMS)


def test_no_lane_change_reaches_a_conflict_zone():
    # the highway's three forward lanes cross a (hand-made) zone at 300 .. 310 m, paired with
    # its first backward lane; a car behind a slow truck wants to pass it
    graph = lane_graph_from_roads(load_world('highway').roads)
    lanes = (100001, 100002, 100003)
    other = next(i for i in sorted(graph.lanes) if i % 100 >= 51)
    graph.set_rules(LaneRules(conflicts=tuple(
        Conflict(lane, other, (300.0, 310.0), (10.0, 20.0)) for lane in lanes)))
    data = {'models': ['Car', 'Truck'], 'placed': [
        {'model': 'Car', 'lanelet': 100002, 's': 230.0, 'speed': 25.0},
        {'model': 'Truck', 'lanelet': 100002, 's': 280.0, 'speed': 8.0, 'speed_factor': 0.25,
         'route': [100102]}]}
    m = TrafficManager(graph, traffic_from_dict(data, 'w.yaml: traffic'),
                       {'Car': (4.5, 1.8), 'Truck': (8.0, 2.4)})
    car = m.vehicles[0]
    starts = []
    for _ in range(int(20.0 / DT)):
        before = car.lane
        m.step(DT)
        if car.lane != before and car.changing:
            starts.append((car.s_m, car.speed_mps))
    assert starts, 'the car never passed the truck'
    for s, speed in starts:     # the change (3 s at its speed, its length) ends before the zone
        assert s + speed * 3.0 + 4.5 < 300.0 - 3.0 or s - 2.25 - 3.0 > 310.0, starts


def test_managers_on_one_graph_share_its_zones_until_the_graph_gets_other_rules():
    # A reset builds a new manager on the same graph: its conflict zones are not worked out
    # again (they are only read); new rules on the graph give new zones with their precedence.
    graph = crossing(lines=None)
    first, again = manager(graph, [EAST]), manager(graph, [NORTH])
    assert again.rules.zones is first.rules.zones
    assert not any(z.yields for zones in first.rules.zones.values() for z in zones)
    ruled = crossing(lines=None, right_of_way=True).rules
    graph.set_rules(ruled)
    later = manager(graph, [EAST])
    assert later.rules.zones is not first.rules.zones
    assert {lane: [z.yields for z in zones] for lane, zones in later.rules.zones.items()} == {
        EAST_X: [False], NORTH_X: [True]}
