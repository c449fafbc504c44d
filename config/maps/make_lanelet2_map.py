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
Write config/maps/lanelet2_map.osm: a small Lanelet2 map, as Autoware's map tools write one.

Run ``python config/maps/make_lanelet2_map.py`` to redraw it. A one-way road of two 3.5 m lanes
runs 100 m east from the map origin (lanelets 2001 right, 2002 left), turns left through 90
degrees, its right edge on a 40 m radius (2003, 2004; 30 km/h), then runs 60 m north (2005, 2006;
50 km/h)::

                                    2006 2005
                                   |    |    |
                                   |    |    |   y = 40
                                  /    /    /
         2002 (left lane)        /    /    /
    ---------------------------''    /    /
         2001 (right lane)          /    /
    -------------------------------    y = 0
    x = 0                         x = 100  x = 140

The lane line is dashed, the left edge a solid line, the right edge a curbstone (solid to the
physics). Every node carries ``lat``/``lon`` (its point on the east-north-up plane of ORIGIN,
the world's ``origin:`` in config/worlds/lanelet2.yaml), ``ele`` 0 and Autoware's
``local_x``/``local_y`` tags equal to that point, so every projector puts the road at the same
place in the world.
"""

import math
from pathlib import Path
import sys

FOLDER = Path(__file__).resolve().parent
sys.path.insert(0, str(FOLDER.parent.parent))    # vehicle_sim from this checkout

from vehicle_sim.core.geometry.geodesy import GeodeticOrigin, LocalTangentPlane  # noqa: E402

# Tokyo, near the sample maps Autoware ships; altitude 0: the nodes' ele is their height [m].
ORIGIN = GeodeticOrigin(35.6812, 139.7671, 0.0)
LANE_WIDTH_M = 3.5
STRAIGHT_M = 100.0
BEND_RADIUS_M = 40.0          # of the right edge in the bend (its outer edge)
EXIT_M = 60.0
POINT_SPACING_M = 10.0        # between nodes along a straight
BEND_POINTS = 13              # nodes along each bend boundary (7.5 degrees apart)
SPEED_LIMITS_KMH = {'bend': 30, 'exit': 50}
NAME = 'lanelet2_map.osm'


def _straight(start, heading_rad, length_m, offset_m):
    # Points along a straight, offset_m to the left of the reference line.
    count = max(1, round(length_m / POINT_SPACING_M))
    cos_h, sin_h = math.cos(heading_rad), math.sin(heading_rad)
    x0 = start[0] - offset_m * sin_h
    y0 = start[1] + offset_m * cos_h
    return [(x0 + length_m * i / count * cos_h, y0 + length_m * i / count * sin_h)
            for i in range(count + 1)]


def _bend(offset_m):
    # Points of the left bend (centre (STRAIGHT_M, BEND_RADIUS_M)), offset_m left of the edge.
    radius = BEND_RADIUS_M - offset_m
    return [(STRAIGHT_M + radius * math.sin(a), BEND_RADIUS_M - radius * math.cos(a))
            for a in (math.pi / 2 * i / (BEND_POINTS - 1) for i in range(BEND_POINTS))]


def boundaries():
    """Return {piece: [right edge, lane line, left edge]}: each a list of (x, y) [m]."""
    exit_start = (STRAIGHT_M + BEND_RADIUS_M, BEND_RADIUS_M)
    offsets = (0.0, LANE_WIDTH_M, 2 * LANE_WIDTH_M)
    return {'straight': [_straight((0.0, 0.0), 0.0, STRAIGHT_M, d) for d in offsets],
            'bend': [_bend(d) for d in offsets],
            'exit': [_straight(exit_start, math.pi / 2, EXIT_M, d) for d in offsets]}


def osm_text():
    """Return the map as OSM XML (JOSM's format, as Lanelet2 and Autoware read it)."""
    plane = LocalTangentPlane(ORIGIN)
    nodes, ways, relations = [], [], []
    ids = {}

    def node(point):
        key = (round(point[0], 6), round(point[1], 6))
        if key not in ids:           # pieces share their end points: one node each
            ids[key] = 1 + len(ids)
            lat, lon, _ = plane.to_geodetic(point[0], point[1], 0.0)
            nodes.append(f'  <node id="{ids[key]}" lat="{lat:.11f}" lon="{lon:.11f}">'
                         f'<tag k="ele" v="0.0"/><tag k="local_x" v="{point[0]:.4f}"/>'
                         f'<tag k="local_y" v="{point[1]:.4f}"/></node>')
        return ids[key]

    tags = (('curbstone', 'high'), ('line_thin', 'dashed'), ('line_thin', 'solid'))
    for piece, (name, lines) in enumerate(boundaries().items()):
        way_ids = []
        for line, (kind, subtype) in zip(lines, tags):
            way_id = 1001 + 3 * piece + len(way_ids)
            refs = ''.join(f'<nd ref="{node(p)}"/>' for p in line)
            ways.append(f'  <way id="{way_id}">{refs}<tag k="type" v="{kind}"/>'
                        f'<tag k="subtype" v="{subtype}"/></way>')
            way_ids.append(way_id)
        limit = SPEED_LIMITS_KMH.get(name)
        extra = '' if limit is None else f'<tag k="speed_limit" v="{limit}"/>'
        for lane, (right, left) in enumerate(((way_ids[0], way_ids[1]),
                                              (way_ids[1], way_ids[2]))):
            relations.append(
                f'  <relation id="{2001 + 2 * piece + lane}"><member type="way" ref="{left}" '
                f'role="left"/><member type="way" ref="{right}" role="right"/>'
                '<tag k="type" v="lanelet"/><tag k="subtype" v="road"/>'
                f'<tag k="location" v="urban"/><tag k="one_way" v="yes"/>{extra}</relation>')
    return '\n'.join(['<?xml version="1.0" encoding="UTF-8"?>',
                      '<osm version="0.6" generator="vehicle_sim make_lanelet2_map.py">',
                      *nodes, *ways, *relations, '</osm>', ''])


def main():
    """Write the map beside this script."""
    path = FOLDER / NAME
    path.write_text(osm_text(), encoding='utf-8')
    print(f'wrote {path}')


if __name__ == '__main__':
    main()
