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
Perception ground truth (issue 32): a 640 x 480 camera with depth vs the same camera alone.

A camera and a range finder with the same view at the same mount share one render per step
(physics/sensors/render.py), so the depth should cost little more than the colour image:
target <= 1.3x. The car drives at 30 km/h through the obstacle course; each step is
``world.step()`` and the samples (camera only, or camera + range finder), blocks of the two
interleaved; the ratio is the median of the blocks' ratios. Run:
``.venv/bin/python benchmarks/bench_perception.py [--quick]``.
"""

import argparse
import statistics
import time

from vehicle_sim.config import load_car, load_world
from vehicle_sim.core.sensors.params import sensor_from_dict
from vehicle_sim.physics import SimulatedCar, World
from vehicle_sim.physics.sensors.camera import CameraSensor
from vehicle_sim.physics.sensors.range_finder import RangeFinderSensor

COURSE = load_world('obstacle_course')
TARGET_RATIO = 1.3
MOUNT = {'x': 1.5, 'z': 1.3}
VIEW = {'width': 640, 'height': 480, 'fov': 1.0}
CAMERA = dict(VIEW, type='camera', name='camera', near=0.05, far=100.0, pose=MOUNT)
DEPTH = dict(VIEW, type='range_finder', name='depth', min_range=0.05, max_range=100.0,
             pose=MOUNT)


def _scene():
    world = World()
    for obstacle in COURSE.obstacles:
        world.add_obstacle(obstacle)
    car = SimulatedCar(world, load_car('Car'), (0.0, 0.0, 0.0), name='Car')
    car.logic.set_cruising_speed_kmh(30.0)
    for _ in range(50):
        world.step()
    return world, car


def _block(world, sensors, steps):
    start = time.perf_counter()
    for _ in range(steps):
        world.step()
        for sensor in sensors:
            sensor.sample(world.time_s)
    return (time.perf_counter() - start) / steps


def figures(quick=False):
    """Return {'camera_ms', 'with_depth_ms', 'ratio'}: per step, the median over blocks."""
    blocks, steps = (3, 5) if quick else (7, 10)
    world, car = _scene()
    camera = CameraSensor(world, car.body, sensor_from_dict(CAMERA, 'bench'))
    depth = RangeFinderSensor(world, car.body, sensor_from_dict(DEPTH, 'bench'))
    alone, both, ratios = [], [], []
    try:
        _block(world, (camera, depth), 2)                      # warm up
        for index in range(blocks):
            if index % 2:
                b = _block(world, (camera, depth), steps)
                a = _block(world, (camera,), steps)
            else:
                a = _block(world, (camera,), steps)
                b = _block(world, (camera, depth), steps)
            alone.append(a)
            both.append(b)
            ratios.append(b / a)
    finally:
        world.close()
    return {'camera_ms': statistics.median(alone) * 1e3,
            'with_depth_ms': statistics.median(both) * 1e3,
            'ratio': statistics.median(ratios)}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[1])
    parser.add_argument('--quick', action='store_true', help='fewer blocks')
    args = parser.parse_args(argv)
    found = figures(args.quick)
    met = 'met' if found['ratio'] <= TARGET_RATIO else 'MISSED'
    print('vehicle_sim perception benchmark (Car at 30 km/h in the obstacle course, 10 ms step)')
    print(f'  640 x 480 camera alone          : {found["camera_ms"]:.1f} ms per step')
    print(f'  same camera + range finder      : {found["with_depth_ms"]:.1f} ms per step')
    print(f'  ratio (target <= {TARGET_RATIO:g}x)           : {found["ratio"]:.3f}x ({met})')
    return 0


if __name__ == '__main__':
    raise SystemExit(main())
