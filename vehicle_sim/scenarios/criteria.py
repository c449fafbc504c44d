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
Pass criteria of a scenario: one class per kind, in the ``CRITERIA`` registry.

Each criterion watches one vehicle: :meth:`Criterion.observe` gets a :class:`Sample` after every
basic step, :meth:`Criterion.collision` each collision event of that vehicle, and a topic
criterion :meth:`Criterion.message` each message of its topic. :meth:`Criterion.result` gives
the verdict with the measured value. Nothing here touches PyBullet or ROS: the runner feeds
them, and the unit tests feed them by hand.
"""

from dataclasses import dataclass
import math
import operator
from typing import Any, Dict, Optional, Tuple

from vehicle_sim.core.geometry.footprint import clearance, distance_to_polyline
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.param_spec import ParamSpec, REQUIRED, validate_table
from vehicle_sim.core.specs.value_text import brief
from vehicle_sim.scenarios.yaml_lines import line_of


@dataclass(frozen=True)
class Sample:
    """A vehicle's ground truth after a step: time [s], x, y [m], yaw [rad], speed [m/s]."""

    time_s: float
    x_m: float
    y_m: float
    yaw_rad: float
    speed_mps: float


@dataclass(frozen=True)
class CriterionResult:
    """
    The verdict of one criterion.

    :param value: the measured value (None when nothing was measured).
    :param unit: its unit.
    :param detail: one line: what was measured against what.
    :param points_m: where the value was measured, for plots ((x, y) [m]; clearance: per
        obstacle, nearest first, the closest point of the vehicle and that of the obstacle;
        min_gap: the vehicle's front and the traffic vehicle's rear at the smallest gap, or
        twice the contact point of a collision; no_collision: the first collision's contact
        point).
    :param at_s: the simulated time of the key moment (when the value was measured: the
        smallest gap or clearance, the first collision), or None.
    :param others: the other vehicles at that moment (min_gap's traffic vehicle, what
        no_collision's vehicle hit).
    """

    name: str
    kind: str
    passed: bool
    value: Optional[float]
    unit: str
    detail: str
    points_m: Tuple[Tuple[float, float], ...] = ()
    at_s: Optional[float] = None
    others: Tuple[str, ...] = ()


def common_specs():
    """Return the keys every criterion has: kind, name, vehicle."""
    return (
        ParamSpec('kind', 'kind', 'enum', REQUIRED, choices=tuple(sorted(CRITERIA)),
                  doc='criterion kind (the sections below)'),
        ParamSpec('name', 'name', 'str', '', empty=True,
                  doc="test case name; '' = the kind (numbered when repeated)"),
        ParamSpec('vehicle', 'vehicle', 'str', '', empty=True,
                  doc="the vehicle it watches; '' = the vehicle under test"),
    )


@dataclass(frozen=True)
class CriterionSpec:
    """One pass criterion: its kind, test name, vehicle and validated values."""

    kind: str
    name: str
    vehicle: str
    values: Dict[str, Any]
    line: Optional[int] = None


class Criterion:
    """Base: a criterion of one vehicle; subclasses set KIND, UNIT and SPECS."""

    KIND = ''
    UNIT = ''
    UNIT_OF_ONE = None          # a counted unit's singular ('collision' for a value of 1)
    SPECS: Tuple[ParamSpec, ...] = ()

    def __init__(self, name, vehicle, values: Dict[str, Any], duration_s):
        self.name = name
        self.vehicle = vehicle
        self.values = values
        self.duration_s = duration_s

    def bind(self, scene):
        """Take the run's scene (vehicle outlines, obstacle footprints) before the first step."""

    def observe(self, sample: Sample):
        """Take the vehicle's state after a step."""

    def collision(self, event):
        """Take a collision event of the vehicle (core CollisionEvent)."""

    def message(self, msg, time_s):
        """Take a message of the criterion's topic, received at simulated time ``time_s``."""

    def result(self) -> CriterionResult:
        raise NotImplementedError

    def _result(self, passed, value, detail):
        unit = self.UNIT_OF_ONE if self.UNIT_OF_ONE and value == 1 else self.UNIT
        return CriterionResult(self.name, self.KIND, bool(passed), value, unit, detail)


