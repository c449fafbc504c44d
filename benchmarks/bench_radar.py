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
Radar cost (docs/sensors.md, "The radar"): microseconds per reading with 60 traffic cars.

The shipped highway (config/worlds/highway.yaml) with 60 traffic cars (seeded; updated every
100 ms), its ego car cruising at 90 km/h, stepped 10 ms at a time, and a radar on the ego car
read after each step. Two radars: Webots' Radar defaults (0.78 rad x 0.1 rad, 1-50 m), and one
that sees all around (2 pi x 0.5 rad, 200 m: every car near enough in its cone, the worst
case). Only the readings are timed, each on its own, in the thread's CPU time (a machine shared
with other jobs preempts some readings; CPU time leaves the waits out): the median reading over
``steps`` steps (best of ``repeats`` runs) is the figure, the mean wall time beside it, and the
number of targets a reading has. Target: <= 50 us per reading.

The same machine's cost of one small numpy operation (a (60, 3) array minus a vector) is
printed beside it: a reading is a few dozen such operations and a loop over the targets, so the
figure scales with it from machine to machine.

Run: ``.venv/bin/python benchmarks/bench_radar.py [--quick]``.
"""

import argparse
import statistics
import time
import timeit

from bench_traffic import highway_spec

from vehicle_sim.core.sensors.params import sensor_from_dict
from vehicle_sim.physics.scene import build_scene
from vehicle_sim.physics.sensors import SensorSuite

TARGET_US = 50.0
CARS = 60
MOUNT = {'type': 'radar', 'name': 'radar', 'pose': {'x': 2.0, 'z': 0.6}}
RADARS = {
    'Webots defaults': {},
    'all around, 200 m': {'horizontal_fov': 6.283, 'vertical_fov': 0.5, 'max_range': 200.0},
}


def per_reading_us(fields, steps=500, repeats=3):
    """Return (median CPU us, mean wall us, mean targets) per reading, best of ``repeats``."""
    best = (float('inf'), 0.0, 0.0)
    for _ in range(repeats):
        scene = build_scene(highway_spec(CARS))
        try:
            car = scene.vehicles['Car'].car
            car.logic.set_cruising_speed_kmh(90.0)
            spec = sensor_from_dict(dict(MOUNT, **fields), 'bench')
            radar = SensorSuite(scene.world, car.body, [spec]).sensors['radar']
            world = scene.world
            for _ in range(50):
                world.step()
            cpu, wall, targets = [], 0.0, 0
            for _ in range(steps):
                world.step()
                start, start_cpu = time.perf_counter(), time.thread_time()
                reading = radar.sample(world.time_s)
                cpu.append(time.thread_time() - start_cpu)
                wall += time.perf_counter() - start
                targets += len(reading.targets)
            best = min(best, (statistics.median(cpu) * 1e6, wall / steps * 1e6,
                              targets / steps))
        finally:
            scene.world.close()
    return best


def numpy_op_us():
    """Return this machine's cost of one small numpy operation [us], best of 20."""
    return min(timeit.repeat('a - b', setup='import numpy as np; a = np.ones((60, 3)); '
                             'b = np.ones(3)', number=10000, repeat=20)) / 10000 * 1e6


def figures(quick=False):
    """Return {radar: (median CPU us, mean wall us, targets)} and the numpy op cost [us]."""
    steps, repeats = (200, 1) if quick else (500, 3)
    return ({name: per_reading_us(fields, steps, repeats) for name, fields in RADARS.items()},
            numpy_op_us())


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[1])
    parser.add_argument('--quick', action='store_true')
    args = parser.parse_args()
    found, op_us = figures(args.quick)
    for name, (median, mean, targets) in found.items():
        print(f'radar ({name}) with {CARS} traffic cars: {median:.1f} us per reading (median '
              f'CPU time; mean wall time {mean:.1f} us), {targets:.1f} targets a reading '
              f'(target <= {TARGET_US:g} us)')
    print(f'one small numpy operation on this machine: {op_us:.2f} us')


if __name__ == '__main__':
    main()
