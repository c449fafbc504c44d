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
Rays over an occupancy grid (core/map/grid_rays.py) against the cell-by-cell ray march.

The march (core/map/occupancy.py's ray_march) is the reference: for horizontal rays the grid's
answer must be the same distance to within 1e-9 m, on random maps with thick filled areas,
rotated grids, rays that start outside the grid or inside a wall.
"""

import math

import numpy as np
import pytest

from vehicle_sim.core.map import grid_rays
from vehicle_sim.core.map.grid_rays import free_squares, GridRays, quadrant_squares
from vehicle_sim.core.map.occupancy import OccupancyGrid, ray_march

HEIGHT_M = 1.0


def _blobby_walls(seed, shape=(90, 120)):
    # thin walls, thick filled squares and scattered cells, as a SLAM map has them
    rng = np.random.default_rng(seed)
    walls = rng.random(shape) < 0.02
    for _ in range(12):
        r, c = rng.integers(0, shape[0]), rng.integers(0, shape[1])
        h, w = rng.integers(1, 25), rng.integers(1, 25)
        walls[r:r + h, c:c + w] = True
    return walls


def _speckled_walls(seed, shape=(90, 120)):
    # ragged: a few large free rooms in a speckle of single wall cells (a SLAM map's edges)
    rng = np.random.default_rng(seed)
    walls = rng.random(shape) < 0.3
    for _ in range(6):
        r, c = rng.integers(0, shape[0]), rng.integers(0, shape[1])
        walls[r:r + rng.integers(5, 40), c:c + rng.integers(5, 40)] = False
    return walls


def _marched(grid, walls, x, y, angles, length):
    return np.array([ray_march(grid, walls, x, y, a, length) for a in angles])


def _cast(rays, x, y, z, angles, length, dz=0.0):
    origin = np.array([x, y, z])
    ends = origin + length * np.stack([np.cos(angles), np.sin(angles),
                                       np.full(len(angles), dz)], axis=1)
    fractions = rays.cast(origin, ends)
    return np.where(fractions < 1.0, fractions * length * math.sqrt(1.0 + dz * dz), np.inf)


def _largest_free_square(walls, row, column, rows, columns):
    # brute force: the largest j with the j x j cells from (row, column) towards (rows,
    # columns) (+1 / -1) all free; cells beyond the grid are free
    size = 0
    while size < 255:
        r = row + rows * np.arange(size + 1)
        c = column + columns * np.arange(size + 1)
        r, c = r[(r >= 0) & (r < walls.shape[0])], c[(c >= 0) & (c < walls.shape[1])]
        if walls[np.ix_(r, c)].any():
            break
        size += 1
    return size


@pytest.mark.parametrize('seed', range(4))
def test_free_squares_reach_from_each_cell_to_the_nearest_wall_cell_in_each_quadrant(seed):
    walls = _blobby_walls(seed, (40, 55))
    squares = quadrant_squares(walls)
    assert np.array_equal(squares[0], free_squares(walls))
    for quadrant, (rows, columns) in enumerate([(1, 1), (1, -1), (-1, 1), (-1, -1)]):
        expected = np.array([[_largest_free_square(walls, r, c, rows, columns)
                              for c in range(walls.shape[1])] for r in range(walls.shape[0])])
        assert np.array_equal(squares[quadrant], expected), quadrant


def test_free_squares_are_capped_at_255_far_from_any_wall():
    walls = np.zeros((300, 700), dtype=bool)
    walls[:, 0] = True
    squares = quadrant_squares(walls)
    assert squares[0, 0, 1] == 255 and squares[1, 0, 1] == 1 and squares[1, 0, 256] == 255
    assert squares[1, 0, 254] == 254 and squares[0, 0, 0] == 0


@pytest.mark.parametrize('seed', range(6))
@pytest.mark.parametrize('yaw', [0.0, 0.4])
@pytest.mark.parametrize('draw', [_blobby_walls, _speckled_walls])
def test_rays_meet_the_walls_where_the_ray_march_does(seed, yaw, draw):
    # 400 rays, and few (the last rays walk cell by cell: GridRays._window)
    walls = draw(seed)
    resolution = 0.1
    origin = (-3.0, 2.0, yaw)
    grid = OccupancyGrid(np.where(walls, 100, 0).astype(np.int8), resolution, origin)
    rays = GridRays(walls, resolution, origin, HEIGHT_M)
    rng = np.random.default_rng(100 + seed)
    angles = np.concatenate([[0.0, math.pi / 2, -math.pi], rng.uniform(-math.pi, math.pi, 400)])
    starts = 0
    while starts < 5:
        u, v = rng.uniform(-20, 140), rng.uniform(-20, 110)      # also outside the grid
        x, y = grid.grid_point(u, v)
        cell = grid.cell_at(x, y)
        if cell is not None and walls[cell]:
            continue
        starts += 1
        for length in (30.0, 3.0):
            marched = _marched(grid, walls, x, y, angles, length)
            got = _cast(rays, x, y, 0.5, angles, length)
            assert np.array_equal(np.isinf(got), np.isinf(marched) | (marched > length))
            near = np.isfinite(got)
            assert np.max(np.abs(got[near] - marched[near]), initial=0.0) < 1e-9
            few = _cast(rays, x, y, 0.5, angles[:7], length)
            assert np.array_equal(np.isinf(few), np.isinf(got[:7]))
            assert np.allclose(few, got[:7], rtol=0.0, atol=1e-9)


def test_a_ray_through_the_corner_two_walls_share_is_stopped_there():
    # two wall cells touching at a corner: a 45-degree ray through that corner does not pass
    walls = np.zeros((10, 10), dtype=bool)
    walls[5, 5] = walls[4, 4] = True
    rays = GridRays(walls, 1.0, (0.0, 0.0, 0.0), HEIGHT_M)
    got = _cast(rays, 2.5, 7.5, 0.5, np.array([-math.pi / 4]), 10.0)
    assert got[0] == pytest.approx(2.5 * math.sqrt(2.0), abs=1e-9)


@pytest.mark.parametrize('seed', range(3))
def test_the_walk_over_the_next_cells_meets_the_walls_where_the_ray_march_does(seed,
                                                                               monkeypatch):
    # one jump, then every ray walks (GridRays._window), on a speckle of single wall cells
    monkeypatch.setattr(grid_rays, '_JUMPS_PER_LOOK', 1)
    walls = _speckled_walls(seed)
    grid = OccupancyGrid(np.where(walls, 100, 0).astype(np.int8), 0.1, (0.0, 0.0, 0.0))
    rays = GridRays(walls, 0.1, (0.0, 0.0, 0.0), HEIGHT_M)
    rng = np.random.default_rng(200 + seed)
    angles = rng.uniform(-math.pi, math.pi, 60)
    for row, column in np.argwhere(~walls)[rng.integers(0, (~walls).sum(), 6)]:
        x, y = 0.1 * (column + rng.random()), 0.1 * (row + rng.random())
        marched = _marched(grid, walls, x, y, angles, 30.0)
        got = _cast(rays, x, y, 0.5, angles, 30.0)
        assert np.array_equal(np.isinf(got), np.isinf(marched))
        near = np.isfinite(got)
        assert np.max(np.abs(got[near] - marched[near]), initial=0.0) < 1e-9


@pytest.mark.parametrize('cells', [[(5, 5)], [(4, 4)], [(5, 5), (4, 4)]])
def test_the_walk_stops_a_ray_at_the_corner_of_a_wall_cell_beside_it(cells, monkeypatch):
    # as the jumps do: a ray passing exactly through a corner touches the cells beside it
    monkeypatch.setattr(grid_rays, '_JUMPS_PER_LOOK', 1)
    walls = np.zeros((10, 10), dtype=bool)
    walls[tuple(np.transpose(cells))] = True
    walls[9, 3] = True                  # off the ray: its first jump ends at (3, 7)
    rays = GridRays(walls, 1.0, (0.0, 0.0, 0.0), HEIGHT_M)
    got = _cast(rays, 0.5, 9.5, 0.5, np.array([-math.pi / 4]), 10.0)
    assert got[0] == pytest.approx(4.5 * math.sqrt(2.0), abs=1e-9)


def test_a_ray_that_starts_inside_a_filled_area_meets_it_at_once():
    walls = np.zeros((30, 30), dtype=bool)
    walls[5:25, 5:25] = True
    rays = GridRays(walls, 0.5, (0.0, 0.0, 0.0), HEIGHT_M)
    angles = np.linspace(-math.pi, math.pi, 16)
    assert np.all(_cast(rays, 7.5, 7.5, 0.5, angles, 20.0) == 0.0)


def test_rays_over_the_walls_miss_them_and_rays_from_above_meet_their_tops():
    walls = np.zeros((20, 40), dtype=bool)
    walls[:, 20:] = True                     # a filled area from x = 20 m on, 1 m high
    rays = GridRays(walls, 1.0, (0.0, 0.0, 0.0), HEIGHT_M)
    east = np.array([0.0])
    assert _cast(rays, 10.5, 10.5, 1.5, east, 30.0)[0] == math.inf           # above the top
    assert _cast(rays, 10.5, 10.5, 0.5, east, 30.0)[0] == pytest.approx(9.5)
    # from 2 m up, 1 m down per 10 m: the top (z = 1) at x = 20.5, inside the filled area
    down = _cast(rays, 10.5, 10.5, 2.0, east, 30.0, dz=-0.1)[0]
    assert down == pytest.approx(10.0 * math.sqrt(1.01))
    # downwards to the ground before the wall: the grid has nothing there (the ground is Bullet's)
    assert _cast(rays, 10.5, 10.5, 0.5, east, 30.0, dz=-0.2)[0] == math.inf
    # straight down onto a wall's top, and onto free ground
    origin = np.array([25.5, 3.5, 3.0])
    fractions = rays.cast(origin, origin + np.array([[0.0, 0.0, -5.0]]))
    assert fractions[0] * 5.0 == pytest.approx(2.0)
    origin = np.array([5.5, 3.5, 3.0])
    assert rays.cast(origin, origin + np.array([[0.0, 0.0, -5.0]]))[0] == 1.0


def test_no_rays_and_zero_length_rays():
    walls = np.zeros((5, 5), dtype=bool)
    walls[2, 2] = True
    rays = GridRays(walls, 1.0, (0.0, 0.0, 0.0), HEIGHT_M)
    assert rays.cast(np.zeros(3), np.zeros((0, 3))).shape == (0,)
    origin = np.array([0.5, 0.5, 0.5])
    assert rays.cast(origin, origin[None, :]).tolist() == [1.0]


@pytest.mark.parametrize('angle', [math.pi / 2, math.pi / 2 + 0.01, math.pi / 2 - 0.01])
def test_the_walk_on_a_map_only_a_few_cells_tall_looks_no_cell_past_the_grid(angle):
    # A ray up a corridor beside a wall column (one cell a jump, then the walk over its next
    # 64 cells) on a map 10 cells tall: the cells the walk would look up past the top lie
    # beyond the table of squares; it leaves the grid without a hit as the march does.
    walls = np.zeros((10, 6), dtype=bool)
    walls[:, 3] = walls[:, 1] = True
    grid = OccupancyGrid(np.where(walls, 100, 0).astype(np.int8), 1.0, (0.0, 0.0, 0.0))
    rays = GridRays(walls, 1.0, (0.0, 0.0, 0.0), HEIGHT_M)
    marched = _marched(grid, walls, 2.5, 0.5, [angle], 30.0)
    got = _cast(rays, 2.5, 0.5, 0.5, np.array([angle]), 30.0)
    assert np.array_equal(np.isinf(got), np.isinf(marched) | (marched > 30.0))
    assert got[np.isfinite(got)] == pytest.approx(marched[np.isfinite(got)], abs=1e-9)
