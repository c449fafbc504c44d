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
``/map`` from it and logs its ``describe()``).

An occupancy grid (:func:`build_occupancy_grid`) becomes static walls: its wall cells (value
100, and unknown cells with ``unknown: occupied``) merged into rectangles
(core/map/rectangles.py), each a box from the ground up to ``wall_height`` (its four sides and
its top), ordered by area into static triangle meshes of at most :data:`BOXES_PER_BODY` boxes
(Bullet's BVH meshes: a contact finds its triangles through a tree, and static meshes cost
nothing against the ground or each other, so a large map leaves the step as it was; PyBullet's
compound shapes would hold at most 16 boxes each). The World names them ``map``
(``World.add_static``): cameras see them, collisions report ``other: map``, and a teleport into
one is refused like one into an obstacle (also one that would put the body's centre inside a
thick wall, where it touches no face). Lidar and distance sensors find the walls over the grid
instead (core/map/grid_rays.py's GridRays, ``World.add_ray_grid``): the same solid and the same
hits as the ray march, at a cost that does not grow with the walls' faces (Bullet walks a
mesh's tree along the whole ray, past its first hit: on a SLAM map with thick, ragged walls
that made a lidar cost 8 times as much as in an empty world). A vehicle whose
start position lies on a wall cell is refused before anything is built, naming the world file's
field; one whose outline touches a wall is refused by the World.

A lane map (lanelet2, and the SUMO networks sumo, opendrive and osm:
:func:`~vehicle_sim.physics.lane_layer.build_lane_map`) becomes its road surface, markings and
barriers (physics/lane_layer.py); its lanes were loaded before the bodies (``spec.lanes``).
"""

from dataclasses import dataclass
import math
from typing import Callable, Dict, Optional, Tuple

import numpy as np
import pybullet

from vehicle_sim.core.map.grid_rays import GridRays
from vehicle_sim.core.map.kinds import OccupancyMapSpec
from vehicle_sim.core.map.occupancy import describe_size, MapYaml, OccupancyGrid, wall_mask
from vehicle_sim.core.map.rectangles import COLUMN, COLUMNS, merge_rectangles, ROW, ROWS
from vehicle_sim.core.map.wall_boxes import wall_boxes, WallBoxes
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.value_text import count
from vehicle_sim.core.world.params import WorldSpec
from vehicle_sim.maps.occupancy_files import load_occupancy_grid
from vehicle_sim.physics.lane_layer import build_lane_map

MAP_BODY_NAME = 'map'
# Boxes of one static mesh body, and the side of the square of cells they are ordered by.
# PyBullet takes at most 131072 vertices per mesh: 8 per box.
BOXES_PER_BODY = 8192
TILE_CELLS = 256
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
    :param body_ids: the static mesh bodies holding the walls.
    :param rays: the walls for ray sensors (core/map/grid_rays.py); None without walls.
    """

    spec: OccupancyMapSpec
    map_yaml: MapYaml
    grid: OccupancyGrid
    walls: np.ndarray
    rectangles: np.ndarray
    body_ids: Tuple[int, ...]
    rays: Optional[GridRays] = None

    def describe(self) -> str:
        """One line for logs: the file, its size, its walls (every built map has one)."""
        return (f'{self.map_yaml.source}: {describe_size(self.grid)}, '
                f"{count(len(self.rectangles), 'wall rectangle', 'wall rectangles')}")

    def wall_boxes(self) -> Optional[WallBoxes]:
        """Return the wall boxes in the world frame (scenario footprints, the live view)."""
        if len(self.rectangles) == 0:
            return None
        return wall_boxes(self.grid, self.rectangles, self.spec.world_in_map,
                          self.spec.wall_height_m)

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


# The faces of a box from its 8 corners (0..3 at the ground, 4..7 on top, counter-clockwise
# seen from above): four sides and the top, two triangles each, facing out.
_BOX_TRIANGLES = np.array([0, 1, 5, 0, 5, 4, 1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6,
                           3, 0, 4, 3, 4, 7, 4, 5, 6, 4, 6, 7], dtype=np.int64)


