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
A Lanelet2 ``.osm`` map read with the ``lanelet2`` package, as a core LaneGraph with its rules.

``lanelet2`` (PyPI) is optional: ``pip install 'vehicle_sim[lanelet2]'``; it is imported only
when a lanelet2 map is loaded. What becomes of the file:

- the lanes are the lanelets a vehicle may drive on (Lanelet2's German traffic rules for
  vehicles, ``canPass``: subtypes road, highway, play_street, exit) and the road-like lanelets
  of :data:`OTHER_LANE_SUBTYPES` (road shoulders, bicycle and bus lanes, ...); each lane keeps
  its subtype (``Lane.subtype``; traffic drives road and highway lanes only). A lanelet that is
  not one-way is two lanes, the inverted one with the negated id;
- successors and left/right neighbours of the vehicles' lanes are those of Lanelet2's routing
  graph for those rules: ``following``, ``left``/``right`` (a lane change allowed) and
  ``adjacentLeft``/``adjacentRight`` (a neighbour, no lane change); the other lanes' successors
  are the lanes that start where they end (the same two bound points), without neighbours;
- crosswalk and walkway lanelets are walking areas, and Lanelet2's areas (parking, keepout,
  building, ...) are areas of the rules (``LaneGraph.rules.areas``, lanelet2_rules.py); a lanelet
  of any other subtype (rail, ...) is skipped with one warning naming the subtype and its ids;
- centrelines are Lanelet2's (``lanelet.centerline``); widths are measured between the bounds
  (a taper, where the bounds meet, has width 0 there);
- boundary line types come from the line strings' ``type``/``subtype`` tags (line_thin and
  line_thick: their subtype, solid, dashed, solid_solid, ...; curbstone; road_border;
  guard_rail, wall and fence: wall; virtual);
- a lanelet's speed limit is Lanelet2's (its ``speed_limit`` tag or a speed limit regulatory
  element) where it has either, else the map's ``default_speed_limit``;
- regulatory elements become the lane graph's rules: vehicle_sim/maps/lanelet2_rules.py.

Lanelet2's robust loading gives the map and a list of errors. The PyPI package does not know
Autoware's regulatory element types (road_marking, crosswalk, detection_area, ...): lanelet2
leaves them out, and lanelet2_rules.py reads them from the file itself; every other error is
one warning (:class:`Lanelet2MapWarning`) listing them, and the map is loaded without the
primitives named. A map is refused only when it cannot be read at all, has no lane, is larger
than ``MAX_OSM_BYTES`` (lanelet2_file.py: the file's checks, Autoware's node tags), or a vehicle
lane's geometry is wrong (naming the lanelet).

The projectors are described in core/map/lanelet2_params.py (and docs/lanes.md).
"""

import math
import os
import re
import tempfile

from vehicle_sim.core.geometry.geodesy import GeodeticOrigin
from vehicle_sim.core.map.lane_graph import Boundary, Lane, LaneGraph
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.units import kmh_to_mps
from vehicle_sim.maps.lanelet2_file import (
    check_lat_lon,
    check_near_origin,
    check_osm,
    lat_lon_unused,
    local_positions_as_lat_lon,
    origin_hint,
    use_local_tags,
    UTM_ZONE_ERROR,
)
from vehicle_sim.maps.lanelet2_primitives import (  # noqa: F401  (Lanelet2MapWarning: users')
    counted,
    id_list,
    lane_id_of,
    Lanelet2MapWarning,
    tags_of,
    WALKING_SUBTYPES,
    warn,
)
from vehicle_sim.maps.lanelet2_rules import rules_of

EXTRA_HINT = "pip install 'vehicle_sim[lanelet2]' (or pip install lanelet2)"

_LINE_SUBTYPES = ('solid', 'dashed', 'solid_solid', 'dashed_solid', 'solid_dashed',
                  'dashed_dashed')
_LINE_TYPES_BY_TAG = {'curbstone': 'curbstone', 'road_border': 'road_border',
                      'guard_rail': 'wall', 'wall': 'wall', 'fence': 'wall',
                      'virtual': 'virtual'}

# Road-like lanelet subtypes that vehicles may not use under Lanelet2's rules but that are lanes
# here (with their subtype): Lanelet2's and Autoware's (its extra lanelet subtypes).
OTHER_LANE_SUBTYPES = ('road_shoulder', 'bicycle_lane', 'bus_lane', 'emergency_lane',
                       'roadside_lane', 'road', 'highway', 'play_street', 'exit')

# lanelet2's words for a regulatory element type it has no class for, and for a reference to one.
_UNKNOWN_RULE = re.compile(r'Error parsing primitive (-?\d+): Creating a regulatory element of '
                           r'type (\S+) failed: No regulatory element found that implements')
_PRIMITIVE = re.compile(r'Error parsing primitive (-?\d+)')
_MISSING_ID = re.compile(r'Error parsing primitive (-?\d+): Failed to get id (-?\d+) from map')


class Lanelet2Unavailable(InvalidParameterError):
    """The lanelet2 package is not installed."""


def _lanelet2():
    try:
        import lanelet2
        import lanelet2.core
        import lanelet2.io
        import lanelet2.projection
        import lanelet2.routing
        import lanelet2.traffic_rules
    except ImportError:
        raise Lanelet2Unavailable('a lanelet2 map needs the lanelet2 package: '
                                  + EXTRA_HINT) from None
    return lanelet2


def line_type_of(attributes):
    """Return the core line type of a Lanelet2 line string's tags (a mapping)."""
    kind = attributes.get('type', '')
    if kind in ('line_thin', 'line_thick'):
        subtype = attributes.get('subtype', 'solid')
        return subtype if subtype in _LINE_SUBTYPES else 'solid'
    return _LINE_TYPES_BY_TAG.get(kind, 'none')