class ReachGoal(Criterion):
    """The vehicle enters a circle (optionally slower than a speed) within a time."""

    KIND = 'reach_goal'
    UNIT = 's'
    SPECS = (
        ParamSpec('goal', 'goal', 'floats', REQUIRED, 'm', 'centre [x, y] of the goal region',
                  length=2),
        ParamSpec('radius', 'radius_m', 'float', REQUIRED, 'm', 'radius of the goal region',
                  gt=0.0),
        ParamSpec('within', 'within_s', 'float', None, 's', 'deadline; null = the duration',
                  gt=0.0, optional=True),
        ParamSpec('max_speed', 'max_speed_mps', 'float', None, 'm/s', 'counts only below this '
                  'speed (e.g. 0.05: stopped in the region); null = any speed', ge=0.0,
                  optional=True),
    )

    def __init__(self, *args):
        super().__init__(*args)
        self.reached_s = None
        self.closest_m = math.inf
        self.entered_s = None           # first time inside the region, at any speed
        self.slowest_inside = None      # (speed [m/s], time [s]) slowest while inside

    def observe(self, sample):
        gx, gy = self.values['goal']
        distance = math.hypot(sample.x_m - gx, sample.y_m - gy)
        self.closest_m = min(self.closest_m, distance)
        if distance > self.values['radius_m']:
            return
        speed_mps = abs(sample.speed_mps)
        if self.entered_s is None:
            self.entered_s = sample.time_s
        if self.slowest_inside is None or speed_mps < self.slowest_inside[0]:
            self.slowest_inside = (speed_mps, sample.time_s)
        slow = self.values['max_speed_mps'] is None or speed_mps <= self.values['max_speed_mps']
        if self.reached_s is None and slow:
            self.reached_s = sample.time_s

    def result(self):
        within = self.values['within_s'] or self.duration_s
        goal = f'goal ({self.values["goal"][0]:g}, {self.values["goal"][1]:g}) r=' \
               f'{self.values["radius_m"]:g} m'
        if self.values['max_speed_mps'] is not None:
            goal += f' below {self.values["max_speed_mps"]:g} m/s'
        if self.reached_s is None and self.entered_s is not None:
            # In the region, but never slow enough there: say so, with the speed it had.
            speed_mps, at_s = self.slowest_inside
            return self._result(False, None, f'{goal} entered at {self.entered_s:.2f} s but '
                                              f'never below the limit there (slowest '
                                              f'{speed_mps:.3g} m/s at {at_s:.2f} s, '
                                              f'{speed_mps - self.values["max_speed_mps"]:.3g} '
                                              f'm/s above it); deadline {within:g} s')
        if self.reached_s is None:
            return self._result(False, None, f'{goal} not reached (closest '
                                              f'{self.closest_m:.3f} m); deadline {within:g} s')
        passed = self.reached_s <= within + 1e-9
        return self._result(passed, self.reached_s, f'{goal} reached at '
                                                    f'{self.reached_s:.2f} s (deadline '
                                                    f'{within:g} s)')


class NoCollision(Criterion):
    """The vehicle touches nothing but the ground (and the bodies it may ignore)."""

    KIND = 'no_collision'
    UNIT = 'collisions'
    UNIT_OF_ONE = 'collision'
    SPECS = (
        ParamSpec('ignore', 'ignore', 'raw', (), doc='names of bodies it may touch',
                  check=lambda v: None if isinstance(v, (list, tuple)) and all(
                      isinstance(a, str) for a in v) else 'must be a list of names'),
    )

    def __init__(self, *args):
        super().__init__(*args)
        self.events = []

    def collision(self, event):
        if event.other not in self.values['ignore']:
            self.events.append(event)

    def result(self):
        count = len(self.events)
        if not count:
            return self._result(True, 0, 'no collision')
        first = ', '.join(f'{e.other} at {e.time_s:.2f} s' for e in self.events[:3])
        counted = f'{count} {self.UNIT_OF_ONE if count == 1 else self.UNIT}'
        event = self.events[0]
        point = () if event.position_m is None else (tuple(event.position_m[:2]),)
        return CriterionResult(self.name, self.KIND, False, count, self.UNIT_OF_ONE
                               if count == 1 else self.UNIT, f'{counted}: {first}', point,
                               event.time_s, (event.other,))


