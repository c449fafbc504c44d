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
Occupancy-map cost (issue 18): loading a 3000 x 2250-cell map, stepping and ray casting on it.

Targets: the map loads (YAML, PGM, thresholds, merged walls, bodies) in <= 2 s and adds
<= 300 MB of RSS; the in-process step of a car with that map loaded / the same car without a
map <= 1.1x; a 1080-ray, 270-degree lidar at 40 Hz on the map <= 15 % of one core.

The map is drawn here (0.05 m cells, 150 x 112.5 m): rooms of 150 cells with door gaps, 300
round pillars and 12 diagonal walls (the worst case for merging: about one rectangle per row).
Loading is measured in a fresh process (its RSS before and its peak after, the peak reset by
``/proc/self/clear_refs``); the step ratio in interleaved blocks of steps in one process, and
the lidar's cost per sample, as this process's CPU time (one thread: less moved by other work on
a shared machine than wall time). The lidar finds the walls over the grid (core/map/grid_rays.py)
and casts Bullet's rays only up to them; benchmarks/bench_occupancy_lidar.py measures it on a
map like a SLAM map, against the same lidar in an empty world. Run:
``.venv/bin/python benchmarks/bench_maps.py [--quick]``.
"""

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))

WIDTH, HEIGHT = 3000, 2250
RESOLUTION_M = 0.05
ORIGIN = (-10.0, -10.0, 0.0)
LIDAR = {'name': 'lidar', 'type': 'lidar', 'fov': 4.71238898, 'horizontal_resolution': 1080,
         'max_range': 30.0, 'pose': {'x': 1.0, 'z': 0.5}, 'rate_hz': 40.0}
TARGETS = {'load_s': 2.0, 'rss_mb': 300.0, 'step_ratio': 1.1, 'lidar_share': 0.15}


def draw_map(folder):
    """Write the benchmark's map (PGM + YAML) into ``folder``; return the YAML's path."""
    from PIL import Image
    rng = np.random.default_rng(18)
    image = np.full((HEIGHT, WIDTH), 254, dtype=np.uint8)
    image[:4, :] = image[-4:, :] = image[:, :4] = image[:, -4:] = 0
    for row in range(150, HEIGHT, 150):           # room walls with doors
        image[row:row + 3, :] = 0
        for door in range(60, WIDTH, 150):
            image[row:row + 3, door:door + 30] = 254
    for column in range(150, WIDTH, 150):
        image[:, column:column + 3] = 0
        for door in range(60, HEIGHT, 150):
            image[door:door + 30, column:column + 3] = 254
    rows, columns = np.mgrid[0:HEIGHT, 0:WIDTH]
    for _ in range(300):                          # round pillars
        r, c, radius = rng.integers(20, HEIGHT - 20), rng.integers(20, WIDTH - 20), \
            rng.integers(4, 15)
        window = (slice(max(r - radius, 0), r + radius + 1),
                  slice(max(c - radius, 0), c + radius + 1))
        disc = (rows[window] - r) ** 2 + (columns[window] - c) ** 2 <= radius ** 2
        image[window][disc] = 0
    for _ in range(12):                           # diagonal walls, 3 cells thick
        r, c = rng.integers(100, HEIGHT - 400), rng.integers(100, WIDTH - 400)
        for step in range(300):
            image[r + step, c + step:c + step + 3] = 0
    free = (slice(HEIGHT - 200 - 20, HEIGHT - 200 + 20), slice(180, 320))
    image[free] = 254                             # the car's spot, see _world
    Image.fromarray(image).save(os.path.join(folder, 'big.pgm'))
    path = os.path.join(folder, 'big.yaml')
    with open(path, 'w', encoding='utf-8') as stream:
        stream.write(f'image: big.pgm\nresolution: {RESOLUTION_M}\norigin: {list(ORIGIN)}\n'
                     'negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n')
    return path


def _world(map_path, sensors=(), unknown='free', car=None):
    from vehicle_sim.config import world_from_data
    # the car in the free patch: 200 cells from the bottom, columns 180 .. 320
    x, y = car or (ORIGIN[0] + 200 * RESOLUTION_M, ORIGIN[1] + 200 * RESOLUTION_M)
    data = {'vehicles': [{'name': 'car', 'model': 'Car', 'pose': {'x': x, 'y': y},
                          'sensors': list(sensors)}]}
    if map_path:
        data['map'] = {'type': 'occupancy_grid', 'file': map_path, 'unknown': unknown}
    return world_from_data(data, 'bench_maps.yaml')


_LOAD_SCRIPT = """
import json, sys, time
sys.path.insert(0, {root!r})
def rss_mb(key):
    for line in open('/proc/self/status'):
        if line.startswith(key):
            return int(line.split()[1]) / 1024.0
from bench_maps import _world
from vehicle_sim.physics.map_layer import MapLayer
from vehicle_sim.physics.scene import build_scene
import PIL.Image
spec = _world({path!r}, unknown={unknown!r}, car={car!r})
scene = build_scene(_world(None, car={car!r}))   # the same world without its map: the baseline
before = rss_mb('VmRSS')
open('/proc/self/clear_refs', 'w').write('5')   # reset the peak
start = time.perf_counter()
built = MapLayer().build(scene.world, spec)
load_s = time.perf_counter() - start
after, peak = rss_mb('VmRSS'), rss_mb('VmHWM')
print(json.dumps({{'load_s': load_s, 'rss_after_mb': after - before,
                  'rss_peak_mb': peak - before, 'rectangles': len(built.rectangles),
                  'bodies': len(built.body_ids)}}))
