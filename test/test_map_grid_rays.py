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
rotated grids, rays that start outside the grid or inside a wall. Each test runs the numpy
march and the compiled one (core/map/grid_rays_jit.py, numba: skipped where it is missing),
and the compiled one's fractions are the numpy one's to the bit.
"""

import math
import subprocess
import sys
import warnings

import numpy as np
import pytest

from vehicle_sim.config import world_from_data
from vehicle_sim.core.map import grid_rays
from vehicle_sim.core.map.grid_rays import (
    compiled_march_installed,
    free_squares,
    GridRays,
    quadrant_squares,
)
from vehicle_sim.core.map.occupancy import OccupancyGrid, ray_march
from vehicle_sim.core.specs.errors import InvalidParameterError

HEIGHT_M = 1.0
NO_NUMBA = "numba is not installed (the fast extra: pip install 'vehicle_sim[fast]')"
COMPILED = pytest.param('compiled', marks=pytest.mark.skipif(not compiled_march_installed(),
                                                             reason=NO_NUMBA))


@pytest.fixture(params=['numpy', COMPILED])
def march(request):
    """Each march: 'numpy', and 'compiled' where numba is installed."""
    return request.param


def _rays(walls, resolution, corner, march):
    rays = GridRays(walls, resolution, corner, HEIGHT_M, march)
    assert rays.compiled == (march == 'compiled')        # numba imports where it is installed
    return rays


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
def test_rays_meet_the_walls_where_the_ray_march_does(seed, yaw, draw, march):
    # 400 rays, and few (the last rays walk cell by cell: GridRays._window)
    walls = draw(seed)
    resolution = 0.1
    origin = (-3.0, 2.0, yaw)
    grid = OccupancyGrid(np.where(walls, 100, 0).astype(np.int8), resolution, origin)
    rays = _rays(walls, resolution, origin, march)
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


def test_a_ray_through_the_corner_two_walls_share_is_stopped_there(march):
    # two wall cells touching at a corner: a 45-degree ray through that corner does not pass
    walls = np.zeros((10, 10), dtype=bool)
    walls[5, 5] = walls[4, 4] = True
    rays = _rays(walls, 1.0, (0.0, 0.0, 0.0), march)
    got = _cast(rays, 2.5, 7.5, 0.5, np.array([-math.pi / 4]), 10.0)
    assert got[0] == pytest.approx(2.5 * math.sqrt(2.0), abs=1e-9)


@pytest.mark.parametrize('seed', range(3))
def test_the_walk_over_the_next_cells_meets_the_walls_where_the_ray_march_does(seed,
                                                                               monkeypatch,
                                                                               march):
    # one jump, then every ray walks (GridRays._window), on a speckle of single wall cells
    monkeypatch.setattr(grid_rays, '_JUMPS_PER_LOOK', 1)
    walls = _speckled_walls(seed)
    grid = OccupancyGrid(np.where(walls, 100, 0).astype(np.int8), 0.1, (0.0, 0.0, 0.0))
    rays = _rays(walls, 0.1, (0.0, 0.0, 0.0), march)
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
def test_the_walk_stops_a_ray_at_the_corner_of_a_wall_cell_beside_it(cells, monkeypatch,
                                                                      march):
    # as the jumps do: a ray passing exactly through a corner touches the cells beside it
    monkeypatch.setattr(grid_rays, '_JUMPS_PER_LOOK', 1)
    walls = np.zeros((10, 10), dtype=bool)
    walls[tuple(np.transpose(cells))] = True
    walls[9, 3] = True                  # off the ray: its first jump ends at (3, 7)
    rays = _rays(walls, 1.0, (0.0, 0.0, 0.0), march)
    got = _cast(rays, 0.5, 9.5, 0.5, np.array([-math.pi / 4]), 10.0)
    assert got[0] == pytest.approx(4.5 * math.sqrt(2.0), abs=1e-9)


def test_a_ray_that_starts_inside_a_filled_area_meets_it_at_once(march):
    walls = np.zeros((30, 30), dtype=bool)
    walls[5:25, 5:25] = True
    rays = _rays(walls, 0.5, (0.0, 0.0, 0.0), march)
    angles = np.linspace(-math.pi, math.pi, 16)
    assert np.all(_cast(rays, 7.5, 7.5, 0.5, angles, 20.0) == 0.0)


def test_rays_over_the_walls_miss_them_and_rays_from_above_meet_their_tops(march):
    walls = np.zeros((20, 40), dtype=bool)
    walls[:, 20:] = True                     # a filled area from x = 20 m on, 1 m high
    rays = _rays(walls, 1.0, (0.0, 0.0, 0.0), march)
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


def test_no_rays_and_zero_length_rays(march):
    walls = np.zeros((5, 5), dtype=bool)
    walls[2, 2] = True
    rays = _rays(walls, 1.0, (0.0, 0.0, 0.0), march)
    assert rays.cast(np.zeros(3), np.zeros((0, 3))).shape == (0,)
    origin = np.array([0.5, 0.5, 0.5])
    assert rays.cast(origin, origin[None, :]).tolist() == [1.0]


@pytest.mark.parametrize('angle', [math.pi / 2, math.pi / 2 + 0.01, math.pi / 2 - 0.01])
def test_the_walk_on_a_map_only_a_few_cells_tall_looks_no_cell_past_the_grid(angle, march):
    # A ray up a corridor beside a wall column (one cell a jump, then the walk over its next
    # 64 cells) on a map 10 cells tall: the cells the walk would look up past the top lie
    # beyond the table of squares; it leaves the grid without a hit as the march does.
    walls = np.zeros((10, 6), dtype=bool)
    walls[:, 3] = walls[:, 1] = True
    grid = OccupancyGrid(np.where(walls, 100, 0).astype(np.int8), 1.0, (0.0, 0.0, 0.0))
    rays = _rays(walls, 1.0, (0.0, 0.0, 0.0), march)
    marched = _marched(grid, walls, 2.5, 0.5, [angle], 30.0)
    got = _cast(rays, 2.5, 0.5, 0.5, np.array([angle]), 30.0)
    assert np.array_equal(np.isinf(got), np.isinf(marched) | (marched > 30.0))
    assert got[np.isfinite(got)] == pytest.approx(marched[np.isfinite(got)], abs=1e-9)


def _scan(rng, count, length):
    # rays from one origin in every direction, level and tilted up or down
    angles = rng.uniform(-math.pi, math.pi, count)
    return length * np.stack([np.cos(angles), np.sin(angles), rng.uniform(-0.08, 0.08, count)],
                             axis=1)


@pytest.mark.skipif(not compiled_march_installed(), reason=NO_NUMBA)
@pytest.mark.parametrize('draw', [_blobby_walls, _speckled_walls])
@pytest.mark.parametrize('jumps', [3, 1])
def test_the_compiled_march_gives_the_numpy_march_s_fractions_to_the_bit(draw, jumps,
                                                                          monkeypatch):
    # The same arithmetic in the same order, the same looks and walks: equal floats, on scans
    # of 1080 rays (most jump, the last ones walk), of 40 (they walk after the first look) and
    # of 3, from inside the grid, outside it, above the walls and on a wall cell's border.
    monkeypatch.setattr(grid_rays, '_JUMPS_PER_LOOK', jumps)
    rng = np.random.default_rng(7)
    for seed in range(4):
        walls = draw(seed)
        corner = (-3.0, 2.0, rng.uniform(-math.pi, math.pi))
        numpy_rays = GridRays(walls, 0.1, corner, HEIGHT_M, 'numpy')
        compiled_rays = GridRays(walls, 0.1, corner, HEIGHT_M, 'compiled')
        origins = [(rng.uniform(-20.0, 20.0), rng.uniform(-15.0, 25.0), rng.uniform(0.0, 1.2))
                   for _ in range(12)] + [(-3.0, 2.0, 0.5), (-3.0, 2.0, HEIGHT_M)]
        for origin in origins:
            for count, length in ((1080, 30.0), (40, 8.0), (3, 30.0)):
                ends = np.asarray(origin) + _scan(rng, count, length)
                expected = numpy_rays.cast(origin, ends)
                got = compiled_rays.cast(origin, ends)
                assert got.tobytes() == expected.tobytes(), (seed, origin, count)


def test_cast_cut_gives_the_fractions_the_rays_cut_there_and_their_box(march):
    # what physics/sensors/rays.py casts Bullet's rays along: origin + (ends - origin) * f,
    # to the bit as numpy works it out, and the box of the origin and those ends
    walls = _blobby_walls(3)
    rays = _rays(walls, 0.1, (-3.0, 2.0, 0.4), march)
    rng = np.random.default_rng(11)
    hits = 0
    for origin in ((0.8, 8.5, 0.5), (-8.0, 1.0, 0.2), (3.0, 4.0, 1.5)):     # in, out, above
        origin = np.array(origin)
        ends = origin + _scan(rng, 500, 30.0)
        fractions, cut, box = rays.cast_cut(origin, ends)
        assert fractions.tobytes() == rays.cast(origin, ends).tobytes()
        hits += np.count_nonzero(fractions < 1.0)
        assert cut.tobytes() == (origin + (ends - origin) * fractions[:, None]).tobytes()
        assert box.tolist() == [np.minimum(cut.min(axis=0), origin).tolist(),
                                np.maximum(cut.max(axis=0), origin).tolist()]
    assert hits > 300
    fractions, cut, box = rays.cast_cut(np.ones(3), np.zeros((0, 3)))
    assert fractions.shape == (0,) and cut.shape == (0, 3) and box.tolist() == [[1.0] * 3] * 2


def test_a_march_that_is_not_one_of_the_three_is_refused_naming_it():
    with pytest.raises(InvalidParameterError, match=r"ray march 'fast': must be one of auto, "
                                                    r'numpy, compiled'):
        GridRays(np.zeros((4, 4), dtype=bool), 1.0, (0.0, 0.0, 0.0), HEIGHT_M, 'fast')


def _without_numba(monkeypatch):
    # numba cannot be imported (import numba raises ImportError, find_spec finds nothing), as
    # where it is not installed; grid_rays_jit and the march it gave are forgotten meanwhile
    monkeypatch.setitem(sys.modules, 'numba', None)
    monkeypatch.delitem(sys.modules, 'vehicle_sim.core.map.grid_rays_jit', raising=False)
    monkeypatch.setattr(grid_rays, '_COMPILED', {})


def test_without_numba_auto_casts_with_numpy_and_compiled_names_the_extra(monkeypatch):
    _without_numba(monkeypatch)
    walls = np.zeros((10, 10), dtype=bool)
    walls[:, 6] = True
    origin = np.array([0.5, 5.5, 0.5])
    auto = GridRays(walls, 1.0, (0.0, 0.0, 0.0), HEIGHT_M)
    with warnings.catch_warnings():
        warnings.simplefilter('error')            # not installed: no warning, numpy casts
        assert auto.cast(origin, origin + [[10.0, 0.0, 0.0]])[0] == pytest.approx(0.55)
    assert not auto.compiled
    compiled = GridRays(walls, 1.0, (0.0, 0.0, 0.0), HEIGHT_M, 'compiled')
    with pytest.raises(ImportError, match=r"needs numba.*pip install 'vehicle_sim\[fast\]'"):
        compiled.cast(origin, origin + [[10.0, 0.0, 0.0]])


def test_auto_warns_where_numba_is_installed_but_does_not_import(monkeypatch):
    _without_numba(monkeypatch)
    monkeypatch.setattr(grid_rays, 'compiled_march_installed', lambda: True)
    walls = np.zeros((10, 10), dtype=bool)
    rays = GridRays(walls, 1.0, (0.0, 0.0, 0.0), HEIGHT_M, 'auto')
    with pytest.warns(RuntimeWarning, match=r'ray_march auto: .*needs numba.*the numpy march'):
        assert not rays.compiled


def _world(ray_march):
    return {'vehicles': [{'name': 'car', 'model': 'Car'}],
            'map': {'type': 'occupancy_grid', 'file': 'm.yaml', 'ray_march': ray_march}}


def test_ray_march_compiled_without_numba_is_refused_when_the_world_is_read(monkeypatch):
    _without_numba(monkeypatch)
    with pytest.raises(InvalidParameterError,
                       match=r"w\.yaml: map: field 'ray_march' = 'compiled' needs numba, which "
                             r"is not installed: pip install 'vehicle_sim\[fast\]'"):
        world_from_data(_world('compiled'), 'w.yaml')
    assert world_from_data(_world('auto'), 'w.yaml').map.ray_march == 'auto'


def test_ray_march_is_read_from_the_world_file():
    assert world_from_data(_world('numpy'), 'w.yaml').map.ray_march == 'numpy'
    with pytest.raises(InvalidParameterError, match=r"field 'ray_march' = 'jit'"):
        world_from_data(_world('jit'), 'w.yaml')


def test_numba_is_imported_by_the_first_cast_not_with_the_package():
    # the simulator starts without it: importing the package, the world and the map layer
    # leaves numba out; a map's GridRays brings it in on its first cast where it is installed
    code = (
        'import sys\n'
        'import numpy as np\n'
        'import vehicle_sim, vehicle_sim.config, vehicle_sim.physics.map_layer\n'
        'from vehicle_sim.core.map.grid_rays import GridRays\n'
        'rays = GridRays(np.zeros((4, 4), dtype=bool), 1.0, (0.0, 0.0, 0.0), 1.0)\n'
        "print('numba' in sys.modules)\n"
        'rays.cast(np.array([0.5, 0.5, 0.5]), np.array([[3.5, 0.5, 0.5]]))\n'
        "print('numba' in sys.modules)\n")
    done = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True,
                          timeout=300, check=True)
    assert done.stdout.split() == ['False', str(compiled_march_installed())]