class StayOnPath(Criterion):
    """The vehicle stays within a lateral distance of a polyline."""

    KIND = 'stay_on_path'
    UNIT = 'm'
    SPECS = (
        ParamSpec('path', 'path', 'rows', REQUIRED, 'm', 'the polyline [[x, y], ...] (at '
                  'least 2 points)', length=2),
        ParamSpec('max_distance', 'max_distance_m', 'float', REQUIRED, 'm',
                  'largest lateral distance allowed', gt=0.0),
    )

    def __init__(self, *args):
        super().__init__(*args)
        self.worst_m = 0.0
        self.worst_s = None

    def observe(self, sample):
        distance = distance_to_polyline(sample.x_m, sample.y_m, self.values['path'])
        if self.worst_s is None or distance > self.worst_m:
            self.worst_m, self.worst_s = distance, sample.time_s

    def result(self):
        limit = self.values['max_distance_m']
        at = f' at {self.worst_s:.2f} s' if self.worst_s is not None else ''
        return self._result(self.worst_m <= limit, self.worst_m,
                            f'max lateral distance {self.worst_m:.3f} m{at} (limit {limit:g} m)')


class MaxSpeed(Criterion):
    """The vehicle's ground-truth speed never exceeds a limit."""

    KIND = 'max_speed'
    UNIT = 'm/s'
    SPECS = (
        ParamSpec('limit', 'limit_mps', 'float', REQUIRED, 'm/s', 'speed limit (ground truth, '
                  'horizontal)', gt=0.0),
    )

    def __init__(self, *args):
        super().__init__(*args)
        self.top_mps = 0.0
        self.top_s = None

    def observe(self, sample):
        speed = abs(sample.speed_mps)
        if self.top_s is None or speed > self.top_mps:
            self.top_mps, self.top_s = speed, sample.time_s

    def result(self):
        limit = self.values['limit_mps']
        at = f' at {self.top_s:.2f} s' if self.top_s is not None else ''
        return self._result(self.top_mps <= limit, self.top_mps,
                            f'top speed {self.top_mps:.3f} m/s{at} (limit {limit:g} m/s)')


class MeanSpeed(Criterion):
    """The vehicle's ground-truth speed, averaged over the run, reaches a bound."""

    KIND = 'mean_speed'
    UNIT = 'm/s'
    SPECS = (
        ParamSpec('min', 'min_mps', 'float', REQUIRED, 'm/s', 'smallest mean speed (ground '
                  'truth, horizontal, averaged over time from the first sample to the last)',
                  ge=0.0),
    )

    def __init__(self, *args):
        super().__init__(*args)
        self.first = self.last = None
        self.distance_m = 0.0

    def observe(self, sample):
        speed = abs(sample.speed_mps)
        if self.last is not None:       # the trapezoid rule between two samples
            self.distance_m += 0.5 * (speed + self.last[1]) * (sample.time_s - self.last[0])
        else:
            self.first = sample.time_s
        self.last = (sample.time_s, speed)

    def result(self):
        bound = self.values['min_mps']
        if self.last is None or self.last[0] <= self.first:
            return self._result(False, None, 'no time driven')
        mean = self.distance_m / (self.last[0] - self.first)
        return self._result(mean >= bound, mean,
                            f'mean speed {mean:.3f} m/s over {self.last[0] - self.first:.2f} s '
                            f'(at least {bound:g} m/s)')