def _wall_corners(grid: OccupancyGrid, rectangles: np.ndarray, spec: OccupancyMapSpec):
    # float (n, 8, 3): the corners of every rectangle's box in the world frame.
    u0 = rectangles[:, COLUMN].astype(float)
    v0 = rectangles[:, ROW].astype(float)
    u1, v1 = u0 + rectangles[:, COLUMNS], v0 + rectangles[:, ROWS]
    us = np.stack([u0, u1, u1, u0], axis=1)
    vs = np.stack([v0, v0, v1, v1], axis=1)
    ox, oy, grid_yaw = grid.origin
    c, s = math.cos(grid_yaw), math.sin(grid_yaw)
    resolution = grid.resolution_m
    map_x = ox + (c * us - s * vs) * resolution
    map_y = oy + (s * us + c * vs) * resolution
    placement = spec.world_in_map
    pc, ps = math.cos(placement.yaw_rad), math.sin(placement.yaw_rad)
    dx, dy = map_x - placement.x_m, map_y - placement.y_m
    corners = np.empty((len(rectangles), 8, 3))
    corners[:, :4, 0] = corners[:, 4:, 0] = pc * dx + ps * dy
    corners[:, :4, 1] = corners[:, 4:, 1] = -ps * dx + pc * dy
    corners[:, :4, 2] = 0.0
    corners[:, 4:, 2] = spec.wall_height_m
    return corners


def _spatial_order(rectangles, width):
    # Rectangles sorted by the tile their first cell lies in, so that each body is compact.
    tiles = (rectangles[:, ROW] // TILE_CELLS) * (width // TILE_CELLS + 1) \
        + rectangles[:, COLUMN] // TILE_CELLS
    return np.argsort(tiles, kind='stable')


def _create_walls(world, grid, rectangles, spec) -> Tuple[int, ...]:
    # Static triangle meshes (Bullet's BVH triangle mesh: rays and contacts find the triangles
    # they meet through a tree), at most BOXES_PER_BODY boxes each.
    if len(rectangles) == 0:
        return ()
    cid = world.client_id
    corners = _wall_corners(grid, rectangles, spec)[_spatial_order(rectangles, grid.width)]
    body_ids = []
    for start in range(0, len(corners), BOXES_PER_BODY):
        chunk = corners[start:start + BOXES_PER_BODY]
        vertices = chunk.reshape(-1, 3).tolist()
        indices = (_BOX_TRIANGLES[None, :]
                   + 8 * np.arange(len(chunk))[:, None]).ravel().tolist()
        collision = pybullet.createCollisionShape(
            pybullet.GEOM_MESH, vertices=vertices, indices=indices,
            flags=pybullet.GEOM_FORCE_CONCAVE_TRIMESH, physicsClientId=cid)
        visual = pybullet.createVisualShape(
            pybullet.GEOM_MESH, vertices=vertices, indices=indices,
            rgbaColor=list(WALL_COLOR), physicsClientId=cid)
        body_ids.append(pybullet.createMultiBody(0.0, collision, visual, physicsClientId=cid))
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
    world.add_static(MAP_BODY_NAME, built.body_ids, built.wall_at)
    for body_id in built.body_ids:
        world.labels.set(body_id, 'wall')
    if built.body_ids:
        built.rays = GridRays(walls, grid.resolution_m, _grid_corner(grid, map_spec),
                              map_spec.wall_height_m, map_spec.ray_march)
        world.add_ray_grid(built.rays, built.body_ids)
    return built


def _grid_corner(grid: OccupancyGrid, spec: OccupancyMapSpec):
    # (x, y, yaw) of cell (0, 0)'s lower-left corner in the world frame.
    placement = spec.world_in_map
    ox, oy, grid_yaw = grid.origin
    c, s = math.cos(placement.yaw_rad), math.sin(placement.yaw_rad)
    dx, dy = ox - placement.x_m, oy - placement.y_m
    return c * dx + s * dy, -s * dx + c * dy, grid_yaw - placement.yaw_rad


# map kind (core/map/kinds.py MAP_KINDS) -> build(world, WorldSpec) -> what callers read
# (``scene.parts['map']``): an object with ``spec``, ``describe()`` (one line for logs) and
# ``wall_boxes()`` (its walls as core/map/wall_boxes.py's WallBoxes, or None), which the scenario
# footprints and the live view read without naming the kind.
MAP_BUILDERS: Dict[str, Callable] = {
    'occupancy_grid': build_occupancy_grid,
    'lanelet2': build_lane_map,      # physics/lane_layer.py: a LaneMap
    'sumo': build_lane_map,
    'opendrive': build_lane_map,
    'osm': build_lane_map,
}


class MapLayer:
    """The scene part of a world's map: builds ``spec.map`` with its kind's builder."""

    name = 'map'

    def build(self, world, spec: WorldSpec):
        """Build the map into ``world``; return what its builder returns (None: no map)."""
        if spec.map is None:
            return None
        return MAP_BUILDERS[spec.map.type](world, spec)