"""


def measure_load(map_path, unknown='free', car=None):
    """
    Load the map in a fresh process; return its figures (time, RSS added, rectangles).

    :param unknown: the map's ``unknown`` (free or occupied).
    :param car: the car's (x, y) [m] in free space; None: this benchmark's map's spot.
    """
    script = _LOAD_SCRIPT.format(root=os.path.dirname(HERE), path=map_path, unknown=unknown,
                                 car=car)
    env = dict(os.environ, PYTHONPATH=HERE + os.pathsep + os.environ.get('PYTHONPATH', ''))
    out = subprocess.run([sys.executable, '-c', script], capture_output=True, text=True,
                         env=env, check=True, timeout=300)
    return json.loads(out.stdout.strip().splitlines()[-1])


def _step_cost(world, steps):
    # CPU time of this process (one thread): less moved by other work on a shared machine.
    start = time.process_time()
    for _ in range(steps):
        world.step()
    return (time.process_time() - start) / steps


def measure_step_ratio(map_path, blocks, steps):
    """Median step cost with the map / without, in interleaved blocks; and both costs [s]."""
    from vehicle_sim.physics.scene import build_scene
    plain = build_scene(_world(None))
    mapped = build_scene(_world(map_path))
    for scene in (plain, mapped):
        for _ in range(100):
            scene.world.step()
    ratios, costs = [], []
    for block in range(blocks):
        order = (plain, mapped) if block % 2 else (mapped, plain)
        cost = {id(scene): _step_cost(scene.world, steps) for scene in order}
        ratios.append(cost[id(mapped)] / cost[id(plain)])
        costs.append((cost[id(mapped)], cost[id(plain)]))
    plain.world.close()
    mapped.world.close()
    return statistics.median(ratios), statistics.median(c[0] for c in costs), \
        statistics.median(c[1] for c in costs)


def measure_lidar(map_path, samples):
    """Median cost of one 1080-ray lidar sample on the map; its share of a core at 40 Hz."""
    from vehicle_sim.physics.scene import build_scene, mount_suite
    scene = build_scene(_world(map_path, [LIDAR]), mount=mount_suite)
    for _ in range(50):
        scene.world.step()
    suite = scene.vehicles['car'].sensors
    times = []
    for _ in range(samples):
        start = time.process_time()
        scan = suite.sample('lidar')
        times.append(time.process_time() - start)
    hits = int(np.isfinite(scan.scan).sum())
    scene.world.close()
    cost = statistics.median(times)
    return cost, cost * LIDAR['rate_hz'], hits


def figures(quick=False):
    """Run every measurement; return {name: value} (see TARGETS)."""
    with tempfile.TemporaryDirectory(prefix='bench_maps_') as folder:
        map_path = draw_map(folder)
        load = measure_load(map_path)
        ratio, mapped_s, plain_s = measure_step_ratio(map_path, 5 if quick else 11,
                                                      200 if quick else 400)
        lidar_s, share, hits = measure_lidar(map_path, 50 if quick else 200)
    return dict(load, step_ratio=ratio, step_mapped_us=mapped_s * 1e6,
                step_plain_us=plain_s * 1e6, lidar_ms=lidar_s * 1e3, lidar_share=share,
                lidar_hits=hits, rss_mb=max(load['rss_after_mb'], load['rss_peak_mb']))


def _verdict(value, target):
    return 'meets' if value <= target else f'MISSES by {100 * (value / target - 1):.0f} %'


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[1])
    parser.add_argument('--quick', action='store_true', help='fewer blocks and samples')
    args = parser.parse_args(argv)
    found = figures(args.quick)
    print(f'vehicle_sim map benchmark: {WIDTH} x {HEIGHT} cells of {RESOLUTION_M} m, '
          f'{found["rectangles"]} wall rectangles in {found["bodies"]} bodies')
    print(f'  load (YAML, PGM, values, walls, bodies): {found["load_s"]:.2f} s '
          f'(<= {TARGETS["load_s"]} s: {_verdict(found["load_s"], TARGETS["load_s"])})')
    print(f'  RSS added: {found["rss_after_mb"]:.0f} MB after, {found["rss_peak_mb"]:.0f} MB at '
          f'the peak (<= {TARGETS["rss_mb"]:.0f} MB: '
          f'{_verdict(found["rss_mb"], TARGETS["rss_mb"])})')
    print(f'  step with the map / without: {found["step_ratio"]:.3f}x '
          f'({found["step_mapped_us"]:.0f} vs {found["step_plain_us"]:.0f} us; '
          f'<= {TARGETS["step_ratio"]}x: '
          f'{_verdict(found["step_ratio"], TARGETS["step_ratio"])})')
    print(f'  lidar 1080 rays, 270 deg, 40 Hz on the map: {found["lidar_ms"]:.3f} ms per sample, '
          f'{found["lidar_share"]:.1%} of one core, {found["lidar_hits"]} rays hit '
          f'(<= {TARGETS["lidar_share"]:.0%}: '
          f'{_verdict(found["lidar_share"], TARGETS["lidar_share"])})')
    return 0


if __name__ == '__main__':
    raise SystemExit(main())
