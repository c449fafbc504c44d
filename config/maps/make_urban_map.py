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
Write config/maps/urban_map.osm: a signalised four-way intersection in Autoware's Lanelet2 format.

Run ``python config/maps/make_urban_map.py`` to redraw it. Two two-way roads (one 3.5 m lane each
way, driving on the right) cross at the map origin; each arm runs 70 m out from the centre::

                          N (arm 3)
                    |  ¦  |
                    |  ¦  |      a crosswalk across each arm 10 .. 14 m from the centre,
            --------+     +--------     the stop line 15 m out (a traffic light per arm)
      W (arm 0)  ===   box   ===  E (arm 2): two lanes out for 30 m, the right one
            --------+     +--------     tapering to nothing over the next 20 m (a merge)
                    |  ¦  |
                    |  ¦  |
                          S (arm 1)

What Autoware's format has, as its lanelet2 extension documents it:

- lanelets (``subtype`` road; ``turn_direction`` straight/left/right inside the intersection,
  whose bounds are ``virtual``; ``speed_limit`` 40 km/h on the arms, 30 inside), the arms' edges
  ``curbstone``, the centre lines ``line_thin`` solid, the line of the east arm's two lanes
  dashed;
- per arm a ``traffic_light`` regulatory element: ``refers`` the light (a ``traffic_light`` line
  string, ``height`` 0.5, its bottom 5 m up, across the intersection on the right),
  ``light_bulbs`` its three bulbs (``color`` green, yellow, red from left to right, as Japanese
  lights are), ``ref_line`` the ``stop_line`` 15 m out; the arm's incoming lanelet refers to it;
- per arm a ``crosswalk`` lanelet (``participant:pedestrian``) and a ``crosswalk`` regulatory
  element (``refers`` it, ``crosswalk_polygon``) that the arm's lanelets refer to;
- per straight movement a ``right_of_way`` element: it goes before the opposite left turn
  (``yield``);
- the east arm's right lane (lanelet 190, fed by the south arm's right turn) ends in a taper
  (lanelet 191: its bounds meet at its end): vehicles on it change into lane 125.

Every node carries ``lat``/``lon`` (its point on the east-north-up plane of ORIGIN), ``ele`` (its
height) and Autoware's ``local_x``/``local_y`` (that point), so every projector puts the map at
the same place; ``MetaInfo`` gives format_version 1 and map_version 1, as Autoware's maps do.
"""

import math
from pathlib import Path
import sys

FOLDER = Path(__file__).resolve().parent
sys.path.insert(0, str(FOLDER.parent.parent))    # vehicle_sim from this checkout

from vehicle_sim.core.geometry.geodesy import GeodeticOrigin, LocalTangentPlane  # noqa: E402

ORIGIN = GeodeticOrigin(35.6812, 139.7671, 0.0)   # Tokyo, as config/maps/lanelet2_map.osm
NAME = 'urban_map.osm'
LANE_M = 3.5
BOX_M = 10.0                   # the intersection's half size: the arms start here
CROSSWALK_M = (10.0, 14.0)     # each crosswalk's span from the centre
STOP_M = 15.0                  # each stop line's distance from the centre
ARM_M = 70.0                   # each arm's length from the centre
STEP_M = 10.0                  # node spacing along the arms
ARC_POINTS = 10
LIGHT_ELE_M, LIGHT_HEIGHT_M = 5.0, 0.5
SPEED_KMH = {'arm': 40, 'box': 30}
# east arm (2): its outgoing right lane runs 10 .. 40 m, then tapers to nothing at 60 m
LANE2_END_M, TAPER_END_M = 40.0, 60.0


def _turn(points, k):
    """Rotate canonical points (the arm to the west, incoming eastbound) to arm k."""
    c, s = [(1, 0), (0, 1), (-1, 0), (0, -1)][k]
    return [(c * x - s * y, s * x + c * y) for x, y in points]


def _line(x0, x1, y):
    count = max(1, round(abs(x1 - x0) / STEP_M))
    return [(x0 + (x1 - x0) * i / count, y) for i in range(count + 1)]


def _arc(centre, radii, angles):
    """Points of an arc around centre, from angles[0] to [1], the radius going r0 -> r1."""
    return [(centre[0] + r * math.cos(a), centre[1] + r * math.sin(a))
            for r, a in ((radii[0] + (radii[1] - radii[0]) * i / ARC_POINTS,
                          angles[0] + (angles[1] - angles[0]) * i / ARC_POINTS)
                         for i in range(ARC_POINTS + 1))]


class _Map:
    """The primitives, as OSM XML lines, with ids given in order."""

    def __init__(self):
        self.plane = LocalTangentPlane(ORIGIN)
        self.nodes, self.ways, self.relations = [], [], []
        self.node_ids = {}
        self.next_way = 1000

    def node(self, x, y, ele=0.0, tags=()):
        key = (round(x, 6) + 0.0, round(y, 6) + 0.0, round(ele, 6), tuple(tags))
        if key not in self.node_ids:
            self.node_ids[key] = 1 + len(self.node_ids)
            lat, lon, _ = self.plane.to_geodetic(x, y, 0.0)
            extra = ''.join(f'\n    <tag k="{k}" v="{v}"/>' for k, v in tags)
            self.nodes.append(
                f'  <node id="{self.node_ids[key]}" lat="{lat:.11f}" lon="{lon:.11f}">\n'
                f'    <tag k="local_x" v="{x:.4f}"/>\n    <tag k="local_y" v="{y:.4f}"/>\n'
                f'    <tag k="ele" v="{ele:.2f}"/>{extra}\n  </node>')
        return self.node_ids[key]

    def way(self, points, tags, ele=0.0):
        self.next_way += 1
        refs = ''.join(f'\n    <nd ref="{self.node(x, y, ele)}"/>' for x, y in points)
        self.ways.append(f'  <way id="{self.next_way}">{refs}{_tags(tags)}\n  </way>')
        return self.next_way

    def way_of_nodes(self, node_ids, tags):
        self.next_way += 1
        refs = ''.join(f'\n    <nd ref="{n}"/>' for n in node_ids)
        self.ways.append(f'  <way id="{self.next_way}">{refs}{_tags(tags)}\n  </way>')
        return self.next_way

    def relation(self, rel_id, members, tags):
        lines = ''.join(f'\n    <member type="{kind}" ref="{ref}" role="{role}"/>'
                        for kind, ref, role in members)
        self.relations.append(f'  <relation id="{rel_id}">{lines}{_tags(tags)}\n  </relation>')

    def lanelet(self, rel_id, left, right, speed_kmh, elements=(), **tags):
        members = [('way', left, 'left'), ('way', right, 'right')] + [
            ('relation', e, 'regulatory_element') for e in elements]
        self.relation(rel_id, members, dict(
            type='lanelet', subtype='road', location='urban', one_way='yes',
            speed_limit=str(speed_kmh), **{'participant:vehicle': 'yes'}, **tags))


def _tags(tags):
    return ''.join(f'\n    <tag k="{k}" v="{v}"/>' for k, v in tags.items())


LINE = {'type': 'line_thin', 'subtype': 'solid'}
DASHED = {'type': 'line_thin', 'subtype': 'dashed'}
CURB = {'type': 'curbstone', 'subtype': 'high'}
VIRTUAL = {'type': 'virtual'}


# Where each arm's road is cut into lanelets [m from the centre]: the east arm (2) where its
# outgoing right lane ends and where its taper ends.
CUTS = {0: (BOX_M, ARM_M), 1: (BOX_M, ARM_M), 2: (BOX_M, LANE2_END_M, TAPER_END_M, ARM_M),
        3: (BOX_M, ARM_M)}


def lanelet_ids(k):
    """Return arm k's lanelet ids: in, out (both at the box), straight on, left, right."""
    return 100 + 10 * k, 101 + 10 * k, 200 + 10 * k, 201 + 10 * k, 202 + 10 * k


