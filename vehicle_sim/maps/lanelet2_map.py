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
than :data:`MAX_OSM_BYTES`, or a vehicle lane's geometry is wrong (naming the lanelet).

The projectors are described in core/map/lanelet2_params.py (and docs/lanes.md).
"""

import math
import os
import re
import tempfile
import warnings
import xml.etree.ElementTree as ElementTree

from vehicle_sim.core.geometry.geodesy import GeodeticOrigin
from vehicle_sim.core.map.lane_graph import Boundary, Lane, LaneGraph
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.units import kmh_to_mps

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
# Lanelet subtypes that are walking areas, and the area kind each becomes.
WALKING_SUBTYPES = {'crosswalk': 'crosswalk', 'walkway': 'walkway', 'shared_walkway': 'walkway',
                    'pedestrian_lane': 'walkway', 'stairs': 'walkway'}

# A map whose lanes lie farther than this from the world's origin on a lat/lon projector's plane
# is refused [m]: at 100 km the east-north-up plane is 0.8 km above the ground, and PyBullet's
# single-precision shapes lose millimetres. A world file without origin: puts the origin at
# latitude 0, longitude 0, thousands of km from any real map.
FAR_FROM_ORIGIN_M = 100_000.0
UTM_ZONE_ERROR = 'out of legal range for UTM zone'
# The largest .osm file read [bytes], checked before parsing: lanelet2 holds about 15 bytes of
# memory per byte of OSM XML (a 50 MB map of 18,000 lanelets: 0.85 GB at the peak, 17 s of CPU;
# benchmarks/bench_lanelet2_maps.py).
MAX_OSM_BYTES = 100_000_000
# lanelet2's words for a regulatory element type it has no class for, and for a reference to one.
_UNKNOWN_RULE = re.compile(r'Error parsing primitive (-?\d+): Creating a regulatory element of '
                           r'type (\S+) failed: No regulatory element found that implements')
_PRIMITIVE = re.compile(r'Error parsing primitive (-?\d+)')
_MISSING_ID = re.compile(r'Error parsing primitive (-?\d+): Failed to get id (-?\d+) from map')


class Lanelet2Unavailable(InvalidParameterError):
    """The lanelet2 package is not installed."""


class Lanelet2MapWarning(UserWarning):
    """Part of a Lanelet2 map is not simulated (named in the message); the rest is loaded."""


def warn(message):
    """Warn about a map (one :class:`Lanelet2MapWarning`)."""
    warnings.warn(message, Lanelet2MapWarning, stacklevel=3)


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


def tags_of(primitive):
    """Return a lanelet2 primitive's attributes as a plain dict of strings."""
    return {key: str(value) for key, value in primitive.attributes.items()}


def _check_osm(path, source):
    """Refuse a file that is missing, too large, not XML, or XML whose root is not <osm>."""
    if not os.path.isfile(path):
        raise InvalidParameterError(f'{source}: {path}: no such file')
    size = os.path.getsize(path)
    if size > MAX_OSM_BYTES:
        raise InvalidParameterError(
            f'{source}: {path}: {size / 1e6:,.0f} MB is larger than the {MAX_OSM_BYTES / 1e6:.0f}'
            ' MB a lanelet2 map may have (lanelet2 holds about 15 times the file in memory): '
            'cut the map to the area simulated')
    try:
        for _, element in ElementTree.iterparse(path, events=('start',)):
            if element.tag != 'osm':
                raise InvalidParameterError(f'{source}: {path}: not an OSM file (its root '
                                            f'element is <{element.tag}>, not <osm>)')
            return
    except ElementTree.ParseError as error:
        raise InvalidParameterError(f'{source}: {path}: not an OSM file (not XML: '
                                    f'{error})') from None
    except OSError as error:
        raise InvalidParameterError(f'{source}: {path}: cannot be read: {error}') from None


