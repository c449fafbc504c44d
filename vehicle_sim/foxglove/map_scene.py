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
The static layers of the Foxglove scene: an occupancy map's walls and a lane map.

Both are built once per scene (entity sources registered ``static`` in :mod:`.scene`) from what
the scene builder already made, in the ``world`` frame, with the very geometry the physics uses:

- ``'map'``: a map's walls (``scene.parts['map'].wall_boxes()``: an occupancy-grid map's) as
  one entity ``map/walls`` with
  one cube per merged wall rectangle (core/map/rectangles.py, placed by core/map/wall_boxes.py),
  ``wall_height`` high: the walls the lidar sees, at the cost of one cube per rectangle.
- ``'lanes'``: a lane map (``scene.lanes``, from a lanelet2 map, a SUMO network or ``roads:``) as
  ``lanes/surface`` (the road surface, one triangle list), ``lanes/markings`` (each painted
  stripe a line ``LINE_WIDTH_M`` wide: a line strip for a solid one, a line list of its dashes
  for a dashed one, coloured by stripe type), ``lanes/barriers`` (a cube per curbstone, road
  border or wall piece) and ``lanes/centerlines`` (thin line strips, one per lane); from the
  map's rules (``graph.rules``), when it has them: ``lanes/areas`` (each area's polygon in its
  kind's colour, core/map/lane_geometry.py's ``area_color``: one triangle list per kind),
  ``lanes/stop_lines`` (a white line ``STOP_LINE_WIDTH_M`` wide per stop line),
  ``lanes/crosswalks`` (the zebra stripes, one white triangle list) and ``lanes/signal_poles``
  (a cube per traffic light pole, core/map/signal_lamps.py).

The traffic lights' heads change with their state: ``signals/<group id>`` (:func:`lamp_entities`,
the entity source ``'signals'``, sent when it changes): a cube per bulb's housing and a sphere
per bulb, lit in its colour or dark as the physics shows it (``scene.parts['signal_lamps']``).
"""

import math
from typing import List
import weakref

import numpy as np

from vehicle_sim.core.geometry.frames import quaternion_from_rpy
from vehicle_sim.core.map.lane_geometry import (
    area_color,
    area_meshes,
    BARRIER_WIDTH_M,
    barriers,
    crosswalk_mesh,
    LINE_WIDTH_M,
    MARKING_Z_M,
    PAINT_COLOR,
    painted_pieces,
    STOP_LINE_WIDTH_M,
    surface_mesh,
)
from vehicle_sim.core.map.signal_lamps import (
    HOUSING_COLOR,
    LAMP_RADIUS_M,
    lamps,
    POLE_COLOR,
    POLE_WIDTH_M,
    poles,
)
from vehicle_sim.core.map.wall_boxes import WallBoxes
from vehicle_sim.foxglove.entities import Entity, Lines, Primitive, Triangles, WORLD_FRAME

WALL_COLOR = (0.55, 0.55, 0.6, 1.0)          # concrete grey, as the physics draws them
SURFACE_COLOR = (0.3, 0.3, 0.32, 1.0)        # asphalt
BARRIER_COLOR = (0.7, 0.7, 0.68, 1.0)        # concrete
# Painted stripes by type: solid white (not to be crossed), dashed amber (may be crossed).
MARKING_COLOR = {'solid': (0.95, 0.95, 0.95, 1.0), 'dashed': (1.0, 0.75, 0.2, 1.0)}
CENTERLINE_COLOR = (0.3, 0.8, 1.0, 0.6)
CENTERLINE_WIDTH_M = 0.05
# Centrelines just above the paint, so that they show where they cross it.
CENTERLINE_Z_M = MARKING_Z_M + 0.002


# ------------------------------------------------------------------------------ occupancy walls

def walls_entity(boxes: WallBoxes) -> Entity:
    """Return the walls as one entity ``map/walls``: a cube per box."""
    orientation = quaternion_from_rpy(0.0, 0.0, boxes.yaw_rad)
    cubes = tuple(Primitive('cube', tuple(centre), orientation, tuple(size), WALL_COLOR)
                  for centre, size in zip(boxes.centres_m.tolist(), boxes.sizes_m.tolist()))
    return Entity('map/walls', WORLD_FRAME, cubes)


def wall_entities(scene) -> List[Entity]:
    """Return a map's walls (the entity source ``'map'``); none without a map or walls."""
    built = getattr(scene, 'parts', {}).get('map')
    boxes = None if built is None else built.wall_boxes()
    return [] if boxes is None else [walls_entity(boxes)]


# ------------------------------------------------------------------------------ lanes

def _at(points_2d, z_m) -> np.ndarray:
    return np.column_stack((points_2d, np.full(len(points_2d), z_m)))


def surface_entity(graph) -> Entity:
    """Return the road surface ``lanes/surface``: one indexed triangle list."""
    mesh = surface_mesh(graph)
    return Entity('lanes/surface', WORLD_FRAME, (), triangles=(
        Triangles(mesh.vertices, mesh.triangles, SURFACE_COLOR),))


def markings_entity(graph) -> Entity:
    """
    Return the painted lines ``lanes/markings``.

    One line strip per solid stripe; one line list per dashed stripe (each dash's points
    joined in pairs), so that the gaps stay empty.
    """
    lines = []
    dashes = {}        # (boundary id, stripe middle) -> the dashes' segment end points
    for boundary, kind, piece in painted_pieces(graph):
        points = _at(piece, MARKING_Z_M)
        if kind == 'solid':
            lines.append(Lines('line_strip', points, LINE_WIDTH_M, MARKING_COLOR['solid']))
        else:
            pairs = np.empty((2 * (len(points) - 1), 3))
            pairs[0::2], pairs[1::2] = points[:-1], points[1:]
            dashes.setdefault(boundary.id, []).append(pairs)
    lines.extend(Lines('line_list', np.vstack(parts), LINE_WIDTH_M, MARKING_COLOR['dashed'])
                 for parts in dashes.values())
    return Entity('lanes/markings', WORLD_FRAME, (), lines=tuple(lines))


