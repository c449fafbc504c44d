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
Occupancy-grid maps, read as nav2 map_server reads them: values, cells, merged walls.

The reference is a per-pixel transcription of map_server's loop (map_io.cpp,
``loadMapFromFile``), written here independently of the vectorised code under test.
"""

import math

from map_helpers import write_map
import numpy as np
from PIL import Image
import pytest

from vehicle_sim.core.map.kinds import map_from_dict, MAP_KINDS, MapPlacement
from vehicle_sim.core.map.occupancy import (
    map_yaml_from_dict,
    MapYaml,
    occupancy_values,
    OccupancyGrid,
    ray_march,
    wall_mask,
)
from vehicle_sim.core.map.rectangles import merge_rectangles, rectangles_mask
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.maps.occupancy_files import load_occupancy_grid
from vehicle_sim.physics.map_layer import MAP_BUILDERS


def _reference_cell(channels, alpha, spec):
    # One pixel as map_server computes it: channels are 8-bit values, quanta are 16-bit.
    quanta = [c * 257.0 for c in channels]
    if spec.mode == 'trinary' and alpha is not None:
        quanta.append(alpha * 257.0)
    shade = (sum(quanta) / len(quanta)) / 65535.0
    if spec.mode == 'raw':
        percent = math.floor(shade * 255.0 + 0.5)
        return percent if 0 <= percent <= 100 else -1
    occ = shade if spec.negate else 1.0 - shade
    if spec.mode == 'scale' and alpha is not None and alpha != 255:
        return -1
    if spec.occupied_thresh < occ:
        return 100
    if occ < spec.free_thresh:
        return 0
    if spec.mode == 'trinary':
        return -1
    return int(np.rint((occ - spec.free_thresh) / (spec.occupied_thresh - spec.free_thresh)
                       * 100.0))


def _reference(color, alpha, spec):
    height, width = color.shape[:2]
    data = np.zeros((height, width), dtype=np.int8)
    for y in range(height):
        for x in range(width):
            channels = list(color[y, x]) if color.ndim == 3 else [color[y, x]] * 3
            a = None if alpha is None else int(alpha[y, x])
            data[height - y - 1, x] = _reference_cell([int(c) for c in channels], a, spec)
    return data


def _spec(mode='trinary', negate=False, occupied=0.65, free=0.196):
    return MapYaml('map.pgm', 0.05, (0.0, 0.0, 0.0), negate, occupied, free, mode)


GREYS = np.arange(256, dtype=np.uint8).reshape(16, 16)   # every grey value once
RNG = np.random.default_rng(18)
RGB = RNG.integers(0, 256, (12, 9, 3), dtype=np.uint8)
ALPHA = RNG.choice(np.array([0, 128, 255, 255], dtype=np.uint8), (12, 9))


@pytest.mark.parametrize('mode', ['trinary', 'scale', 'raw'])
@pytest.mark.parametrize('negate', [False, True])
def test_grey_values_become_map_server_s_cells_for_every_grey(mode, negate):
    spec = _spec(mode, negate)
    assert np.array_equal(occupancy_values(GREYS, None, spec), _reference(GREYS, None, spec))


@pytest.mark.parametrize('mode', ['trinary', 'scale', 'raw'])
@pytest.mark.parametrize('with_alpha', [False, True])
def test_rgb_and_alpha_pixels_average_as_map_server_does(mode, with_alpha):
    spec = _spec(mode)
    alpha = ALPHA if with_alpha else None
    assert np.array_equal(occupancy_values(RGB, alpha, spec), _reference(RGB, alpha, spec))


def test_trinary_values_of_black_white_and_grey():
    # occ = 1 - v/255: black 1.0 > 0.65 -> 100; white 0.0 < 0.196 -> 0; 128: 0.498 -> -1
    image = np.array([[0, 254, 128]], dtype=np.uint8)
    assert occupancy_values(image, None, _spec()).tolist() == [[100, 0, -1]]
    assert occupancy_values(image, None, _spec(negate=True)).tolist() == [[0, 100, -1]]


def test_scale_mode_interpolates_between_the_thresholds():
    # v = 140: occ = 1 - 140/255 = 0.45098; (0.45098 - 0.25) / (0.65 - 0.25) * 100 = 50.2 -> 50
    image = np.array([[140]], dtype=np.uint8)
    assert occupancy_values(image, None, _spec('scale', free=0.25)).tolist() == [[50]]


def test_raw_mode_keeps_the_grey_value_up_to_100():
    image = np.array([[0, 37, 100, 101, 255]], dtype=np.uint8)
    assert occupancy_values(image, None, _spec('raw')).tolist() == [[0, 37, 100, -1, -1]]


def test_the_bottom_image_row_becomes_grid_row_zero():
    image = np.array([[0, 0], [254, 254]], dtype=np.uint8)     # top row black
    assert occupancy_values(image, None, _spec()).tolist() == [[0, 0], [100, 100]]


def test_cells_of_a_rotated_grid():
    # origin (1, 2), yaw 90 deg: the grid's columns run along +y, its rows along -x.
    grid = OccupancyGrid(np.zeros((4, 5), dtype=np.int8), 0.5, (1.0, 2.0, math.pi / 2))
    assert grid.cell_at(0.9, 2.1) == (0, 0)          # 0.1 m along -x (row), 0.1 m along y
    assert grid.cell_at(0.4, 3.3) == (1, 2)
    assert grid.cell_at(1.1, 2.1) is None            # behind the origin
    x, y = grid.cell_centre(1, 2)
    assert (x, y) == pytest.approx((1.0 - 0.75, 2.0 + 1.25))


def test_ray_march_stops_at_the_first_wall_cell_face():
    data = np.zeros((5, 10), dtype=np.int8)
    data[:, 7] = 100
    grid = OccupancyGrid(data, 1.0, (0.0, 0.0, 0.0))
    walls = wall_mask(grid)
    assert ray_march(grid, walls, 0.5, 2.5, 0.0, 20.0) == pytest.approx(6.5)
    # 45 degrees from (4.5, 0.5): enters the wall column at x = 7, y = 3
    assert ray_march(grid, walls, 4.5, 0.5, math.pi / 4, 20.0) == pytest.approx(2.5 * 2 ** 0.5)
    # from (0.5, 0.5) it leaves the grid (y = 5) before x = 7: nothing to hit
    assert ray_march(grid, walls, 0.5, 0.5, math.pi / 4, 20.0) == math.inf
    assert ray_march(grid, walls, 0.5, 2.5, math.pi, 20.0) == math.inf


def test_unknown_cells_are_walls_only_when_asked():
    grid = OccupancyGrid(np.array([[0, 100, -1]], dtype=np.int8), 1.0, (0.0, 0.0, 0.0))
    assert wall_mask(grid).tolist() == [[False, True, False]]
    assert wall_mask(grid, unknown_occupied=True).tolist() == [[False, True, True]]


@pytest.mark.parametrize('seed', range(5))
def test_merged_rectangles_cover_every_wall_cell_once(seed):
    mask = np.random.default_rng(seed).random((40, 60)) < 0.3
    rectangles = merge_rectangles(mask)
    assert np.array_equal(rectangles_mask(rectangles, mask.shape), mask)
    assert int(rectangles[:, 2].astype(int) @ rectangles[:, 3]) == int(mask.sum())  # disjoint


def test_straight_walls_and_blocks_merge_into_one_rectangle_each():
    mask = np.zeros((50, 50), dtype=bool)
    mask[0:3, :] = True          # a horizontal wall
    mask[10:40, 5:7] = True      # a vertical wall
    mask[20:30, 20:30] = True    # a block
    assert len(merge_rectangles(mask)) == 3
    assert len(merge_rectangles(np.zeros((5, 5), dtype=bool))) == 0


def test_map_yaml_image_is_relative_to_the_yaml_folder():
    spec = map_yaml_from_dict({'image': 'track.pgm', 'resolution': 0.05, 'origin': [1, 2, 0.5],
                               'negate': 0, 'occupied_thresh': 0.65, 'free_thresh': 0.196},
                              '/maps/track.yaml', '/maps')
    assert spec.image == '/maps/track.pgm'
    assert spec.mode == 'trinary' and spec.negate is False and spec.origin == (1.0, 2.0, 0.5)


def test_world_in_map_places_the_world_frame():
    placement = MapPlacement(2.0, 1.0, math.pi / 2)
    assert placement.to_map(1.0, 0.0) == pytest.approx((2.0, 2.0))
    assert placement.to_world(*placement.to_map(0.3, -0.7)) == pytest.approx((0.3, -0.7))


def test_map_kinds_of_core_and_physics_are_the_same():
    assert sorted(MAP_KINDS) == sorted(MAP_BUILDERS)


def test_world_map_key_resolves_its_file_against_the_world_folder():
    spec = map_from_dict({'type': 'occupancy_grid', 'file': 'maps/room.yaml'},
                         '/worlds/w.yaml: map', '/worlds')
    assert spec.file == '/worlds/maps/room.yaml'
    assert (spec.wall_height_m, spec.unknown, spec.world_in_map.identity) == (1.0, 'free', True)


# ----------------------------------------------------------------------- files
# (maps/occupancy_files.py)

def _grid_of(tmp_path, **kwargs):
    path = write_map(tmp_path, **kwargs)
    spec = map_from_dict({'type': 'occupancy_grid', 'file': str(path)}, 'w.yaml: map', '')
    return load_occupancy_grid(spec)


@pytest.mark.parametrize('suffix', ['.pgm', '.png'])
def test_grey_pgm_and_png_files_read_the_same(tmp_path, suffix):
    _, grid = _grid_of(tmp_path, pixels=GREYS, image_suffix=suffix)
    assert np.array_equal(grid.data, _reference(GREYS, None, _spec(free=0.25)))


def test_rgba_png_averages_its_alpha_in_trinary_mode(tmp_path):
    pixels = np.dstack([RGB, ALPHA])
    _, grid = _grid_of(tmp_path, pixels=pixels, image_suffix='.png')
    assert np.array_equal(grid.data, _reference(RGB, ALPHA, _spec(free=0.25)))


def test_grey_alpha_png_is_unknown_where_transparent_in_scale_mode(tmp_path):
    grey = np.full((3, 4), 0, dtype=np.uint8)
    alpha = np.full((3, 4), 255, dtype=np.uint8)
    alpha[1, 2] = 0
    image = Image.fromarray(np.dstack([grey, alpha]), 'LA')
    _, grid = _grid_of(tmp_path, mode_image=image, image_suffix='.png', mode='scale')
    expected = np.full((3, 4), 100, dtype=np.int8)
    expected[1, 2] = -1          # image row 1 of 3 is grid row 1
    assert np.array_equal(grid.data, expected)


def test_palette_png_reads_as_its_colours(tmp_path):
    image = Image.fromarray(GREYS).convert('P')
    _, grid = _grid_of(tmp_path, mode_image=image, image_suffix='.png')
    assert np.array_equal(grid.data, _reference(GREYS, None, _spec(free=0.25)))


def test_negate_true_and_1_read_alike(tmp_path):
    _, as_int = _grid_of(tmp_path, pixels=GREYS, negate=1)
    _, as_bool = _grid_of(tmp_path, pixels=GREYS, negate=True)
    assert np.array_equal(as_int.data, as_bool.data)
    assert np.array_equal(as_int.data, _reference(GREYS, None, _spec(negate=True, free=0.25)))


def test_unknown_map_yaml_key_is_refused_naming_it():
    with pytest.raises(InvalidParameterError, match=r"m\.yaml: unknown field 'colour'"):
        map_yaml_from_dict({'image': 'a.pgm', 'resolution': 0.05, 'origin': [0, 0, 0],
                            'negate': 0, 'occupied_thresh': 0.65, 'free_thresh': 0.196,
                            'colour': 1}, 'm.yaml')


def test_docs_maps_embeds_the_tables_generated_from_the_rows():
    from pathlib import Path

    from vehicle_sim.core.map.kinds import OCCUPANCY_GRID_SPECS
    from vehicle_sim.core.map.occupancy import MAP_YAML_SPECS
    from vehicle_sim.core.specs.param_spec import parameter_table_markdown
    from vehicle_sim.ros.endpoints import topic_table_markdown
    from vehicle_sim.ros.map_interfaces import MAP_TOPICS
    text = (Path(__file__).resolve().parent.parent / 'docs' / 'maps.md').read_text()
    for table in (parameter_table_markdown(OCCUPANCY_GRID_SPECS, 'key'),
                  parameter_table_markdown(MAP_YAML_SPECS, 'key'),
                  topic_table_markdown(MAP_TOPICS['occupancy_grid'])):
        assert table in text
