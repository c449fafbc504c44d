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
A Lanelet2 ``.osm`` map read with the ``lanelet2`` package, as a core LaneGraph.

``lanelet2`` (PyPI) is optional: ``pip install 'vehicle_sim[lanelet2]'``; it is imported only
when a lanelet2 map is loaded. What becomes of the file:

- the lanes are the lanelets a vehicle may drive on (Lanelet2's German traffic rules for
  vehicles, ``canPass``); a lanelet that is not one-way is two lanes, the inverted one with
  the negated id;
- successors and left/right neighbours are those of Lanelet2's routing graph for those rules:
  ``following``, ``left``/``right`` (a lane change allowed) and ``adjacentLeft``/
  ``adjacentRight`` (a neighbour, no lane change);
- centrelines are Lanelet2's (``lanelet.centerline``); widths are measured between the bounds;
- boundary line types come from the line strings' ``type``/``subtype`` tags (line_thin and
  line_thick: their subtype, solid, dashed, solid_solid, ...; curbstone; road_border;
  guard_rail, wall and fence: wall; virtual);
- a lanelet's speed limit is Lanelet2's (its ``speed_limit`` tag or a speed limit regulatory
  element) where it has either, else the map's ``default_speed_limit``.

The projectors are described in core/map/lanelet2_params.py (and docs/lanes.md).
"""

import math
import os
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


# A map whose lanes lie farther than this from the world's origin on a lat/lon projector's plane
# is refused [m]: at 100 km the east-north-up plane is 0.8 km above the ground, and PyBullet's
# single-precision shapes lose millimetres. A world file without origin: puts the origin at
# latitude 0, longitude 0, thousands of km from any real map.
FAR_FROM_ORIGIN_M = 100_000.0
UTM_ZONE_ERROR = 'out of legal range for UTM zone'


class Lanelet2Unavailable(InvalidParameterError):
    """The lanelet2 package is not installed."""


def _lanelet2():
    try:
        import lanelet2
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


def _check_osm(path, source):
    """Refuse a file that is missing, not XML, or XML whose root is not <osm>."""
    if not os.path.isfile(path):
        raise InvalidParameterError(f'{source}: {path}: no such file')
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
    return lanelet2.projection.LocalCartesianProjector(where)


def _first_node_lat_lon(path):
    # (lat, lon) of the file's first node, or None (the file was checked to be OSM XML).
    for _, element in ElementTree.iterparse(path, events=('start',)):
        if element.tag == 'node' and 'lat' in element.attrib and 'lon' in element.attrib:
            try:
                return float(element.attrib['lat']), float(element.attrib['lon'])
            except ValueError:
                return None
    return None


def _origin_hint(path, origin):
    """Return (the origin, as errors name it; what to set: the key, a value near the map)."""
    near = _first_node_lat_lon(path)
    example = '' if near is None else (
        f', e.g. origin: {{latitude: {round(near[0], 4):g}, longitude: {round(near[1], 4):g}}}')
    return (f"the world's origin (latitude {origin.latitude_deg:g}, longitude "
            f"{origin.longitude_deg:g})", f"set the world file's origin: near the map{example}")


def _check_near_origin(lanes, path, source, origin, projector):
    """Refuse lanes that a lat/lon projector puts thousands of km from the world's origin."""
    nearest_m = min(float(min(map(math.hypot, *lane.centerline.T))) for lane in lanes)
    if nearest_m <= FAR_FROM_ORIGIN_M:
        return
    where, what = _origin_hint(path, origin)
    raise InvalidParameterError(
        f"{source}: {path}: its lanes lie {nearest_m / 1000.0:,.0f} km from {where} with "
        f"projector '{projector}', which places the map's lat/lon around that origin: {what}")


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
            z = float(tags['ele']) if 'ele' in tags else 0.0
        except ValueError:
            raise InvalidParameterError(f'{source}: {path}: node {point.id}: local_x/local_y/'
                                        f'ele are not numbers') from None
        if not all(math.isfinite(v) for v in (x, y, z)):
            raise InvalidParameterError(f'{source}: {path}: node {point.id}: local_x/local_y/'
                                        f'ele must be finite')
        point.x, point.y, point.z = x, y, z
    for lanelet in lanelet_map.laneletLayer:
        lanelet.resetCache()


def _lane_id(lanelet):
    return -lanelet.id if lanelet.inverted() else lanelet.id