def _projector(lanelet2, projector, origin):
    where = lanelet2.io.Origin(origin.latitude_deg, origin.longitude_deg, origin.altitude_m)
    if projector == 'utm':
        return lanelet2.projection.UtmProjector(where)
    if projector == 'autoware_local':     # x, y: the local tags; Mercator keeps z = ele as is
        return lanelet2.projection.MercatorProjector(lanelet2.io.Origin(0.0, 0.0, 0.0))
    return lanelet2.projection.LocalCartesianProjector(where)


def _first_nodes(path, count=1):
    """Return [(node id, lat text, lon text, has local_x/local_y tags)] of the first nodes."""
    found = []
    for _, element in ElementTree.iterparse(path, events=('end',)):
        if element.tag == 'node':
            keys = {tag.get('k') for tag in element.iter('tag')}
            found.append((element.get('id'), element.get('lat', ''), element.get('lon', ''),
                          {'local_x', 'local_y'} <= keys))
            if len(found) == count:
                break
        elif element.tag in ('way', 'relation'):
            break
    return found


def _first_node(path):
    # the file's first node (as _first_nodes gives it), or None
    return next(iter(_first_nodes(path)), None)


def _lat_lon_unused(path, sample=20):
    """Return whether the first nodes' lat/lon are not places (empty, not numbers, all equal)."""
    places = set()
    for _, lat, lon, _ in _first_nodes(path, sample):
        try:
            places.add((float(lat), float(lon)))
        except ValueError:
            return True
    return len(places) < 2


def _check_lat_lon(path, source, projector):
    """Refuse empty lat/lon (Autoware's local and MGRS maps) for a projector that reads them."""
    first = _first_node(path)
    if first is None:
        return
    node_id, lat, lon, local = first
    try:
        float(lat), float(lon)
    except ValueError:
        hint = (": its local_x/local_y tags are Autoware's map frame: set the map's projector: "
                'autoware_local') if local else ''
        raise InvalidParameterError(
            f"{source}: {path}: node {node_id} has lat {lat!r}, lon {lon!r}, not numbers: "
            f"projector '{projector}' reads them{hint}") from None


def _origin_hint(path, origin):
    """Return (the origin, as errors name it; what to set: the key, a value near the map)."""
    first = _first_node(path)
    near = None
    if first is not None:
        try:
            near = float(first[1]), float(first[2])
        except ValueError:
            near = None
    example = '' if near is None else (
        f', e.g. origin: {{latitude: {round(near[0], 4):g}, longitude: {round(near[1], 4):g}}}')
    local = (" (or, its nodes having local_x/local_y tags, the map's projector: autoware_local)"
             if first is not None and first[3] else '')
    return (f"the world's origin (latitude {origin.latitude_deg:g}, longitude "
            f"{origin.longitude_deg:g})", f"set the world file's origin: near the map{example}"
            f'{local}')


def _check_near_origin(lanes, path, source, origin, projector):
    """Refuse lanes that a lat/lon projector puts thousands of km from the world's origin."""
    nearest_m = min(float(min(map(math.hypot, *lane.centerline.T))) for lane in lanes)
    if nearest_m <= FAR_FROM_ORIGIN_M:
        return
    where, what = _origin_hint(path, origin)
    raise InvalidParameterError(
        f"{source}: {path}: its lanes lie {nearest_m / 1000.0:,.0f} km from {where} with "
        f"projector '{projector}', which places the map's lat/lon around that origin: {what}")


_NODE = re.compile(r'<node\b([^>]*?)(/?)>(.*?</node>)?', re.S)
_LAT_LON = re.compile(r'\s(lat|lon)\s*=\s*("[^"]*"|\'[^\']*\')')
_LOCAL_TAG = re.compile(r'<tag\s+k\s*=\s*["\'](local_[xy])["\']\s+v\s*=\s*["\']([^"\']*)["\']')
EARTH_RADIUS_M = 6378137.0       # lanelet2's MercatorProjector's sphere