def _projector(lanelet2, projector, origin):
    where = lanelet2.io.Origin(origin.latitude_deg, origin.longitude_deg, origin.altitude_m)
    if projector == 'utm':
        return lanelet2.projection.UtmProjector(where)
    if projector == 'autoware_local':     # x, y: the local tags; Mercator keeps z = ele as is
        return lanelet2.projection.MercatorProjector(lanelet2.io.Origin(0.0, 0.0, 0.0))
    return lanelet2.projection.LocalCartesianProjector(where)


def _sorted_errors(errors):
    """
    Split lanelet2's error list: (unknown regulatory element types, other errors).

    :return: ({type: [ids]} of the regulatory elements lanelet2 has no class for, the other
        errors' texts). A lanelet's reference to one of those elements is no error here (its
        element is read from the file); the first error is lanelet2's heading, left out.
    """
    unknown, refs, others = {}, [], []
    for text in (str(e).strip() for e in errors):
        found = _UNKNOWN_RULE.search(text)
        if found:
            unknown.setdefault(found.group(2), []).append(int(found.group(1)))
            continue
        missing = _MISSING_ID.search(text)
        if missing:
            refs.append((int(missing.group(2)), text))
        elif not text.startswith('Errors ocurred while parsing'):
            others.append(text.lstrip('- '))
    skipped = {i for ids in unknown.values() for i in ids}
    others += [text.lstrip('- ') for ref, text in refs if ref not in skipped]
    return unknown, others


def _centerline(lanelet):
    """
    Return Lanelet2's centreline of a lanelet, from the bounds' start to their end.

    Lanelet2 draws the centreline of a taper (its bounds meeting at the end) from the meeting
    point back: such a centreline is turned round.
    """
    points = [(p.x, p.y) for p in lanelet.centerline]
    left, right = lanelet.leftBound, lanelet.rightBound
    start = (0.5 * (left[0].x + right[0].x), 0.5 * (left[0].y + right[0].y))
    if math.dist(points[-1], start) < math.dist(points[0], start):
        points.reverse()
    return points


def _boundary(line):
    return Boundary(line.id, [(p.x, p.y) for p in line], line_type_of(tags_of(line)))


def _speed_limit_mps(rules, lanelet, vehicle, default_mps):
    tags = lanelet.attributes
    regulated = any(element.attributes['subtype'] == 'speed_limit'
                    for element in lanelet.regulatoryElements
                    if 'subtype' in element.attributes)
    if vehicle and ('speed_limit' in tags or regulated):
        limit = kmh_to_mps(rules.speedLimit(lanelet).speedLimit)  # lanelet2's Python: km/h
    elif 'speed_limit' in tags:
        try:
            limit = kmh_to_mps(float(tags['speed_limit']))
        except ValueError:
            limit = default_mps
    else:
        limit = default_mps
    return limit if math.isfinite(limit) and limit > 0.0 else default_mps


