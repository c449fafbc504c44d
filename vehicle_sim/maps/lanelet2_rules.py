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
A Lanelet2 map's regulatory elements and areas as the lane graph's rules (core/map/lane_rules.py).

Lanelet2's own elements come from the lanelet2 map; Autoware's (which the PyPI ``lanelet2`` has
no classes for, so it leaves them out) are read from the file's ``<relation>`` elements here.
Every element applies to the lanes whose lanelet refers to it (the lanelet's direction; a
two-way lanelet's inverted lane gets none):

- ``traffic_light`` (Lanelet2's, with Autoware's ``light_bulbs``): a TrafficLightGroup (the
  element's id) of the lanes, a stop line on each at its ``ref_line`` (none: the lane's end),
  the bulbs of its ``light_bulbs`` line strings (their points' ``color`` and ``arrow`` tags, the
  height above the lane; bulbs the map puts on the ground, without ``ele`` tags, are lifted
  4.5 m); a light without bulbs gets red, yellow and green ones (its subtype's
  colours) stacked over the middle of its line string, ``height`` metres tall (default 1 m), its
  bottom at the line's height, or 4.5 m above the lane where the line lies on the ground.
  A group that only crosswalk lanelets refer to is a pedestrians' signal: no lanes, its bulbs;
- ``traffic_sign`` (Lanelet2's): a stop sign (``stop_sign``, German ``de206``) or a yield sign
  (``yield``, ``de205``) is a stop line on each lane at its ``ref_line`` (none: the lane's end);
  other signs are not simulated (speed limit signs act through the lanes' speed limits);
- ``right_of_way`` (Lanelet2's): a RightOfWay (priority and yield lanes), the yield lanes' stop
  lines at its ``ref_line``;
- ``road_marking`` (Autoware): its stop_line (``refers``) is a stop line on each lane;
- ``crosswalk`` (Autoware): the crosswalk's area (its ``crosswalk_polygon``, else the crosswalk
  lanelet's) crossed by the lanes that refer to it, each with a yield stop line at ``ref_line``;
- ``detection_area``, ``no_stopping_area``, ``no_parking_area``, ``bus_stop_area``,
  ``speed_bump`` (Autoware): areas of their kind, drawn, not simulated;
- ``speed_limit`` (Lanelet2's): the lanes' speed limits (lanelet2_map.py);
- any other type (``virtual_traffic_light``, ``roundabout``, ...): skipped.

Each type drawn only or skipped gets one :class:`~vehicle_sim.maps.lanelet2_map.Lanelet2MapWarning`
naming how many and their ids, as does every stop line that does not lie on its lane (skipped).
Conflicts are those of Lanelet2's routing graph (``RoutingGraph.conflicting``) between lanes
that neither follow nor diverge from each other, with the arc-length ranges where the two lanes'
areas overlap (core/map/lane_conflicts.py). Crosswalk and walkway lanelets and Lanelet2's areas
(parking, keepout, building, ...; Autoware's parking_lot polygons as parking) are areas.
"""

import copy
from dataclasses import replace
from types import SimpleNamespace
import xml.etree.ElementTree as ElementTree

import numpy as np

from vehicle_sim.core.map.lane_conflicts import lane_conflicts
from vehicle_sim.core.map.lane_polygons import lanes_through
from vehicle_sim.core.map.lane_rules import (
    Bulb,
    LaneRules,
    MapArea,
    RightOfWay,
    STOP_LINE_TOLERANCE_M,
    StopLine,
    TrafficLightGroup,
)
from vehicle_sim.maps import lanelet2_primitives as l2

# Autoware's regulatory elements that are areas here (drawn, not simulated): the role of their
# polygons.
AREA_ELEMENTS = ('detection_area', 'no_stopping_area', 'no_parking_area', 'bus_stop_area',
                 'speed_bump')
STOP_SIGNS = ('stop_sign', 'de206', 'us_R1-1')
YIELD_SIGNS = ('yield', 'yield_sign', 'de205', 'us_R1-2')
# Autoware's polygons (ways with area=yes) kept as areas: their type -> the area's kind.
POLYGON_KINDS = {'parking_lot': 'parking', 'hatched_road_markings': 'hatched_road_markings'}
_ARROWS = {'left': 'left_arrow', 'up_left': 'left_arrow', 'right': 'right_arrow',
           'up_right': 'right_arrow', 'up': 'up_arrow', 'down': 'down_arrow'}
LIGHT_HEIGHT_M = 1.0            # a traffic light without a height tag [m]
LIGHT_ON_POLE_M = 4.5           # its bottom above the lane when the map puts it on the ground [m]


def _autoware_elements(path, ids):
    """Return {id: (tags, [(member type, ref, role)])} of the file's relations among ``ids``."""
    found = {}
    if not ids:
        return found
    for _, element in ElementTree.iterparse(path, events=('end',)):
        if element.tag == 'relation':
            rel_id = int(element.get('id', '0'))
            if rel_id in ids:
                tags = {t.get('k'): t.get('v') for t in element.iter('tag')}
                members = [(m.get('type'), int(m.get('ref')), m.get('role'))
                           for m in element.iter('member')]
                found[rel_id] = (tags, members)
            element.clear()
        elif element.tag in ('node', 'way'):
            element.clear()
    return found


class _Builder:
    """Collects the rules of one map (stop line ids kept unique)."""

    def __init__(self, lanelet_map, graph, path, source):
        self.map, self.graph, self.path, self.source = lanelet_map, graph, path, source
        self.stop_lines, self.groups, self.right_of_way, self.areas = [], [], [], []
        self.area_ids = set()
        self.used_ids = set()
        # ids for more stop lines on one line string: above the map's (lanelet2 gives the
        # primitives it makes ids near 2**63: left out)
        self.next_id = 1 + max([p.id for layer in (lanelet_map.laneletLayer,
                                                   lanelet_map.lineStringLayer)
                                for p in layer if p.id < 2 ** 53] + [0])
        self.off_lane = []
        self.lanes_of = {}      # regulatory element id -> [lane ids referring to it], sorted
        for lanelet in sorted(lanelet_map.laneletLayer, key=lambda one: one.id):
            if lanelet.id in graph.lanes:
                for element in lanelet.regulatoryElements:
                    self.lanes_of.setdefault(element.id, []).append(lanelet.id)

    def stop_line(self, lane_id, line, kind, element_id, group_id=None):
        """
        Add a stop line on a lane where ``line`` (a line string; None: the lane's end) is.

        A line that lies before the lane (at the end of a lane leading to it, as Lanelet2 maps
        draw the stop lines of lanes inside an intersection) is put on that lane.

        :return: the StopLine, or None when the line lies on neither (noted in off_lane).
        """
        if line is None:
            lane = self.graph.lanes[lane_id]
            s_m = lane.length_m
        else:
            points = np.array([(p.x, p.y) for p in line], dtype=float)
            for on_id in (lane_id,) + self.graph.predecessors[lane_id]:
                lane = self.graph.lanes[on_id]
                s_m = _crossing_s(lane, points)
                if s_m is None:
                    s_m = _nearest_s(lane, points)
                if s_m is not None:
                    break
            if s_m is None:
                self.off_lane.append((line.id, element_id, lane_id))
                return None
        s_m = min(max(s_m, 0.0), lane.length_m)
        line_id = line.id if line is not None and line.id not in self.used_ids else self.next_id
        if line_id == self.next_id:
            self.next_id += 1
        self.used_ids.add(line_id)
        x, y, yaw = lane.centre_pose(s_m)
        k = lane.segment_at(s_m)
        half = 0.5 * lane.width_at(k, s_m - lane.s0[k])
        nx, ny = -np.sin(yaw) * half, np.cos(yaw) * half
        stop = StopLine(line_id, lane.id, float(s_m),
                        [(x + nx, y + ny), (x - nx, y - ny)], kind, group_id)
        self.stop_lines.append(stop)
        return stop

    def area(self, area_id, kind, points, lanes=()):
        """Add an area (a polygon of 3 points or more); an id seen before is not added again."""
        if area_id in self.area_ids:
            return
        points = np.array(points, dtype=float).reshape(-1, 2)
        if len(points) > 1 and np.allclose(points[0], points[-1]):
            points = points[:-1]
        if len(points) >= 3:
            self.areas.append(MapArea(area_id, kind, points, tuple(lanes)))
            self.area_ids.add(area_id)


def _crossing_s(lane, points):
    """Return the least arc length where a polyline crosses a lane's centreline, or None."""
    c = np.column_stack((lane.xs, lane.ys))
    a0, a1 = c[:-1, None, :], c[1:, None, :]
    b0, b1 = points[None, :-1, :], points[None, 1:, :]
    da, db = a1 - a0, b1 - b0
    denom = da[..., 0] * db[..., 1] - da[..., 1] * db[..., 0]
    rel = b0 - a0
    with np.errstate(divide='ignore', invalid='ignore'):
        t = (rel[..., 0] * db[..., 1] - rel[..., 1] * db[..., 0]) / denom
        u = (rel[..., 0] * da[..., 1] - rel[..., 1] * da[..., 0]) / denom
    hit = (denom != 0) & (t >= 0) & (t <= 1) & (u >= 0) & (u <= 1)
    if not hit.any():
        return None
    k, _ = np.nonzero(hit)
    s = np.asarray(lane.s0)[k] + t[hit] * np.asarray(lane.seg_len)[k]
    return float(s.min())


def _nearest_s(lane, points):
    """
    Return the arc length of a line's point nearest a lane's centreline, or None.

    None when no point of the line (sampled every 0.25 m) lies on the lane's area, within
    STOP_LINE_TOLERANCE_M of its sides and ends.
    """
    samples = []
    for a, b in zip(points[:-1], points[1:]):
        count = max(1, int(np.ceil(np.hypot(*(b - a)) / 0.25)))
        samples += [a + (b - a) * i / count for i in range(count)]
    samples.append(points[-1])
    best, k, last = None, 0, lane.segment_count - 1
    for x, y in samples:
        k, t, offset = lane.walk(float(x), float(y), k)
        if (k == 0 and t < -STOP_LINE_TOLERANCE_M) or \
                (k == last and t > lane.seg_len[k] + STOP_LINE_TOLERANCE_M):
            continue
        if abs(offset) <= 0.5 * lane.width_at(k, t) + STOP_LINE_TOLERANCE_M and \
                (best is None or abs(offset) < best[0]):
            best = (abs(offset), lane.s0[k] + t)
    return None if best is None else best[1]


def _ground_z(lanelet_map, lanelet_ids):
    """Return the height of the first of these lanelets' centreline ends (0 when none)."""
    for lanelet_id in lanelet_ids:
        if lanelet_id in lanelet_map.laneletLayer:
            return float(lanelet_map.laneletLayer[lanelet_id].centerline[-1].z)
    return 0.0


def _bulbs(element, ground_z):
    """Return the Bulbs of a traffic light regulatory element, heights above ``ground_z``."""
    bulbs = []
    parameters = element.parameters
    for line in (parameters['light_bulbs'] if 'light_bulbs' in parameters else []):
        lamps = [point for point in line
                 if l2.tags_of(point).get('color') in ('red', 'yellow', 'green')]
        heights = [point.z - ground_z for point in lamps]
        lift = LIGHT_ON_POLE_M if heights and max(heights) < 1.0 else 0.0   # no ele tags
        for point, height in zip(lamps, heights):
            tags = l2.tags_of(point)
            bulbs.append(Bulb(tags['color'], point.x, point.y, height + lift,
                              _ARROWS.get(tags.get('arrow', ''), 'circle')))
    if bulbs:
        return tuple(bulbs)
    for light in element.trafficLights:
        points = [(p.x, p.y, p.z) for p in getattr(light, 'outerBoundPolygon', lambda: light)()]
        if not points:
            continue
        tags = l2.tags_of(light)
        colors = [c for c in tags.get('subtype', '').split('_') if c in ('red', 'yellow', 'green')]
        colors = colors or ['red', 'yellow', 'green']
        try:
            height = float(tags.get('height', LIGHT_HEIGHT_M))
        except ValueError:
            height = LIGHT_HEIGHT_M
        x, y, z = np.mean(points, axis=0)
        bottom = z - ground_z if z - ground_z >= 1.0 else LIGHT_ON_POLE_M
        step = height / len(colors)
        bulbs += [Bulb(color, float(x), float(y), float(bottom + step * (len(colors) - i - 0.5)))
                  for i, color in enumerate(colors)]     # the first colour on top
    return tuple(bulbs)


def _polygon(primitive):
    return [(p.x, p.y) for p in primitive]


def rules_of(lanelet_map, routing_graph, graph, walking, unknown, path, source):
    """
    Return the LaneRules of a lanelet2 map whose lanes are ``graph``.

    :param lanelet_map: the lanelet2 map (projected).
    :param routing_graph: its vehicles' routing graph.
    :param graph: the LaneGraph of its lanes.
    :param walking: its crosswalk and walkway lanelets.
    :param unknown: {type: [ids]} of the regulatory elements lanelet2 left out (Autoware's).
    :param path: the file (its relations are read for ``unknown``).
    :param source: what warnings name first.
    """
    import lanelet2.core as core
    build = _Builder(lanelet_map, graph, path, source)
    walking_ids = {ll.id for ll in walking}
    for element in lanelet_map.regulatoryElementLayer:
        lanes = build.lanes_of.get(element.id, [])
        if isinstance(element, core.TrafficLight):
            _traffic_light(build, element, lanes, walking_ids)
        elif isinstance(element, core.RightOfWay):
            _right_of_way(build, element)
        elif isinstance(element, core.TrafficSign):
            sign = str(element.type())
            kind = 'stop_sign' if sign in STOP_SIGNS else 'yield' if sign in YIELD_SIGNS else None
            if kind is not None:
                lines = list(element.refLines()) or [None]
                for lane_id in lanes:
                    for line in lines:
                        build.stop_line(lane_id, line, kind, element.id)
    crosswalk_polygons = _autoware(build, _autoware_elements(path, {
        i for ids in unknown.values() for i in ids}))
    for lanelet in walking:
        kind = l2.WALKING_SUBTYPES[l2.tags_of(lanelet).get('subtype')]
        polygon = crosswalk_polygons.get(lanelet.id) or (
            _polygon(lanelet.leftBound) + _polygon(lanelet.rightBound)[::-1])
        build.area(lanelet.id, kind, polygon, lanes_through(graph, polygon)
                   if kind == 'crosswalk' else ())
    for area in lanelet_map.areaLayer:
        kind = l2.tags_of(area).get('subtype', l2.tags_of(area).get('type', 'area'))
        build.area(area.id, kind, _polygon(area.outerBoundPolygon()))
    for polygon in lanelet_map.polygonLayer:
        kind = POLYGON_KINDS.get(l2.tags_of(polygon).get('type'))
        if kind is not None:
            build.area(polygon.id, kind, _polygon(polygon))
    if build.off_lane:
        l2.warn(f'{source}: {path}: {l2.counted(build.off_lane, "stop line")} off the lanes '
                'that refer to them, skipped: ' + '; '.join(
                 f'line {line} of regulatory element {element} on lanelet {lane}'
                 for line, element, lane in build.off_lane[:5]))
    return LaneRules(build.stop_lines, build.groups, build.right_of_way,
                     _conflicts(routing_graph, lanelet_map, graph), build.areas)


def _traffic_light(build, element, lanes, walking_ids):
    stops = [build.stop_line(lane_id, element.stopLine, 'traffic_light', element.id, element.id)
             for lane_id in lanes]
    stops = [stop for stop in stops if stop is not None]
    controlled = tuple(dict.fromkeys(stop.lane_id for stop in stops))   # in order, once each
    ground = _ground_z(build.map, [abs(i) for i in controlled] or sorted(walking_ids))
    build.groups.append(TrafficLightGroup(element.id, controlled,
                                          tuple(stop.id for stop in stops),
                                          _bulbs(element, ground), str(element.id)))


def _right_of_way(build, element):
    lanes = build.graph.lanes
    priority = tuple(l2.lane_id_of(ll) for ll in element.rightOfWayLanelets()
                     if l2.lane_id_of(ll) in lanes)
    yielding = tuple(l2.lane_id_of(ll) for ll in element.yieldLanelets()
                     if l2.lane_id_of(ll) in lanes)
    if not priority or not yielding:
        return
    stops = tuple(s.id for s in (build.stop_line(lane_id, element.stopLine, 'yield', element.id)
                                 for lane_id in yielding if element.stopLine is not None)
                  if s is not None)
    build.right_of_way.append(RightOfWay(element.id, priority, yielding, stops))


def _autoware(build, elements):
    """Add Autoware's elements; warn once per type drawn only or skipped; return crosswalks."""
    crosswalk_polygons = {}
    drawn, skipped = {}, {}
    line_layer, polygon_layer = build.map.lineStringLayer, build.map.polygonLayer
    for element_id, (tags, members) in sorted(elements.items()):
        subtype = tags.get('subtype', '')
        lanes = build.lanes_of.get(element_id, [])
        ways = [(ref, role) for kind, ref, role in members if kind == 'way']
        if subtype == 'road_marking':
            for ref, role in ways:
                if role == 'refers' and ref in line_layer and \
                        l2.tags_of(line_layer[ref]).get('type') == 'stop_line':
                    for lane_id in lanes:
                        build.stop_line(lane_id, line_layer[ref], 'road_marking', element_id)
        elif subtype == 'crosswalk':
            for ref, role in ways:
                if role == 'ref_line' and ref in line_layer:
                    for lane_id in lanes:
                        build.stop_line(lane_id, line_layer[ref], 'yield', element_id)
            polygon = next((_polygon(polygon_layer[ref] if ref in polygon_layer
                                     else line_layer[ref]) for ref, role in ways
                            if role == 'crosswalk_polygon'
                            and (ref in polygon_layer or ref in line_layer)), None)
            for kind, ref, role in members:
                if kind == 'relation' and role == 'refers' and polygon is not None:
                    crosswalk_polygons[ref] = polygon
        elif subtype in AREA_ELEMENTS:
            drawn.setdefault(subtype, []).append(element_id)
            for ref, role in ways:
                if role == 'refers' and (ref in polygon_layer or ref in line_layer):
                    primitive = polygon_layer[ref] if ref in polygon_layer else line_layer[ref]
                    build.area(ref, subtype, _polygon(primitive), lanes)
        else:
            skipped.setdefault(subtype or '(no subtype)', []).append(element_id)
    where = f'{build.source}: {build.path}'
    for subtype, ids in sorted(drawn.items()):
        l2.warn(f'{where}: {l2.counted(ids, subtype + " regulatory element")} '
                f'{l2.id_list(ids)} drawn as areas only: the simulator does not act on them')
    for subtype, ids in sorted(skipped.items()):
        l2.warn(f'{where}: {l2.counted(ids, subtype + " regulatory element")} '
                f'{l2.id_list(ids)} skipped: the simulator does not use them')
    return crosswalk_polygons


def _conflicts(routing_graph, lanelet_map, graph):
    """
    Return the Conflicts of the routing graph's conflicting lanelets, each pair once.

    Lanelet2 names the pairs; their ranges are core/map/lane_conflicts.py's, from the lanes'
    areas (computed for the lanes of those pairs only; a pair whose areas only touch is left
    out, as are forks: lanes leaving one lane).
    """
    lanes = graph.lanes
    pairs = set()
    for lane in lanes.values():
        if abs(lane.id) not in lanelet_map.laneletLayer:
            continue
        lanelet = lanelet_map.laneletLayer[abs(lane.id)]
        if lane.id < 0:
            lanelet = lanelet.invert()
        for other in routing_graph.conflicting(lanelet):
            other_id = l2.lane_id_of(other)
            if other_id in lanes and other_id != lane.id and not (
                    set(graph.predecessors[lane.id]) & set(graph.predecessors[other_id])):
                pairs.add((min(lane.id, other_id), max(lane.id, other_id)))
    if not pairs:
        return ()
    involved = {i for pair in pairs for i in pair}
    only = {}                       # the lanes of the pairs, their references among them
    for lane_id in involved:
        lane = copy.copy(lanes[lane_id])
        lane.successors = tuple(i for i in lane.successors if i in involved)
        lane.left_lane = lane.left_lane if lane.left_lane in involved else None
        lane.right_lane = lane.right_lane if lane.right_lane in involved else None
        only[lane_id] = lane
    found = []
    for conflict in lane_conflicts(SimpleNamespace(lanes=only)):
        if (conflict.lane_id, conflict.other_id) in pairs:
            common = set(lanes[conflict.lane_id].successors) & set(
                lanes[conflict.other_id].successors)
            found.append(replace(conflict, kind='merging' if common else 'crossing'))
    return tuple(found)
