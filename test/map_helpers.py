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
Maps the map tests draw: a room with a pillar, written as nav2 map_server files.

The room is ROOM_WIDTH x ROOM_HEIGHT cells of RESOLUTION_M, a wall WALL_CELLS thick all round
and a square pillar; black (0) is occupied, white (254) free, as map_saver writes them.
"""

from pathlib import Path

import numpy as np
from PIL import Image
import yaml

RESOLUTION_M = 0.1
ROOM_WIDTH = 200          # cells: 20 m
ROOM_HEIGHT = 120         # cells: 12 m
WALL_CELLS = 3
PILLAR = (80, 160, 8)     # lower-left row and column (from the bottom), side, in cells
ORIGIN = (-10.0, -6.0, 0.0)
FREE_GREY = 254
WALL_GREY = 0


def room_pixels(studs=0):
    """
    uint8 (height, width) image of the room, top row first (as stored in the file).

    :param studs: this many more small square pillars (2 to 4 cells), seeded, none within
        1.5 m of the car's box (x -1.5 .. 6 m, |y| < 2.5 m).
    """
    image = np.full((ROOM_HEIGHT, ROOM_WIDTH), FREE_GREY, dtype=np.uint8)
    rng = np.random.default_rng(18)
    placed = 0
    while placed < studs:
        side = int(rng.integers(2, 5))
        row = int(rng.integers(WALL_CELLS, ROOM_HEIGHT - WALL_CELLS - side))
        column = int(rng.integers(WALL_CELLS, ROOM_WIDTH - WALL_CELLS - side))
        x = ORIGIN[0] + column * RESOLUTION_M
        y = ORIGIN[1] + row * RESOLUTION_M
        if -3.0 < x < 7.5 and -4.0 < y < 4.0:
            continue
        top = ROOM_HEIGHT - row - side
        image[top:top + side, column:column + side] = WALL_GREY
        placed += 1
    image[:WALL_CELLS, :] = WALL_GREY
    image[-WALL_CELLS:, :] = WALL_GREY
    image[:, :WALL_CELLS] = WALL_GREY
    image[:, -WALL_CELLS:] = WALL_GREY
    row, column, side = PILLAR
    top = ROOM_HEIGHT - row - side       # rows counted from the bottom -> image rows
    image[top:top + side, column:column + side] = WALL_GREY
    return image


def write_map(folder, pixels=None, name='room', image_suffix='.pgm', mode_image=None,
              **yaml_values):
    """
    Write ``<name><image_suffix>`` and ``<name>.yaml`` into ``folder``; return the YAML's path.

    :param pixels: uint8 array (grey (h, w), or (h, w, 3|4)); None = the room.
    :param mode_image: a ready PIL image instead of ``pixels``.
    :param yaml_values: map YAML values replacing the defaults (a value None drops the key).
    """
    folder = Path(folder)
    image = mode_image if mode_image is not None else Image.fromarray(
        room_pixels() if pixels is None else pixels)
    image.save(folder / f'{name}{image_suffix}')
    values = {'image': f'{name}{image_suffix}', 'resolution': RESOLUTION_M,
              'origin': list(ORIGIN), 'negate': 0, 'occupied_thresh': 0.65,
              'free_thresh': 0.25, 'mode': 'trinary'}
    values.update(yaml_values)
    values = {k: v for k, v in values.items() if v is not None}
    path = folder / f'{name}.yaml'
    path.write_text(yaml.safe_dump(values), encoding='utf-8')
    return path


def world_data(map_file, pose=(0.0, 0.0, 0.0), sensors=(), **map_values):
    """Return a world mapping: one car at ``pose`` with ``sensors``, the map ``map_file``."""
    x, y, yaw = pose
    vehicle = {'name': 'car', 'model': 'Car', 'pose': {'x': x, 'y': y, 'yaw': yaw}}
    if sensors:
        vehicle['sensors'] = list(sensors)
    return {'vehicles': [vehicle],
            'map': {'type': 'occupancy_grid', 'file': str(map_file), **map_values}}