def _section_ids(k, i):
    """Return (incoming, outgoing) lanelet ids of arm k's section i (0: at the box)."""
    incoming, outgoing = lanelet_ids(k)[:2]
    return (incoming, outgoing) if i == 0 else (102 + 10 * k + 2 * i, 103 + 10 * k + 2 * i)


def _arm(m, k):
    """Add arm k's lanelets, its light and its crosswalk; return its right bounds out."""
    cuts = CUTS[k]
    out_bounds = []
    for i, (near, far) in enumerate(zip(cuts[:-1], cuts[1:])):
        incoming, outgoing = _section_ids(k, i)
        centre = m.way(_turn(_line(-far, -near, 0.0), k), LINE)
        edge_in = m.way(_turn(_line(-far, -near, -LANE_M), k), CURB)
        two_lanes = k == 2 and far <= TAPER_END_M          # a lane (or its taper) beside it
        edge_out = m.way(_turn(_line(-near, -far, LANE_M), k), DASHED if two_lanes else CURB)
        out_bounds.append(edge_out)
        if i == 0:
            stop = m.way(_turn([(-STOP_M, 0.0), (-STOP_M, -LANE_M)], k), {'type': 'stop_line'})
            _light(m, k, stop)
            _crosswalk(m, k)
            m.lanelet(incoming, centre, edge_in, SPEED_KMH['arm'], [400 + k, 500 + k])
            m.lanelet(outgoing, centre, edge_out, SPEED_KMH['arm'], [500 + k])
        else:
            m.lanelet(incoming, centre, edge_in, SPEED_KMH['arm'])
            m.lanelet(outgoing, centre, edge_out, SPEED_KMH['arm'])
    return out_bounds