class Clearance(Criterion):
    """The vehicle's footprint keeps a distance from every obstacle (and map wall)."""

    KIND = 'clearance'
    UNIT = 'm'
    SPECS = (
        ParamSpec('min', 'min_m', 'float', REQUIRED, 'm', "smallest distance allowed between "
                  "the vehicle's footprint rectangle and any obstacle's footprint (seen from "
                  'above); touching one (a collision) fails whatever the bound', ge=0.0),
    )

    def __init__(self, *args):
        super().__init__(*args)
        self.outline = None
        self.scene = None
        self.nearest = {}         # obstacle name: (distance, time, vehicle point, its point)
        self.contacts = {}        # obstacle name: the first collision with it (CollisionEvent)

    def bind(self, scene):
        self.outline = scene.outline(self.vehicle)
        self.scene = scene

    def collision(self, event):
        if self.scene is not None and event.other not in self.contacts and \
                event.other in self.scene.footprint_names():
            self.contacts[event.other] = event

    def observe(self, sample):
        if self.outline is None:
            return
        corners = self.outline.corners(sample.x_m, sample.y_m, sample.yaw_rad)
        xs, ys = [x for x, _ in corners], [y for _, y in corners]
        within = {name: best[0] for name, best in self.nearest.items()}
        for lower, footprint in self.scene.footprints_near((min(xs), min(ys), max(xs), max(ys)),
                                                           within):
            best = self.nearest.get(footprint.name)
            if best is not None and lower >= best[0]:
                continue            # cannot come nearer than the nearest so far
            distance, on_vehicle, on_other = clearance(corners, footprint)
            if best is None or distance < best[0]:
                self.nearest[footprint.name] = (distance, sample.time_s, on_vehicle, on_other)

    def result(self):
        bound = self.values['min_m']
        nearest = dict(self.nearest)
        for name, event in self.contacts.items():
            point = None if event.position_m is None else tuple(event.position_m[:2])
            nearest[name] = (0.0, event.time_s, point, point)
        if not nearest:
            return self._result(True, None, f'no obstacle to keep {bound:g} m from')
        # the touched first (by time), then by distance
        ranked = sorted(nearest.items(), key=lambda item: (
            item[0] not in self.contacts, item[1][0], item[1][1] if item[0] in self.contacts
            else 0.0))
        name, (distance, time_s, _, _) = ranked[0]
        others = ''.join(f'; {other} {d:.3f} m at {t:.2f} s' for other, (d, t, _, _)
                         in ranked[1:3])
        # two points per obstacle (vehicle, obstacle), nearest first; none where they overlapped
        points = tuple(p for _, (_, _, on_vehicle, on_other) in ranked if on_vehicle is not None
                       for p in (on_vehicle, on_other))
        if self.contacts:
            return CriterionResult(self.name, self.KIND, False, 0.0, self.UNIT,
                                   f'touched {name} at {time_s:.2f} s (a collision: distance 0; '
                                   f'bound {bound:g} m){others}', points, time_s)
        return CriterionResult(self.name, self.KIND, distance >= bound, distance, self.UNIT,
                               f'closest {distance:.3f} m to {name} at {time_s:.2f} s '
                               f'(bound {bound:g} m){others}', points, time_s)


class MinGap(Criterion):
    """The vehicle keeps a gap to the traffic vehicle ahead of it in its lane (its corridor)."""

    KIND = 'min_gap'
    UNIT = 'm'
    SPECS = (
        ParamSpec('min', 'min_m', 'float', REQUIRED, 'm', 'smallest gap allowed between the '
                  "vehicle's front and the rear of a traffic vehicle ahead of it (its box "
                  "overlapping the corridor of the vehicle's width); touching a traffic vehicle "
                  '(a collision, from any side) is a gap of 0 and fails whatever the bound',
                  ge=0.0),
        ParamSpec('after', 'after_s', 'float', 0.0, 's', 'checked from this simulated time on',
                  ge=0.0),
    )

    def __init__(self, *args):
        super().__init__(*args)
        self.outline = None
        self.traffic = None
        self.worst = None           # (gap, time, other's name, vehicle point, other's point)
        self.contact = None         # the first collision with a traffic vehicle (CollisionEvent)

    def bind(self, scene):
        self.outline = scene.outline(self.vehicle)
        self.traffic = getattr(scene, 'traffic', None)

    def collision(self, event):
        if self.contact is not None or self.traffic is None or \
                event.time_s < self.values['after_s'] - 1e-9:
            return
        if any(name == event.other for name, *_ in self.traffic()):
            self.contact = event

    def observe(self, sample):
        if self.traffic is None or sample.time_s < self.values['after_s'] - 1e-9:
            return
        c, s = math.cos(sample.yaw_rad), math.sin(sample.yaw_rad)
        front = self.outline.x_max_m
        left, right = self.outline.y_max_m, self.outline.y_min_m
        for name, x, y, yaw, length, width in self.traffic():
            dx, dy = x - sample.x_m, y - sample.y_m
            ahead, side = c * dx + s * dy, -s * dx + c * dy     # in the vehicle's frame
            turn = yaw - sample.yaw_rad
            half_across = 0.5 * (abs(math.sin(turn)) * length + abs(math.cos(turn)) * width)
            half_along = 0.5 * (abs(math.cos(turn)) * length + abs(math.sin(turn)) * width)
            if side - half_across >= left or side + half_across <= right:
                continue                # beside the corridor
            if ahead <= 0.0:
                continue                # behind the vehicle's reference point: not ahead
            gap = ahead - half_along - front
            if self.worst is None or gap < self.worst[0]:
                # the gap's ends, on the line along the heading through the other's centre
                # (within the vehicle's width)
                lateral = min(max(side, right), left)

                def world(along, c=c, s=s, x0=sample.x_m, y0=sample.y_m, lateral=lateral):
                    return (x0 + c * along - s * lateral, y0 + s * along + c * lateral)

                self.worst = (gap, sample.time_s, name, world(front), world(front + gap))

    def result(self):
        bound = self.values['min_m']
        if self.traffic is None:
            return self._result(False, None, 'the world has no traffic (traffic: in the world)')
        measured = ''
        if self.worst is not None:
            gap, time_s, name, on_vehicle, on_other = self.worst
            measured = f'smallest gap {gap:.3f} m to {name} at {time_s:.2f} s (bound {bound:g} m)'
        if self.contact is not None:
            event = self.contact
            point = None if event.position_m is None else tuple(event.position_m[:2])
            gap = 0.0 if self.worst is None else min(0.0, self.worst[0])
            ahead = f'; ahead: {measured}' if measured else ''
            return CriterionResult(
                self.name, self.KIND, False, gap, self.UNIT,
                f'touched {event.other} at {event.time_s:.2f} s (a collision: the gap reached '
                f'0 m; bound {bound:g} m){ahead}', () if point is None else (point, point),
                event.time_s, (event.other,))
        if self.worst is None:
            return self._result(True, None, f'no traffic vehicle ahead (bound {bound:g} m)')
        return CriterionResult(self.name, self.KIND, gap >= bound, gap, self.UNIT, measured,
                               (on_vehicle, on_other), time_s, (name,))


