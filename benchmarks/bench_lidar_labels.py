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
A labelled 32-layer lidar against the same lidar plain (issue 32).

Target: a 32-layer x 1024-ray, 360-degree lidar with ``labels: true`` (each point's label,
instance id and intensity, physics/sensors/lidar.py) costs <= 1.2x the same lidar without
(``labels: false``). Both lidars sit at the same mount of one car in the obstacle course
(config/worlds/obstacle_course.yaml) with its obstacles and 20 placed traffic-like boxes around,
so the rays hit walls, poles, boxes and the ground; each sample's cost is this process's CPU time
(one thread), the two lidars sampled in interleaved blocks, medians. Run:
``.venv/bin/python benchmarks/bench_lidar_labels.py [--quick]``.
"""

import argparse
import math
import os
import statistics
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))

TARGET_RATIO = 1.2
LIDAR = {'type': 'lidar', 'fov': 6.283, 'horizontal_resolution': 1024, 'layers': 32,
         'vertical_fov': 0.7, 'max_range': 100.0, 'rate_hz': 10.0,
         'pose': {'x': 1.0, 'z': 1.8}}


def _scene():
    from vehicle_sim.config import load_car, load_world
    from vehicle_sim.core.sensors.sets import merge_sensors
    from vehicle_sim.core.world.params import obstacle_from_dict
    from vehicle_sim.physics import SimulatedCar, World
    from vehicle_sim.physics.sensors import SensorSuite
    course = load_world('obstacle_course')
    world = World()
    for obstacle in course.obstacles:
        world.add_obstacle(obstacle)
    for index in range(20):
        angle = 2.0 * math.pi * index / 20
        world.add_obstacle(obstacle_from_dict(
            {'name': f'box_{index}', 'shape': 'box', 'size': [4.5, 1.8, 1.5],
             'position': [15.0 * math.cos(angle), 15.0 * math.sin(angle), 0.75],
             'yaw': angle}, 'bench.yaml'), placed=True)
    params = load_car('Car')
    car = SimulatedCar(world, params, (0.0, 0.0, 0.0), name='Car')
    sensors = [dict(LIDAR, name='plain', topic='plain'),
               dict(LIDAR, name='labelled', topic='labelled', labels=True)]
    suite = SensorSuite(world, car.body, merge_sensors(params.sensor_set, sensors, 'bench'),
                        course.origin)
    for _ in range(50):
        world.step()
    return world, suite


def _sample_cost(suite, name, samples):
    times = []
    for _ in range(samples):
        start = time.process_time()
        suite.sample(name)
        times.append(time.process_time() - start)
    return statistics.median(times)


def figures(quick=False):
    """Return {'plain_ms', 'labelled_ms', 'ratio'}: CPU per sample, medians of blocks."""
    world, suite = _scene()
    try:
        costs = {'plain': [], 'labelled': []}
        for block in range(5 if quick else 11):
            for name in (('plain', 'labelled') if block % 2 else ('labelled', 'plain')):
                costs[name].append(_sample_cost(suite, name, 5 if quick else 10))
    finally:
        world.close()
    plain, labelled = statistics.median(costs['plain']), statistics.median(costs['labelled'])
    return {'plain_ms': plain * 1e3, 'labelled_ms': labelled * 1e3, 'ratio': labelled / plain}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[1])
    parser.add_argument('--quick', action='store_true', help='fewer blocks and samples')
    args = parser.parse_args(argv)
    found = figures(args.quick)
    verdict = 'meets' if found['ratio'] <= TARGET_RATIO else 'MISSES'
    print(f"vehicle_sim labelled lidar benchmark: {LIDAR['layers']} layers x "
          f"{LIDAR['horizontal_resolution']} rays, obstacle course with 20 boxes (CPU per sample)")
    print(f"  plain {found['plain_ms']:.2f} ms, labelled {found['labelled_ms']:.2f} ms: "
          f"{found['ratio']:.2f}x (<= {TARGET_RATIO}x: {verdict}); load "
          f"{'/'.join(f'{x:.1f}' for x in os.getloadavg())}")


if __name__ == '__main__':
    main()