def _light(m, k, stop):
    """Add arm k's traffic light regulatory element (400 + k), its light and bulbs."""
    # across the box on the right, seen from the stop line: its bottom left, then right
    x = BOX_M + 4.0
    light = m.way(_turn([(x, -2 * LANE_M - 1.4), (x, -2 * LANE_M - 2.6)], k),
                  {'type': 'traffic_light', 'subtype': 'red_yellow_green',
                   'height': str(LIGHT_HEIGHT_M)}, LIGHT_ELE_M)
    points = _turn([(x, -2 * LANE_M - 1.6 - 0.4 * i) for i in range(3)], k)
    bulbs = m.way_of_nodes([m.node(px, py, LIGHT_ELE_M + 0.25, (('color', color),))
                            for (px, py), color in zip(points, ('green', 'yellow', 'red'))],
                           {'type': 'light_bulbs', 'traffic_light_id': str(light)})
    m.relation(400 + k, [('way', light, 'refers'), ('way', stop, 'ref_line'),
                         ('way', bulbs, 'light_bulbs')],
               {'type': 'regulatory_element', 'subtype': 'traffic_light'})


def _crosswalk(m, k):
    """Add arm k's crosswalk lanelet (300 + k) and regulatory element (500 + k)."""
    low = -LANE_M - 1.0
    high = (2 * LANE_M + 1.0) if k == 2 else (LANE_M + 1.0)   # the east arm: two lanes out
    near, far = -CROSSWALK_M[0], -CROSSWALK_M[1]
    left = m.way(_turn([(far, low), (far, high)], k), {'type': 'pedestrian_marking'})
    right = m.way(_turn([(near, low), (near, high)], k), {'type': 'pedestrian_marking'})
    m.relation(300 + k, [('way', left, 'left'), ('way', right, 'right')], {
        'type': 'lanelet', 'subtype': 'crosswalk', 'location': 'urban', 'one_way': 'no',
        'speed_limit': '10', 'participant:pedestrian': 'yes'})
    polygon = m.way(_turn([(far, low), (near, low), (near, high), (far, high)], k),
                    {'type': 'crosswalk_polygon', 'area': 'yes'})
    m.relation(500 + k, [('relation', 300 + k, 'refers'), ('way', polygon, 'crosswalk_polygon')],
               {'type': 'regulatory_element', 'subtype': 'crosswalk'})


def _box(m, k):
    """Add the lanelets from arm k through the box: straight on, left, right; its right of way."""
    _, _, straight, left, right = lanelet_ids(k)
    box = SPEED_KMH['box']
    m.lanelet(straight, m.way(_turn(_line(-BOX_M, BOX_M, 0.0), k), VIRTUAL),
              m.way(_turn(_line(-BOX_M, BOX_M, -LANE_M), k), VIRTUAL), box, [600 + k],
              turn_direction='straight')
    quarter = (-0.5 * math.pi, 0.0)                  # around (-10, 10)
    m.lanelet(left, m.way(_turn(_arc((-BOX_M, BOX_M), (BOX_M, BOX_M), quarter), k), VIRTUAL),
              m.way(_turn(_arc((-BOX_M, BOX_M), (BOX_M + LANE_M,) * 2, quarter), k), VIRTUAL),
              box, [600 + (k + 2) % 4], turn_direction='left')
    # around (-10, -10); arm 1's right turn leads into the east arm's right lane, a lane further
    inner = BOX_M - 2 * LANE_M if k == 1 else BOX_M - LANE_M
    quarter = (0.5 * math.pi, 0.0)
    m.lanelet(right, m.way(_turn(_arc((-BOX_M, -BOX_M), (BOX_M, inner + LANE_M), quarter), k),
                           VIRTUAL),
              m.way(_turn(_arc((-BOX_M, -BOX_M), (BOX_M - LANE_M, inner), quarter), k),
                    VIRTUAL), box, turn_direction='right')
    # the straight movement goes before the opposite arm's left turn
    m.relation(600 + k, [('relation', straight, 'right_of_way'),
                         ('relation', lanelet_ids((k + 2) % 4)[3], 'yield')],
               {'type': 'regulatory_element', 'subtype': 'right_of_way'})


def osm_text():
    """Return the map as OSM XML, in Autoware's format."""
    m = _Map()
    east_out = None
    for k in range(4):
        bounds = _arm(m, k)
        east_out = bounds if k == 2 else east_out
    for k in range(4):
        _box(m, k)
    # the east arm's right lane (190) beside 121, then its taper (191) beside 125
    outer = m.way(_line(BOX_M, LANE2_END_M, -2 * LANE_M), CURB)
    taper_edge = m.way([(LANE2_END_M, -2 * LANE_M), (TAPER_END_M, -LANE_M)], CURB)
    m.lanelet(190, east_out[0], outer, SPEED_KMH['arm'], [502])
    m.lanelet(191, east_out[1], taper_edge, SPEED_KMH['arm'])
    return '\n'.join(['<?xml version="1.0" encoding="UTF-8"?>',
                      '<osm version="0.6" generator="vehicle_sim make_urban_map.py">',
                      '  <MetaInfo format_version="1" map_version="1"/>',
                      *m.nodes, *m.ways, *m.relations, '</osm>', ''])


def main():
    """Write the map beside this script."""
    path = FOLDER / NAME
    path.write_text(osm_text(), encoding='utf-8')
    print(f'wrote {path}')


if __name__ == '__main__':
    main()
