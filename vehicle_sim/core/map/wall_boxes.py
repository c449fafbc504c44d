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
An occupancy map's merged wall rectangles as boxes in the world frame.

Each rectangle of :func:`~vehicle_sim.core.map.rectangles.merge_rectangles` (cells of the grid)
becomes one box standing on the ground, ``height_m`` high: its centre, its yaw (the grid's yaw
in the map frame, less the ``world_in_map`` yaw) and its size. The physics' wall meshes and the
Foxglove scene's wall cubes are the same boxes.
"""

from dataclasses import dataclass
import math

import numpy as np

from vehicle_sim.core.map.rectangles import COLUMN, COLUMNS, ROW, ROWS


@dataclass(frozen=True, eq=False)
class WallBoxes:
    """
    Boxes standing on the ground, all turned alike.

    :param centres_m: float (n, 3) [m].
    :param yaw_rad: the yaw of every box (the grid is straight) [rad].
    :param sizes_m: float (n, 3): along each box's own x, y, z [m].
    """

    centres_m: np.ndarray
    yaw_rad: float
    sizes_m: np.ndarray


def wall_boxes(grid, rectangles: np.ndarray, world_in_map, height_m: float) -> WallBoxes:
    """
    Return the boxes of a grid's wall rectangles in the world frame.

    :param grid: the OccupancyGrid (resolution, origin in the map frame).
    :param rectangles: int (n, 4) rows of merge_rectangles (row, column, rows, columns).
    :param world_in_map: the map spec's MapPlacement (the world frame's pose in the map frame).
    :param height_m: the walls' height [m].
    """
    rectangles = np.asarray(rectangles, dtype=np.int64).reshape(-1, 4)
    u = rectangles[:, COLUMN] + 0.5 * rectangles[:, COLUMNS]
    v = rectangles[:, ROW] + 0.5 * rectangles[:, ROWS]
    ox, oy, grid_yaw = grid.origin
    c, s = math.cos(grid_yaw), math.sin(grid_yaw)
    resolution = grid.resolution_m
    dx = ox + (c * u - s * v) * resolution - world_in_map.x_m
    dy = oy + (s * u + c * v) * resolution - world_in_map.y_m
    pc, ps = math.cos(world_in_map.yaw_rad), math.sin(world_in_map.yaw_rad)
    centres = np.column_stack((pc * dx + ps * dy, -ps * dx + pc * dy,
                               np.full(len(rectangles), 0.5 * height_m)))
    sizes = np.column_stack((rectangles[:, COLUMNS] * resolution, rectangles[:, ROWS] * resolution,
                             np.full(len(rectangles), float(height_m))))
    return WallBoxes(centres, grid_yaw - world_in_map.yaw_rad, sizes)
