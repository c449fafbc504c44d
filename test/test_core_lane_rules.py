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


"""The lane map's rules (stop lines, groups, conflicts) and the fixed-time signal plan."""

from lane_helpers import straight
import pytest

from vehicle_sim.core.map.lane_graph import LaneGraph
from vehicle_sim.core.map.lane_rules import Conflict, LaneRules, StopLine, TrafficLightGroup
from vehicle_sim.core.map.signal_plan import FixedTimePlan, SignalController
from vehicle_sim.core.specs.errors import InvalidParameterError


def crossing():
    """Return lanes 1 then 2 east, 3 then 4 north; 2 and 4 cross around (10, 0)."""
    return LaneGraph([straight(1, -20, 0, 0, 0, [2]), straight(2, 0, 0, 20, 0),
                      straight(3, 10, -30, 10, -10, [4]), straight(4, 10, -10, 10, 10)])


def rules_of_crossing(line_s=18.0):
    east = StopLine(101, 1, line_s, [(line_s - 20, -1.75), (line_s - 20, 1.75)],
                    'traffic_light', 11)
    north = StopLine(102, 3, 18.0, [(8.25, -12), (11.75, -12)], 'traffic_light', 12)
    return LaneRules(stop_lines=(east, north),
                     groups=(TrafficLightGroup(11, (1,), (101,)),
                             TrafficLightGroup(12, (3,), (102,))),
                     conflicts=(Conflict(2, 4, (8.25, 11.75), (8.25, 11.75)),))


def test_next_stop_line_is_found_ahead_on_the_lane_and_its_successors():
    graph = crossing()
    graph.set_rules(rules_of_crossing())
    line, distance = graph.rules.next_stop_line(graph, 1, 5.0, 50.0)
    assert line.id == 101 and distance == pytest.approx(13.0)
    assert graph.rules.next_stop_line(graph, 1, 19.0, 50.0) is None     # passed it
    assert graph.rules.next_stop_line(graph, 1, 0.0, 10.0) is None      # beyond the horizon
    assert [c.other_id for c in graph.rules.conflicts_of(4)] == [2]


def test_a_stop_line_off_its_lane_or_naming_an_unknown_group_is_refused():
    graph = crossing()
    far = StopLine(101, 1, 10.0, [(-10, 5.0), (-10, 8.0)], 'stop_sign')
    with pytest.raises(InvalidParameterError, match='stop line 101.*off its lane'):
        graph.set_rules(LaneRules(stop_lines=(far,)))
    orphan = StopLine(101, 1, 10.0, [(-10, -1.75), (-10, 1.75)], 'traffic_light', 99)
    with pytest.raises(InvalidParameterError, match='group 99 is not in the map'):
        graph.set_rules(LaneRules(stop_lines=(orphan,)))
    assert graph.rules.empty                    # nothing was attached


def test_conflicting_groups_are_never_green_together_over_a_cycle():
    graph = crossing()
    graph.set_rules(rules_of_crossing())
    plan = FixedTimePlan(green_s=10.0, yellow_s=3.0, all_red_s=2.0)
    signals = SignalController(graph, plan)
    seen = set()
    for step in range(0, 600):
        signals.update(step * 0.1)
        states = signals.states()
        assert not (states[11] in ('green', 'yellow') and states[12] in ('green', 'yellow'))
        seen.add((states[11], states[12]))
    assert ('green', 'red') in seen and ('red', 'green') in seen and ('red', 'red') in seen
    signals.update(0.0)
    assert signals.state(11) == 'green' and signals.state(12) == 'red'
    signals.update(11.0)
    assert signals.state(11) == 'yellow'


def test_a_forced_state_holds_until_released_and_bad_input_changes_nothing():
    graph = crossing()
    graph.set_rules(rules_of_crossing())
    signals = SignalController(graph)
    signals.force(12, 'green')
    signals.update(1.0)
    assert signals.state(12) == 'green'
    with pytest.raises(InvalidParameterError, match="'blue' is not one of"):
        signals.force(12, 'blue')
    with pytest.raises(InvalidParameterError, match='group 7 is not in the map'):
        signals.force(7, 'red')
    assert signals.state(12) == 'green'
    signals.release()
    assert signals.state(12) == 'red'


def test_phases_that_put_conflicting_groups_green_together_are_refused():
    with pytest.raises(InvalidParameterError, match='groups 11 and 12 are green together'):
        graph = crossing()
        graph.set_rules(rules_of_crossing())
        SignalController(graph, phases=[[[11, 12]]])


def test_skipping_the_recomputation_between_phase_boundaries_gives_the_same_states():
    graph = crossing()
    graph.set_rules(rules_of_crossing())
    plan = FixedTimePlan(green_s=7.3, yellow_s=2.9, all_red_s=1.1, offset_s=0.37)
    fast, fresh = SignalController(graph, plan), None
    for step in range(0, 5000):
        t = step * 0.01
        fast.update(t)
        fresh = SignalController(graph, plan)
        fresh.update(t)
        assert fast.states() == fresh.states(), t
