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
Occupancy-grid maps in nav2 map_server's format: the map YAML, thresholding, cells, rays.

The map YAML is validated against :data:`MAP_YAML_SPECS` (the keys nav2 map_server's
``map_io.cpp`` reads, required where it requires them). The image's pixels, already decoded by
the file reader (``vehicle_sim/maps/occupancy_files.py``), become cell values exactly as
map_server computes them (:func:`occupancy_values`):

- a pixel's *shade* is the mean of its red, green and blue channels (a grey pixel: its grey
  value), scaled to [0, 1]; in ``trinary`` mode an image with an alpha channel averages the
  alpha in too (opaque = 1); ``occ`` = ``1 - shade`` (``shade`` when ``negate``);
- ``trinary``: 100 when ``occ > occupied_thresh``, 0 when ``occ < free_thresh``, else -1;
- ``scale``: -1 for a pixel that is not fully opaque, 100 / 0 as in trinary, else
  ``rint((occ - free_thresh) / (occupied_thresh - free_thresh) * 100)``;
- ``raw``: ``round(shade * 255)`` when it lies in 0 .. 100, else -1 (``negate`` is ignored).

Images are stored top row first; the grid's row 0 is the image's bottom row, whose left cell
has its lower-left corner at ``origin`` (x, y, yaw: yaw turns the grid about that corner), as
``nav_msgs/OccupancyGrid`` orders its data. Everything here is file-free: numbers in, numbers
out.
"""

from dataclasses import dataclass
import math
import os
from typing import Optional, Tuple

import numpy as np

from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.param_spec import ParamSpec, REQUIRED, validate_table

MAP_MODES = ('trinary', 'scale', 'raw')
FREE = 0
OCCUPIED = 100
UNKNOWN = -1
# The largest image accepted (cells = width x height): 25 million cells, e.g. 5000 x 5000.
# Reading one costs about 10 bytes per cell at its peak (pixels, sums, values, wall mask).
MAX_CELLS = 25_000_000

# map_server reads pixels as GraphicsMagick quanta (16 bits): an 8-bit value v is v * 257.
_QUANTUM_PER_BYTE = 257.0
_MAX_QUANTUM = 65535.0


def _negate_rule(value):
    # map_server reads negate as an int, else as a bool: 0/1 and true/false.
    if isinstance(value, bool) or (isinstance(value, int) and value in (0, 1)):
        return None
    return 'must be 0, 1, true or false'


MAP_YAML_SPECS = (
    ParamSpec('image', 'image', 'str', REQUIRED, '',
              'image file (PGM, PNG, ...), relative to the YAML file'),
    ParamSpec('resolution', 'resolution_m', 'float', REQUIRED, 'm', 'size of one cell', gt=0.0),
    ParamSpec('origin', 'origin', 'floats', REQUIRED, 'm, m, rad',
              'pose [x, y, yaw] of the lower-left corner of the lower-left pixel in the map '
              'frame; yaw turns the grid about it', length=3),
    ParamSpec('negate', 'negate', 'raw', REQUIRED, '',
              '0 / false: white is free, black occupied; 1 / true: the reverse',
              check=_negate_rule),
    ParamSpec('occupied_thresh', 'occupied_thresh', 'float', REQUIRED, '',
              'a cell whose occupancy is above this is occupied (100)', ge=0.0, le=1.0),
    ParamSpec('free_thresh', 'free_thresh', 'float', REQUIRED, '',
              'a cell whose occupancy is below this is free (0)', ge=0.0, le=1.0),
    ParamSpec('mode', 'mode', 'enum', 'trinary', '',
              'trinary (0 / 100 / -1), scale (0 .. 100, -1 where transparent) or raw '
              '(the grey value itself)', choices=MAP_MODES),
)


@dataclass(frozen=True)
class MapYaml:
    """
    A validated map YAML.

    :param image: the image's path (relative to the YAML file's folder made absolute).
    :param resolution_m: cell size [m].
    :param origin: (x [m], y [m], yaw [rad]) of the lower-left pixel's corner in the map frame.
    :param negate: black is free, white occupied.
    :param occupied_thresh: occupancy above which a cell is occupied.
    :param free_thresh: occupancy below which a cell is free.
    :param mode: 'trinary', 'scale' or 'raw'.
    :param source: the YAML file, quoted in errors.
    """

    image: str
    resolution_m: float
    origin: Tuple[float, float, float]
    negate: bool
    occupied_thresh: float
    free_thresh: float
    mode: str = 'trinary'
    source: str = ''


def map_yaml_from_dict(data, source, base_dir='') -> MapYaml:
    """
    Validate the content of a map YAML (nav2 map_server's keys).

    :param data: the parsed YAML.
    :param source: the YAML file, quoted in errors.
    :param base_dir: folder a relative ``image`` is resolved in (the YAML file's).
    :raises InvalidParameterError: naming the file and the field.
    """
    values = validate_table(MAP_YAML_SPECS, data, source, what='a map YAML')
    if not values['occupied_thresh'] > values['free_thresh']:
        raise InvalidParameterError(
            f"{source}: field 'occupied_thresh' = {values['occupied_thresh']:g}: must be > "
            f"free_thresh ({values['free_thresh']:g})")
    values['negate'] = bool(values['negate'])
    values['image'] = os.path.normpath(os.path.join(base_dir, values['image']))
    return MapYaml(source=source, **values)


def check_size(width, height, source):
    """
    Refuse an image of more than :data:`MAX_CELLS` cells, or an empty one.

    :raises InvalidParameterError: naming the image and its size.
    """
    if width < 1 or height < 1:
        raise InvalidParameterError(f'{source}: the image is empty ({width} x {height} pixels)')
    if width * height > MAX_CELLS:
        raise InvalidParameterError(
            f'{source}: {width} x {height} = {width * height} cells is more than the '
            f'{MAX_CELLS} cells a map may have (docs/maps.md, limits)')


def _value_table(count, negate, mode, occupied_thresh, free_thresh):
    # The cell value of each possible channel sum 0 .. 255 * count, computed as map_server does
    # per pixel (in doubles, on 16-bit quanta).
    sums = np.arange(255 * count + 1, dtype=np.float64)
    shade = (sums * _QUANTUM_PER_BYTE / count) / _MAX_QUANTUM
    if mode == 'raw':
        percent = np.floor(shade * 255.0 + 0.5)     # std::round, for values >= 0
        return np.where(percent <= OCCUPIED, percent, UNKNOWN).astype(np.int8)
    occ = shade if negate else 1.0 - shade
    values = np.full(sums.shape, UNKNOWN, dtype=np.int8)
    if mode == 'scale':
        scaled = np.rint((occ - free_thresh) / (occupied_thresh - free_thresh) * 100.0)
        middle = (occ >= free_thresh) & (occ <= occupied_thresh)
        values[middle] = scaled[middle].astype(np.int8)
    values[occ > occupied_thresh] = OCCUPIED
    values[occ < free_thresh] = FREE
    return values


def occupancy_values(color: np.ndarray, alpha: Optional[np.ndarray], spec: MapYaml) -> np.ndarray:
    """
    Return the cell values map_server publishes for an image (see the module text).

    :param color: uint8 pixels, top row first: (height, width) grey or (height, width, 3) RGB.
    :param alpha: uint8 (height, width) alpha (255 = opaque), or None for an image without one.
    :param spec: the map YAML (mode, negate, thresholds).
    :return: int8 (height, width), row 0 = the image's bottom row (OccupancyGrid order).
    """
    rgb = color.ndim == 3
    count = 3 if rgb else 1
    if rgb:
        sums = color[:, :, 0].astype(np.uint16)
        sums += color[:, :, 1]
        sums += color[:, :, 2]
    else:
        sums = color.astype(np.uint16)
    if spec.mode == 'trinary' and alpha is not None:
        # map_server averages the alpha in with the colour (opaque counts as white); a grey
        # image has three equal colour channels there.
        if not rgb:
            sums *= 3
        sums += alpha
        count = 4
    values = _value_table(count, spec.negate, spec.mode, spec.occupied_thresh,
                          spec.free_thresh)[sums]
    del sums
    if spec.mode == 'scale' and alpha is not None:
        values[alpha != 255] = UNKNOWN
    return np.ascontiguousarray(values[::-1])


@dataclass(frozen=True, eq=False)
class OccupancyGrid:
    """
    An occupancy grid in the map frame: cell values and where the cells lie.

    :param data: int8 (height, width) cell values (0 .. 100, -1 unknown); row 0 is the bottom
        row (``nav_msgs/OccupancyGrid`` order: ``data.ravel()`` is the message's data).
    :param resolution_m: cell size [m].
    :param origin: (x [m], y [m], yaw [rad]) of cell (0, 0)'s lower-left corner in the map frame.
    """

    data: np.ndarray
    resolution_m: float
    origin: Tuple[float, float, float]

    @property
    def height(self) -> int:
        return self.data.shape[0]

    @property
    def width(self) -> int:
        return self.data.shape[1]

    def to_grid(self, x_m: float, y_m: float) -> Tuple[float, float]:
        """Return a map-frame point in grid units: (column, row) as floats (cell = 1 x 1)."""
        ox, oy, yaw = self.origin
        dx, dy = x_m - ox, y_m - oy
        c, s = math.cos(yaw), math.sin(yaw)
        return ((c * dx + s * dy) / self.resolution_m, (-s * dx + c * dy) / self.resolution_m)

    def cell_at(self, x_m: float, y_m: float) -> Optional[Tuple[int, int]]:
        """Return the (row, column) of the cell holding a map-frame point; None outside."""
        u, v = self.to_grid(x_m, y_m)
        column, row = math.floor(u), math.floor(v)
        if 0 <= row < self.height and 0 <= column < self.width:
            return row, column
        return None

    def cell_centre(self, row: int, column: int) -> Tuple[float, float]:
        """Return the map-frame (x, y) [m] of a cell's centre."""
        return self.grid_point(column + 0.5, row + 0.5)

    def grid_point(self, u: float, v: float) -> Tuple[float, float]:
        """Return the map-frame (x, y) [m] of a point in grid units (column u, row v)."""
        ox, oy, yaw = self.origin
        c, s = math.cos(yaw), math.sin(yaw)
        du, dv = u * self.resolution_m, v * self.resolution_m
        return ox + c * du - s * dv, oy + s * du + c * dv


def wall_mask(grid: OccupancyGrid, unknown_occupied: bool = False) -> np.ndarray:
    """
    Return the bool (height, width) mask of the cells that are walls.

    A wall is a cell of value 100 (nav2's costmap static layer reads that value as lethal by
    default); an unknown cell (-1) is one when ``unknown_occupied``.
    """
    walls = grid.data == OCCUPIED
    if unknown_occupied:
        walls |= grid.data == UNKNOWN
    return walls


def ray_march(grid: OccupancyGrid, walls: np.ndarray, x_m: float, y_m: float, angle_rad: float,
              max_range_m: float) -> float:
    """
    March a ray over the grid cell by cell; return the distance to the first wall cell.

    An exact grid walk (each cell the ray enters, in order, as Amanatides and Woo's traversal
    visits them): the distance is where the ray enters that cell. A reference for tests (one
    Python step per cell). Cells outside the grid are free.

    :param walls: the wall mask (:func:`wall_mask`).
    :param x_m: ray start in the map frame [m]; likewise ``y_m``.
    :param angle_rad: ray direction in the map frame [rad].
    :param max_range_m: the longest distance looked at [m].
    :return: the distance [m], or ``math.inf`` when no wall lies within ``max_range_m``.
    """
    u, v = grid.to_grid(x_m, y_m)
    direction = angle_rad - grid.origin[2]
    du, dv = math.cos(direction), math.sin(direction)
    column, row = math.floor(u), math.floor(v)
    resolution = grid.resolution_m

    def first_crossing(position, cell, towards):
        # distance [m] to the first cell border along one axis, and between two borders
        if towards == 0.0:
            return math.inf, math.inf
        border = cell + 1 if towards > 0.0 else cell
        return (border - position) / towards * resolution, resolution / abs(towards)

    next_u, delta_u = first_crossing(u, column, du)
    next_v, delta_v = first_crossing(v, row, dv)
    step_u, step_v = (1 if du > 0.0 else -1), (1 if dv > 0.0 else -1)
    distance = 0.0
    while distance <= max_range_m:
        if 0 <= row < grid.height and 0 <= column < grid.width and walls[row, column]:
            return distance
        if next_u < next_v:
            column, distance, next_u = column + step_u, next_u, next_u + delta_u
        else:
            row, distance, next_v = row + step_v, next_v, next_v + delta_v
    return math.inf


def describe_size(grid: OccupancyGrid) -> str:
    """One line about a grid: cells and metres ('400 x 300 cells (20 x 15 m)')."""
    return (f'{grid.width} x {grid.height} cells ({grid.width * grid.resolution_m:g} x '
            f'{grid.height * grid.resolution_m:g} m)')


__all__ = ['check_size', 'describe_size', 'FREE', 'map_yaml_from_dict', 'MAP_MODES',
           'MAP_YAML_SPECS', 'MapYaml', 'MAX_CELLS', 'OCCUPIED', 'occupancy_values',
           'OccupancyGrid', 'ray_march', 'UNKNOWN', 'wall_mask']
