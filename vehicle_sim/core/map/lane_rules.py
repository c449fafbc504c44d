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
The rules of a lane map: stop lines, traffic light groups, right of way, conflicts and areas.

These are the lane graph's facts beyond its lanes (a :class:`LaneRules` in ``LaneGraph.rules``,
empty for a map that has none). Every lane map fills them the same way, so that what reads them
(the signal plan, the traffic, the lane state, the criteria, the ROS topics and the drawing)
never asks which kind of map they came from:

- a :class:`StopLine` is where vehicles on one lane stop: an arc length ``s_m`` on the lane (the
  front of a stopped vehicle stays before it) and the line as drawn; its ``kind`` says why
  (a traffic light, a stop sign, a yield sign, a road marking);
- a :class:`TrafficLightGroup` is one signal: the lanes it controls, their stop lines and the
  bulbs that show its state (Autoware's traffic light regulatory element; its id is the group
  id on ``/perception/traffic_light_recognition/traffic_signals``);
- a :class:`RightOfWay` names the lanes that have priority and those that yield to them;
- a :class:`Conflict` is a pair of lanes whose areas overlap where neither follows the other
  (they cross or merge at an intersection), with the arc-length range of the overlap on each;
- a :class:`MapArea` is a polygon with a kind: a crosswalk or walkway (walking areas), a
  parking lot, keep-out zone or building, a junction's surface, or a regulatory element's area
  the simulator only draws (a detection area, a bus stop, ...);
- ``programs``: the map's own signal programs (a SUMO network's, core/map/signal_programs.py
  SignalProgram), which the world's signal controller runs instead of a fixed-time plan.

