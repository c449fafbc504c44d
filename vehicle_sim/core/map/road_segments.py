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
Roads built from segments in a world file, turned into the LaneGraph a Lanelet2 map gives too.

The segments are those of Webots' worlds: StraightRoadSegment, CurvedRoadSegment and a simple
RoadIntersection.

A world's ``roads:`` is a list of roads. Each road starts at a pose and is a chain of segments
joined end to start: ``straight`` (a length), ``arc`` (a radius and a signed angle, + = left)
and ``intersection`` (a straight piece whose lines are virtual, so that a crossing road can run
through it)::

    roads:
      - name: main
        start: {x: 0.0, y: 0.0, yaw: 0.0}
        lanes: 2                # lanes in the direction of the chain (on its right)
        backward_lanes: 2       # lanes the other way (on its left); 0 = one-way
        lane_width: 3.5
        speed_limit: 13.9       # m/s; a segment may set its own
        segments:
          - {type: straight, length: 200.0}
          - {type: arc, radius: 50.0, angle: 90.0}
          - {type: intersection, length: 12.0}

The chain's line (the reference line) separates the two directions; forward lanes lie on its
right, backward lanes on its left (right-hand traffic). Lane ``i`` counts from the reference
line outwards. Every lane of a segment continues in the same lane of the next segment; a
``closed`` road's last segment continues in its first (its end must meet its start).

