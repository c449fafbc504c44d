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


"""The rules of ``roads:`` intersections: signals, stop signs, right of way, conflicts."""

import math

import pytest

from vehicle_sim.core.map.road_segments import lane_graph_from_roads, roads_from_list
from vehicle_sim.core.map.signal_plan import default_phases, group_conflicts, SignalController
from vehicle_sim.core.specs.errors import InvalidParameterError


def four_way(ew=None, ns=None):
    """Return the graph of two roads crossing at (0, 0): 'ew' east, 'ns' north (1 + 1 lanes)."""
    def road(name, yaw, extra):
        return {'name': name, 'start': {'x': -50 * math.cos(yaw), 'y': -50 * math.sin(yaw),
                                        'yaw': yaw},
                'segments': [{'type': 'straight', 'length': 44},
                             dict({'type': 'intersection', 'length': 12}, **(extra or {})),
                             {'type': 'straight', 'length': 44}]}
    roads = roads_from_list([road('ew', 0.0, ew), road('ns', math.pi / 2, ns)], 'w.yaml: roads')
    return lane_graph_from_roads(roads, 'w.yaml: roads')


def test_a_signalised_intersection_has_a_group_per_approach_with_lines_and_lamps():
    graph = four_way({'signals': True}, {'signals': True})
    rules = graph.rules
    # road r, segment j, direction: the group is 4e9 + the intersection segment's lane id
    assert sorted(g.id for g in rules.groups) == [4000100101, 4000100151, 4000200101,
                                                  4000200151]
    east = rules.group(4000100101)
    assert (east.lanes, east.stop_lines, east.name) == ((100001,), (3000100001,), 'ew/1/+')
    line = rules.stop_lines_on(100001)[0]
    assert (line.id, line.kind, line.group_id) == (3000100001, 'traffic_light', 4000100101)
    # the entry of the intersection: the lane ends at x = -6 (its 44 m from x = -50)
    assert line.s_m == pytest.approx(44.0)
    assert line.points.ravel().tolist() == pytest.approx([-6.0, 0.0, -6.0, -3.5])
    # lamps on a pole 1 m beyond the right edge (y = -3.5) at the line, red on top
    assert [b.color for b in east.bulbs] == ['red', 'yellow', 'green']
    assert [(b.x_m, b.y_m, b.z_m) for b in east.bulbs] == [
        pytest.approx(p) for p in ((-6.0, -4.5, 3.2), (-6.0, -4.5, 2.9), (-6.0, -4.5, 2.6))]
    westbound = rules.group(4000100151)
    assert westbound.lanes == (100251,)
    assert westbound.bulbs[0].x_m == pytest.approx(6.0) and \
        westbound.bulbs[0].y_m == pytest.approx(4.5)
    # every approach's path crosses every other's (left turns cross the opposite through lane):
    # four phases, never two conflicting groups green together
    assert all(len(others) == 3 for others in group_conflicts(rules, graph).values())
    assert [len(phases) for phases in default_phases(rules, graph)] == [4]
    signals = SignalController(graph)
    assert sorted(signals.states().values()) == ['green', 'red', 'red', 'red']
    assert rules.conflicts and rules.right_of_way == ()


def test_stop_signs_on_one_road_give_the_other_priority_and_no_keys_give_only_conflicts():
    graph = four_way(ns={'stop_signs': True})
    rules = graph.rules
    assert rules.groups == ()
    assert sorted((line.lane_id, line.kind) for line in rules.stop_lines) == [
        (200001, 'stop_sign'), (200251, 'stop_sign')]
    (rule,) = rules.right_of_way
    assert rule.id == 5000100101
    assert sorted(rule.priority_lanes) == [100001, 100251]
    assert sorted(rule.yield_lanes) == [200001, 200251]
    assert sorted(rule.stop_lines) == [3000200001, 3000200251]
    all_way = four_way({'stop_signs': True}, {'stop_signs': True}).rules
    assert len(all_way.stop_lines) == 4 and all_way.right_of_way == ()
    plain = four_way().rules
    assert plain.stop_lines == () and plain.groups == () and plain.right_of_way == ()
    assert len(plain.conflicts) == len(rules.conflicts) > 0


def test_a_road_without_lights_at_a_signalised_intersection_is_refused():
    with pytest.raises(InvalidParameterError, match=r"w.yaml: roads\[1\].segments\[1\]: field "
                       r"'signals' is false, but w.yaml: roads\[0\].segments\[1\] signals"):
        four_way({'signals': True})
    with pytest.raises(InvalidParameterError, match=r"roads\[0\].segments\[1\]: fields "
                       "'signals' and 'stop_signs' are both true"):
        four_way({'signals': True, 'stop_signs': True})
    with pytest.raises(InvalidParameterError, match="field 'signals'"):
        four_way({'signals': 'yes'})