def _local_positions_as_lat_lon(path):
    """
    Return the file's text with each node's lat/lon where its local_x/local_y tags are.

    For projector autoware_local, which parses with lanelet2's Mercator projector at latitude
    0, longitude 0: lanelet2 builds areas and orients lanelets' bounds while parsing, from the
    nodes' lat/lon, which Autoware's local maps may leave empty, 0 or anything
    (:func:`_lat_lon_unused`: the first 20 nodes' are not numbers or all the same); a node
    without the tags keeps its lat/lon (:func:`_use_local_tags` refuses it).
    """
    def placed(match):
        head, closed, body = match.group(1), match.group(2), match.group(3) or ''
        tags = dict(_LOCAL_TAG.findall(body))
        try:
            x, y = float(tags['local_x']), float(tags['local_y'])
        except (KeyError, ValueError):
            return match.group(0)
        lat = math.degrees(2.0 * math.atan(math.exp(y / EARTH_RADIUS_M)) - 0.5 * math.pi)
        lon = math.degrees(x / EARTH_RADIUS_M)
        head = _LAT_LON.sub('', head) + f' lat="{lat!r}" lon="{lon!r}"'
        return f'<node{head}{closed}>{body}'

    with open(path, encoding='utf-8', errors='replace') as text:
        return _NODE.sub(placed, text.read())


def _use_local_tags(lanelet_map, path, source):
    """Autoware's rule: every node's x, y are its local_x, local_y tags (z: its ele tag)."""
    for point in lanelet_map.pointLayer:
        tags = point.attributes
        if 'local_x' not in tags or 'local_y' not in tags:
            raise InvalidParameterError(
                f"{source}: {path}: node {point.id} has no local_x/local_y tags (projector "
                f"'autoware_local' reads every node's position from them)")
        try:
            x, y = float(tags['local_x']), float(tags['local_y'])
            z = float(tags['ele']) if 'ele' in tags else point.z   # lanelet2 reads ele as z
        except ValueError:
            raise InvalidParameterError(f'{source}: {path}: node {point.id}: local_x/local_y/'
                                        f'ele are not numbers') from None
        if not all(math.isfinite(v) for v in (x, y, z)):
            raise InvalidParameterError(f'{source}: {path}: node {point.id}: local_x/local_y/'
                                        f'ele must be finite')
        point.x, point.y, point.z = x, y, z
    for lanelet in lanelet_map.laneletLayer:
        lanelet.resetCache()


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


def lane_id_of(lanelet):
    return -lanelet.id if lanelet.inverted() else lanelet.id


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
    from vehicle_sim.maps.lanelet2_rules import rules_of  # the regulatory elements
    source = source or 'map'
    lanelet2 = _lanelet2()
    _check_osm(path, source)
    if projector != 'autoware_local':
        _check_lat_lon(path, source, projector)
    parsed = path
    if projector == 'autoware_local' and _lat_lon_unused(path):   # parse where the tags say
        handle, parsed = tempfile.mkstemp(suffix='.osm')
        with os.fdopen(handle, 'w', encoding='utf-8') as copy:
            copy.write(_local_positions_as_lat_lon(path))
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
        where, what = _origin_hint(path, origin)
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
        _use_local_tags(lanelet_map, path, source)
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
        _check_near_origin(lanes, path, source, origin, projector)
    lane_graph = LaneGraph(lanes, f'{source}: {path}')
    lane_graph.set_rules(rules_of(lanelet_map, graph, lane_graph, walking, unknown, path,
                                  source))
    return lane_graph, lanelet_map, graph


def counted(ids, what):
    return f'{len(ids)} {what}' + ('' if len(ids) == 1 else 's')


def id_list(ids, shown=10):
    ids = sorted(ids)
    more = f', ... ({len(ids) - shown} more)' if len(ids) > shown else ''
    return f"({'id' if len(ids) == 1 else 'ids'} {', '.join(map(str, ids[:shown]))}{more})"


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
