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
A SUMO network (``.net.xml``) read with ``sumolib``, as a core LaneGraph with its rules.

``sumolib`` (PyPI, in the ``sumo`` extra: ``pip install 'vehicle_sim[sumo]'``) is imported only
when such a map is loaded. The network is read with its internal lanes, its pedestrian
connections and its traffic light programs. What becomes of it:

- **lanes**: every lane of a normal or internal edge that the map's ``vclass`` may use (SUMO's
  permissions; default ``passenger``) is a lane of subtype ``road`` (the lanes the traffic
  drives); a lane of another road vehicle class is a lane of its subtype (:data:`SUBTYPES`:
  ``bus_lane``, ``bicycle_lane``, ``emergency_lane``, else ``restricted_lane``); a sidewalk
  (pedestrians only) is a ``walkway`` area, not a lane; any other lane (rail, ship, a lane that
  allows nothing) is left out with one :class:`SumoNetWarning`. Internal lanes (the paths
  through junctions, ``:J1_0_0``) are lanes.
- **ids**: a lane's id is its place among the network's ``<lane>`` elements as sumolib reads
  them (edges in file order, internal ones included, lanes by index), counting from 1, whatever
  the ``vclass``; its ``name`` is SUMO's lane id (``E0_0``, ``:J1_0_0``), and
  :func:`lane_ids` (or ``LaneGraph.lane_named``) gives the id of a name. The map's other ids lie
  in ranges of their own: boundaries from :data:`BOUNDARY_ID`, stop lines from
  :data:`STOP_LINE_ID`, traffic light groups from :data:`GROUP_ID`, right-of-way rules from
  :data:`RIGHT_OF_WAY_ID`, areas from :data:`AREA_ID` (each + its index).
- **geometry**: the centreline is the lane's shape, its width the lane's; the boundaries are the
  centreline shifted by half the width. Speed limits are the lanes' ``speed``.
- **successors**: through the connections: a lane's successors are its connections' first
  internal lanes (``via``), an internal lane's the next internal lane or the lane it leads to
  (connections without internal lanes: the lane itself). An internal lane too short to have a
  direction (its shape a single point) is skipped and its predecessors lead on to its successors.
- **neighbours and lines**: lanes of one edge are neighbours (index + 1 on the left); the line
  between two lanes of one subtype is dashed (a lane change is allowed), between lanes of two
  subtypes solid, beside a sidewalk a curbstone, and at the edge's outer sides solid. Internal
  lanes have virtual (unpainted) boundaries and no neighbours.