def _boundary(line):
    attributes = {key: value for key, value in line.attributes.items()}
    return Boundary(line.id, [(p.x, p.y) for p in line], line_type_of(attributes))


def _speed_limit_mps(rules, lanelet, default_mps):
    has_limit = 'speed_limit' in lanelet.attributes or any(
        element.attributes.get('subtype') == 'speed_limit'
        for element in lanelet.regulatoryElements)
    if not has_limit:
        return default_mps
    return kmh_to_mps(rules.speedLimit(lanelet).speedLimit)   # lanelet2's Python gives km/h


def load_lanelet2(path, origin=GeodeticOrigin(), projector='local_cartesian',
                  default_speed_limit_mps=13.9, source=None):
    """
    Read a Lanelet2 ``.osm`` file into a LaneGraph.

    :param path: the file.
    :param origin: the world's geodetic origin (the projectors' origin).
    :param projector: 'local_cartesian', 'utm' or 'autoware_local'.
    :param default_speed_limit_mps: the limit of lanelets that give none [m/s].
    :param source: what errors name first (the world file's key); None = the path.
    :return: (LaneGraph, the lanelet2 map, its routing graph).
    :raises InvalidParameterError: naming the file: missing, not OSM, lanelet2's parse errors,
        a node without local tags (autoware_local), no lanelet a vehicle may drive on.
    :raises Lanelet2Unavailable: lanelet2 is not installed (with the extra to install).
    """
    source = source or 'map'
    lanelet2 = _lanelet2()
    _check_osm(path, source)
    try:
        lanelet_map, errors = lanelet2.io.loadRobust(path, _projector(lanelet2, projector,
                                                                      origin))
    except RuntimeError as error:
        raise InvalidParameterError(f'{source}: {path}: lanelet2 cannot read it: '
                                    f'{error}') from None
    zone = next((str(e) for e in errors if UTM_ZONE_ERROR in str(e)), None)
    if zone is not None:      # the utm projector: the origin's zone is not the map's
        where, what = _origin_hint(path, origin)
        raise InvalidParameterError(
            f"{source}: {path}: its nodes lie outside the UTM zone of {where}, as lanelet2 "
            f"says: '{zone.rsplit(': ', 1)[-1]}': {what}")
    if errors:
        shown = '; '.join(str(e) for e in errors[:3])
        more = f' (and {len(errors) - 3} more)' if len(errors) > 3 else ''
        raise InvalidParameterError(f'{source}: {path}: lanelet2 reports errors: {shown}{more}')
    if projector == 'autoware_local':
        _use_local_tags(lanelet_map, path, source)
    traffic_rules = lanelet2.traffic_rules
    rules = traffic_rules.create(traffic_rules.Locations.Germany,
                                 traffic_rules.Participants.Vehicle)
    drivable = [ll for ll in lanelet_map.laneletLayer if rules.canPass(ll)]
    if not drivable:
        count = len(lanelet_map.laneletLayer)
        raise InvalidParameterError(
            f'{source}: {path}: has no lanelets' if not count else
            f'{source}: {path}: none of its {count} lanelets may be driven on by a vehicle')
    graph = lanelet2.routing.RoutingGraph(lanelet_map, rules)
    lanes = []
    for lanelet in drivable:
        both = (lanelet,) if rules.isOneWay(lanelet) else (lanelet, lanelet.invert())
        for one in both:
            lanes.append(_lane(one, graph, rules, default_speed_limit_mps))
    if projector != 'autoware_local':      # local_x/local_y are the map frame: no origin
        _check_near_origin(lanes, path, source, origin, projector)
    return LaneGraph(lanes, f'{source}: {path}'), lanelet_map, graph


def _lane(lanelet, graph, rules, default_mps):
    left, adjacent_left = graph.left(lanelet), graph.adjacentLeft(lanelet)
    right, adjacent_right = graph.right(lanelet), graph.adjacentRight(lanelet)
    left_lane = left if left is not None else adjacent_left
    right_lane = right if right is not None else adjacent_right
    return Lane(
        _lane_id(lanelet), [(p.x, p.y) for p in lanelet.centerline],
        _boundary(lanelet.leftBound), _boundary(lanelet.rightBound),
        _speed_limit_mps(rules, lanelet, default_mps),
        successors=[_lane_id(f) for f in graph.following(lanelet)],
        left_lane=None if left_lane is None else _lane_id(left_lane),
        right_lane=None if right_lane is None else _lane_id(right_lane),
        left_change=left is not None, right_change=right is not None, name=str(lanelet.id))


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