def load_lanelet2(path, origin=GeodeticOrigin(), projector='local_cartesian',
                  default_speed_limit_mps=13.9, source=None):
    """
    Read a Lanelet2 ``.osm`` file into a LaneGraph with its rules (``graph.rules``).

    :param path: the file.
    :param origin: the world's geodetic origin (the projectors' origin).
    :param projector: 'local_cartesian', 'utm' or 'autoware_local'.
    :param default_speed_limit_mps: the limit of lanelets that give none [m/s].
    :param source: what errors name first (the world file's key); None = 'map'.
    :return: (LaneGraph, the lanelet2 map, its routing graph).
    :raises InvalidParameterError: naming the file: missing, too large, not OSM, empty lat/lon
        for a lat/lon projector, a node without local tags (autoware_local), no lane, a vehicle
        lanelet whose geometry is wrong (naming it).
    :raises Lanelet2Unavailable: lanelet2 is not installed (with the extra to install).
    """
    source = source or 'map'
    lanelet2 = _lanelet2()
    check_osm(path, source)
    if projector != 'autoware_local':
        check_lat_lon(path, source, projector)
    parsed = path
    if projector == 'autoware_local' and lat_lon_unused(path):   # parse where the tags say
        handle, parsed = tempfile.mkstemp(suffix='.osm')
        with os.fdopen(handle, 'w', encoding='utf-8') as copy:
            copy.write(local_positions_as_lat_lon(path))
    try:
        lanelet_map, errors = lanelet2.io.loadRobust(parsed, _projector(lanelet2, projector,
                                                                        origin))
    except RuntimeError as error:
        raise InvalidParameterError(f'{source}: {path}: lanelet2 cannot read it: '
                                    f'{error}') from None
    finally:
        if parsed != path:
            os.unlink(parsed)
    zone = next((str(e) for e in errors if UTM_ZONE_ERROR in str(e)), None)
    if zone is not None:      # the utm projector: the origin's zone is not the map's
        where, what = origin_hint(path, origin)
        raise InvalidParameterError(
            f"{source}: {path}: its nodes lie outside the UTM zone of {where}, as lanelet2 "
            f"says: '{zone.rsplit(': ', 1)[-1]}': {what}")
    unknown, others = _sorted_errors(errors)
    broken = {int(found.group(1)) for found in map(_PRIMITIVE.search, others) if found}
    if others:
        shown = '; '.join(others[:3])
        more = f' (and {len(others) - 3} more)' if len(others) > 3 else ''
        warn(f'{source}: {path}: lanelet2 reports {len(others)} error(s), the map is loaded '
             f'without the primitives they name: {shown}{more}')
    if projector == 'autoware_local':
        use_local_tags(lanelet_map, path, source)
    traffic_rules = lanelet2.traffic_rules
    rules = traffic_rules.create(traffic_rules.Locations.Germany,
                                 traffic_rules.Participants.Vehicle)
    drivable, other_lanes, walking, skipped = _sort_lanelets(lanelet_map, rules, broken)
    if not drivable and not other_lanes:
        count = len(lanelet_map.laneletLayer)
        raise InvalidParameterError(
            f'{source}: {path}: has no lanelets' if not count else
            f'{source}: {path}: none of its {count} lanelets is a lane (a vehicle may drive on '
            f'none, and none is a road shoulder, bicycle or bus lane)')
    for subtype, ids in sorted(skipped.items()):
        warn(f'{source}: {path}: {counted(ids, "lanelet")} of subtype {subtype!r} '
             f'{id_list(ids)} skipped: not a lane the simulator drives')
    # a lanelet lanelet2 could not make whole (a bound missing) crashes its routing graph
    whole = broken.isdisjoint(ll.id for ll in lanelet_map.laneletLayer)
    routed = lanelet_map if whole else lanelet2.core.createMapFromLanelets(drivable)
    graph = lanelet2.routing.RoutingGraph(routed, rules)
    lanes = []
    for lanelet in drivable:
        both = (lanelet,) if rules.isOneWay(lanelet) else (lanelet, lanelet.invert())
        for one in both:
            lanes.append(_checked(path, source, one, lambda one=one: _lane(
                one, graph, rules, default_speed_limit_mps)))
    lanes += _other_lanes(other_lanes, rules, default_speed_limit_mps, path, source)
    if projector != 'autoware_local':      # local_x/local_y are the map frame: no origin
        check_near_origin(lanes, path, source, origin, projector)
    lane_graph = LaneGraph(lanes, f'{source}: {path}')
    lane_graph.set_rules(rules_of(lanelet_map, graph, lane_graph, walking, unknown, path,
                                  source))
    return lane_graph, lanelet_map, graph


