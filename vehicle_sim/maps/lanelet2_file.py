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
A Lanelet2 ``.osm`` file around lanelet2's parse: the checks before it, the node tags after it.

Before lanelet2 parses a file (vehicle_sim/maps/lanelet2_map.py): the file exists, is no
larger than :data:`MAX_OSM_BYTES` and is OSM XML; a projector that reads ``lat``/``lon`` finds
numbers there; Autoware's local maps, whose ``lat``/``lon`` may be anything, are parsed from a
copy with ``lat``/``lon`` where their ``local_x``/``local_y`` tags put the nodes. After it: the
tags are the nodes' x, y (projector ``autoware_local``), and a map that a lat/lon projector puts
far from the world's origin is refused naming the key to set.
"""

import math
import os
import re
import xml.etree.ElementTree as ElementTree

from vehicle_sim.core.specs.errors import InvalidParameterError

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


def check_osm(path, source):
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


def lat_lon_unused(path, sample=20):
    """Return whether the first nodes' lat/lon are not places (empty, not numbers, all equal)."""
    places = set()
    for _, lat, lon, _ in _first_nodes(path, sample):
        try:
            places.add((float(lat), float(lon)))
        except ValueError:
            return True
    return len(places) < 2


def check_lat_lon(path, source, projector):
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


def origin_hint(path, origin):
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


def check_near_origin(lanes, path, source, origin, projector):
    """Refuse lanes that a lat/lon projector puts thousands of km from the world's origin."""
    nearest_m = min(float(min(map(math.hypot, *lane.centerline.T))) for lane in lanes)
    if nearest_m <= FAR_FROM_ORIGIN_M:
        return
    where, what = origin_hint(path, origin)
    raise InvalidParameterError(
        f"{source}: {path}: its lanes lie {nearest_m / 1000.0:,.0f} km from {where} with "
        f"projector '{projector}', which places the map's lat/lon around that origin: {what}")


_NODE = re.compile(r'<node\b([^>]*?)(/?)>(.*?</node>)?', re.S)
_LAT_LON = re.compile(r'\s(lat|lon)\s*=\s*("[^"]*"|\'[^\']*\')')
_LOCAL_TAG = re.compile(r'<tag\s+k\s*=\s*["\'](local_[xy])["\']\s+v\s*=\s*["\']([^"\']*)["\']')
EARTH_RADIUS_M = 6378137.0       # lanelet2's MercatorProjector's sphere


def local_positions_as_lat_lon(path):
    """
    Return the file's text with each node's lat/lon where its local_x/local_y tags are.

    For projector autoware_local, which parses with lanelet2's Mercator projector at latitude
    0, longitude 0: lanelet2 builds areas and orients lanelets' bounds while parsing, from the
    nodes' lat/lon, which Autoware's local maps may leave empty, 0 or anything
    (:func:`lat_lon_unused`: the first 20 nodes' are not numbers or all the same); a node
    without the tags keeps its lat/lon (:func:`use_local_tags` refuses it).
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


def use_local_tags(lanelet_map, path, source):
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
