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
A 1080-ray lidar on a map like a real SLAM map (issue 30): thick walls, large unknown areas.

Targets: on a 3000 x 2250-cell map as map_saver writes one (0.05 m cells, 150 x 112.5 m;
occupied 0, free 254, unknown 205) loaded with ``unknown: occupied``, a 1080-ray, 270-degree,
30 m lidar at 40 Hz costs <= 15 % of one core and <= 1.3x the same lidar in a world without a
map; the map loads in <= 2 s (its RSS stated).

The map is drawn here (seeded): a building of rooms whose walls are 6 to 16 cells thick
(0.3 .. 0.8 m), an outer wall of 20 cells, doors, a quarter of the rooms unexplored (unknown
behind a closed door), furniture seen from one side (unknown blobs with an occupied rim), the
unknown world outside the building (about half of the map is unknown or occupied), and
SLAM's ragged edges (cells along every occupied / free border flipped at random). The car stands
in a large room. The lidar's cost per sample is this process's CPU time (one thread), the empty
world and the map with each ray march (``ray_march: compiled``, numba's, where it is installed,
and ``numpy``) sampled in interleaved blocks; the targets are read on the march a world gets by
default (``auto``: the compiled one where numba imports). Load time and RSS are measured in a
fresh process (benchmarks/bench_maps.py's ``measure_load``). Run:
``.venv/bin/python benchmarks/bench_occupancy_lidar.py [--quick]``.
"""

import argparse
import os
import statistics
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
sys.path.insert(0, HERE)

import bench_maps  # noqa: E402

WIDTH, HEIGHT = 3000, 2250
RESOLUTION_M = 0.05
ORIGIN = (-10.0, -10.0, 0.0)
FREE, OCCUPIED, UNKNOWN = 254, 0, 205           # map_saver's shades
LIDAR = bench_maps.LIDAR
# The car's cell (row, column of the grid, from the lower left): in a large room.
CAR_CELL = (900, 1100)
TARGETS = {'lidar_share': 0.15, 'lidar_ratio': 1.3, 'load_s': 2.0}


def _neighbours(mask):
    # bool: cells with a True cell among their 4 neighbours
    out = np.zeros_like(mask)
    out[1:] |= mask[:-1]
    out[:-1] |= mask[1:]
    out[:, 1:] |= mask[:, :-1]
    out[:, :-1] |= mask[:, 1:]
    return out


def slam_grid(seed=30):
    """Return the map's uint8 shades, row 0 = the bottom row (grid order)."""
    rng = np.random.default_rng(seed)
    image = np.full((HEIGHT, WIDTH), UNKNOWN, dtype=np.uint8)
    bottom, top, left, right = 250, 2000, 300, 2700      # the building's outer wall, outside
    image[bottom:top, left:right] = FREE
    rows = [bottom] + list(range(bottom + 300, top - 150, 300)) + [top]
    columns = [left] + list(range(left + 350, right - 150, 350)) + [right]
    thick = {}
    for index, row in enumerate(rows):
        t = 20 if index in (0, len(rows) - 1) else int(rng.integers(6, 17))
        thick['r', row] = t
        image[max(row - t // 2, 0):row + (t + 1) // 2, left - 10:right + 10] = OCCUPIED
    for index, column in enumerate(columns):
        t = 20 if index in (0, len(columns) - 1) else int(rng.integers(6, 17))
        thick['c', column] = t
        image[bottom - 10:top + 10, column - t // 2:column + (t + 1) // 2] = OCCUPIED
    car_room = None
    for r0, r1 in zip(rows[:-1], rows[1:]):
        for c0, c1 in zip(columns[:-1], columns[1:]):
            inner = (slice(r0 + thick['r', r0] // 2 + 1, r1 - thick['r', r1] // 2),
                     slice(c0 + thick['c', c0] // 2 + 1, c1 - thick['c', c1] // 2))
            has_car = r0 <= CAR_CELL[0] < r1 and c0 <= CAR_CELL[1] < c1
            if has_car:
                car_room = inner
            if not has_car and rng.random() < 0.25:
                image[inner] = UNKNOWN                  # unexplored: its doors stay closed
                continue
            # doors: in the room's top and right walls (not the outer wall)
            if r1 != top:
                door = int(rng.integers(c0 + 40, c1 - 70))
                t = thick['r', r1]
                image[r1 - t // 2:r1 + (t + 1) // 2, door:door + 28] = FREE
            if c1 != right:
                door = int(rng.integers(r0 + 40, r1 - 70))
                t = thick['c', c1]
                image[door:door + 28, c1 - t // 2:c1 + (t + 1) // 2] = FREE
            # furniture: boxes and discs seen from one side (unknown inside an occupied rim)
            room_rows, room_columns = inner
            for _ in range(int(rng.integers(3, 8))):
                h, w = int(rng.integers(12, 60)), int(rng.integers(12, 90))
                r = int(rng.integers(room_rows.start + 5, room_rows.stop - h - 5))
                c = int(rng.integers(room_columns.start + 5, room_columns.stop - w - 5))
                if has_car and r - 60 < CAR_CELL[0] < r + h + 60 \
                        and c - 120 < CAR_CELL[1] < c + w + 60:
                    continue
                image[r:r + h, c:c + w] = OCCUPIED
                image[r + 2:r + h - 2, c + 2:c + w - 2] = UNKNOWN
    # SLAM's ragged edges: free cells next to occupied ones become occupied, occupied ones next
    # to free ones free, at random; unknown speckles on the free side of the unknown's border
    free, occupied = image == FREE, image == OCCUPIED
    grow = free & _neighbours(occupied) & (rng.random(image.shape) < 0.35)
    shrink = occupied & _neighbours(free) & (rng.random(image.shape) < 0.2)
    speckle = free & _neighbours(image == UNKNOWN) & (rng.random(image.shape) < 0.3)
    image[grow] = OCCUPIED
    image[shrink] = FREE
    image[speckle] = UNKNOWN
    around = (slice(CAR_CELL[0] - 40, CAR_CELL[0] + 40),
              slice(CAR_CELL[1] - 120, CAR_CELL[1] + 160))
    image[around] = FREE
    assert car_room is not None
    return image


def draw_map(folder):
    """Write the map (PGM + YAML) into ``folder``; return the YAML's path."""
    from PIL import Image
    Image.fromarray(np.ascontiguousarray(slam_grid()[::-1])).save(
        os.path.join(folder, 'slam.pgm'))
    path = os.path.join(folder, 'slam.yaml')
    with open(path, 'w', encoding='utf-8') as stream:
        stream.write(f'image: slam.pgm\nresolution: {RESOLUTION_M}\norigin: {list(ORIGIN)}\n'
                     'negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n')
    return path


def car_pose():
    """Return the car's (x, y) [m]: CAR_CELL's corner."""
    return ORIGIN[0] + CAR_CELL[1] * RESOLUTION_M, ORIGIN[1] + CAR_CELL[0] * RESOLUTION_M


def _world(map_path, sensors=(), ray_march='auto'):
    from vehicle_sim.config import world_from_data
    x, y = car_pose()
    data = {'vehicles': [{'name': 'car', 'model': 'Car', 'pose': {'x': x, 'y': y},
                          'sensors': list(sensors)}]}
    if map_path:
        data['map'] = {'type': 'occupancy_grid', 'file': map_path, 'unknown': 'occupied',
                       'ray_march': ray_march}
    return world_from_data(data, 'bench_occupancy_lidar.yaml')


def _sample_cost(suite, samples):
    times = []
    for _ in range(samples):
        start = time.process_time()
        suite.sample('lidar')
        times.append(time.process_time() - start)
    return statistics.median(times)


def measure_lidar(map_path, blocks, samples):
    """
    Median CPU time of one lidar sample in the empty world and on the map with each march.

    The worlds are sampled in interleaved blocks (their order turned each block): ``empty``,
    ``numpy`` (the map, ``ray_march: numpy``) and ``compiled`` (``ray_march: compiled``, left
    out where numba is not installed).

    :return: {name: median seconds}, {name: (lowest, highest) ratio to the empty world's
        block}, rays that hit on the map, whether the marches' scans are equal to the bit,
        the compiled march's first sample (wall, CPU) [s] (numba imported, the march compiled
        or read from numba's cache; None without it), and the built map.
    """
    from vehicle_sim.core.map.grid_rays import compiled_march_installed
    from vehicle_sim.physics.scene import build_scene, mount_suite
    scenes = {'empty': build_scene(_world(None, [LIDAR]), mount=mount_suite),
              'numpy': build_scene(_world(map_path, [LIDAR], 'numpy'), mount=mount_suite)}
    if compiled_march_installed():
        scenes['compiled'] = build_scene(_world(map_path, [LIDAR], 'compiled'),
                                         mount=mount_suite)
    for scene in scenes.values():
        for _ in range(50):
            scene.world.step()
    suites = {name: scene.vehicles['car'].sensors for name, scene in scenes.items()}
    scans, first_s = {}, None
    for name, suite in suites.items():
        start, start_cpu = time.perf_counter(), time.process_time()
        scans[name] = suite.sample('lidar').scan
        if name == 'compiled':
            first_s = (time.perf_counter() - start, time.process_time() - start_cpu)
    same = all(scans[name].tobytes() == scans['numpy'].tobytes() for name in scans
               if name != 'empty')
    names = list(suites)
    costs = {name: [] for name in names}
    for block in range(blocks):
        turn = block % len(names)
        for name in names[turn:] + names[:turn]:
            costs[name].append(_sample_cost(suites[name], samples))
    medians = {name: statistics.median(blocks_s) for name, blocks_s in costs.items()}
    spread = {}
    for name, blocks_s in costs.items():
        ratios = [cost / empty for cost, empty in zip(blocks_s, costs['empty'])]
        spread[name] = (min(ratios), max(ratios))
    hits = int(np.isfinite(scans['numpy']).sum())
    built = scenes['numpy'].parts['map']
    for scene in scenes.values():
        scene.world.close()
    return medians, spread, hits, same, first_s, built


def figures(quick=False):
    """Run every measurement; return {name: value} (see TARGETS)."""
    with tempfile.TemporaryDirectory(prefix='bench_occupancy_') as folder:
        map_path = draw_map(folder)
        load = bench_maps.measure_load(map_path, unknown='occupied', car=car_pose())
        medians, spread, hits, same, first_s, built = measure_lidar(
            map_path, 5 if quick else 11, 10 if quick else 20)
    solid = built.walls
    march = 'compiled' if 'compiled' in medians else 'numpy'     # what ray_march auto gives
    found = dict(load, march=march, lidar_hits=hits, same_scans=same, first_s=first_s,
                 solid_share=float(solid.mean()),
                 rss_mb=max(load['rss_after_mb'], load['rss_peak_mb']))
    rate = LIDAR['rate_hz']
    for name, cost in medians.items():
        found[name + '_ms'] = cost * 1e3
        found[name + '_share'] = cost * rate
        found[name + '_ratio'] = cost / medians['empty']
        found[name + '_spread'] = spread[name]
    found.update(lidar_ms=found[march + '_ms'], lidar_share=found[march + '_share'],
                 lidar_ratio=found[march + '_ratio'])
    return found


def _verdict(value, target):
    return 'meets' if value <= target else f'MISSES by {100 * (value / target - 1):.0f} %'


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[1])
    parser.add_argument('--quick', action='store_true', help='fewer blocks and samples')
    args = parser.parse_args(argv)
    load_before = '/'.join(f'{x:.1f}' for x in os.getloadavg())
    found = figures(args.quick)
    print(f'vehicle_sim SLAM-like map benchmark: {WIDTH} x {HEIGHT} cells of {RESOLUTION_M} m, '
          f'{found["solid_share"]:.0%} of them occupied or unknown (unknown: occupied); '
          f'{found["rectangles"]} wall rectangles in {found["bodies"]} bodies')
    print(f'  load (YAML, PGM, values, walls, bodies): {found["load_s"]:.2f} s '
          f'(<= {TARGETS["load_s"]} s: {_verdict(found["load_s"], TARGETS["load_s"])})')
    print(f'  RSS added: {found["rss_after_mb"]:.0f} MB after, {found["rss_peak_mb"]:.0f} MB at '
          'the peak')
    print(f'  lidar 1080 rays, 270 deg, 30 m, 40 Hz on the map ({found["march"]} march, '
          f'what ray_march auto gives here): {found["lidar_ms"]:.3f} ms per sample, '
          f'{found["lidar_share"]:.1%} of one core, {found["lidar_hits"]} rays hit '
          f'(<= {TARGETS["lidar_share"]:.0%}: '
          f'{_verdict(found["lidar_share"], TARGETS["lidar_share"])}); on the map / empty: '
          f'{found["lidar_ratio"]:.2f}x (<= {TARGETS["lidar_ratio"]}x: '
          f'{_verdict(found["lidar_ratio"], TARGETS["lidar_ratio"])})')
    print(f'  same lidar in the empty world: {found["empty_ms"]:.3f} ms, '
          f'{found["empty_share"]:.1%} of one core')
    for name in ('compiled', 'numpy'):
        if name + '_ms' not in found:
            print('  compiled march: numba is not installed, its row left out (pip install '
                  "'vehicle_sim[fast]')")
            continue
        low, high = found[name + '_spread']
        print(f'  {name} march: {found[name + "_ms"]:.3f} ms per sample, '
              f'{found[name + "_share"]:.1%} of one core, {found[name + "_ratio"]:.2f}x the '
              f'empty world (blocks {low:.2f}-{high:.2f}x)')
    if found['first_s'] is not None:
        wall_s, cpu_s = found['first_s']
        print(f'  compiled march: first sample {wall_s:.2f} s, {cpu_s:.2f} s of CPU (numba '
              "imported, the march compiled or read from numba's cache); the two marches' "
              'scans ' + ('equal to the bit' if found['same_scans'] else 'DIFFER'))
    print(f'  load average {load_before} before, '
          + '/'.join(f'{x:.1f}' for x in os.getloadavg()) + ' after')
    return 0


if __name__ == '__main__':
    raise SystemExit(main())
