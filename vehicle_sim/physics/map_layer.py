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
The map layer: the scene part that builds a world's ``map:`` into the World.

:class:`MapLayer` is a scene part (``physics/scene.py``); the scene builder adds it when the
WorldSpec has a map. It looks the map's ``type`` up in :data:`MAP_BUILDERS` (one builder per
kind of core/map/kinds.py's ``MAP_KINDS``; a test checks both list the same kinds) and returns
what the builder returns, which callers read as ``scene.parts['map']`` (the ROS node publishes
``/map`` from it).

An occupancy grid (:func:`build_occupancy_grid`) becomes static walls: its wall cells (value
100, and unknown cells with ``unknown: occupied``) merged into rectangles
(core/map/rectangles.py), each a box from the ground up to ``wall_height``, grouped by area into
compound bodies of at most :data:`BOXES_PER_BODY` boxes. The World names them ``map``
(``World.add_static``): lidar, distance sensors and cameras see them, collisions report
``other: map``, and a teleport into one is refused like one into an obstacle. A vehicle whose
start position lies on a wall cell is refused before anything is built, naming the world file's
field; one whose outline touches a wall is refused by the World.
"""

from dataclasses import dataclass
import math
from typing import Callable, Dict, Tuple

import numpy as np
import pybullet

from vehicle_sim.core.errors import InvalidParameterError
from vehicle_sim.core.frames import quaternion_from_yaw
from vehicle_sim.core.map.kinds import OccupancyMapSpec
from vehicle_sim.core.map.occupancy import MapYaml, OccupancyGrid, wall_mask
from vehicle_sim.core.map.rectangles import COLUMN, COLUMNS, merge_rectangles, ROW, ROWS
from vehicle_sim.core.world_params import WorldSpec
from vehicle_sim.map_files import load_occupancy_grid

MAP_BODY_NAME = 'map'
# Boxes of one compound body, and the side of the square of cells they are grouped by.
BOXES_PER_BODY = 256
TILE_CELLS = 64
WALL_COLOR = (0.55, 0.55, 0.6, 1.0)     # concrete grey


@dataclass(eq=False)
class OccupancyMap:
    """
    A built occupancy-grid map: what the ROS layer publishes and tests read.

    :param spec: the world file's map spec.
    :param map_yaml: the validated map YAML.
    :param grid: the cell values (as map_server publishes them) and their place.
    :param walls: bool (height, width) mask of the wall cells.
    :param rectangles: the merged wall rectangles (core/map/rectangles.py's rows).
    :param body_ids: the compound bodies holding the walls.
    """

    spec: OccupancyMapSpec
    map_yaml: MapYaml
    grid: OccupancyGrid
    walls: np.ndarray
    rectangles: np.ndarray
    body_ids: Tuple[int, ...]

    def wall_at(self, x_m: float, y_m: float) -> bool:
        """Return True when the world-frame point lies on a wall cell."""
        cell = self.grid.cell_at(*self.spec.world_in_map.to_map(x_m, y_m))
        return cell is not None and bool(self.walls[cell])


def _check_spawns(spec: WorldSpec, built: OccupancyMap):
    for index, vehicle in enumerate(spec.vehicles):
        if built.wall_at(vehicle.x_m, vehicle.y_m):
            row, column = built.grid.cell_at(
                *built.spec.world_in_map.to_map(vehicle.x_m, vehicle.y_m))
            raise InvalidParameterError(
                f"{spec.source}: vehicles[{index}] ({vehicle.name}): field 'pose' = "
                f'{{x: {vehicle.x_m:g}, y: {vehicle.y_m:g}}}: on an occupied cell (row '
                f'{row}, column {column} from the lower left) of map {built.map_yaml.source}; '
                'place it in free space')


def _wall_boxes(grid: OccupancyGrid, rectangles: np.ndarray, spec: OccupancyMapSpec):
    # Centres (world frame), half extents and the yaw of every rectangle's box.
    resolution = grid.resolution_m
    u = rectangles[:, COLUMN] + rectangles[:, COLUMNS] / 2.0
    v = rectangles[:, ROW] + rectangles[:, ROWS] / 2.0
    ox, oy, grid_yaw = grid.origin
    c, s = math.cos(grid_yaw), math.sin(grid_yaw)
    map_x = ox + (c * u - s * v) * resolution
    map_y = oy + (s * u + c * v) * resolution
    placement = spec.world_in_map
    pc, ps = math.cos(placement.yaw_rad), math.sin(placement.yaw_rad)
    dx, dy = map_x - placement.x_m, map_y - placement.y_m
    centres = np.stack([pc * dx + ps * dy, -ps * dx + pc * dy,
                        np.full(len(u), spec.wall_height_m / 2.0)], axis=1)
    halves = np.stack([rectangles[:, COLUMNS] * (resolution / 2.0),
                       rectangles[:, ROWS] * (resolution / 2.0),
                       np.full(len(u), spec.wall_height_m / 2.0)], axis=1)
    tiles = (v // TILE_CELLS).astype(np.int64) * (grid.width // TILE_CELLS + 1) \
        + (u // TILE_CELLS).astype(np.int64)
    return centres, halves, grid_yaw - placement.yaw_rad, tiles


def _groups(tiles):
    # Index groups: rectangles of one tile, at most BOXES_PER_BODY each.
    order = np.argsort(tiles, kind='stable')
    sorted_tiles = tiles[order]
    bounds = np.flatnonzero(np.diff(sorted_tiles)) + 1
    for chunk in np.split(order, bounds):
        for start in range(0, len(chunk), BOXES_PER_BODY):
            yield chunk[start:start + BOXES_PER_BODY]


def _create_walls(world, grid, rectangles, spec) -> Tuple[int, ...]:
    if len(rectangles) == 0:
        return ()
    cid = world.client_id
    centres, halves, yaw, tiles = _wall_boxes(grid, rectangles, spec)
    q = list(quaternion_from_yaw(yaw))
    body_ids = []
    for group in _groups(tiles):
        count = len(group)
        positions = centres[group].tolist()
        extents = halves[group].tolist()
        orientations = [q] * count
        collision = pybullet.createCollisionShapeArray(
            [pybullet.GEOM_BOX] * count, halfExtents=extents, collisionFramePositions=positions,
            collisionFrameOrientations=orientations, physicsClientId=cid)
        visual = pybullet.createVisualShapeArray(
            [pybullet.GEOM_BOX] * count, halfExtents=extents, visualFramePositions=positions,
            visualFrameOrientations=orientations, physicsClientId=cid)
        body = pybullet.createMultiBody(0.0, collision, visual, physicsClientId=cid)
        pybullet.changeVisualShape(body, -1, rgbaColor=list(WALL_COLOR), physicsClientId=cid)
        body_ids.append(body)
    return tuple(body_ids)


def build_occupancy_grid(world, spec: WorldSpec) -> OccupancyMap:
    """
    Read a world's occupancy-grid map and build its walls into ``world``.

    :raises InvalidParameterError: for a map file that cannot be read or is wrong, or a
        vehicle placed on a wall cell (naming the file and the field); nothing is added.
    :raises InvalidPoseError: for a vehicle whose outline is inside a wall.
    """
    map_spec = spec.map
    map_yaml, grid = load_occupancy_grid(map_spec)
    walls = wall_mask(grid, map_spec.unknown == 'occupied')
    rectangles = merge_rectangles(walls)
    built = OccupancyMap(map_spec, map_yaml, grid, walls, rectangles, ())
    _check_spawns(spec, built)
    built.body_ids = _create_walls(world, grid, rectangles, map_spec)
    world.add_static(MAP_BODY_NAME, built.body_ids)
    return built


# map kind (core/map/kinds.py MAP_KINDS) -> build(world, WorldSpec) -> what callers read.
MAP_BUILDERS: Dict[str, Callable] = {
    'occupancy_grid': build_occupancy_grid,
}


class MapLayer:
    """The scene part of a world's map: builds ``spec.map`` with its kind's builder."""

    name = 'map'

    def build(self, world, spec: WorldSpec):
        """Build the map into ``world``; return what its builder returns (None: no map)."""
        if spec.map is None:
            return None
        return MAP_BUILDERS[spec.map.type](world, spec)
