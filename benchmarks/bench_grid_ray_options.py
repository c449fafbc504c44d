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
The SLAM-like map's lidar (issue 30) against two other ways of finding the grid's walls.

bench_occupancy_lidar.py's map, car and 1080-ray lidar, sampled in interleaved blocks (CPU time
of this process, median per block) in five worlds:

- ``empty``: the same car and lidar in a world without a map (the ratios' baseline);
- ``grid``: the map as the simulator builds it: its walls found over the grid
  (core/map/grid_rays.py, numpy), Bullet's rays cast with the walls' meshes away;
- ``no march``: the map as built, its GridRays answering "no wall" at once (what the map costs
  besides the march: the walls' meshes moved out of the rays' way and back, Bullet's rays to
  the walls; the floor of any march);
- ``trimesh``: the empty world plus the walls given to Bullet as static triangle meshes of their
  boundary only (a vertical quad from the ground to ``wall_height`` on every border between a
  wall cell and a free one, collinear runs of borders merged into one quad; at most 32 768
  quads a body, PyBullet's 131 072 vertices), every ray cast by one rayTestBatch;
- ``numba`` (only where numba is installed; it is no dependency of vehicle_sim): the map as
  built, its GridRays' cast compiled by numba (GridRays._band and the jumps of GridRays._march
  with their corner checks, one ray at a time, no walk: the same hits but for rays that graze a
  wall cell's corner or run along its side, which the walk counts and the jumps may not).

It prints the mesh's size and build time, numba's compile time, each world's cost per sample
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
import types

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


def compiled_cast():
    """Return a GridRays.cast whose march numba compiles (None without numba)."""
    try:
        import numba
    except ImportError:
        return None
    from vehicle_sim.core.map.grid_rays import _NUDGE_CELLS as NUDGE

    @numba.njit(nogil=True, error_model='numpy', inline='always')
    def band(position, speeds, tops):
        # GridRays._band for one ray: its fractions [low, high] between the ground and the
        # walls' top and inside the grid, within [0, 1]
        low, high = 0.0, 1.0
        for axis in range(3):
            if speeds[axis] == 0.0:
                if not 0.0 <= position[axis] <= tops[axis]:
                    return 1.0, 0.0
                continue
            inverse = 1.0 / speeds[axis]
            near, far = -position[axis] * inverse, (tops[axis] - position[axis]) * inverse
            low, high = max(low, min(near, far)), min(high, max(near, far))
        return low, high

    @numba.njit(nogil=True, error_model='numpy')
    def march(squares, stride, quadrant_rows, tops, z, start_x, start_y, speed, speed_z,
              result):
        # GridRays._band, then _march's jumps and _corner_hits, one ray at a time (the same
        # arithmetic)
        position, speeds = np.array([z, start_x, start_y]), np.empty(3)
        for ray in range(speed.shape[1]):
            vx, vy = speed[0, ray], speed[1, ray]
            speeds[0], speeds[1], speeds[2] = speed_z[ray], vx, vy
            t, end = band(position, speeds, tops)
            if not t <= end:
                continue
            back_x, back_y = (1.0 if vx < 0.0 else 0.0), (1.0 if vy < 0.0 else 0.0)
            sign_x = 1.0 if vx > 0.0 else (-1.0 if vx < 0.0 else 0.0)
            sign_y = 1.0 if vy > 0.0 else (-1.0 if vy < 0.0 else 0.0)
            inverse_x, inverse_y = 1.0 / abs(vx), 1.0 / abs(vy)
            padded_x = start_x + 1.0
            padded_y = start_y + 1.0 + (2.0 * back_y + back_x) * quadrant_rows
            nudged_x, nudged_y = padded_x + sign_x * NUDGE, padded_y + sign_y * NUDGE
            offset_x, offset_y = sign_x * padded_x + back_x, sign_y * padded_y + back_y
            tie = max(inverse_x, inverse_y) * (4.0 * NUDGE)
            if tie == np.inf:
                tie = 0.0
            hit = False
            while True:
                cell_x, cell_y = math.floor(vx * t + nudged_x), math.floor(vy * t + nudged_y)
                k = squares[int(cell_y * stride + cell_x)]
                if k == 0:
                    hit = True
                    break
                exit_x = ((sign_x * cell_x + k) - offset_x) * inverse_x if vx != 0.0 else np.inf
                exit_y = ((sign_y * cell_y + k) - offset_y) * inverse_y if vy != 0.0 else np.inf
                t = min(max(t, min(exit_x, exit_y)), end)
                if abs(exit_x - exit_y) <= tie and t < end:
                    x, y = nudged_x + vx * t, nudged_y + vy * t
                    ahead_x, ahead_y = math.floor(x), math.floor(y)
                    behind_x = math.floor(x - sign_x * (2.0 * NUDGE))
                    behind_y = math.floor(y - sign_y * (2.0 * NUDGE))
                    if ahead_x != behind_x and ahead_y != behind_y and min(
                            squares[int(behind_y * stride + ahead_x)],
                            squares[int(ahead_y * stride + behind_x)]) == 0:
                        hit = True
                        break
                if t >= end:
                    break
            result[ray] = t if hit else 1.0

    def cast(self, origin, ends):
        origin = np.asarray(origin, dtype=float)
        vectors = np.asarray(ends, dtype=float) - origin
        result = np.ones(len(vectors))
        if len(vectors) == 0:
            return result
        speed = np.ascontiguousarray(self._axes @ vectors[:, :2].T)
        start = self._axes @ (origin[:2] - self._corner)
        march(self._squares, float(self._stride), float(self._quadrant_rows), self._tops,
              origin[2], start[0], start[1], speed, np.ascontiguousarray(vectors[:, 2]), result)
        return result

    return cast


def measure(blocks, samples):
    """Return {name: value}: the worlds' costs per sample [s], sizes and times."""
    from vehicle_sim.physics.scene import build_scene, mount_suite
    lidar = [bench_occupancy_lidar.LIDAR]
    found = {}
    with tempfile.TemporaryDirectory(prefix='bench_grid_rays_') as folder:
        path = bench_occupancy_lidar.draw_map(folder)
        scenes = {'empty': build_scene(bench_occupancy_lidar._world(None, lidar),
                                       mount=mount_suite),
                  'grid': build_scene(bench_occupancy_lidar._world(path, lidar),
                                      mount=mount_suite),
                  'trimesh': build_scene(bench_occupancy_lidar._world(None, lidar),
                                         mount=mount_suite)}
        scenes['no march'] = build_scene(bench_occupancy_lidar._world(path, lidar),
                                         mount=mount_suite)
        cast = compiled_cast()
        if cast is not None:
            scenes['numba'] = build_scene(bench_occupancy_lidar._world(path, lidar),
                                          mount=mount_suite)
    built = scenes['grid'].parts['map']
    start = time.perf_counter()
    bodies, found['quads'] = add_boundary_meshes(scenes['trimesh'].world, built)
    found['mesh_s'], found['mesh_bodies'] = time.perf_counter() - start, len(bodies)
    rays = scenes['no march'].world.ray_grids[0]
    rays.cast = lambda origin, ends: np.ones(len(ends))
    if cast is not None:
        rays = scenes['numba'].world.ray_grids[0]
        rays.cast = types.MethodType(cast, rays)
    for scene in scenes.values():
        for _ in range(50):
            scene.world.step()
    suites = {name: scene.vehicles['car'].sensors for name, scene in scenes.items()}
    reference = suites['grid'].sample('lidar').scan
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
    if 'numba' not in found:
        print('  numba: not installed, its row left out')
    else:
        print(f"  numba: first sample (compiling the march) {found['numba', 'first_s']:.2f} s")
    empty = found['empty']
    for name in ('empty', 'grid', 'no march', 'trimesh', 'numba'):
        if name not in found:
            continue
        low, high = found[name, 'ratios']
        line = (f'  {name:9s}{found[name] * 1e3:6.3f} ms per sample, {found[name] * rate:5.1%} '
                f'of one core, {found[name] / empty:.2f}x the empty world (blocks {low:.2f}-'
                f'{high:.2f}x)')
        if name in ('trimesh', 'numba'):
            line += (f"; scan against the grid's: {found[name, 'apart']} rays hit on one side "
                     f"only, {found[name, 'off_m']:.1e} m apart at most")
        print(line)
    print(f'  load average {load_before} before, '
          + '/'.join(f'{x:.1f}' for x in os.getloadavg()) + ' after')
    return 0


if __name__ == '__main__':
    raise SystemExit(main())