Ids: road ``r`` (1-based), segment ``j`` (0-based): forward lane ``i`` is
``r * 100000 + j * 100 + 1 + i``, backward lane ``i`` is ``... + 51 + i``, the boundary at
``m`` lane widths left of the reference line ``... + 30 + m``. A boundary's points run along the
chain. Where intersection segments of two roads share their centre, turn lanes connect them
(core/map/road_intersections.py: ids from 1e9); its stop lines, signal groups and right of way
(``signals``/``stop_signs``) and every pair of conflicting lanes (core/map/lane_conflicts.py)
are the graph's rules (``LaneGraph.rules``).
"""

from dataclasses import dataclass
import math
from typing import Optional, Tuple

import numpy as np

from vehicle_sim.core.geometry.angles import wrap_angle_rad
from vehicle_sim.core.geometry.frames import Pose
from vehicle_sim.core.map.lane_conflicts import lane_conflicts
from vehicle_sim.core.map.lane_graph import (
    Boundary,
    Lane,
    LaneGraph,
    line_crossable,
    LINE_TYPES,
)
from vehicle_sim.core.map.lane_rules import LaneRules
from vehicle_sim.core.map.road_intersections import (
    Approach,
    connector_lanes,
    intersection_rules,
)
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.param_spec import (
    parameter_table_markdown,
    ParamSpec,
    REQUIRED,
    validate_table,
)
from vehicle_sim.core.specs.value_text import brief

SEGMENT_TYPES = ('straight', 'arc', 'intersection')
MAX_LANES = 8
CHORD_ERROR_M = 0.005           # largest gap between an arc and its polyline
CLOSE_GAP_M = 0.05              # a closed road's end must meet its start within this
CLOSE_TURN_RAD = math.radians(0.5)

ROAD_SPECS = (
    ParamSpec('name', 'name', 'str', None, optional=True, doc="the road's name; null = "
              "'road<index>'"),
    ParamSpec('start', 'start', 'pose', Pose(), 'm, rad', 'pose of the start of the reference '
              'line {x, y, yaw}', choices=('x', 'y', 'yaw')),
    ParamSpec('lanes', 'lanes', 'int', 1, '', 'lanes in the direction of the chain (right of '
              'the reference line)', ge=1, le=MAX_LANES),
    ParamSpec('backward_lanes', 'backward_lanes', 'int', None, '', 'lanes the other way (left '
              'of it); null = as many as lanes; 0 = one-way', ge=0, le=MAX_LANES,
              optional=True),
    ParamSpec('lane_width', 'lane_width_m', 'float', 3.5, 'm', 'width of every lane', gt=0.0),
    ParamSpec('speed_limit', 'speed_limit_mps', 'float', 13.9, 'm/s', 'speed limit of its '
              'lanes (a segment may set its own)', gt=0.0),
    ParamSpec('edge_line', 'edge_line', 'enum', 'solid', choices=LINE_TYPES,
              doc='line type of the outer edges'),
    ParamSpec('centre_line', 'centre_line', 'enum', 'solid', choices=LINE_TYPES,
              doc='line type between the two directions'),
    ParamSpec('lane_line', 'lane_line', 'enum', 'dashed', choices=LINE_TYPES,
              doc='line type between lanes of one direction'),
    ParamSpec('closed', 'closed', 'bool', False, doc="the last segment continues in the first "
              "(its end must meet the road's start)"),
    ParamSpec('segments', 'segments', 'raw', REQUIRED, doc='the segments, joined end to start '
              '(tables below)', check=lambda v: None if isinstance(v, list) and v else
              'must be a non-empty list of segments'),
)


def _segment_common(kind):
    return (
        ParamSpec('type', 'type', 'enum', kind, choices=SEGMENT_TYPES,
                  doc='straight, arc or intersection'),
        ParamSpec('speed_limit', 'speed_limit_mps', 'float', None, 'm/s', "this segment's "
                  "speed limit; null = the road's", gt=0.0, optional=True),
    )


_LENGTH = ParamSpec('length', 'length_m', 'float', REQUIRED, 'm', 'length along the '
                    'reference line', gt=0.0)
_LANE_LINE = ParamSpec('lane_line', 'lane_line', 'enum', None, choices=LINE_TYPES,
                       optional=True, doc="line type between lanes here; null = the road's")

SEGMENT_SPECS = {
    'straight': _segment_common('straight') + (_LENGTH, _LANE_LINE),
    'arc': _segment_common('arc') + (
        ParamSpec('radius', 'radius_m', 'float', REQUIRED, 'm', 'radius of the reference line',
                  gt=0.0),
        ParamSpec('angle', 'angle_deg', 'float', REQUIRED, 'deg', 'turn, + = left',
                  ge=-359.0, le=359.0,
                  check=lambda v: 'must not be 0' if v == 0 else None),
        _LANE_LINE),
    'intersection': _segment_common('intersection') + (
        _LENGTH,
        ParamSpec('signals', 'signals', 'bool', False, doc='traffic lights: one signal group per '
                  'direction of approach, a stop line at the entry of every arriving lane; every '
                  'road through the intersection must say so'),
        ParamSpec('stop_signs', 'stop_signs', 'bool', False, doc="this road's approaches stop "
                  'at a stop sign (a stop line at the entry; the roads without give them way)')),
}


@dataclass(frozen=True)
class SegmentSpec:
    """One validated segment: type, length or arc, speed limit and lane line (None = road's)."""

    type: str
    speed_limit_mps: Optional[float]
    length_m: float = 0.0
    radius_m: float = 0.0
    angle_deg: float = 0.0
    lane_line: Optional[str] = None
    signals: bool = False
    stop_signs: bool = False


@dataclass(frozen=True)
class RoadSpec:
    """One validated road of ``roads:``."""

    name: str
    start: Pose
    lanes: int
    backward_lanes: int
    lane_width_m: float
    speed_limit_mps: float
    edge_line: str
    centre_line: str
    lane_line: str
    closed: bool
    segments: Tuple[SegmentSpec, ...]


def roads_markdown():
    """Return the key tables of ``roads:`` (a road, then each segment type) for the docs."""
    parts = ['#### Keys of a road\n\n', parameter_table_markdown(ROAD_SPECS, 'key')]
    for kind, specs in SEGMENT_SPECS.items():
        parts.append(f'\n#### Segment `{kind}`\n\n' + parameter_table_markdown(specs, 'key'))
    return ''.join(parts)


def _segment(data, where):
    if not isinstance(data, dict):
        raise InvalidParameterError(f'{where}: a segment must be a mapping, got {brief(data)}')
    kind = data.get('type', REQUIRED)
    if kind not in SEGMENT_SPECS:
        what = 'is required' if kind is REQUIRED else f'= {brief(kind)}: unknown segment type'
        raise InvalidParameterError(f"{where}: field 'type' {what}; valid: "
                                    + ', '.join(SEGMENT_TYPES))
    segment = SegmentSpec(**validate_table(SEGMENT_SPECS[kind], data, where, what='a segment'))
    if segment.signals and segment.stop_signs:
        raise InvalidParameterError(f"{where}: fields 'signals' and 'stop_signs' are both true: "
                                    'an intersection has traffic lights or stop signs')
    return segment


def roads_from_list(data, source) -> Tuple[RoadSpec, ...]:
    """
    Validate a world's ``roads:`` list (names unique; arcs wider than the road).

    :raises InvalidParameterError: naming the source, the road, the segment and the field.
    """
    if not isinstance(data, list) or not data:
        raise InvalidParameterError(f'{source}: must be a non-empty list of roads, got '
                                    f'{brief(data)}')
    roads = []
    for index, entry in enumerate(data):
        where = f'{source}[{index}]'
        values = validate_table(ROAD_SPECS, entry, where, what='a road')
        values['name'] = values['name'] or f'road{index}'
        if values['backward_lanes'] is None:
            values['backward_lanes'] = values['lanes']
        values['segments'] = tuple(_segment(item, f'{where}.segments[{j}]')
                                   for j, item in enumerate(values['segments']))
        road = RoadSpec(**values)
        widest = max(road.lanes, road.backward_lanes) * road.lane_width_m
        for j, segment in enumerate(road.segments):
            if segment.type == 'arc' and segment.radius_m <= widest:
                raise InvalidParameterError(
                    f"{where}.segments[{j}]: field 'radius' = {segment.radius_m:g}: must be > "
                    f'{widest:g} m (the width of the road on one side of its reference line)')
        roads.append(road)
    names = [road.name for road in roads]
    twice = sorted({name for name in names if names.count(name) > 1})
    if twice:
        raise InvalidParameterError(f'{source}: two roads are named {brief(twice[0])}')
    return tuple(roads)


def _segment_line(pose, segment, lateral_m):
    """Return the (N, 2) points of a segment's line at a lateral offset (+ = left)."""
    x, y, yaw = pose
    if segment.type != 'arc':
        heading = np.array([yaw, yaw])
        along = np.array([0.0, segment.length_m])
        px, py = x + along * math.cos(yaw), y + along * math.sin(yaw)
    else:
        turn = math.radians(segment.angle_deg)
        sign = 1.0 if turn > 0.0 else -1.0
        step = 2.0 * math.sqrt(2.0 * CHORD_ERROR_M / (segment.radius_m + abs(lateral_m)))
        pieces = max(1, math.ceil(abs(turn) / step))
        heading = yaw + turn * np.linspace(0.0, 1.0, pieces + 1)
        cx = x - sign * segment.radius_m * math.sin(yaw)
        cy = y + sign * segment.radius_m * math.cos(yaw)
        px = cx + sign * segment.radius_m * np.sin(heading)
        py = cy - sign * segment.radius_m * np.cos(heading)
    return np.column_stack((px - lateral_m * np.sin(heading), py + lateral_m * np.cos(heading)))


def _segment_end(pose, segment):
    x, y, yaw = pose
    if segment.type != 'arc':
        return (x + segment.length_m * math.cos(yaw), y + segment.length_m * math.sin(yaw), yaw)
    end = _segment_line(pose, segment, 0.0)[-1]
    return (float(end[0]), float(end[1]), yaw + math.radians(segment.angle_deg))


def _lane_id(road_index, j, backward, i):
    return road_index * 100000 + j * 100 + (51 if backward else 1) + i


def _line_type(road, segment, m):
    """Line type of the boundary ``m`` lane widths left of the reference line."""
    if segment.type == 'intersection':
        return 'virtual'
    if m == -road.lanes or m == road.backward_lanes:
        return road.edge_line
    if m == 0:
        return road.centre_line
    return segment.lane_line or road.lane_line


def _road_lanes(road, road_index, source):
    w = road.lane_width_m
    pose = (road.start.x_m, road.start.y_m, road.start.yaw_rad)
    count = len(road.segments)
    lanes = []
    for j, segment in enumerate(road.segments):
        nxt = (j + 1) % count if (road.closed or j + 1 < count) else None
        prv = (j - 1) % count if (road.closed or j > 0) else None
        limit = segment.speed_limit_mps or road.speed_limit_mps
        bounds = {m: Boundary(road_index * 100000 + j * 100 + 30 + m,
                              _segment_line(pose, segment, m * w), _line_type(road, segment, m))
                  for m in range(-road.lanes, road.backward_lanes + 1)}
        for i in range(road.lanes):                     # forward: right of the reference line
            left, right = bounds[-i], bounds[-(i + 1)]
            lanes.append(Lane(
                _lane_id(road_index, j, False, i), _segment_line(pose, segment, -(i + 0.5) * w),
                left, right, limit,
                () if nxt is None else (_lane_id(road_index, nxt, False, i),),
                _lane_id(road_index, j, False, i - 1) if i > 0 else None,
                _lane_id(road_index, j, False, i + 1) if i + 1 < road.lanes else None,
                line_crossable(left.line_type, False), line_crossable(right.line_type, True),
                widths=w, name=f'{road.name}/{j}/+{i}'))
        for i in range(road.backward_lanes):            # backward: left of it, reversed
            left, right = bounds[i], bounds[i + 1]
            lanes.append(Lane(
                _lane_id(road_index, j, True, i),
                _segment_line(pose, segment, (i + 0.5) * w)[::-1], left, right, limit,
                () if prv is None else (_lane_id(road_index, prv, True, i),),
                _lane_id(road_index, j, True, i - 1) if i > 0 else None,
                _lane_id(road_index, j, True, i + 1) if i + 1 < road.backward_lanes else None,
                line_crossable(left.line_type, True), line_crossable(right.line_type, False),
                widths=w, name=f'{road.name}/{j}/-{i}'))
        pose = _segment_end(pose, segment)
    if road.closed:
        gap = math.hypot(pose[0] - road.start.x_m, pose[1] - road.start.y_m)
        turn = abs(wrap_angle_rad(pose[2] - road.start.yaw_rad))
        if gap > CLOSE_GAP_M or turn > CLOSE_TURN_RAD:
            raise InvalidParameterError(
                f'{source}: road {road.name!r} is closed but its end ({pose[0]:.3f}, '
                f'{pose[1]:.3f}, yaw {math.degrees(pose[2]):.2f} deg) misses its start by '
                f'{gap:.3f} m and {math.degrees(turn):.2f} deg (allowed {CLOSE_GAP_M} m, '
                f'{math.degrees(CLOSE_TURN_RAD)} deg)')
    return lanes


def lane_graph_from_roads(roads, source='roads') -> LaneGraph:
    """
    Return the LaneGraph of validated roads (``roads_from_list``).

    :raises InvalidParameterError: a closed road whose end misses its start.
    """
    lanes = []
    for index, road in enumerate(roads):
        lanes.extend(_road_lanes(road, index + 1, source))
    by_id = {lane.id: lane for lane in lanes}
    approaches = [approach for index, road in enumerate(roads)
                  for approach in _approaches(road, index + 1, by_id, source)]
    graph = LaneGraph(lanes + connector_lanes(approaches, by_id), source)
    stop_lines, groups, right_of_way = intersection_rules(approaches, graph, source)
    graph.set_rules(LaneRules(stop_lines=stop_lines, groups=groups, right_of_way=right_of_way,
                              conflicts=lane_conflicts(graph)))
    return graph


def _approaches(road, r, lanes, source):
    """Yield the Approaches (both directions) of a road's intersection segments."""
    count = len(road.segments)
    for j, segment in enumerate(road.segments):
        if segment.type != 'intersection':
            continue
        reference = lanes[_lane_id(r, j, False, 0)].left.points     # the reference line
        (x0, y0), (x1, y1) = reference[0], reference[-1]
        centre, heading = (0.5 * (x0 + x1), 0.5 * (y0 + y1)), math.atan2(y1 - y0, x1 - x0)
        prv = (j - 1) % count if (road.closed or j > 0) else None
        nxt = (j + 1) % count if (road.closed or j + 1 < count) else None

        def ids(k, backward, n):
            return () if k is None else tuple(_lane_id(r, k, backward, i) for i in range(n))
        control = 'signals' if segment.signals else (
            'stop_signs' if segment.stop_signs else 'none')
        where = f'{source}[{r - 1}].segments[{j}]'
        yield Approach(r, centre, heading, ids(prv, False, road.lanes),
                       ids(nxt, False, road.lanes), control, _lane_id(r, j, False, 0),
                       f'{road.name}/{j}/+', where)
        yield Approach(r, centre, heading + math.pi, ids(nxt, True, road.backward_lanes),
                       ids(prv, True, road.backward_lanes), control, _lane_id(r, j, True, 0),
                       f'{road.name}/{j}/-', where)