- **signals**: one TrafficLightGroup per (traffic light, link index) whose connections are
  lanes here (``name``: ``'<tls id>:<index>'``), controlling the connections' first internal
  lanes, each with a stop line at its start (the end of the approach lane). SUMO has no lamp
  positions: each group's head (red, yellow, green; an arrow of the connection's direction
  where its approach lane has connections of several directions, else circles) hangs over its
  approach lane at the stop line, :data:`HEAD_HEIGHT_M` up, the heads of one lane side by side
  (left turns on the left). ``LaneRules.programs``: one SignalProgram per traffic light (its
  last program in the file, the one SUMO runs), ``links[i]`` the group of link index ``i``
  (None for a pedestrian crossing's link).
- **right of way**: at every junction without a traffic light, the connections SUMO makes
  major (link state ``M``) have priority over the minor ones (``m``, and ``s``: a stop sign, a
  stop line at the connection's start); all-way stops (``w``) are stop lines with no priority;
  right-before-left and zipper junctions (``=``, ``Z``) and unregulated ones have no rule
  here (their conflicts are served first come first served). Conflicts are the lanes'
  geometric overlaps (core/map/lane_conflicts.py).
- **areas**: sidewalks and walking areas are ``walkway`` areas, crossings ``crosswalk`` areas
  (with the lanes of the edges they cross and the junction's lanes that pass through them),
  junctions' polygons ``junction`` areas (drawn as road surface).
"""

import math
import os
import warnings

import numpy as np

from vehicle_sim.core.map.lane_conflicts import lane_conflicts
from vehicle_sim.core.map.lane_graph import Boundary, Lane, LaneGraph
from vehicle_sim.core.map.lane_polygons import lanes_through
from vehicle_sim.core.map.lane_rules import (
    Bulb,
    LaneRules,
    MapArea,
    RightOfWay,
    StopLine,
    TrafficLightGroup,
)
from vehicle_sim.core.map.signal_programs import SignalProgram
from vehicle_sim.core.specs.errors import InvalidParameterError

EXTRA_HINT = "pip install 'vehicle_sim[sumo]' (or pip install eclipse-sumo sumolib)"

BOUNDARY_ID = 10_000_000
STOP_LINE_ID = 20_000_000
GROUP_ID = 30_000_000
RIGHT_OF_WAY_ID = 40_000_000
AREA_ID = 50_000_000

# The lane subtype of a lane the map's vclass may not use, by the first class it allows.
SUBTYPES = (('bus', 'bus_lane'), ('coach', 'bus_lane'), ('bicycle', 'bicycle_lane'),
            ('emergency', 'emergency_lane'), ('authority', 'emergency_lane'))
# SUMO's road vehicle classes (the others run on rails, water or in the air).
ROAD_CLASSES = frozenset((
    'private', 'emergency', 'authority', 'army', 'vip', 'passenger', 'hov', 'taxi', 'bus',
    'coach', 'delivery', 'truck', 'trailer', 'motorcycle', 'moped', 'bicycle', 'evehicle',
    'scooter', 'custom1', 'custom2'))
WALKING_CLASSES = frozenset(('pedestrian', 'wheelchair'))
# A traffic light head over its approach lane: the bulbs' centres above the road [m], the
# distance between the heads of one lane [m] at most.
HEAD_HEIGHT_M = (('red', 5.6), ('yellow', 5.3), ('green', 5.0))
HEAD_SPACING_M = 0.8
# The connection's direction (SUMO's dir: turn, left, partly left, straight, partly right,
# right) -> the arrow, and the heads' order across a lane (left first).
ARROWS = {'t': 'left_arrow', 'l': 'left_arrow', 'L': 'left_arrow', 's': 'up_arrow',
          'R': 'right_arrow', 'r': 'right_arrow'}
DIRECTION_ORDER = 'tlLsRr'


class SumoNetWarning(UserWarning):
    """Part of a SUMO network is not simulated (named in the message); the rest is loaded."""


class SumoUnavailable(InvalidParameterError):
    """The sumolib package (the ``sumo`` extra) is not installed."""


def _sumolib():
    try:
        import sumolib
    except ImportError:
        raise SumoUnavailable('a SUMO network map needs the sumolib package: '
                              + EXTRA_HINT) from None
    return sumolib


def _warn(message):
    warnings.warn(message, SumoNetWarning, stacklevel=3)


def read_net(path, source):
    """
    Read a ``.net.xml`` with sumolib (internal lanes, pedestrian connections, programs).

    :raises InvalidParameterError: naming ``source`` and the file: missing, unreadable, not a
        SUMO network (the parser's message).
    :raises SumoUnavailable: sumolib is not installed (with the extra to install).
    """
    sumolib = _sumolib()
    if not os.path.isfile(path):
        raise InvalidParameterError(f'{source}: {path}: no such file')
    try:
        with open(path, 'rb') as handle:
            head = handle.read(2)
    except OSError as error:
        raise InvalidParameterError(f'{source}: {path}: cannot be read: '
                                    f'{error.strerror}') from None
    if not head:
        raise InvalidParameterError(f'{source}: {path}: is empty, not a SUMO network')
    try:
        net = sumolib.net.readNet(path, withInternal=True, withPedestrianConnections=True,
                                  withPrograms=True)
    except Exception as error:      # sumolib raises the XML parser's errors and its own
        raise InvalidParameterError(f'{source}: {path}: not a SUMO network that sumolib can '
                                    f'read: {type(error).__name__}: {error}') from None
    return net


def lane_ids(net):
    """Return {SUMO lane id: lane id} of every lane of a sumolib network (module text)."""
    ids, number = {}, 0
    for edge in net.getEdges(withInternal=True):
        for lane in edge.getLanes():
            number += 1
            ids[lane.getID()] = number
    return ids


def _normals(points):
    seg = np.diff(points, axis=0)
    seg /= np.maximum(np.hypot(seg[:, 0], seg[:, 1]), 1e-12)[:, None]
    tangent = np.vstack((seg[:1], seg[:-1] + seg[1:], seg[-1:]))
    tangent /= np.maximum(np.hypot(tangent[:, 0], tangent[:, 1]), 1e-12)[:, None]
    return np.column_stack((-tangent[:, 1], tangent[:, 0]))


def _shape(lane):
    """Return a lane's shape (N, 2) without repeated points, or None when it is a point."""
    points = np.asarray(lane.getShape(), dtype=float).reshape(-1, 2)
    keep = np.ones(len(points), dtype=bool)
    keep[1:] = np.hypot(*np.diff(points, axis=0).T) > 1e-6
    points = points[keep]
    return points if len(points) >= 2 else None


def _strip(points, width):
    """Return the polygon of a polyline swept by ``width`` (left side, then right reversed)."""
    shift = 0.5 * width * _normals(points)
    return np.vstack((points + shift, (points - shift)[::-1]))


def _kind(lane, vclass):
    """Return a lane's subtype, 'walkway' (a sidewalk) or None (not a road lane)."""
    if lane.allows(vclass):
        return 'road'
    allowed = set(lane.getPermissions())
    if allowed and allowed <= WALKING_CLASSES and 'pedestrian' in allowed:
        return 'walkway'
    if not allowed & ROAD_CLASSES:
        return None
    return next((subtype for cls, subtype in SUBTYPES if cls in allowed), 'restricted_lane')


class _NetReader:
    """Collects a network's lanes and rules."""

    def __init__(self, net, vclass, path, source):
        self.net, self.vclass, self.path, self.source = net, vclass, path, source
        self.where = f'{source}: {path}'
        self.ids = lane_ids(net)
        self.sumo = {}          # lane id -> sumolib lane, the lanes of the graph
        self.kinds = {}         # SUMO lane id -> subtype / 'walkway' / None
        self.shapes = {}        # lane id -> its shape
        self.boundary_count = 0
        self.areas = []
        self.skipped = {}       # reason -> [SUMO lane ids]

    def next_boundary(self, points, line_type):
        self.boundary_count += 1
        return Boundary(BOUNDARY_ID + self.boundary_count, points, line_type)

    def area(self, kind, polygon, lanes=()):
        polygon = np.asarray(polygon, dtype=float).reshape(-1, 2)
        if len(polygon) > 1 and np.allclose(polygon[0], polygon[-1]):
            polygon = polygon[:-1]
        if len(polygon) >= 3:
            self.areas.append(MapArea(AREA_ID + len(self.areas) + 1, kind, polygon,
                                      tuple(lanes)))

    def sort_lanes(self):
        """Classify every lane: graph lanes, sidewalks, skipped."""
        for edge in self.net.getEdges(withInternal=True):
            function = edge.getFunction()
            for lane in edge.getLanes():
                name = lane.getID()
                if function in ('crossing', 'walkingarea'):
                    continue
                kind = _kind(lane, self.vclass)
                shape = _shape(lane)
                if kind is None:
                    self.skipped.setdefault('it allows no road vehicle', []).append(name)
                elif shape is None:
                    if function != 'internal':
                        self.skipped.setdefault('its shape is a point', []).append(name)
                    kind = None
                elif kind != 'walkway':
                    self.sumo[self.ids[name]] = lane
                    self.shapes[self.ids[name]] = shape
                self.kinds[name] = kind

    def lanes(self):
        """Return the Lanes (their successors spliced past the skipped internal lanes)."""
        made = []
        for edge in self.net.getEdges(withInternal=True):
            if edge.getFunction() in ('crossing', 'walkingarea'):
                continue
            internal = edge.getFunction() == 'internal'
            members = edge.getLanes()
            bounds = {}
            for lane in members:
                name = lane.getID()
                lane_id = self.ids[name]
                kind = self.kinds.get(name)
                if kind == 'walkway':
                    self.area('walkway', _strip(_shape(lane), lane.getWidth())
                              if _shape(lane) is not None else ())
                if lane_id not in self.sumo:
                    continue
                made.append(self._lane(lane, lane_id, members, internal, bounds))
        return made

    def _line_type(self, below, above):
        """Return the line between two lanes of one edge (None: nothing on that side)."""
        kinds = [None if lane is None else self.kinds.get(lane.getID()) for lane in
                 (below, above)]
        if 'walkway' in kinds:
            return 'curbstone'
        if None in kinds:
            return 'solid'
        return 'dashed' if kinds[0] == kinds[1] else 'solid'

    def _bound(self, members, index, bounds, points, internal):
        """Return the boundary below lane ``index`` of an edge (shared with the one below)."""
        if index in bounds:
            return bounds[index]
        below = members[index - 1] if index > 0 else None
        above = members[index] if index < len(members) else None
        line_type = 'virtual' if internal else self._line_type(below, above)
        bounds[index] = self.next_boundary(points, line_type)
        return bounds[index]

    def _lane(self, lane, lane_id, members, internal, bounds):
        points = self.shapes[lane_id]
        width = lane.getWidth()
        shift = 0.5 * width * _normals(points)
        index = lane.getIndex()
        right = self._bound(members, index, bounds, points - shift, internal)
        left = self._bound(members, index + 1, bounds, points + shift, internal)
        left_lane = right_lane = None
        left_change = right_change = False
        if not internal:
            if index + 1 < len(members) and self.ids[members[index + 1].getID()] in self.sumo:
                left_lane = self.ids[members[index + 1].getID()]
                left_change = left.line_type == 'dashed'
            if index > 0 and self.ids[members[index - 1].getID()] in self.sumo:
                right_lane = self.ids[members[index - 1].getID()]
                right_change = right.line_type == 'dashed'
        try:
            return Lane(lane_id, points, left, right, lane.getSpeed(),
                        successors=self.successors(lane), left_lane=left_lane,
                        right_lane=right_lane, left_change=left_change,
                        right_change=right_change, widths=width, name=lane.getID(),
                        subtype=self.kinds[lane.getID()])
        except InvalidParameterError as error:
            raise InvalidParameterError(f'{self.where}: lane {lane.getID()!r}: '
                                        f'{error}') from None

    def successors(self, lane, seen=()):
        """Return the lane ids a lane leads to (past internal lanes that are not lanes)."""
        found = []
        for connection in lane.getOutgoing():
            via = connection.getViaLaneID()
            target = self.net.getLane(via) if via else connection.getToLane()
            target_id = self.ids.get(target.getID())
            if target_id in self.sumo:
                found.append(target_id)
            elif self.kinds.get(target.getID()) is None and target.getID().startswith(':') \
                    and target.getID() not in seen:        # a skipped point-like internal lane
                found.extend(self.successors(target, seen + (target.getID(),)))
        return list(dict.fromkeys(found))

    def controlled(self, connection):
        """Return the lane id a connection's rule applies to (its first internal lane), or None."""
        via = connection.getViaLaneID()
        if via and self.ids.get(via) in self.sumo:
            return self.ids[via]
        from_id = self.ids.get(connection.getFromLane().getID())
        return from_id if from_id in self.sumo else None

    def connections(self):
        """Yield every connection from a normal lane of the graph, in file order."""
        for edge in self.net.getEdges(withInternal=False):
            for lane in edge.getLanes():
                if self.ids[lane.getID()] in self.sumo:
                    yield from lane.getOutgoing()


def _stop_line(line_id, graph, lane_id, kind, group_id=None):
    """Return a stop line at the start of a lane (or at the end of an approach lane)."""
    lane = graph.lanes[lane_id]
    s_m = 0.0 if lane.name.startswith(':') else lane.length_m
    x, y, yaw = lane.centre_pose(s_m)
    half = 0.5 * lane.widths[0 if s_m == 0.0 else -1]
    nx, ny = -math.sin(yaw) * half, math.cos(yaw) * half
    return StopLine(line_id, lane_id, s_m, [(x + nx, y + ny), (x - nx, y - ny)], kind,
                    group_id)


def _heads(graph, reader, signalled):
    """
    Return {group id: its Bulbs}: a head per group over its approach lane, at the stop line.

    :param signalled: [(group id, connection)] of the groups' connections.
    """
    by_lane = {}
    for group_id, connection in signalled:
        by_lane.setdefault(connection.getFromLane().getID(), []).append(
            (group_id, connection.getDirection()))
    bulbs = {}
    for lane_name, heads in by_lane.items():
        approach = graph.lanes.get(reader.ids[lane_name])
        if approach is None:
            continue
        heads = sorted(dict(heads).items(), key=lambda head: (
            DIRECTION_ORDER.find(head[1]), head[0]))
        arrows = len({ARROWS.get(direction, 'circle') for _, direction in heads}) > 1
        x, y, yaw = approach.centre_pose(approach.length_m)
        width = approach.widths[-1]
        spacing = min(HEAD_SPACING_M, width / max(len(heads), 1))
        for k, (group_id, direction) in enumerate(heads):
            lateral = (0.5 * (len(heads) - 1) - k) * spacing      # + = left, left turns first
            px, py = x - math.sin(yaw) * lateral, y + math.cos(yaw) * lateral
            shape = ARROWS.get(direction, 'circle') if arrows else 'circle'
            bulbs.setdefault(group_id, []).extend(
                Bulb(color, px, py, z, shape) for color, z in HEAD_HEIGHT_M)
    return {group_id: tuple(found) for group_id, found in bulbs.items()}


def _signals(graph, reader):
    """Return (stop lines, groups, programs) of the network's traffic lights."""
    links = {}                              # (tls id, link index) -> [connections]
    for connection in reader.connections():
        tls, index = connection.getTLSID(), connection.getTLLinkIndex()
        if tls and index >= 0 and reader.controlled(connection) is not None:
            links.setdefault((tls, index), []).append(connection)
    order = {tls.getID(): k for k, tls in enumerate(reader.net.getTrafficLights())}
    group_of, stop_lines, groups, signalled = {}, [], [], []
    for key in sorted(links, key=lambda key: (order.get(key[0], len(order)), key[1])):
        group_id = GROUP_ID + len(group_of) + 1
        group_of[key] = group_id
        lines = []
        for connection in links[key]:
            lane_id = reader.controlled(connection)
            if any(line.lane_id == lane_id for line in lines):
                continue
            lines.append(_stop_line(STOP_LINE_ID + len(stop_lines) + len(lines) + 1, graph,
                                    lane_id, 'traffic_light', group_id))
            signalled.append((group_id, connection))
        stop_lines.extend(lines)
        groups.append((group_id, tuple(line.lane_id for line in lines),
                       tuple(line.id for line in lines), f'{key[0]}:{key[1]}'))
    heads = _heads(graph, reader, signalled)
    groups = tuple(TrafficLightGroup(group_id, lanes, lines, heads.get(group_id, ()), name)
                   for group_id, lanes, lines, name in groups)
    programs = []
    for tls in reader.net.getTrafficLights():
        found = list(tls.getPrograms().values())
        if not found:
            continue
        program = found[-1]
        phases = tuple((float(phase.duration), phase.state) for phase in program.getPhases())
        count = max([len(state) for _, state in phases] + [0])
        try:
            programs.append(SignalProgram(
                tls.getID(), tuple(group_of.get((tls.getID(), i)) for i in range(count)),
                phases, float(program.getOffset() or 0.0),
                str(getattr(program, '_id', '0'))))
        except InvalidParameterError as error:
            raise InvalidParameterError(f'{reader.where}: {error}') from None
    return stop_lines, groups, tuple(programs)


def _right_of_way(graph, reader, first_line_id):
    """Return (stop lines, RightOfWay rules) of the junctions without traffic lights."""
    junctions = {}
    for connection in reader.connections():
        if connection.getTLSID():
            continue
        lane_id = reader.controlled(connection)
        if lane_id is None:
            continue
        node = connection.getFrom().getToNode().getID()
        junctions.setdefault(node, []).append((connection.getState(), lane_id))
    stop_lines, rules = [], []
    for node, links in junctions.items():
        priority = tuple(dict.fromkeys(lane for state, lane in links if state == 'M'))
        yielding = tuple(dict.fromkeys(lane for state, lane in links if state in 'ms'))
        lines = []
        for state, lane_id in links:
            if state in 'sw' and not any(line.lane_id == lane_id for line in lines):
                lines.append(_stop_line(first_line_id + len(stop_lines) + len(lines), graph,
                                        lane_id, 'stop_sign'))
        stop_lines.extend(lines)
        if priority and yielding:
            rules.append(RightOfWay(RIGHT_OF_WAY_ID + len(rules) + 1, priority, yielding,
                                    tuple(line.id for line in lines
                                          if line.lane_id in yielding)))
    return stop_lines, rules


def _walking_areas(graph, reader):
    """Add the walking areas, crossings and junction polygons as areas."""
    for edge in reader.net.getEdges(withInternal=True):
        function = edge.getFunction()
        for lane in edge.getLanes():
            if function == 'walkingarea':
                reader.area('walkway', lane.getShape())
            elif function == 'crossing':
                shape = _shape(lane)
                if shape is not None:
                    polygon = _strip(shape, lane.getWidth())
                    crossed = {reader.ids[one.getID()] for crossed_edge in
                               edge.getCrossingEdges() for one in crossed_edge.getLanes()}
                    reader.area('crosswalk', polygon, sorted(
                        set(lanes_through(graph, polygon))
                        | {i for i in crossed if i in graph.lanes}))
    for node in reader.net.getNodes():
        if node.getType() != 'internal':
            reader.area('junction', node.getShape())


def load_sumo_net(path, vclass='passenger', source=None):
    """
    Read a SUMO network into a LaneGraph with its rules (``graph.rules``).

    :param path: the ``.net.xml`` file.
    :param vclass: the SUMO vehicle class of the traffic's lanes.
    :param source: what errors name first (the world file's key); None = 'map'.
    :return: (LaneGraph, the sumolib network).
    :raises InvalidParameterError: naming the file: missing, not a SUMO network, no lane the
        map's vehicles or other road vehicles may use, a lane whose geometry is wrong.
    :raises SumoUnavailable: sumolib is not installed (with the extra to install).
    """
    source = source or 'map'
    net = read_net(path, source)
    reader = _NetReader(net, vclass, path, source)
    reader.sort_lanes()
    lanes = reader.lanes()
    if not lanes:
        raise InvalidParameterError(f'{reader.where}: has no lane a road vehicle may use '
                                    f'(of {sum(1 for _ in reader.ids)} lanes)')
    for reason, names in sorted(reader.skipped.items()):
        shown = ', '.join(names[:5]) + (f', ... ({len(names) - 5} more)'
                                        if len(names) > 5 else '')
        _warn(f'{reader.where}: {len(names)} lane(s) skipped, {reason}: {shown}')
    graph = LaneGraph(lanes, reader.where)
    stop_lines, groups, programs = _signals(graph, reader)
    signs, right_of_way = _right_of_way(graph, reader,
                                        STOP_LINE_ID + len(stop_lines) + 1)
    _walking_areas(graph, reader)
    graph.set_rules(LaneRules(tuple(stop_lines) + tuple(signs), groups, right_of_way,
                              lane_conflicts(graph), reader.areas, programs))
    return graph, net
