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
A camera's segmentation and recognition cost (issue 32): a 640 x 480 camera, colour only vs with.

Target: a 640 x 480 camera with segmentation and recognition costs <= 1.3x the same camera with
colour only (issue 32's "camera with depth and segmentation"; the range finder's part is
bench_range_finder's, beside this one). The car stands in the obstacle course
(config/worlds/obstacle_course.yaml) with eight labelled boxes and cylinders ahead (cars,
pedestrians, an obstacle), so the mask holds several objects; each sample is one render (the
world steps between samples, so nothing comes from the renderer's per-step cache). Two worlds,
one per camera, are sampled in interleaved blocks; the cost is the median of a sample's wall
time. Run: ``.venv/bin/python benchmarks/bench_camera_perception.py [--quick]``.
"""

import argparse
import statistics
import time

from vehicle_sim.config import load_car, load_world, world_from_data
from vehicle_sim.core.sensors.sets import merge_sensors
from vehicle_sim.physics import SimulatedCar, World
from vehicle_sim.physics.sensors import SensorSuite

COURSE = load_world('obstacle_course')
CAMERA = {'name': 'camera', 'width': 640, 'height': 480, 'fov': 1.2,
          'pose': {'x': 1.5, 'z': 1.3}}
PERCEPTION = {'segmentation': True, 'recognition': True}
TARGET_RATIO = 1.3
# name, label, obstacle entry: what the camera sees besides the course's wall and pole
OBJECTS = [(f'{label}_{i}', label, entry) for i, (label, entry) in enumerate([
    ('car', {'shape': 'box', 'size': [4.0, 1.8, 1.5], 'position': [12.0, 2.0, 0.75]}),
    ('car', {'shape': 'box', 'size': [4.0, 1.8, 1.5], 'position': [15.0, -2.5, 0.75]}),
    ('car', {'shape': 'box', 'size': [4.5, 1.9, 1.6], 'position': [8.0, -4.0, 0.8]}),
    ('pedestrian', {'shape': 'cylinder', 'radius': 0.3, 'height': 1.8,
                    'position': [7.0, 3.0, 0.9]}),
    ('pedestrian', {'shape': 'cylinder', 'radius': 0.3, 'height': 1.8,
                    'position': [9.0, 0.5, 0.9]}),
    ('pedestrian', {'shape': 'cylinder', 'radius': 0.3, 'height': 1.8,
                    'position': [16.0, 4.0, 0.9]}),
    ('obstacle', {'shape': 'box', 'size': [1.0, 1.0, 1.0], 'position': [6.0, -1.5, 0.5]}),
    ('truck', {'shape': 'box', 'size': [8.0, 2.5, 3.2], 'position': [14.0, 7.0, 1.6]}),
])]


def _scene(extra):
    world = World()
    for obstacle in COURSE.obstacles:
        world.add_obstacle(obstacle)
    boxes = world_from_data({'vehicles': [{'name': 'Car'}], 'obstacles': [
        dict(entry, name=name) for name, _, entry in OBJECTS]}, 'bench').obstacles
    for (name, label, _), obstacle in zip(OBJECTS, boxes):
        world.labels.set(world.add_obstacle(obstacle), label, world.labels.instance(name))
    params = load_car('Car')
    car = SimulatedCar(world, params, (0.0, 0.0, 0.0), name='Car')
    specs = merge_sensors(params.sensor_set, [dict(CAMERA, **extra)], 'bench')
    suite = SensorSuite(world, car.body, specs, COURSE.origin)
    world.step()
    return world, suite


def _sample_s(world, suite, samples):
    times = []
    for _ in range(samples):
        world.step()
        start = time.perf_counter()
        reading = suite.sample('camera')
        times.append(time.perf_counter() - start)
    return times, reading


def measure(blocks, samples):
    """Return the median sample cost [s] of the colour camera and the perceiving one."""
    colour_world, colour_suite = _scene({})
    seen_world, seen_suite = _scene(PERCEPTION)
    colour, seen = [], []
    for block in range(blocks):
        pairs = [(colour, colour_world, colour_suite), (seen, seen_world, seen_suite)]
        for out, world, suite in (pairs if block % 2 == 0 else pairs[::-1]):
            times, reading = _sample_s(world, suite, samples)
            out.extend(times)
    objects = len(seen_suite.latest('camera').objects)
    colour_world.close()
    seen_world.close()
    return statistics.median(colour), statistics.median(seen), objects


def figures(quick):
    """Return {'colour_ms', 'seen_ms', 'ratio', 'objects'} (benchmarks/run_all.py)."""
    colour_s, seen_s, objects = measure(*((4, 5) if quick else (10, 10)))
    return {'colour_ms': colour_s * 1e3, 'seen_ms': seen_s * 1e3, 'ratio': seen_s / colour_s,
            'objects': objects}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--quick', action='store_true', help='fewer samples')
    args = parser.parse_args(argv)
    found = figures(args.quick)
    ratio = found['ratio']
    print(f'640 x 480 camera, colour only:                 {found["colour_ms"]:7.1f} ms/sample')
    print(f'same camera with segmentation and recognition: {found["seen_ms"]:7.1f} ms/sample '
          f'({found["objects"]} objects recognised)')
    print(f'ratio: {ratio:.2f}x (target <= {TARGET_RATIO}x): '
          f'{"met" if ratio <= TARGET_RATIO else "missed"}')
    return ratio


if __name__ == '__main__':
    main()