Coordinates are world metres (x east, y north), as the lanes'.
"""

from collections import Counter
from dataclasses import dataclass, field
import math
from typing import Dict, Optional, Sequence, Tuple

import numpy as np

from vehicle_sim.core.specs.errors import InvalidParameterError

# Why vehicles stop at a line.
STOP_KINDS = ('traffic_light', 'stop_sign', 'yield', 'road_marking')
# The colours of a bulb, and the states of a signal group (Autoware's TrafficLightElement
# colours; 'off': dark, as a group is before its plan starts or when a scenario switches it off).
BULB_COLORS = ('red', 'yellow', 'green')
SIGNAL_STATES = ('red', 'yellow', 'green', 'off')
# What a bulb shows: a full circle or an arrow (Autoware's TrafficLightElement shapes).
BULB_SHAPES = ('circle', 'left_arrow', 'right_arrow', 'up_arrow', 'down_arrow')
CONFLICT_KINDS = ('crossing', 'merging')
# Walking areas first: the kinds pedestrians may use.
WALKING_AREA_KINDS = ('crosswalk', 'walkway')

# A stop line lies on its lane when its midpoint is within this of the lane's area [m].
STOP_LINE_TOLERANCE_M = 0.5


def _polyline(data, what, at_least=2):
    points = np.asarray(data, dtype=float)
    if points.ndim != 2 or points.shape[0] < at_least or points.shape[1] < 2:
        raise InvalidParameterError(f'{what}: needs at least {at_least} points [x, y]')
    points = points[:, :2]
    if not np.all(np.isfinite(points)):
        raise InvalidParameterError(f'{what}: every coordinate must be finite')
    return points


@dataclass(frozen=True, eq=False)
class StopLine:
    """
    Where vehicles on one lane stop.

    :param id: the line's id (the map's line string id; generated ids for ``roads:``).
    :param lane_id: the lane it stops.
    :param s_m: the line's arc length on the lane [m]: a stopping vehicle's front stays before it.
    :param points: the line as drawn, (N, 2) world points [m], N >= 2.
    :param kind: one of :data:`STOP_KINDS`.
    :param group_id: the TrafficLightGroup that governs it (kind 'traffic_light'), else None.
    """

    id: int
    lane_id: int
    s_m: float
    points: np.ndarray
    kind: str
    group_id: Optional[int] = None

    def __post_init__(self):
        if self.kind not in STOP_KINDS:
            raise InvalidParameterError(f'stop line {self.id}: kind {self.kind!r} is not one of '
                                        + ', '.join(STOP_KINDS))
        if not (isinstance(self.s_m, (int, float)) and math.isfinite(self.s_m)):
            raise InvalidParameterError(f'stop line {self.id}: s = {self.s_m!r} must be finite')
        object.__setattr__(self, 'points', _polyline(self.points, f'stop line {self.id}'))


@dataclass(frozen=True)
class Bulb:
    """One lamp of a traffic light: its colour, shape and position (world, z up) [m]."""

    color: str
    x_m: float
    y_m: float
    z_m: float
    shape: str = 'circle'

    def __post_init__(self):
        if self.color not in BULB_COLORS:
            raise InvalidParameterError(f'bulb colour {self.color!r} is not one of '
                                        + ', '.join(BULB_COLORS))
        if self.shape not in BULB_SHAPES:
            raise InvalidParameterError(f'bulb shape {self.shape!r} is not one of '
                                        + ', '.join(BULB_SHAPES))
        if not all(math.isfinite(v) for v in (self.x_m, self.y_m, self.z_m)):
            raise InvalidParameterError('a bulb position must be finite')


@dataclass(frozen=True)
class TrafficLightGroup:
    """
    One signal: the lanes it controls, their stop lines, its bulbs.

    :param id: the group id (the map's traffic light regulatory element id; generated ids for
        ``roads:``), as ``traffic_light_group_id`` on ROS.
    :param lanes: ids of the lanes it controls.
    :param stop_lines: ids of their stop lines (StopLine.group_id is this group's id).
    :param bulbs: the Bulbs of its lights (may be empty: a signal no camera sees).
    :param name: a readable name ('' = none).
    """

    id: int
    lanes: Tuple[int, ...]
    stop_lines: Tuple[int, ...] = ()
    bulbs: Tuple[Bulb, ...] = ()
    name: str = ''


@dataclass(frozen=True)
class RightOfWay:
    """
    A right-of-way rule: the lanes with priority and the lanes that yield to them.

    :param id: the rule's id (the map's right_of_way regulatory element id, or generated).
    :param priority_lanes: ids of the lanes that go first.
    :param yield_lanes: ids of the lanes that give way.
    :param stop_lines: ids of the yield lanes' stop lines (may be empty: they yield at the
        conflict itself).
    """

    id: int
    priority_lanes: Tuple[int, ...]
    yield_lanes: Tuple[int, ...]
    stop_lines: Tuple[int, ...] = ()


@dataclass(frozen=True)
class Conflict:
    """
    Two lanes whose areas overlap where neither follows the other (both directions are listed).

    :param lane_id: one lane.
    :param other_id: the other lane.
    :param s_m: (first, last) arc length on ``lane_id`` of the overlap [m].
    :param other_s_m: (first, last) arc length on ``other_id`` of the overlap [m].
    :param kind: 'crossing' (their paths cross) or 'merging' (they end on one lane).
    """

    lane_id: int
    other_id: int
    s_m: Tuple[float, float]
    other_s_m: Tuple[float, float]
    kind: str = 'crossing'

    def reversed(self) -> 'Conflict':
        """Return the same conflict seen from the other lane."""
        return Conflict(self.other_id, self.lane_id, self.other_s_m, self.s_m, self.kind)


@dataclass(frozen=True, eq=False)
class MapArea:
    """
    A polygon of the map with a kind (crosswalk, walkway, parking, keepout, building, ...).

    :param id: the map's id of the area (or of its regulatory element).
    :param kind: what it is: a walking area (:data:`WALKING_AREA_KINDS`), an area's subtype,
        or the type of a regulatory element drawn as an area (e.g. 'detection_area').
    :param polygon: (N, 2) world points [m], N >= 3, not closed (the last point is not the first).
    :param lanes: ids of the lanes that cross it (a crosswalk's road lanes), else ().
    """

    id: int
    kind: str
    polygon: np.ndarray
    lanes: Tuple[int, ...] = ()

    def __post_init__(self):
        object.__setattr__(self, 'polygon', _polyline(self.polygon, f'{self.kind} {self.id}', 3))

    @property
    def walkable(self) -> bool:
        return self.kind in WALKING_AREA_KINDS


@dataclass(eq=False)
class LaneRules:
    """
    The rules of a lane map (every field may be empty).

    :param stop_lines: the StopLines.
    :param groups: the TrafficLightGroups.
    :param right_of_way: the RightOfWay rules.
    :param conflicts: the Conflicts, each pair once (:meth:`conflicts_of` gives both ways).
    :param areas: the MapAreas.
    :param programs: the map's signal programs (core/map/signal_programs.py SignalProgram);
        () = none: the groups run a fixed-time plan (core/map/signal_plan.py).
    """

    stop_lines: Tuple[StopLine, ...] = ()
    groups: Tuple[TrafficLightGroup, ...] = ()
    right_of_way: Tuple[RightOfWay, ...] = ()
    conflicts: Tuple[Conflict, ...] = ()
    areas: Tuple[MapArea, ...] = ()
    programs: Tuple = ()
    _on_lane: Dict[int, Tuple[StopLine, ...]] = field(default_factory=dict, repr=False)
    _conflicts_of: Dict[int, Tuple[Conflict, ...]] = field(default_factory=dict, repr=False)

    def __post_init__(self):
        self.stop_lines = tuple(self.stop_lines)
        self.groups = tuple(self.groups)
        self.right_of_way = tuple(self.right_of_way)
        self.conflicts = tuple(self.conflicts)
        self.areas = tuple(self.areas)
        self.programs = tuple(self.programs)
        on_lane: Dict[int, list] = {}
        for line in self.stop_lines:
            on_lane.setdefault(line.lane_id, []).append(line)
        self._on_lane = {lane: tuple(sorted(lines, key=lambda line: line.s_m))
                         for lane, lines in on_lane.items()}
        both: Dict[int, list] = {}
        for conflict in self.conflicts:
            both.setdefault(conflict.lane_id, []).append(conflict)
            both.setdefault(conflict.other_id, []).append(conflict.reversed())
        self._conflicts_of = {lane: tuple(c) for lane, c in both.items()}
        # by id: an engine driving a city's signals looks up hundreds of groups a step
        self._group_of = {group.id: group for group in self.groups}

    @property
    def empty(self) -> bool:
        return not (self.stop_lines or self.groups or self.right_of_way or self.conflicts
                    or self.areas)

    def group(self, group_id) -> TrafficLightGroup:
        """Return a group by id; InvalidParameterError naming the id and the groups if none."""
        try:
            group = None if isinstance(group_id, bool) else self._group_of.get(group_id)
        except TypeError:                   # an unhashable id is no group's
            group = None
        if group is not None:
            return group
        known = ', '.join(str(g.id) for g in self.groups) or 'none'
        raise InvalidParameterError(f'traffic light group {group_id!r} is not in the map '
                                    f'(its groups: {known})')

    def stop_lines_on(self, lane_id) -> Tuple[StopLine, ...]:
        """Return the stop lines of a lane, by increasing arc length."""
        return self._on_lane.get(lane_id, ())

    def conflicts_of(self, lane_id) -> Tuple[Conflict, ...]:
        """Return the conflicts of a lane, each seen from it (``lane_id`` is this lane)."""
        return self._conflicts_of.get(lane_id, ())

    def next_stop_line(self, graph, lane_id, s_m, horizon_m, route: Sequence[int] = ()):
        """
        Return the first stop line ahead of arc length ``s_m`` on a lane, and the way to it.

        Searches the lane beyond ``s_m``, then its successors: the ``route``'s next lanes
        where given, else the first successor, up to ``horizon_m`` of travel.

        :return: (StopLine, distance along the lanes from ``s_m`` to the line [m]) or None.
        """
        lane = graph.lanes.get(lane_id)
        start_m = -s_m                  # the distance to the start of ``lane``
        route = list(route)
        while lane is not None and start_m <= horizon_m:
            for line in self.stop_lines_on(lane.id):
                distance = start_m + line.s_m
                if distance >= 0.0:
                    return (line, distance) if distance <= horizon_m else None
            start_m += lane.length_m
            following = route.pop(0) if route else (
                lane.successors[0] if lane.successors else None)
            lane = None if following is None else graph.lanes.get(following)
        return None

    def check(self, graph, source='lane map'):
        """
        Check the rules against a LaneGraph; raise InvalidParameterError naming what is wrong.

        Every lane named exists; ids are unique per kind; a stop line lies on its lane
        (``s_m`` within it, its midpoint within half the lane's width plus
        :data:`STOP_LINE_TOLERANCE_M` of the centreline there); a traffic light stop line names
        a group that lists it and the group's lanes include the line's lane.
        """
        def known(lane_id, what):
            if lane_id not in graph.lanes:
                raise InvalidParameterError(f'{source}: {what}: lane {lane_id} is not in the map')

        for kind, items in (('stop line', self.stop_lines), ('traffic light group', self.groups),
                            ('right of way', self.right_of_way), ('area', self.areas)):
            counts = Counter(item.id for item in items)
            twice = sorted(i for i, n in counts.items() if n > 1)
            if twice:
                raise InvalidParameterError(f'{source}: {kind} id(s) used twice: {twice}')
        groups = {group.id: group for group in self.groups}
        for line in self.stop_lines:
            what = f'stop line {line.id}'
            known(line.lane_id, what)
            lane = graph.lanes[line.lane_id]
            if not 0.0 <= line.s_m <= lane.length_m:
                raise InvalidParameterError(
                    f'{source}: {what}: s = {line.s_m:.3f} m is off lane {lane.id} '
                    f'(0 .. {lane.length_m:.3f} m)')
            mid_x, mid_y = line.points.mean(axis=0)
            position, _ = graph.locate_on(lane.id, float(mid_x), float(mid_y), near_s_m=line.s_m)
            allowed = 0.5 * position.width_m + STOP_LINE_TOLERANCE_M
            if abs(position.offset_m) > allowed:
                raise InvalidParameterError(
                    f'{source}: {what}: its middle lies {abs(position.offset_m):.2f} m from '
                    f"lane {lane.id}'s centreline (at most {allowed:.2f} m): it is off its lane")
            if line.kind == 'traffic_light':
                group = groups.get(line.group_id)
                if group is None:
                    raise InvalidParameterError(f'{source}: {what}: traffic light group '
                                                f'{line.group_id!r} is not in the map')
                if line.lane_id not in group.lanes or line.id not in group.stop_lines:
                    raise InvalidParameterError(
                        f'{source}: {what}: group {group.id} does not list it and its lane')
        for group in self.groups:
            for lane_id in group.lanes:
                known(lane_id, f'traffic light group {group.id}')
        for rule in self.right_of_way:
            for lane_id in rule.priority_lanes + rule.yield_lanes:
                known(lane_id, f'right of way {rule.id}')
        for conflict in self.conflicts:
            known(conflict.lane_id, 'conflict')
            known(conflict.other_id, 'conflict')
        for area in self.areas:
            for lane_id in area.lanes:
                known(lane_id, f'{area.kind} {area.id}')
        for program in self.programs:
            for group_id in program.links:
                if group_id is not None and group_id not in groups:
                    raise InvalidParameterError(
                        f'{source}: signal program {program.tls_id!r}: traffic light group '
                        f'{group_id} is not in the map')

