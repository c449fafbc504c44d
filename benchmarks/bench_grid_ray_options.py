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
The SLAM-like map's lidar (issue 30) against three other ways of finding the grid's walls.

bench_occupancy_lidar.py's map, car and 1080-ray lidar, sampled in interleaved blocks (CPU time
of this process, median per block) in six worlds:

- ``empty``: the same car and lidar in a world without a map (the ratios' baseline);
- ``grid``: the map as the simulator builds it with ``ray_march: numpy``: its walls found over
  the grid (core/map/grid_rays.py), Bullet's rays cast with the walls' meshes they reach away;
- ``no march``: the map as built, its GridRays answering "no wall" at once (what the map costs
  besides the march: the walls' meshes moved out of the rays' way and back, Bullet's rays to
  the walls; the floor of any march);
- ``fan``: the map as built, its GridRays with a first pass shared by the rays from the origin
  (numpy, no new dependency; ``fan_grid_rays``): four more bytes a cell hold each cell's run
  of free cells along its row towards +x and -x and along its column towards +y and -y; per
  quadrant of directions, the rows from the origin's row on and the columns from its column
  on are read once (256 of each, one gather for all), and each ray finds with one
  np.searchsorted the first row (column) where it leaves the free run that starts at the
  origin's column (row): there it meets a wall, or enters one, or is only known free up to
  that line. The rays settled neither way march on (GridRays' march) from there;
 the walls given to Bullet as static triangle meshes of their
  boundary only (a vertical quad from the ground to ``wall_height`` on every border between a
  wall cell and a free one, collinear runs of borders merged into one quad; at most 32 768
  quads a body, PyBullet's 131 072 vertices), every ray cast by one rayTestBatch;
- ``compiled`` (where numba, the ``fast`` extra, is installed): the map as built with
  ``ray_march: compiled``, the same march compiled (core/map/grid_rays_jit.py), what a world
  gets by default with numba.

It prints the mesh's size and build time, the compiled march's first sample (numba imported,
the march compiled or read from its cache), the fan's tables (build time,
memory) and how many rays it leaves to the march, each world's cost per sample
and its ratio to the empty world, and how far each scan lies from the grid's. Run:
``.venv/bin/python benchmarks/bench_grid_ray_options.py [--quick]``.
"""

import argparse
import math
import os
import statistics
import sys
import tempfile
import time

import numpy as np
import pybullet

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
sys.path.insert(0, HERE)

import bench_occupancy_lidar  # noqa: E402

QUADS_PER_BODY = 32768
TILE_M = 12.8           # the quads are ordered by the square of this side their first end is in


def _runs(lines):
    # bool (lines, n): per line, its runs of True as (line, first, past the last)
    padded = np.zeros((lines.shape[0], lines.shape[1] + 2), dtype=np.int8)
    padded[:, 1:-1] = lines
    steps = np.diff(padded, axis=1)
    line, first = np.nonzero(steps == 1)
    _, last = np.nonzero(steps == -1)
    return line, first, last


def boundary_segments(walls):
    """
    Return the borders between wall cells and free cells, merged along their lines.

    :param walls: bool (height, width) wall mask; cells beyond the grid are free.
    :return: float (n, 2, 2): each segment's two ends (x, y) [cells] from cell (0, 0)'s
        lower-left corner; first the ones along the grid's y axis, then along x.
    """
    height, width = walls.shape
    padded = np.zeros((height + 2, width + 2), dtype=bool)
    padded[1:-1, 1:-1] = walls
    across_x = padded[1:-1, 1:] != padded[1:-1, :-1]      # (height, width + 1): line x = c
    across_y = padded[1:, 1:-1] != padded[:-1, 1:-1]      # (height + 1, width): line y = r
    column, row0, row1 = _runs(across_x.T)
    row, column0, column1 = _runs(across_y)
    starts = np.concatenate([np.stack([column, row0], axis=1), np.stack([column0, row], axis=1)])
    ends = np.concatenate([np.stack([column, row1], axis=1), np.stack([column1, row], axis=1)])
    return np.stack([starts, ends], axis=1).astype(float)


def add_boundary_meshes(world, built):
    """
    Add an occupancy map's walls to ``world`` as static meshes of their boundary quads.

    :param built: the map as built in another world (physics/map_layer.py's OccupancyMap).
    :return: (body ids, quads).
    """
    from vehicle_sim.physics.map_layer import _grid_corner
    segments = boundary_segments(built.walls)
    x0, y0, yaw = _grid_corner(built.grid, built.spec)
    turn = np.array([[math.cos(yaw), -math.sin(yaw)],
                     [math.sin(yaw), math.cos(yaw)]]) * built.grid.resolution_m
    ends = segments @ turn.T + (x0, y0)
    quads = np.empty((len(ends), 4, 3))
    quads[:, 0, :2] = quads[:, 3, :2] = ends[:, 0]
    quads[:, 1, :2] = quads[:, 2, :2] = ends[:, 1]
    quads[:, :2, 2] = 0.0
    quads[:, 2:, 2] = built.spec.wall_height_m
    tiles = np.floor(quads[:, 0, 1] / TILE_M) * 1e6 + np.floor(quads[:, 0, 0] / TILE_M)
    quads = quads[np.argsort(tiles, kind='stable')]
    cid = world.client_id
    bodies = []
    for first in range(0, len(quads), QUADS_PER_BODY):
        chunk = quads[first:first + QUADS_PER_BODY]
        indices = (np.array([0, 1, 2, 0, 2, 3])[None, :]
                   + 4 * np.arange(len(chunk))[:, None]).ravel()
        shape = pybullet.createCollisionShape(
            pybullet.GEOM_MESH, vertices=chunk.reshape(-1, 3).tolist(), indices=indices.tolist(),
            flags=pybullet.GEOM_FORCE_CONCAVE_TRIMESH, physicsClientId=cid)
        bodies.append(pybullet.createMultiBody(0.0, shape, physicsClientId=cid))
    return bodies, len(quads)


# The fan (``fan``): free runs along each row and column, capped at a byte, and the lines looked
# at from the origin at once.
_FAN_LINES = 256
_MAX_RUN = 255
# The rays the fan leaves march on from at least this far [cells] before where they are known
# free, along each axis.
_BACK_CELLS = 1e-5


def free_runs(walls, out=None):
    """
    Return each cell's run of free cells up its column (towards +y), capped at 255: uint8.

    :param walls: bool (height, width) wall mask (row 0 = the bottom row).
    :param out: where to write them (a view will do), else a new array.
    """
    height = walls.shape[0]
    dtype = np.int32 if height >= 32767 else np.int16
    rows = np.arange(height, dtype=dtype)[:, None]
    # per cell, the row of the first wall cell at or above it (the grid's top without one)
    first = np.where(walls, rows, dtype(height))
    np.minimum.accumulate(first[::-1], axis=0, out=first[::-1])
    first -= rows
    np.minimum(first, _MAX_RUN, out=first)
    runs = np.empty(walls.shape, dtype=np.uint8) if out is None else out
    runs[...] = first
    return runs


def fan_grid_rays():
    """Return a GridRays class whose rays from the origin go through the fan before the march."""
    from vehicle_sim.core.map import grid_rays
    from vehicle_sim.core.map.grid_rays import GridRays
    _NUDGE_CELLS = grid_rays._NUDGE_CELLS
    _START, _SPEED, _T, _HIGH, _ID = (grid_rays._START, grid_rays._SPEED, grid_rays._T,
                                      grid_rays._HIGH, grid_rays._ID)
    count_nonzero = np.count_nonzero

    class FanGridRays(GridRays):
        """GridRays with the fan (module text): four more bytes a cell."""

        def __init__(self, walls, resolution_m, corner, height_m, march='numpy'):
            super().__init__(walls, resolution_m, corner, height_m, march)
            # free cells along each row towards +x and -x (stored column by column: a column
            # of the grid is a row of theirs) and each column towards +y and -y, on the grid
            # with a free border, one table after the other
            border = np.zeros((walls.shape[0] + 2, walls.shape[1] + 2), dtype=bool)
            border[1:-1, 1:-1] = walls
            cells = border.size
            self._runs = np.empty(4 * cells, dtype=np.uint8)
            runs = self._runs.reshape(4, *border.shape)
            across = np.ascontiguousarray(border.T)
            along_x = self._runs[:2 * cells].reshape(2, *across.shape)
            free_runs(across, out=along_x[0])
            free_runs(across[::-1], out=along_x[1][::-1])
            free_runs(border, out=runs[2])
            free_runs(border[::-1], out=runs[3][::-1])
            self._run_tables = cells * np.arange(4)
            self._run_shape = border.shape
            self.marched = 0

        @property
        def nbytes(self):
            return super().nbytes + self._runs.nbytes

        def _march(self, result, rays):
            # the rays from the origin (inside their band from its start) through the fan, the
            # others and the ones it leaves through GridRays' march
            speed, t = rays[_SPEED], rays[_T]
            fan = (t == 0.0) & ((speed[0] != 0.0) | (speed[1] != 0.0))
            if count_nonzero(fan):
                found = np.ones(rays.shape[1])
                done = self._fan(rays[_START][:, 0], speed, t, rays[_HIGH], fan, found)
                result[rays[_ID, done].astype(np.intp)] = found[done]
                keep = ~done
                if not count_nonzero(keep):
                    self.marched = 0
                    return result
                rays = rays.compress(keep, axis=1)
            self.marched = rays.shape[1]
            return super()._march(result, rays)

        def _fan(self, origin, speed, t, high, fan, result):
            # The rays from the origin over lines of cells looked at once for all of them: per
            # quadrant (sx, sy) of the rays' directions, the rows r0 + sy k (k = 0, 1, ...) from
            # the origin's cell (r0, c0) and, in each, the run of free cells from column c0 towards
            # sx; likewise the columns c0 + sx k and their runs from row r0 towards sy. A ray of
            # the quadrant crosses rows k = 0, 1, ... in turn and spans, in each, the cells from
            # where it enters to where it leaves, all at or past column c0: all free while it
            # leaves the row before the run's end g(k). In the quadrant's own axes (the origin at
            # (a, b) in its cell, the ray moving c cells along per cell across), it leaves row k
            # at a + c (k + 1 - b), so rows 0..k are free while c < min over j <= k of
            # (g(j) - a) / (j + 1 - b): a running minimum, shared by the quadrant's rays, in which
            # each ray finds its first row k* that is not (np.searchsorted). There it enters the
            # cell g(k*), a wall, unless it entered the row past it (or the run is capped): then
            # it meets a wall where it enters the row if that cell is one (a wall across its
            # way), else all it knows is that it is free up to row k*. Each ray is looked at both
            # ways
            # (rows and columns: walls beside it on one side stop only one of them); the ones
            # with neither a hit nor their band's end march on from where they are known free.
            # The families' keys are 2 apart, so that a ray's key never lands in the family
            # before its own.
            # Margins of a nudge: a ray leaving a row within one of the run's end counts as
            # reaching it (the march's corner rule decides).
            which = np.flatnonzero(fan)
            vx, vy = speed[0, which], speed[1, which]
            x0, y0 = float(origin[0]) + 1.0, float(origin[1]) + 1.0      # with the border
            height, stride = self._run_shape
            tables = self._run_tables
            bases, steps, sideways, along, across = [], [], [], [], []
            for quadrant in range(4):
                sx, sy = (-1 if quadrant & 1 else 1), (-1 if quadrant & 2 else 1)
                c0 = math.floor(x0 + sx * _NUDGE_CELLS)
                r0 = math.floor(y0 + sy * _NUDGE_CELLS)
                fx = x0 - c0 if sx > 0 else c0 + 1 - x0
                fy = y0 - r0 if sy > 0 else r0 + 1 - y0
                # rows: runs along x (stored by columns); columns: runs along y
                bases += [tables[0 if sx > 0 else 1] + c0 * height + r0,
                          tables[2 if sy > 0 else 3] + r0 * stride + c0]
                steps += [sy, sx]
                sideways += [sx * height, sy * stride]
                along += [fx, fy]
                across += [fy, fx]
            along, across = np.array(along), np.array(across)
            lines = np.arange(_FAN_LINES)
            index = np.array(steps)[:, None] * lines
            index += np.array(bases)[:, None]
            runs = self._runs.take(index, mode='clip').astype(float)
            bound = runs - (along + _NUDGE_CELLS)[:, None]
            bound /= (lines + 1.0) - across[:, None]
            np.minimum.accumulate(bound, axis=1, out=bound)
            # keys rising along the lines, family f's in (2 f, 2 f + 1] (a ray's in [2 f, 2 f + 1])
            np.maximum(bound, 0.0, out=bound)
            bound += 1.0
            keys = np.divide(1.0, bound, out=bound)
            keys += 2.0 * np.arange(len(bases))[:, None]
            # per ray, its rows' family (2 q) and its columns' (2 q + 1), as one
            family = 2 * ((vx < 0.0) + 2 * (vy < 0.0))
            family = np.concatenate([family, family + 1])
            speed_along = np.abs(np.concatenate([vx, vy]))
            speed_across = np.abs(np.concatenate([vy, vx]))
            slope = speed_along / speed_across
            slope += 1.0
            found = keys.ravel().searchsorted(np.divide(1.0, slope, out=slope) + 2.0 * family)
            line = found - family * _FAN_LINES
            run = runs.ravel().take(found, mode='clip')
            near, side = along[family], across[family]
            enter = np.fmax((line - side) / speed_across, 0.0)
            leave = (line + 1.0 - side) / speed_across
            wall = (run - near) / speed_along
            inside = near + speed_along * enter
            within = line < _FAN_LINES
            hits = within & (run < _MAX_RUN) & (inside <= run + 1.0) & (wall <= leave)
            # or it enters the line in a wall cell past the run (a wall across its way)
            cell = (np.array(bases)[family] + np.array(steps)[family] * line
                    + np.array(sideways)[family] * np.floor(inside).astype(np.intp))
            entered = within & (self._runs.take(cell, mode='clip') == 0)
            wall = np.where(entered, -np.inf, wall)
            hits |= entered
            count = len(which)
            hit_at = np.where(hits, np.fmax(enter, wall), np.inf)
            hit_at = np.minimum(hit_at[:count], hit_at[count:])
            known = np.maximum(enter[:count], enter[count:])
            end = high[which]
            done = (hit_at < np.inf) | (known >= end)
            result[which] = np.where(hit_at <= end, hit_at, 1.0)
            # the others march on from before where they are known free: half a cell along the
            # ray's main axis and _BACK_CELLS at least along the other (the march looks its cell up
            # a nudge ahead along both)
            speed_x, speed_y = np.abs(vx), np.abs(vy)
            back = np.maximum(0.5 / np.maximum(speed_x, speed_y),
                              _BACK_CELLS / np.minimum(speed_x, speed_y))
            t[which] = np.maximum(known - back, 0.0)
            out = np.zeros(len(t), dtype=bool)
            out[which] = done
            return out

    return FanGridRays


def measure(blocks, samples):
    """Return {name: value}: the worlds' costs per sample [s], sizes and times."""
    from vehicle_sim.core.map.grid_rays import compiled_march_installed
    from vehicle_sim.physics.scene import build_scene, mount_suite
    lidar = [bench_occupancy_lidar.LIDAR]
    found = {}
    with tempfile.TemporaryDirectory(prefix='bench_grid_rays_') as folder:
        path = bench_occupancy_lidar.draw_map(folder)
        world = bench_occupancy_lidar._world
        scenes = {'empty': build_scene(world(None, lidar), mount=mount_suite),
                  'grid': build_scene(world(path, lidar, 'numpy'), mount=mount_suite),
                  'trimesh': build_scene(world(None, lidar), mount=mount_suite),
                  'no march': build_scene(world(path, lidar, 'numpy'), mount=mount_suite),
                  'fan': build_scene(world(path, lidar, 'numpy'), mount=mount_suite)}
        if compiled_march_installed():
            scenes['compiled'] = build_scene(world(path, lidar, 'compiled'),
                                             mount=mount_suite)
    built = scenes['grid'].parts['map']
    start = time.perf_counter()
    bodies, found['quads'] = add_boundary_meshes(scenes['trimesh'].world, built)
    found['mesh_s'], found['mesh_bodies'] = time.perf_counter() - start, len(bodies)
    from vehicle_sim.physics.map_layer import _grid_corner
    walls_args = (built.walls, built.grid.resolution_m, _grid_corner(built.grid, built.spec),
                  built.spec.wall_height_m, 'numpy')
    fan_class = fan_grid_rays()
    start = time.process_time()
    fan = fan_class(*walls_args)
    found['fan_s'] = time.process_time() - start
    start = time.process_time()
    found['grid_bytes'] = type(fan).__mro__[1](*walls_args).nbytes
    found['grid_s'] = time.process_time() - start
    found['fan_bytes'] = fan.nbytes
    scenes['fan'].world.ray_grids[0] = fan
    rays = scenes['no march'].world.ray_grids[0]
    rays.cast = lambda origin, ends: np.ones(len(ends))
    everywhere = np.array([[-np.inf] * 3, [np.inf] * 3])      # every wall body moves
    rays.cast_cut = lambda origin, ends: (np.ones(len(ends)), np.asarray(ends, dtype=float),
                                          everywhere)
    for scene in scenes.values():
        for _ in range(50):
            scene.world.step()
    suites = {name: scene.vehicles['car'].sensors for name, scene in scenes.items()}
    reference = suites['grid'].sample('lidar').scan
    suites['fan'].sample('lidar')
    found['fan_marched'] = fan.marched
    for name, suite in suites.items():
        start = time.perf_counter()
        scan = suite.sample('lidar').scan
        found[name, 'first_s'] = time.perf_counter() - start
        if name in ('empty', 'no march'):
            continue
        both = np.isfinite(scan) & np.isfinite(reference)
        found[name, 'apart'] = int(np.sum(np.isfinite(scan) != np.isfinite(reference)))
        found[name, 'off_m'] = float(np.max(np.abs(scan[both] - reference[both]), initial=0.0))
    costs = {name: [] for name in suites}
    names = list(suites)
    for block in range(blocks):
        shift = block % len(names)
        for name in names[shift:] + names[:shift]:
            times = []
            for _ in range(samples):
                start = time.process_time()
                suites[name].sample('lidar')
                times.append(time.process_time() - start)
            costs[name].append(statistics.median(times))
    for name, blocks_s in costs.items():
        found[name] = statistics.median(blocks_s)
        ratios = [cost / empty for cost, empty in zip(blocks_s, costs['empty'])]
        found[name, 'ratios'] = (min(ratios), max(ratios))
    for scene in scenes.values():
        scene.world.close()
    return found


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[1])
    parser.add_argument('--quick', action='store_true', help='fewer blocks and samples')
    args = parser.parse_args(argv)
    load_before = '/'.join(f'{x:.1f}' for x in os.getloadavg())
    found = measure(5 if args.quick else 11, 10 if args.quick else 20)
    rate = bench_occupancy_lidar.LIDAR['rate_hz']
    print('vehicle_sim SLAM-like map: the grid lidar against its options '
          f'({bench_occupancy_lidar.WIDTH} x {bench_occupancy_lidar.HEIGHT} cells, '
          '1080 rays, 270 deg, 30 m, 40 Hz)')
    print(f"  boundary mesh: {found['quads']} quads ({2 * found['quads']} triangles) in "
          f"{found['mesh_bodies']} bodies, built in {found['mesh_s']:.2f} s")
    if 'compiled' not in found:
        print("  compiled: numba is not installed, its row left out (pip install "
              "'vehicle_sim[fast]')")
    else:
        print(f"  compiled: first sample (numba imported, the march compiled or read from its "
              f"cache) {found['compiled', 'first_s']:.2f} s")
    print(f"  fan: its ray tables built in {found['fan_s']:.2f} s of CPU against "
          f"{found['grid_s']:.2f} s for the grid's alone, {found['fan_bytes'] / 1e6:.0f} MB "
          f"against {found['grid_bytes'] / 1e6:.0f} MB; {found['fan_marched']} of "
          f"{bench_occupancy_lidar.LIDAR['horizontal_resolution']} rays left to the march")
    empty = found['empty']
    for name in ('empty', 'grid', 'no march', 'fan', 'trimesh', 'compiled'):
        if name not in found:
            continue
        low, high = found[name, 'ratios']
        line = (f'  {name:9s}{found[name] * 1e3:6.3f} ms per sample, {found[name] * rate:5.1%} '
                f'of one core, {found[name] / empty:.2f}x the empty world (blocks {low:.2f}-'
                f'{high:.2f}x)')
        if name in ('trimesh', 'compiled', 'fan'):
            line += (f"; scan against the grid's: {found[name, 'apart']} rays hit on one side "
                     f"only, {found[name, 'off_m']:.1e} m apart at most")
        print(line)
    print(f'  load average {load_before} before, '
          + '/'.join(f'{x:.1f}' for x in os.getloadavg()) + ' after')
    return 0


if __name__ == '__main__':
    raise SystemExit(main())
