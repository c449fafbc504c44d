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
A Lanelet2 map the tests write (OSM XML), and a world file that uses it.

The map (local metres; lanes 3.5 m wide, along +x; ids as in Lanelet2's files)::

      y = 7.0   ------1003 solid------------+-----1006 solid--------------
                 2002 (left lane)           |  2004 (speed_limit 30)
      y = 3.5   - - - 1002 dashed - - - - - +-----1005 solid--------------
                 2001 (right lane)          |  2003              | 2005 (two-way)
      y = 0.0   ------1001 solid------------+-----1004 solid-----+--1007 curbstone--
               x = 0                     x = 50               x = 100          x = 150

Every node carries both lat/lon (the local point on the east-north-up plane of ORIGIN, from
core/geometry/geodesy.py) and Autoware's local_x/local_y tags (the local point shifted by
LOCAL_SHIFT, as an MGRS grid position would be), so the projectors can be told apart.
"""

from vehicle_sim.core.geometry.geodesy import GeodeticOrigin, LocalTangentPlane

ORIGIN = GeodeticOrigin(48.1, 11.5, 0.0)
LOCAL_SHIFT = (81000.0, 49000.0)
DEFAULT_MPS = 13.9


def _node(plane, node_id, x, y, local_tags=True):
    lat, lon, alt = plane.to_geodetic(x, y, 0.0)
    tags = (f'<tag k="local_x" v="{x + LOCAL_SHIFT[0]!r}"/><tag k="local_y" '
            f'v="{y + LOCAL_SHIFT[1]!r}"/>' if local_tags else '')
    return (f'  <node id="{node_id}" lat="{lat:.12f}" lon="{lon:.12f}" version="1">'
            f'<tag k="ele" v="{alt:.6f}"/>{tags}</node>\n')


def _way(way_id, nodes, kind, subtype=None):
    refs = ''.join(f'<nd ref="{n}"/>' for n in nodes)
    sub = f'<tag k="subtype" v="{subtype}"/>' if subtype else ''
    return f'  <way id="{way_id}" version="1">{refs}<tag k="type" v="{kind}"/>{sub}</way>\n'


def _lanelet(rel_id, left, right, one_way='yes', extra=''):
    return (f'  <relation id="{rel_id}" version="1"><member type="way" ref="{left}" role="left"/>'
            f'<member type="way" ref="{right}" role="right"/><tag k="type" v="lanelet"/>'
            f'<tag k="subtype" v="road"/><tag k="location" v="urban"/>'
            f'<tag k="one_way" v="{one_way}"/>{extra}</relation>\n')


def local_node(node_id, x, y, ele=0.0, tags=''):
    """
    Return a node at local (x, y) [m] of the map, as Autoware's local maps write one.

    Its local_x/local_y tags are (x, y) shifted by LOCAL_SHIFT; its lat/lon are 0 (for
    projector autoware_local only).
    """
    return (f'  <node id="{node_id}" lat="0" lon="0"><tag k="local_x" '
            f'v="{x + LOCAL_SHIFT[0]!r}"/><tag k="local_y" v="{y + LOCAL_SHIFT[1]!r}"/>'
            f'<tag k="ele" v="{ele!r}"/>{tags}</node>\n')


def write_map(path, lanelets=True, local_tags=True, extra='', members=None):
    """
    Write the map of the module docstring; return its path.

    :param extra: OSM XML added at the end (nodes from :func:`local_node`, ways, relations).
    :param members: {lanelet id: XML added to its relation} (members, tags).
    """
    members = members or {}
    plane = LocalTangentPlane(ORIGIN)
    grid = {}                       # (x, y) -> node id; several points per boundary on 0..50
    text = '<?xml version="1.0" encoding="UTF-8"?>\n<osm version="0.6" generator="test">\n'
    xs = (0.0, 12.5, 25.0, 37.5, 50.0, 100.0, 150.0)
    for x in xs:
        for y in (0.0, 3.5, 7.0):
            grid[(x, y)] = 100 + len(grid)
            text += _node(plane, grid[(x, y)], x, y, local_tags or len(grid) > 1)

    def line(y, x_from, x_to):
        return [grid[(x, y)] for x in xs if x_from <= x <= x_to]

    text += _way(1001, line(0.0, 0, 50), 'line_thin', 'solid')
    text += _way(1002, line(3.5, 0, 50), 'line_thin', 'dashed')
    text += _way(1003, line(7.0, 0, 50), 'line_thin', 'solid')
    text += _way(1004, line(0.0, 50, 100), 'line_thin', 'solid')
    text += _way(1005, line(3.5, 50, 100), 'line_thin', 'solid')
    text += _way(1006, line(7.0, 50, 100), 'line_thin', 'solid')
    text += _way(1007, line(0.0, 100, 150), 'curbstone', 'high')
    text += _way(1008, line(3.5, 100, 150), 'line_thin', 'solid')
    if lanelets:
        text += _lanelet(2001, 1002, 1001, extra=members.get(2001, ''))
        text += _lanelet(2002, 1003, 1002, extra=members.get(2002, ''))
        text += _lanelet(2003, 1005, 1004, extra=members.get(2003, ''))
        text += _lanelet(2004, 1006, 1005,
                         extra='<tag k="speed_limit" v="30"/>' + members.get(2004, ''))
        text += _lanelet(2005, 1008, 1007, one_way='no', extra=members.get(2005, ''))
    path.write_text(text + extra + '</osm>\n', encoding='utf-8')
    return path


def write_world(folder, vehicles, name='world.yaml', **map_values):
    """Write the map (town.osm) and a world using it in ``folder``; return the world's path."""
    import yaml
    write_map(folder / 'town.osm')
    origin = {'latitude': ORIGIN.latitude_deg, 'longitude': ORIGIN.longitude_deg,
              'altitude': ORIGIN.altitude_m}
    data = {'origin': origin, 'vehicles': list(vehicles),
            'map': {'type': 'lanelet2', 'file': 'town.osm', **map_values}}
    path = folder / name
    path.write_text(yaml.safe_dump(data), encoding='utf-8')
    return path