COMPARISONS = {'<': operator.lt, '<=': operator.le, '>': operator.gt, '>=': operator.ge,
               '==': operator.eq, '!=': operator.ne}
TOPIC_MODES = ('always', 'eventually', 'final')


def field_value(msg, dotted):
    """
    Return a message field by its dotted name (``header.stamp.sec``, ``twist.twist.linear.x``).

    :raises InvalidParameterError: naming the missing part.
    """
    value = msg
    for part in dotted.split('.'):
        if not hasattr(value, part):
            raise InvalidParameterError(f'field {brief(dotted)}: the message has no {brief(part)}')
        value = getattr(value, part)
    return value


class TopicPredicate(Criterion):
    """A field of a topic's messages compared with a value: always, eventually or at the end."""

    KIND = 'topic'
    SPECS = (
        ParamSpec('topic', 'topic', 'topic', REQUIRED, doc='topic name (absolute)'),
        ParamSpec('type', 'ros_type', 'str', REQUIRED, doc='message type, e.g. '
                  'vehicle_msgs/msg/Float64Stamped'),
        ParamSpec('field', 'field', 'str', REQUIRED, doc='dotted field name, e.g. data or '
                  'twist.twist.linear.x'),
        ParamSpec('op', 'op', 'enum', REQUIRED, choices=tuple(COMPARISONS),
                  doc='comparison: field <op> value'),
        ParamSpec('value', 'value', 'float', REQUIRED, doc='the number compared with'),
        ParamSpec('mode', 'mode', 'enum', 'always', choices=TOPIC_MODES,
                  doc='always (every message), eventually (one message) or final (the last)'),
        ParamSpec('best_effort', 'best_effort', 'bool', False,
                  doc='read the topic best effort (needed for topics published best effort, '
                      "such as the sensors' /scan; a reliable reader does not match them)"),
    )

    def __init__(self, *args):
        super().__init__(*args)
        self.count = 0
        self.last = None
        self.extreme = {}         # '<': (time, largest value), '>': (time, smallest value)
        self.first_bad = None     # (time, value) of the first message that fails
        self.first_good = None    # (time, value) of the first message that passes
        self.error = None

    def message(self, msg, time_s):
        try:
            value = float(field_value(msg, self.values['field']))
        except (InvalidParameterError, TypeError, ValueError) as error:
            self.error = self.error or str(error)
            return
        self.count += 1
        self.last = (time_s, value)
        # '<' keeps the largest value seen, '>' the smallest
        top, bottom = self.extreme.get('<'), self.extreme.get('>')
        if top is None or value > top[1]:
            self.extreme['<'] = (time_s, value)
        if bottom is None or value < bottom[1]:
            self.extreme['>'] = (time_s, value)
        good = COMPARISONS[self.values['op']](value, self.values['value'])
        if good and self.first_good is None:
            self.first_good = (time_s, value)
        if not good and self.first_bad is None:
            self.first_bad = (time_s, value)

    def result(self):
        v = self.values
        what = f'{v["topic"]} {v["field"]} {v["op"]} {v["value"]:g} ({v["mode"]})'
        if self.error is not None:
            return self._result(False, None, f'{what}: {self.error}')
        if not self.count:
            return self._result(False, None, f'{what}: no message received')
        mode = v['mode']
        if mode == 'always':
            passed = self.first_bad is None
            if passed:      # the value that came closest to failing
                time_s, value = self.extreme.get(v['op'][0], self.last)
                detail = f'{what}: all {self.count} messages pass (closest {value:g} at ' \
                         f'{time_s:.2f} s)'
            else:
                time_s, value = self.first_bad
                detail = f'{what}: {value:g} at {time_s:.2f} s fails'
        elif mode == 'eventually':
            passed = self.first_good is not None
            time_s, value = self.first_good if passed else self.last
            detail = (f'{what}: {value:g} at {time_s:.2f} s' if passed else
                      f'{what}: none of {self.count} messages pass (last {value:g})')
        else:
            time_s, value = self.last
            passed = COMPARISONS[v['op']](value, v['value'])
            detail = f'{what}: last {value:g} at {time_s:.2f} s'
        return self._result(passed, value, detail)