def barriers_entity(graph) -> Entity:
    """Return the curbstones, road borders and walls ``lanes/barriers``: a cube per piece."""
    cubes = []
    for piece in barriers(graph):
        dx, dy = piece.x1_m - piece.x0_m, piece.y1_m - piece.y0_m
        cubes.append(Primitive(
            'cube', (0.5 * (piece.x0_m + piece.x1_m), 0.5 * (piece.y0_m + piece.y1_m),
                     0.5 * piece.height_m),
            quaternion_from_rpy(0.0, 0.0, math.atan2(dy, dx)),
            (math.hypot(dx, dy), BARRIER_WIDTH_M, piece.height_m), BARRIER_COLOR))
    return Entity('lanes/barriers', WORLD_FRAME, tuple(cubes))


def centerlines_entity(graph) -> Entity:
    """Return every lane's centreline ``lanes/centerlines``: thin line strips."""
    return Entity('lanes/centerlines', WORLD_FRAME, (), lines=tuple(
        Lines('line_strip', _at(np.asarray(lane.centerline, dtype=float), CENTERLINE_Z_M),
              CENTERLINE_WIDTH_M, CENTERLINE_COLOR) for lane in graph.lanes.values()))


def rules_entities(graph) -> List[Entity]:
    """
    Return what a LaneGraph's rules draw on the road: areas, stop lines, crosswalks, poles.

    Each entity only when the rules have some of its kind.
    """
    found = []
    rules = graph.rules
    areas = area_meshes(graph)
    if areas:
        found.append(Entity('lanes/areas', WORLD_FRAME, (), triangles=tuple(
            Triangles(mesh.vertices, mesh.triangles, area_color(kind))
            for kind, mesh in areas.items())))
    if rules.stop_lines:
        found.append(Entity('lanes/stop_lines', WORLD_FRAME, (), lines=tuple(
            Lines('line_strip', _at(line.points, MARKING_Z_M), STOP_LINE_WIDTH_M, PAINT_COLOR)
            for line in rules.stop_lines)))
    stripes = crosswalk_mesh(graph)
    if len(stripes.triangles):
        found.append(Entity('lanes/crosswalks', WORLD_FRAME, (), triangles=(
            Triangles(stripes.vertices, stripes.triangles, PAINT_COLOR),)))
    standing = poles(graph, lamps(graph))
    if standing:
        found.append(Entity('lanes/signal_poles', WORLD_FRAME, tuple(
            Primitive('cube', (pole.x_m, pole.y_m, 0.5 * pole.height_m), (0.0, 0.0, 0.0, 1.0),
                      (POLE_WIDTH_M, POLE_WIDTH_M, pole.height_m), POLE_COLOR)
            for pole in standing)))
    return found


def lane_map_entities(graph) -> List[Entity]:
    """
    Return a LaneGraph's entities.

    Surface, markings, barriers (when any), centrelines, then its rules' (:func:`rules_entities`).
    """
    found = [surface_entity(graph), markings_entity(graph)]
    wall_pieces = barriers_entity(graph)
    if wall_pieces.primitives:
        found.append(wall_pieces)
    found.append(centerlines_entity(graph))
    return found + rules_entities(graph)


def lane_entities(scene) -> List[Entity]:
    """Return the scene's lane map (the entity source ``'lanes'``); none without lanes."""
    graph = getattr(scene, 'lanes', None)
    return [] if graph is None else lane_map_entities(graph)


# ------------------------------------------------------------------------------ traffic lights

def group_lamps_entity(group_id, colored) -> Entity:
    """
    Return one traffic light group's heads ``signals/<group id>``.

    :param colored: [(Lamp, RGBA)] of the group's lamps: a housing cube and a bulb sphere each.
    """
    primitives = []
    for lamp, rgba in colored:
        orientation = quaternion_from_rpy(0.0, 0.0, lamp.yaw_rad)
        primitives.append(Primitive('cube', lamp.housing_centre_m, orientation,
                                    lamp.housing_size_m, HOUSING_COLOR))
        bulb = lamp.bulb
        primitives.append(Primitive('sphere', (bulb.x_m, bulb.y_m, bulb.z_m), orientation,
                                    (2 * LAMP_RADIUS_M,) * 3, tuple(rgba)))
    return Entity(f'signals/{group_id}', WORLD_FRAME, tuple(primitives))


def lamp_entities(scene) -> List[Entity]:
    """
    Return the traffic lights' heads as the physics shows them now (the entity source 'signals').

    One entity per group with bulbs (``scene.parts['signal_lamps']``); none without lamps.
    """
    shown = getattr(scene, 'parts', {}).get('signal_lamps')
    if shown is None:
        return []
    shown.refresh()
    cached = _LAMP_ENTITIES.get(shown)
    if cached is not None and cached[0] == shown.changes:   # no lamp changed colour since
        return list(cached[1])
    groups = {}
    for lamp, rgba in shown.lamp_colors():
        groups.setdefault(lamp.group_id, []).append((lamp, rgba))
    found = [group_lamps_entity(group_id, colored) for group_id, colored in groups.items()]
    _LAMP_ENTITIES[shown] = (shown.changes, found)
    return list(found)


# The lamp entities last built for each world's lamps: (their colour changes then, entities).
_LAMP_ENTITIES = weakref.WeakKeyDictionary()
