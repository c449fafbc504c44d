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
The traffic rule criteria of scenarios: traffic_light, stop_sign and yield.

They read the rules of the world's lane map (``scene.lanes.rules``: stop lines, traffic light
groups, right of way, conflicts; core/map/lane_rules.py) and, for ``traffic_light``, the state
of its signals (``scene.signals``, the world's one SignalController, core/map/signal_plan.py).
Each follows the vehicle's *front*: the middle of the front edge of its footprint rectangle
(core Outline, as ``clearance`` measures), with a core LaneTracker of its own. The front
*passes* a stop line when, between two steps, its arc length on the line's lane goes from
before the line's ``s`` to at or beyond it: along the lane, or from the line's lane onto a
successor (or from a predecessor onto it). Importing this module registers them in
``criteria.CRITERIA`` (schema.py imports it).
"""

import math

from vehicle_sim.core.map.lane_state import LaneTracker, OFF_LANE
from vehicle_sim.core.map.priority import priority_conflicts
from vehicle_sim.core.specs.param_spec import ParamSpec
from vehicle_sim.scenarios.criteria import CRITERIA, Criterion, CriterionResult
from vehicle_sim.scenarios.lane_criteria import NO_MAP

NO_SIGNALS = 'the world has no signals (a lane map with traffic light groups runs them)'
# The stop lines a stop_sign criterion watches: stop signs and Autoware's road-marking stop
# lines (its stop line module stops at both).
STOP_SIGN_KINDS = ('stop_sign', 'road_marking')
# How far ahead the front looks for the next red line, to report the closest approach [m].
RED_LOOKAHEAD_M = 50.0
# Slower than this a vehicle is not on its way to a conflict zone [m/s].
STILL_MPS = 0.05
_HALF_TURN = 0.5 * math.pi


def _ids(value):
    if isinstance(value, (list, tuple)) and all(
            isinstance(v, int) and not isinstance(v, bool) for v in value):
        return None
    return 'must be a list of group ids (integers)'


class FrontOnLanes:
    """
    A vehicle's front on the lanes, step to step: its lane state and the stop lines it passes.

    :param graph: the LaneGraph (its ``rules``: the stop lines).
    :param front_m: the front's distance ahead of base_link (the Outline's ``x_max_m``) [m].
    """

    def __init__(self, graph, front_m):
        self.graph = graph
        self.front_m = front_m
        self.tracker = LaneTracker(graph)
        self.state = OFF_LANE
        self.point = None           # (x, y) of the front [m]

    def update(self, sample):
        """Return (the front's LaneState, the StopLines it passed since the last sample)."""
        x = sample.x_m + math.cos(sample.yaw_rad) * self.front_m
        y = sample.y_m + math.sin(sample.yaw_rad) * self.front_m
        before = self.state
        self.state = self.tracker.update(x, y, sample.yaw_rad)
        self.point = (x, y)
        return self.state, self._passed(before, self.state)

    def _passed(self, before, now):
        if not (before.on_lane and now.on_lane):
            return []
        on = self.graph.rules.stop_lines_on
        if before.lane_id == now.lane_id:
            return [line for line in on(now.lane_id) if before.s_m < line.s_m <= now.s_m]
        lanes = self.graph.lanes
        left = lanes[before.lane_id]
        if now.lane_id in left.successors:
            return ([line for line in on(left.id) if line.s_m > before.s_m]
                    + [line for line in on(now.lane_id) if line.s_m <= now.s_m])
        if now.lane_id in (left.left_lane, left.right_lane):      # a lane change
            start = before.s_m / left.length_m * lanes[now.lane_id].length_m
            return [line for line in on(now.lane_id) if start < line.s_m <= now.s_m]
        return []


class _RuleCriterion(Criterion):
    """Base: follows the vehicle's front on the lane map; subclasses take ``observe_front``."""

    def __init__(self, *args):
        super().__init__(*args)
        self.lanes = None
        self.front = None
        self.error = None

    def bind(self, scene):
        self.lanes = getattr(scene, 'lanes', None)
        if self.lanes is None:
            self.error = NO_MAP
            return
        self.front = FrontOnLanes(self.lanes, scene.outline(self.vehicle).x_max_m)
        self.bind_rules(scene, self.lanes.rules)

    def bind_rules(self, scene, rules):
        """Take the scene and the map's rules before the first step; set ``error`` if unusable."""

    def observe(self, sample):
        if self.error is None and self.front is not None:
            state, passed = self.front.update(sample)
            self.observe_front(sample, state, passed)

    def observe_front(self, sample, state, passed):
        raise NotImplementedError

    @property
    def violated(self) -> bool:
        """Return whether it has failed already (a rule broken, or nothing to watch)."""
        return self.error is not None or bool(self.violations())

    def violations(self):
        """Return the rule breaches so far, first first."""
        raise NotImplementedError


class TrafficLight(_RuleCriterion):
    """The vehicle's front never passes a traffic light's stop line while its group is red."""

    KIND = 'traffic_light'
    UNIT = 'crossings'
    UNIT_OF_ONE = 'crossing'
    SPECS = (
        ParamSpec('groups', 'groups', 'raw', (), doc='ids of the traffic light groups it '
                  'watches; [] = every group of the map', check=_ids),
    )

    def __init__(self, *args):
        super().__init__(*args)
        self.signals = None
        self.lines = set()          # ids of the stop lines it watches
        self.crossings = []         # (time, StopLine, state, speed, front point)
        self.closest_red = None     # (distance, time, StopLine): nearest to a red line ahead

    def bind_rules(self, scene, rules):
        known = {group.id for group in rules.groups}
        unknown = [g for g in self.values['groups'] if g not in known]
        if unknown:
            self.error = (f'traffic light group(s) {unknown} not in the lane map (its groups: '
                          f'{", ".join(str(g) for g in sorted(known)) or "none"})')
            return
        watched = set(self.values['groups']) or known
        self.lines = {line.id for line in rules.stop_lines
                      if line.kind == 'traffic_light' and line.group_id in watched}
        if not self.lines:
            self.error = 'the lane map has no traffic light stop line to watch'
            return
        self.signals = getattr(scene, 'signals', None)
        if self.signals is None:
            self.error = NO_SIGNALS

    def observe_front(self, sample, state, passed):
        for line in passed:
            if line.id in self.lines:
                self.crossings.append((sample.time_s, line, self.signals.state(line.group_id),
                                       abs(sample.speed_mps), self.front.point))
        if not state.on_lane:
            return
        ahead = self.lanes.rules.next_stop_line(self.lanes, state.lane_id, state.s_m,
                                                RED_LOOKAHEAD_M)
        if ahead is not None and ahead[0].id in self.lines and \
                self.signals.state(ahead[0].group_id) == 'red' and \
                (self.closest_red is None or ahead[1] < self.closest_red[0]):
            self.closest_red = (ahead[1], sample.time_s, ahead[0])

    def violations(self):
        return [c for c in self.crossings if c[2] == 'red']

    def result(self):
        if self.error:
            return self._result(False, None, self.error)
        red = self.violations()
        if red:
            time_s, line, _, speed, point = red[0]
            more = f'; {len(red) - 1} more on red' if len(red) > 1 else ''
            detail = (f'passed stop line {line.id} (lane {line.lane_id}, group '
                      f'{line.group_id}) on red at {time_s:.2f} s at {speed:.2f} m/s{more}')
            return CriterionResult(self.name, self.KIND, False, len(red),
                                   self.UNIT_OF_ONE if len(red) == 1 else self.UNIT, detail,
                                   (point,), time_s)
        parts = [f'line {line.id} (group {line.group_id}) on {color} at {time_s:.2f} s'
                 for time_s, line, color, _, _ in self.crossings[:3]]
        detail = ('passed ' + ', '.join(parts) if parts
                  else 'passed no traffic light stop line')
        if self.closest_red is not None:
            distance, time_s, line = self.closest_red
            detail += (f'; closest to a red line: {distance:.2f} m before line {line.id} '
                       f'(group {line.group_id}) at {time_s:.2f} s')
        return self._result(True, 0, detail + ' (yellow and off are allowed)')


class StopSign(_RuleCriterion):
    """The vehicle comes to a stop just before each stop sign line its front passes."""

    KIND = 'stop_sign'
    UNIT = 'm/s'
    SPECS = (
        ParamSpec('stop_speed', 'stop_speed_mps', 'float', 0.1, 'm/s', 'a stop: the speed at '
                  'or below this', gt=0.0),
        ParamSpec('stop_within', 'stop_within_m', 'float', 3.0, 'm', "the stop counts with the "
                  "vehicle's front at most this far before the line (along its lanes)", gt=0.0),
    )

    def __init__(self, *args):
        super().__init__(*args)
        self.slowest = {}           # line id: (speed, time) slowest within distance before it
        self.passed = []            # (time, StopLine, speed then, slowest before (or None))

    def bind_rules(self, scene, rules):
        if not any(line.kind in STOP_SIGN_KINDS for line in rules.stop_lines):
            self.error = 'the lane map has no stop sign (or road marking) stop line'

    def observe_front(self, sample, state, passed):
        speed = abs(sample.speed_mps)
        for line in passed:
            if line.kind in STOP_SIGN_KINDS:
                self.passed.append((sample.time_s, line, speed, self.slowest.pop(line.id, None)))
        if not state.on_lane:
            return
        ahead = self.lanes.rules.next_stop_line(self.lanes, state.lane_id, state.s_m,
                                                self.values['stop_within_m'])
        if ahead is not None and ahead[0].kind in STOP_SIGN_KINDS:
            best = self.slowest.get(ahead[0].id)
            if best is None or speed < best[0]:
                self.slowest[ahead[0].id] = (speed, sample.time_s)

    def violations(self):
        bound = self.values['stop_speed_mps']
        return [p for p in self.passed if p[3] is None or p[3][0] > bound]

    def result(self):
        if self.error:
            return self._result(False, None, self.error)
        bound, distance = self.values['stop_speed_mps'], self.values['stop_within_m']
        if not self.passed:
            return self._result(True, None, 'passed no stop sign line')
        worst = None                # the crossing whose slowest approach was fastest
        for time_s, line, speed, slowest in self.passed:
            value = math.inf if slowest is None else slowest[0]
            if worst is None or value > worst[0]:
                worst = (value, time_s, line, speed, slowest)
        value, time_s, line, speed, slowest = worst
        before = (f'never within {distance:g} m before it' if slowest is None else
                  f'slowest {slowest[0]:.3f} m/s within {distance:g} m before it at '
                  f'{slowest[1]:.2f} s')
        if value > bound:
            return self._result(False, None if slowest is None else value,
                                f'rolled through stop line {line.id} (lane {line.lane_id}) at '
                                f'{time_s:.2f} s at {speed:.2f} m/s: {before} (a stop: <= '
                                f'{bound:g} m/s)')
        return self._result(True, value, f'stopped before all {len(self.passed)} stop sign '
                                          f'line(s) passed; the least full stop: line {line.id}:'
                                          f' {before} (a stop: <= {bound:g} m/s)')


class Yield(_RuleCriterion):
    """The vehicle does not enter a conflict zone in front of a vehicle with priority."""

    KIND = 'yield'
    UNIT = 's'
    SPECS = (
        ParamSpec('gap', 'gap_s', 'float', 3.0, 's', 'a vehicle with priority that would reach '
                  'the conflict zone within this time (distance / its speed) must go first',
                  gt=0.0),
    )

    def __init__(self, *args):
        super().__init__(*args)
        self.watch = {}             # lane id: its conflicts whose other lane has priority
        self.inside = set()         # (lane, other lane) of the zones the front is in now
        self.entries = 0
        self.closest = None         # (time to the zone, time, name, conflict, distance, speed)
        self.bad = []               # the entries in front of a priority vehicle (as closest)
        self.scene = None

    def bind_rules(self, scene, rules):
        self.watch = priority_conflicts(self.lanes)
        if not self.watch:
            self.error = ('the lane map gives no lane priority over another (no right of way '
                          'rule, no unsignalled conflict of a stop or yield line)')
        self.scene = scene

    def observe_front(self, sample, state, passed):
        inside = set()
        if state.on_lane:
            for conflict in self.watch.get(state.lane_id, ()):
                if conflict.s_m[0] <= state.s_m <= conflict.s_m[1]:
                    inside.add((conflict.lane_id, conflict.other_id))
                    if (conflict.lane_id, conflict.other_id) not in self.inside:
                        self._entered(sample, conflict)
        self.inside = inside

    def _traffic(self):
        # the traffic vehicles now: (name, front, rear, yaw, speed)
        source = getattr(self.scene, 'traffic', None)
        if source is None:
            return []
        speeds = getattr(self.scene, 'traffic_speeds', None)
        speeds = {} if speeds is None else speeds()
        now = []
        for name, x, y, yaw, length, _ in source():
            c, s = 0.5 * length * math.cos(yaw), 0.5 * length * math.sin(yaw)
            now.append((name, (x + c, y + s), (x - c, y - s), yaw, abs(speeds.get(name, 0.0))))
        return now

    def _ours(self):
        samples = getattr(self.scene, 'samples', None)
        if samples is None:
            return []
        ours = []
        for name, sample in samples().items():
            if name == self.vehicle:
                continue
            outline = self.scene.outline(name)
            c, s = math.cos(sample.yaw_rad), math.sin(sample.yaw_rad)
            x, y = sample.x_m, sample.y_m
            ours.append((name, (x + c * outline.x_max_m, y + s * outline.x_max_m),
                         (x + c * outline.x_min_m, y + s * outline.x_min_m),
                         sample.yaw_rad, abs(sample.speed_mps)))
        return ours

    def _entered(self, sample, conflict):
        self.entries += 1
        for name, front, rear, yaw, speed in self._traffic() + self._ours():
            way = self._to_zone(conflict, front, rear, yaw)
            if way is None:
                continue
            if way == 0.0:
                time_to = 0.0
            elif speed <= STILL_MPS:
                continue
            else:
                time_to = way / speed
            found = (time_to, sample.time_s, name, conflict, way, speed, self.front.point, front)
            if self.closest is None or time_to < self.closest[0]:
                self.closest = found
            if time_to <= self.values['gap_s']:
                self.bad.append(found)

    def _to_zone(self, conflict, front, rear, yaw):
        """Return a vehicle's distance along its lanes to the other lane's zone [m], or None."""
        graph = self.lanes
        first, last = conflict.other_s_m
        other = conflict.other_id
        position, on = graph.locate_on(other, *front, yaw)
        if on and abs(position.heading_error_rad) < _HALF_TURN:
            if position.s_m < first:
                return first - position.s_m
            behind, _ = graph.locate_on(other, *rear, near_s_m=position.s_m)
            return 0.0 if behind.s_m <= last else None          # in the zone, or past it
        # on a lane leading to it (two lanes back at most)
        for before in graph.predecessors[other]:
            for lane_id, extra in [(before, 0.0)] + [
                    (earlier, graph.lanes[before].length_m)
                    for earlier in graph.predecessors[before]]:
                position, on = graph.locate_on(lane_id, *front, yaw)
                if on and abs(position.heading_error_rad) < _HALF_TURN:
                    return graph.lanes[lane_id].length_m - position.s_m + extra + first
        return None

    def violations(self):
        return list(self.bad)

    def result(self):
        if self.error:
            return self._result(False, None, self.error)
        gap = self.values['gap_s']
        if self.bad:
            time_to, time_s, name, conflict, way, speed, ours, theirs = self.bad[0]
            where = (f'while {name} was in it' if time_to == 0.0 else
                     f'while {name} was {time_to:.2f} s from it ({way:.1f} m at '
                     f'{speed:.2f} m/s)')
            more = f'; {len(self.bad) - 1} more' if len(self.bad) > 1 else ''
            return CriterionResult(
                self.name, self.KIND, False, time_to, self.UNIT,
                f'entered the conflict zone of lane {conflict.lane_id} with priority lane '
                f'{conflict.other_id} at {time_s:.2f} s {where}; gap {gap:g} s{more}',
                (ours, theirs), time_s, (name,))
        if self.closest is None:
            return self._result(True, None, f'entered {self.entries} conflict zone(s) of a '
                                             f'priority lane, no priority vehicle coming '
                                             f'(gap {gap:g} s)')
        time_to, time_s, name, conflict, _, _, ours, theirs = self.closest
        return CriterionResult(
            self.name, self.KIND, True, time_to, self.UNIT,
            f'entered {self.entries} conflict zone(s) of a priority lane; the nearest priority '
            f"vehicle {name} {time_to:.2f} s from lane {conflict.other_id}'s zone at "
            f'{time_s:.2f} s (gap {gap:g} s)', (ours, theirs), time_s, (name,))


RULE_CRITERIA = {cls.KIND: cls for cls in (TrafficLight, StopSign, Yield)}
CRITERIA.update(RULE_CRITERIA)
