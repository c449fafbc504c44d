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
Turns at the intersections of road segments: connector lanes from one road onto another.

Where ``intersection`` segments of two roads share their centre (within ``SAME_CENTRE_M``),
every lane approaching the intersection gets the turns a right-hand-traffic junction allows,
besides going straight on along its own road:

- a right turn from its approach's outermost lane onto the outermost lane leaving to the right;
- a left turn from its innermost lane onto the innermost lane leaving to the left.

A turn is a connector lane: a cubic Bezier curve from the end of the arriving lane to the start
of the leaving lane, tangent to both, its control points at 0.5523 of the way to where their
tangents meet (a quarter circle for a right-angled corner whose legs are equal), with virtual
boundaries (no markings, no lane invasion), the arriving lane's width and the lower of the two
speed limits. Connector ``k`` (in the order found) has id ``CONNECTOR_ID + k`` and boundaries
``CONNECTOR_BOUNDARY_ID + 2 k`` (left) and ``+ 2 k + 1`` (right); each becomes a successor of
its arriving lane, and its leaving lane its successor.

The rules of an intersection (:func:`intersection_rules`; ``LaneGraph.rules``) come from its
segments' ``signals`` and ``stop_signs``:

- every lane arriving at an intersection whose road says ``signals`` or ``stop_signs`` gets a
  stop line across its end (the intersection's entry), id ``STOP_LINE_ID`` + the lane's id, of
  kind 'traffic_light' or 'stop_sign'; an approach without either has no line (its vehicles
  give way at the conflicts themselves, which are there in every case);
- a signalised intersection (every road through it must say ``signals``: a road without lights
  at a signalised intersection is refused) has one TrafficLightGroup per direction of approach,
  id ``GROUP_ID`` + the id of the intersection segment's innermost lane in that direction,
  controlling the arriving lanes; its bulbs are a lamp stack on a pole :data:`KERB_OFFSET_M`
  beyond the right-hand edge of the road at the stop line: red, yellow and green lamp centres
  at :data:`LAMP_HEIGHTS_M` above the road;
- where some roads stop at stop signs and others do not (a two-way stop), one RightOfWay, id
  ``RIGHT_OF_WAY_ID`` + the lowest of the intersection's segment lane ids above, gives the
  arriving lanes without signs priority over those with (and names their stop lines); at an
  all-way stop nobody has priority.
"""

from dataclasses import dataclass
import math
from typing import Dict, List, Tuple

import numpy as np

from vehicle_sim.core.geometry.angles import wrap_angle_rad
from vehicle_sim.core.map.lane_graph import Boundary, Lane
from vehicle_sim.core.map.lane_rules import Bulb, RightOfWay, StopLine, TrafficLightGroup
from vehicle_sim.core.specs.errors import InvalidParameterError

SAME_CENTRE_M = 1.0
CONNECTOR_ID = 1_000_000_000
CONNECTOR_BOUNDARY_ID = 2_000_000_000
KAPPA = 0.5523                  # 4 (sqrt(2) - 1) / 3: a cubic Bezier's quarter circle
TURN_POINTS = 17
STOP_LINE_ID = 3_000_000_000
GROUP_ID = 4_000_000_000
RIGHT_OF_WAY_ID = 5_000_000_000
KERB_OFFSET_M = 1.0             # the signal pole beyond the road's right edge [m]
LAMP_HEIGHTS_M = (('red', 3.2), ('yellow', 2.9), ('green', 2.6))   # lamp centres above the road
CONTROLS = ('signals', 'stop_signs', 'none')


@dataclass(frozen=True)
class Approach:
    """
    One direction of travel through an intersection segment.

    :param road: the road's index (1-based).
    :param centre: the intersection's centre (x, y) [m].
    :param heading_rad: the direction of travel through it.
    :param arriving: ids of the lanes that end at its entry, innermost first.
    :param leaving: ids of the lanes that start at its exit, innermost first.
    :param control: one of :data:`CONTROLS`: what its arriving lanes stop at.
    :param key: the id of the intersection segment's innermost lane in this direction.
    :param name: a readable name (road/segment/direction).
    :param where: the segment in the world file (quoted in errors).
    """

    road: int
    centre: Tuple[float, float]
    heading_rad: float
    arriving: Tuple[int, ...]
    leaving: Tuple[int, ...]
    control: str = 'none'
    key: int = 0
    name: str = ''
    where: str = ''


def _bezier(p0, t0, p3, t1):
    """Return TURN_POINTS points of the turn from p0 (direction t0) to p3 (direction t1)."""
    denom = t0[0] * t1[1] - t0[1] * t1[0]
    gap = p3 - p0
    if abs(denom) < 1e-9:                 # parallel tangents: a third of the gap each
        u = v = float(np.hypot(*gap)) / 3.0
    else:
        u = (gap[0] * t1[1] - gap[1] * t1[0]) / denom       # p0 + u t0 = p3 - v t1
        v = (t0[0] * gap[1] - t0[1] * gap[0]) / denom
        u, v = abs(u), abs(v)
    p1, p2 = p0 + KAPPA * u * t0, p3 - KAPPA * v * t1
    f = np.linspace(0.0, 1.0, TURN_POINTS)[:, None]
    return ((1 - f) ** 3) * p0 + 3 * ((1 - f) ** 2) * f * p1 + 3 * (1 - f) * f * f * p2 \
        + (f ** 3) * p3


def _offset(points, lateral):
    seg = np.diff(points, axis=0)
    seg /= np.hypot(seg[:, 0], seg[:, 1])[:, None]
    tangent = np.vstack((seg[:1], seg[:-1] + seg[1:], seg[-1:]))
    tangent /= np.hypot(tangent[:, 0], tangent[:, 1])[:, None]
    return points + lateral * np.column_stack((-tangent[:, 1], tangent[:, 0]))


def _direction(lane, at_end):
    heading = lane.headings[-1] if at_end else lane.headings[0]
    return np.array([math.cos(heading), math.sin(heading)])


def connector_lanes(approaches: List[Approach], lanes: Dict[int, Lane]) -> List[Lane]:
    """
    Return the connector lanes of the intersections among ``approaches``.

    Each connector is added to the successors of its arriving lane in ``lanes``.
    """
    connectors = []
    for a in approaches:
        if not a.arriving:
            continue
        for b in approaches:
            if b.road == a.road or not b.leaving or \
                    math.hypot(a.centre[0] - b.centre[0], a.centre[1] - b.centre[1]) > \
                    SAME_CENTRE_M:
                continue
            turn = wrap_angle_rad(b.heading_rad - a.heading_rad)
            if math.radians(45.0) <= abs(turn) <= math.radians(135.0):
                outer = -1 if turn < 0.0 else 0          # right: outermost; left: innermost
                arriving = lanes[a.arriving[outer]]
                connector = _connector(arriving, lanes[b.leaving[outer]], len(connectors))
                arriving.successors = arriving.successors + (connector.id,)
                connectors.append(connector)
    return connectors


def _connector(arriving, leaving, k):
    p0, p3 = arriving.centerline[-1], leaving.centerline[0]
    points = _bezier(p0, _direction(arriving, True), p3, _direction(leaving, False))
    width = arriving.widths[-1]
    left = Boundary(CONNECTOR_BOUNDARY_ID + 2 * k, _offset(points, 0.5 * width), 'virtual')
    right = Boundary(CONNECTOR_BOUNDARY_ID + 2 * k + 1, _offset(points, -0.5 * width),
                     'virtual')
    return Lane(CONNECTOR_ID + k, points, left, right,
                min(arriving.speed_limit_mps, leaving.speed_limit_mps), (leaving.id,),
                widths=width, name=f'turn {arriving.name} -> {leaving.name}')


def _intersections(approaches):
    """Return the approaches grouped by intersection (centres within SAME_CENTRE_M)."""
    groups: List[List[Approach]] = []
    for approach in approaches:
        for group in groups:
            x, y = group[0].centre
            if math.hypot(approach.centre[0] - x, approach.centre[1] - y) <= SAME_CENTRE_M:
                group.append(approach)
                break
        else:
            groups.append([approach])
    return groups


def _stop_line(lane, kind, group_id=None):
    x, y, heading = lane.xs[-1], lane.ys[-1], lane.headings[-1]
    nx, ny = -math.sin(heading) * 0.5 * lane.widths[-1], math.cos(heading) * 0.5 * lane.widths[-1]
    return StopLine(STOP_LINE_ID + lane.id, lane.id, lane.length_m,
                    [(x + nx, y + ny), (x - nx, y - ny)], kind, group_id)


def _lamps(lane):
    """Return the Bulbs of the lamp stack beside the end of an approach's outermost lane."""
    x, y, heading = lane.xs[-1], lane.ys[-1], lane.headings[-1]
    out = 0.5 * lane.widths[-1] + KERB_OFFSET_M
    px, py = x + math.sin(heading) * out, y - math.cos(heading) * out
    return tuple(Bulb(color, px, py, z) for color, z in LAMP_HEIGHTS_M)


def intersection_rules(approaches: List[Approach], graph, source='roads'):
    """
    Return the stop lines, traffic light groups and right of way of the intersections.

    :param approaches: every Approach of the roads' intersection segments.
    :param graph: the roads' LaneGraph.
    :raises InvalidParameterError: a road without ``signals`` through a signalised intersection.
    """
    stop_lines, groups, right_of_way = [], [], []
    for approaches_here in _intersections(approaches):
        signalled = [a for a in approaches_here if a.control == 'signals']
        if signalled and len(signalled) < len(approaches_here):
            other = next(a for a in approaches_here if a.control != 'signals')
            x, y = signalled[0].centre
            raise InvalidParameterError(
                f"{other.where}: field 'signals' is false, but {signalled[0].where} signals "
                f'the intersection at ({x:.1f}, {y:.1f}): every road through it must say '
                'signals: true')
        priority, yielding, yield_lines = [], [], []
        for approach in approaches_here:
            lanes = [graph.lanes[i] for i in approach.arriving]
            if not lanes:
                continue
            if approach.control == 'signals':
                group_id = GROUP_ID + approach.key
                lines = [_stop_line(lane, 'traffic_light', group_id) for lane in lanes]
                groups.append(TrafficLightGroup(group_id, approach.arriving,
                                                tuple(line.id for line in lines),
                                                _lamps(lanes[-1]), approach.name))
                stop_lines.extend(lines)
            elif approach.control == 'stop_signs':
                lines = [_stop_line(lane, 'stop_sign') for lane in lanes]
                stop_lines.extend(lines)
                yielding.extend(approach.arriving)
                yield_lines.extend(line.id for line in lines)
            else:
                priority.extend(approach.arriving)
        if priority and yielding:
            right_of_way.append(RightOfWay(
                RIGHT_OF_WAY_ID + min(a.key for a in approaches_here), tuple(priority),
                tuple(yielding), tuple(yield_lines)))
    return tuple(stop_lines), tuple(groups), tuple(right_of_way)
