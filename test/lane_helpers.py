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

:func:`signal_crossing` is a hand-made signalised crossing with its rules (stop lines, two
traffic light groups with bulbs, a crosswalk, a parking area), for what draws them.
"""

from vehicle_sim.core.geometry.geodesy import GeodeticOrigin, LocalTangentPlane
from vehicle_sim.core.map.lane_graph import Boundary, Lane, LaneGraph
from vehicle_sim.core.map.lane_rules import (
    Bulb,
    Conflict,
    LaneRules,
    MapArea,
    StopLine,
    TrafficLightGroup,
)
from vehicle_sim.core.map.signal_plan import FixedTimePlan, SignalController

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


# ------------------------------------------------------------------------------ a signal crossing

# The light of group 11: at the kerb south of lane 1, (0, -2.6); red 3.0 m, yellow 2.6 m, green
# 2.2 m up.
LIGHT_XY = (0.0, -2.6)
BULB_Z = {'red': 3.0, 'yellow': 2.6, 'green': 2.2}
# A crosswalk across lane 2 (x 4 .. 7), a parking area south of it.
CROSSWALK = ((4.0, -1.75), (7.0, -1.75), (7.0, 1.75), (4.0, 1.75))
PARKING = ((-15.0, -4.0), (-5.0, -4.0), (-5.0, -9.0), (-15.0, -9.0))


def straight(lane_id, x0, y0, x1, y1, successors=()):
    """Return a 3.5 m lane from (x0, y0) to (x1, y1) (axis-aligned)."""
    nx, ny = (0.0, 1.75) if y0 == y1 else (-1.75, 0.0)
    sign = 1.0 if (x1 - x0) + (y1 - y0) > 0 else -1.0
    nx, ny = sign * nx, sign * ny
    left = Boundary(2 * lane_id, [(x0 + nx, y0 + ny), (x1 + nx, y1 + ny)], 'solid')
    right = Boundary(2 * lane_id + 1, [(x0 - nx, y0 - ny), (x1 - nx, y1 - ny)], 'solid')
    return Lane(lane_id, [(x0, y0), (x1, y1)], left, right, 10.0, successors=successors)


def signal_crossing(areas=True):
    """
    Return a LaneGraph with rules: lane 1 east from (-20, 0) to the crossing, then lane 2.

    Lanes 3 -> 4 go north at x = 10 and cross lane 2. Lane 1's stop line (101) is at x = -2
    (s = 18 m), governed by group 11 (its light at LIGHT_XY, facing west); lane 3's (102) at
    y = -12, group 12 (its light at (12.6, -12)). With ``areas``: the crosswalk 501 over lane 2
    (CROSSWALK) and the parking area 502 (PARKING).
    """
    graph = LaneGraph([straight(1, -20, 0, 0, 0, [2]), straight(2, 0, 0, 20, 0),
                       straight(3, 10, -30, 10, -10, [4]), straight(4, 10, -10, 10, 10)])
    bulbs = tuple(Bulb(color, LIGHT_XY[0], LIGHT_XY[1], z) for color, z in BULB_Z.items())
    graph.set_rules(LaneRules(
        stop_lines=(StopLine(101, 1, 18.0, [(-2, -1.75), (-2, 1.75)], 'traffic_light', 11),
                    StopLine(102, 3, 18.0, [(8.25, -12), (11.75, -12)], 'traffic_light', 12)),
        groups=(TrafficLightGroup(11, (1,), (101,), bulbs),
                TrafficLightGroup(12, (3,), (102,), tuple(
                    Bulb(color, 12.6, -12.0, z) for color, z in BULB_Z.items()))),
        conflicts=(Conflict(2, 4, (8.25, 11.75), (8.25, 11.75)),),
        areas=(MapArea(501, 'crosswalk', CROSSWALK, (2,)),
               MapArea(502, 'parking', PARKING)) if areas else ()))
    return graph


class StandInSignals:
    """A 'signals' part with a short plan (2 s green, 1 s yellow, 1 s all red), stepped."""

    name = 'signals'

    def build(self, world, spec):
        self.world = world
        self.controller = SignalController(spec.lanes, FixedTimePlan(green_s=2.0, yellow_s=1.0,
                                                                     all_red_s=1.0))
        world.add_body(self)
        return self

    def post_step(self):
        self.controller.update(self.world.time_s)