def _sort_lanelets(lanelet_map, rules, broken):
    """
    Return (vehicle lanelets, other lane lanelets, walking lanelets, {subtype: [ids]}).

    The lanelets lanelet2 reports errors about (``broken`` ids) are left out.
    """
    drivable, others, walking, skipped = [], [], [], {}
    for lanelet in lanelet_map.laneletLayer:
        if lanelet.id in broken:
            continue
        subtype = tags_of(lanelet).get('subtype', 'road')
        if rules.canPass(lanelet):
            drivable.append(lanelet)
        elif subtype in WALKING_SUBTYPES:
            walking.append(lanelet)
        elif subtype in OTHER_LANE_SUBTYPES:
            others.append(lanelet)
        else:
            skipped.setdefault(subtype, []).append(lanelet.id)
    return drivable, others, walking, skipped


def _checked(path, source, lanelet, make):
    """Make a lane; InvalidParameterError names the file and the lanelet."""
    try:
        return make()
    except InvalidParameterError as error:
        raise InvalidParameterError(f'{source}: {path}: lanelet {lanelet.id}: '
                                    f'{error}') from None


def _lane(lanelet, graph, rules, default_mps):
    left, adjacent_left = graph.left(lanelet), graph.adjacentLeft(lanelet)
    right, adjacent_right = graph.right(lanelet), graph.adjacentRight(lanelet)
    left_lane = left if left is not None else adjacent_left
    right_lane = right if right is not None else adjacent_right
    return Lane(
        lane_id_of(lanelet), _centerline(lanelet),
        _boundary(lanelet.leftBound), _boundary(lanelet.rightBound),
        _speed_limit_mps(rules, lanelet, True, default_mps),
        successors=[lane_id_of(f) for f in graph.following(lanelet)],
        left_lane=None if left_lane is None else lane_id_of(left_lane),
        right_lane=None if right_lane is None else lane_id_of(right_lane),
        left_change=left is not None, right_change=right is not None, name=str(lanelet.id),
        subtype=tags_of(lanelet).get('subtype', 'road'))


def _other_lanes(lanelets, rules, default_mps, path, source):
    """
    Return the lanes of road-like lanelets vehicles may not use (shoulders, bicycle lanes, ...).

    Their successors are the lanes that start where they end (the same two bound points). A
    lanelet whose geometry is wrong is skipped, with one warning naming them.
    """
    one_ways = [(ll,) if tags_of(ll).get('one_way', 'yes') != 'no' else (ll, ll.invert())
                for ll in lanelets]
    views = [one for pair in one_ways for one in pair]

    def ends(lanelet, at):
        return lanelet.leftBound[at].id, lanelet.rightBound[at].id

    by_start = {}
    for lanelet in views:
        by_start.setdefault(ends(lanelet, 0), []).append(lane_id_of(lanelet))
    lanes, bad = [], []
    for lanelet in views:
        try:
            lanes.append(Lane(
                lane_id_of(lanelet), _centerline(lanelet),
                _boundary(lanelet.leftBound), _boundary(lanelet.rightBound),
                _speed_limit_mps(rules, lanelet, False, default_mps),
                successors=[i for i in by_start.get(ends(lanelet, -1), ())
                            if i != lane_id_of(lanelet)],
                name=str(lanelet.id), subtype=tags_of(lanelet).get('subtype', 'road')))
        except InvalidParameterError as error:
            bad.append((lanelet.id, str(error)))
    if bad:
        kept = {lane.id for lane in lanes}
        for lane in lanes:
            lane.successors = tuple(i for i in lane.successors if i in kept)
        warn(f'{source}: {path}: {counted([i for i, _ in bad], "lanelet")} that vehicles do '
             f'not use skipped, their geometry being wrong: '
             + '; '.join(f'lanelet {i}: {e}' for i, e in bad[:3]))
    return lanes


def lane_graph_from_map(spec, world_file, origin):
    """
    Load a validated lanelet2 ``map:`` of a world (its file relative to the world file's folder).

    :param spec: core.map.lanelet2_params.Lanelet2MapSpec.
    :param world_file: the world file's path ('' = relative to the working directory).
    :param origin: the world's GeodeticOrigin.
    :return: the LaneGraph.
    """
    base = os.path.dirname(world_file) if world_file else ''
    path = os.path.join(base, spec.file)
    graph, _, _ = load_lanelet2(path, origin, spec.projector, spec.default_speed_limit_mps,
                                f"{world_file or 'world'}: map.file")
    return graph
