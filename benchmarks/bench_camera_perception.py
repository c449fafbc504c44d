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

Target: a 640 x 480 camera with segmentation and recognition, and with a range finder of the same
view at the same mount besides (issue 32's "camera with depth and segmentation"), costs <= 1.3x
the same camera with colour only (the depth alone: bench_perception.py). The car stands in the
obstacle course (config/worlds/obstacle_course.yaml) with eight labelled boxes and cylinders
ahead (cars, pedestrians, an obstacle), so the mask holds several objects; each sample is one
render (the world steps between samples, so nothing comes from the renderer's per-step cache).
Three worlds, one per configuration, are sampled in interleaved blocks; the cost is the median
of a step's samples' wall time. Run:
``.venv/bin/python benchmarks/bench_camera_perception.py [--quick]``.
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
# the camera's view: one render serves both
DEPTH = {'type': 'range_finder', 'name': 'depth', 'width': 640, 'height': 480, 'fov': 1.2,
         'min_range': 0.05, 'max_range': 100.0, 'pose': {'x': 1.5, 'z': 1.3}}
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


def _scene(extra, depth=False):
    world = World()
    for obstacle in COURSE.obstacles:
        world.add_obstacle(obstacle)
    boxes = world_from_data({'vehicles': [{'name': 'Car'}], 'obstacles': [
        dict(entry, name=name) for name, _, entry in OBJECTS]}, 'bench').obstacles
    for (name, label, _), obstacle in zip(OBJECTS, boxes):
        world.labels.set(world.add_obstacle(obstacle), label, world.labels.instance(name))
    params = load_car('Car')
    car = SimulatedCar(world, params, (0.0, 0.0, 0.0), name='Car')
    specs = merge_sensors(params.sensor_set,
                          [dict(CAMERA, **extra)] + ([DEPTH] if depth else []), 'bench')
    suite = SensorSuite(world, car.body, specs, COURSE.origin)
    world.step()
    return world, suite


def _sample_s(world, suite, samples):
    times = []
    for _ in range(samples):
        world.step()
        start = time.perf_counter()
        for name in suite.specs:            # the camera first: its render has the mask
            suite.sample(name)
        times.append(time.perf_counter() - start)
    return times


def measure(blocks, samples):
    """Return the median cost [s] of the colour camera, the perceiving one, and with depth."""
    scenes = [_scene({}), _scene(PERCEPTION), _scene(PERCEPTION, depth=True)]
    costs = [[] for _ in scenes]
    for block in range(blocks):
        order = list(range(len(scenes)))
        for index in (order if block % 2 == 0 else order[::-1]):
            costs[index].extend(_sample_s(*scenes[index], samples))
    objects = len(scenes[1][1].latest('camera').objects)
    for world, _ in scenes:
        world.close()
    return tuple(statistics.median(c) for c in costs) + (objects,)


def figures(quick):
    """Return {'colour_ms', 'seen_ms', 'depth_ms', 'ratio', 'depth_ratio', 'objects'}."""
    colour_s, seen_s, depth_s, objects = measure(*((4, 5) if quick else (10, 10)))
    return {'colour_ms': colour_s * 1e3, 'seen_ms': seen_s * 1e3, 'depth_ms': depth_s * 1e3,
            'ratio': seen_s / colour_s, 'depth_ratio': depth_s / colour_s, 'objects': objects}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--quick', action='store_true', help='fewer samples')
    args = parser.parse_args(argv)
    found = figures(args.quick)
    print(f'640 x 480 camera, colour only:                 {found["colour_ms"]:7.1f} ms/sample')
    print(f'same camera with segmentation and recognition: {found["seen_ms"]:7.1f} ms/sample '
          f'({found["objects"]} objects recognised)')
    print(f'  and a range finder of its view:              {found["depth_ms"]:7.1f} ms/sample')
    for name, ratio in (('segmentation and recognition', found['ratio']),
                        ('segmentation, recognition and depth', found['depth_ratio'])):
        print(f'ratio, {name} / colour only: {ratio:.2f}x (target <= {TARGET_RATIO}x): '
              f'{"met" if ratio <= TARGET_RATIO else "missed"}')
    return found['depth_ratio']


if __name__ == '__main__':
    main()
