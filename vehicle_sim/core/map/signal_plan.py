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
The signal plan of a lane map's traffic light groups, and their state at a simulation time.

A :class:`SignalController` holds the state of every TrafficLightGroup of a LaneGraph's rules
(core/map/lane_rules.py) and is advanced by the world's clock (:meth:`SignalController.update`).
Everything that reads signals (the traffic, the lane state, the criteria, the ROS topic, the
lamps) reads :meth:`SignalController.state` of the one controller of the world.

The fixed-time plan (:class:`FixedTimePlan`): the groups whose paths conflict form one
intersection; an intersection's groups are split into phases (groups in one phase never
conflict; by default the fewest phases a greedy colouring of the groups' conflicts finds, in
order of group id), and the phases follow each other: green, yellow, all red. A group is green
in its phase's green time, yellow in its yellow time and red otherwise. ``offset_s`` shifts the
cycle. Every intersection runs the controller's plan unless it is given its own (``plans``: its
times and offset, e.g. a green wave along a street).

A scenario may force a group's state (:meth:`SignalController.force`) until the plan is resumed
(:meth:`SignalController.release`).
"""

from dataclasses import dataclass
import math
from typing import Dict, List, Optional, Sequence, Tuple

from vehicle_sim.core.map.lane_rules import LaneRules, SIGNAL_STATES
from vehicle_sim.core.specs.errors import InvalidParameterError


@dataclass(frozen=True)
class FixedTimePlan:
    """
    A fixed-time plan: the same cycle for every intersection.

    :param green_s: green time of each phase [s].
    :param yellow_s: yellow time after each green [s].
    :param all_red_s: all-red time after each yellow [s].
    :param offset_s: the cycle's start [s] (a group whose phase starts at 0 is green from then).
    """

    green_s: float = 20.0
    yellow_s: float = 3.0
    all_red_s: float = 2.0
    offset_s: float = 0.0

    def __post_init__(self):
        for name in ('green_s', 'yellow_s', 'all_red_s', 'offset_s'):
            value = getattr(self, name)
            if not (isinstance(value, (int, float)) and math.isfinite(value)):
                raise InvalidParameterError(f'signal plan: {name} = {value!r} must be a finite '
                                            'number [s]')
        if self.green_s <= 0.0 or self.yellow_s < 0.0 or self.all_red_s < 0.0:
            raise InvalidParameterError('signal plan: green must be > 0 s, yellow and all red '
                                        '>= 0 s')

    @property
    def phase_s(self) -> float:
        return self.green_s + self.yellow_s + self.all_red_s


def group_conflicts(rules: LaneRules, graph) -> Dict[int, set]:
    """
    Return {group id: ids of the groups whose paths conflict with its own}.

    A group's path is its lanes and their successors (its stop lines may lie at the end of the
    lanes it controls, the intersection beyond).
    """
    lane_groups: Dict[int, set] = {}
    for group in rules.groups:
        for lane_id in group.lanes:
            for one in (lane_id,) + graph.lanes[lane_id].successors:
                lane_groups.setdefault(one, set()).add(group.id)
    conflicts = {group.id: set() for group in rules.groups}
    for conflict in rules.conflicts:
        for a in lane_groups.get(conflict.lane_id, ()):
            for b in lane_groups.get(conflict.other_id, ()):
                if a != b:
                    conflicts[a].add(b)
                    conflicts[b].add(a)
    return conflicts


def default_phases(rules: LaneRules, graph) -> Tuple[Tuple[Tuple[int, ...], ...], ...]:
    """
    Return the phases of each intersection: ((phase: group ids, ...), ...) per intersection.

    An intersection is a connected set of conflicting groups (a group without conflicts is an
    intersection of one phase); its phases colour its groups greedily in order of id.
    """
    conflicts = group_conflicts(rules, graph)
    seen, intersections = set(), []
    for group_id in sorted(conflicts):
        if group_id in seen:
            continue
        todo, members = [group_id], set()
        while todo:
            one = todo.pop()
            if one in members:
                continue
            members.add(one)
            todo.extend(conflicts[one] - members)
        seen |= members
        phases: List[List[int]] = []
        for one in sorted(members):
            for phase in phases:
                if not conflicts[one] & set(phase):
                    phase.append(one)
                    break
            else:
                phases.append([one])
        intersections.append(tuple(tuple(phase) for phase in phases))
    return tuple(intersections)


def check_phases(rules: LaneRules, graph, phases) -> None:
    """Refuse phases in which two conflicting groups are green together, naming them."""
    conflicts = group_conflicts(rules, graph)
    for intersection in phases:
        for phase in intersection:
            for a in phase:
                clash = sorted(conflicts.get(a, set()) & set(phase))
                if clash:
                    raise InvalidParameterError(
                        f'signal plan: groups {a} and {clash[0]} are green together but their '
                        'lanes conflict')


def check_signal_state(rules: LaneRules, group_id, state) -> None:
    """
    Refuse a group not in the map or a state not in SIGNAL_STATES.

    :raises InvalidParameterError: naming the group or the state.
    """
    rules.group(group_id)                   # names a group not in the map
    if state not in SIGNAL_STATES:
        raise InvalidParameterError(f'signal state {state!r} is not one of '
                                    + ', '.join(SIGNAL_STATES))


class GroupStates:
    """
    What every signal controller answers (this one and core/map/signal_programs.py's).

    A subclass keeps ``rules`` (the map's LaneRules), ``_states`` ({group id: state now}) and
    ``_forced`` ({group id: state a scenario holds}).
    """

    rules: LaneRules
    _states: Dict[int, str]
    _forced: Dict[int, str]

    def state(self, group_id) -> str:
        """Return a group's state now: one of SIGNAL_STATES."""
        state = self._states.get(group_id)
        if state is None:
            self.rules.group(group_id)      # raises naming the id
        return state

    def states(self) -> Dict[int, str]:
        """Return {group id: state} of every group now."""
        return dict(self._states)

    def forced(self) -> Dict[int, str]:
        """Return {group id: state} of the groups a scenario forces now."""
        return dict(self._forced)


class SignalController(GroupStates):
    """
    The state of every traffic light group of a map, at the world's time.

    :param graph: the map's LaneGraph (its ``rules``: the groups and conflicts).
    :param plan: the FixedTimePlan of every intersection without one of its own.
    :param phases: per intersection, its phases (group ids green together); None = computed
        (:func:`default_phases`).
    :param plans: {group id: FixedTimePlan} the plan of the intersection that has that group
        (one entry per intersection); None = ``plan`` everywhere.
    :raises InvalidParameterError: a phase or a plan names a group not in the map, conflicting
        groups are green together, two plans for one intersection.
    """

    def __init__(self, graph, plan: FixedTimePlan = FixedTimePlan(),
                 phases: Optional[Sequence] = None,
                 plans: Optional[Dict[int, FixedTimePlan]] = None):
        rules = graph.rules
        self.rules = rules
        self.plan = plan
        self.phases = default_phases(rules, graph) if phases is None else tuple(
            tuple(tuple(phase) for phase in intersection) for intersection in phases)
        for intersection in self.phases:
            for phase in intersection:
                for group_id in phase:
                    rules.group(group_id)           # names the group when it is not in the map
        check_phases(rules, graph, self.phases)
        own = self._intersection_plans(plans or {})
        # group -> (phase index, phase count, its intersection's plan)
        self._slot: Dict[int, Tuple[int, int, FixedTimePlan]] = {}
        for number, intersection in enumerate(self.phases):
            for index, phase in enumerate(intersection):
                for group_id in phase:
                    self._slot[group_id] = (index, len(intersection), own.get(number, plan))
        self._timings = tuple({id(p): p for _, _, p in self._slot.values()}.values()) or (plan,)
        self._forced: Dict[int, str] = {}
        self.time_s = 0.0
        self._states: Dict[int, str] = {}
        self._unchanged = (math.inf, -math.inf)     # times whose states are those computed
        self.update(0.0)

    def _intersection_plans(self, plans):
        """Return {intersection index: plan} of ``plans`` ({group id: plan})."""
        own, by = {}, {}
        for group_id, one in plans.items():
            self.rules.group(group_id)                  # names a group not in the map
            number = next((n for n, intersection in enumerate(self.phases)
                           if any(group_id in phase for phase in intersection)), None)
            if number is None:
                raise InvalidParameterError(f'signal plan: group {group_id} is in no phase')
            if number in own:
                raise InvalidParameterError(
                    f'signal plan: groups {by[number]} and {group_id} are of one intersection: '
                    'give its plan once')
            own[number], by[number] = one, group_id
        return own

    def update(self, time_s: float) -> None:
        """Set every group's state for simulation time ``time_s`` [s]."""
        self.time_s = time_s
        start, end = self._unchanged
        if start <= time_s < end:        # no phase boundary since the states were computed
            return
        self._states = {group.id: self._planned(group.id, time_s) for group in self.rules.groups}
        self._states.update(self._forced)
        self._unchanged = self._window(time_s)

    def _window(self, time_s):
        """Return [start, end) around ``time_s`` without a boundary of any plan's timing."""
        start, end = -math.inf, math.inf
        for plan in self._timings:
            u = (time_s - plan.offset_s) % plan.phase_s
            edges = (0.0, plan.green_s, plan.green_s + plan.yellow_s, plan.phase_s)
            before = max(edge for edge in edges if edge <= u)
            after = min((edge for edge in edges if edge > u), default=plan.phase_s)
            start, end = max(start, time_s - (u - before)), min(end, time_s + (after - u))
        margin = 1e-9 * max(1.0, abs(time_s))      # recompute next to a boundary: rounding
        return start + margin, end - margin

    def _planned(self, group_id, time_s):
        slot = self._slot.get(group_id)
        if slot is None:
            return 'off'
        index, count, plan = slot
        t = (time_s - plan.offset_s) % (count * plan.phase_s) - index * plan.phase_s
        if 0.0 <= t < plan.green_s:
            return 'green'
        if plan.green_s <= t < plan.green_s + plan.yellow_s:
            return 'yellow'
        return 'red'

    def force(self, group_id, state: str) -> None:
        """Hold a group in ``state`` (one of SIGNAL_STATES) until :meth:`release`."""
        check_signal_state(self.rules, group_id, state)
        self._forced[group_id] = state
        self._states[group_id] = state
        self._unchanged = (math.inf, -math.inf)

    def release(self, group_id=None) -> None:
        """Return a group (None: every group) to its plan."""
        if group_id is None:
            self._forced.clear()
        else:
            self.rules.group(group_id)
            self._forced.pop(group_id, None)
        self._unchanged = (math.inf, -math.inf)
        self.update(self.time_s)