CRITERIA = {cls.KIND: cls for cls in (ReachGoal, NoCollision, StayOnPath, MaxSpeed, MeanSpeed,
                                      Clearance, MinGap, TopicPredicate)}


def criterion_specs(kind):
    """Return the full ParamSpec table of a criterion kind (common keys first)."""
    return common_specs() + CRITERIA[kind].SPECS


def build_criteria(specs, duration_s):
    """Instantiate validated CriterionSpecs."""
    return [CRITERIA[s.kind](s.name, s.vehicle, s.values, duration_s) for s in specs]


def criteria_from_list(ctx, data, names, default_vehicle):
    """
    Validate the ``criteria:`` list of a scenario.

    :param ctx: the schema's file context (``fail``, ``validated``, ``lines``).
    :param data: the list.
    :param names: the vehicles of the scenario.
    :param default_vehicle: the vehicle under test.
    :return: tuple of CriterionSpec.
    :raises ScenarioError: naming the line.
    """
    path = ('criteria',)
    if not isinstance(data, list) or not data:
        raise ctx.fail(path, 'criteria must be a non-empty list of {kind: ..., ...}; kinds: '
                             + ', '.join(CRITERIA))
    specs, counts = [], {}
    kinds = ', '.join(sorted(CRITERIA))
    for index, entry in enumerate(data):
        where = path + (index,)
        kind = entry.get('kind') if isinstance(entry, dict) else None
        if isinstance(entry, dict) and 'kind' not in entry:
            raise ctx.fail(where, "a criterion needs 'kind': one of " + kinds)
        if kind not in CRITERIA:
            raise ctx.fail(where + ('kind',) if isinstance(entry, dict) else where,
                           f'criterion kind {brief(kind)}: valid kinds: ' + kinds)
        values = ctx.validated(criterion_specs(kind), entry, where, 'a criterion')
        vehicle = values.pop('vehicle') or default_vehicle
        if vehicle not in names:
            raise ctx.fail(where + ('vehicle',), f'vehicle {brief(vehicle)}: not in the world; '
                                                 f'vehicles: {", ".join(names)}')
        name = values.pop('name')
        values.pop('kind')
        if kind == 'stay_on_path' and len(values['path']) < 2:
            raise ctx.fail(where + ('path',), 'a path needs at least 2 points')
        if not name:
            counts[kind] = counts.get(kind, 0) + 1
        specs.append([kind, name, vehicle, values, line_of(ctx.lines, where)])
    seen = {}
    for spec in specs:
        if not spec[1]:
            seen[spec[0]] = seen.get(spec[0], 0) + 1
            spec[1] = spec[0] if counts[spec[0]] == 1 else f'{spec[0]}_{seen[spec[0]]}'
    names_used = [s[1] for s in specs]
    for spec in specs:
        if names_used.count(spec[1]) > 1:
            raise ctx.fail(('criteria',), f'two criteria are named {brief(spec[1])}')
    return tuple(CriterionSpec(*spec) for spec in specs)


def validate_criterion(kind, data, source='criterion'):
    """Validate one criterion mapping outside a file (tests, Python users): its values."""
    values = validate_table(criterion_specs(kind), dict(data, kind=kind), source)
    for key in ('kind', 'name', 'vehicle'):
        values.pop(key)
    return values
