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
Sensor cost (issue 8): each sensor's cost per sample and its share of one core at its rate.

Targets: a 1080-ray, 270-degree lidar at 40 Hz (f1tenth's default) <= 15 % of one core; IMU +
GNSS at 100 / 10 Hz <= 2 %; a 320 x 240 camera at 10 Hz is reported. The share is the cost of
the samples of one simulated second run in real time: cost per sample x rate. A last check
shows that a car whose sensors are not mounted steps as fast as one without any (the step hot
path does not pay for sensors that are off).

The car drives at 30 km/h through the obstacle course (config/worlds/obstacle_course.yaml), so
the rays hit a wall, a pole and the ground. Medians over interleaved blocks. Run:
``.venv/bin/python benchmarks/bench_sensors.py``.
"""

import argparse
import statistics
import time

from vehicle_sim.config import load_car, load_world
from vehicle_sim.core.sensors.sets import merge_sensors
from vehicle_sim.physics import SimulatedCar, World
from vehicle_sim.physics.sensors import CollisionMonitor, SensorSuite

COURSE = load_world('obstacle_course')

# name, sensor entries (a world's sensors: list), rate [Hz] of the share, target share or None
CASES = (
    ('lidar 1080 rays, 270 deg, 40 Hz', [{'name': 'lidar', 'fov': 4.71238898,
                                          'horizontal_resolution': 1080, 'max_range': 30.0,
                                          'pose': {'x': 1.0, 'z': 1.5}, 'rate_hz': 40.0}],
     0.15),
    ('IMU 100 Hz + GNSS 10 Hz', [{'name': 'imu', 'rate_hz': 100.0},
                                 {'name': 'gnss', 'rate_hz': 10.0}], 0.02),
    ('camera 320 x 240, 10 Hz', [{'name': 'camera', 'width': 320, 'height': 240,
                                  'rate_hz': 10.0}], None),
    ('lidar 16 layers x 1024 rays, 10 Hz', [{'name': 'lidar', 'fov': 6.27, 'layers': 16,
                                             'vertical_fov': 0.52, 'horizontal_resolution': 1024,
                                             'max_range': 50.0, 'pose': {'x': 1.0, 'z': 1.8},
                                             'rate_hz': 10.0}], None),
    ('distance sensor, 9-ray cone, 20 Hz', [{'type': 'distance', 'name': 'front', 'rays': 9,
                                             'aperture': 0.3, 'pose': {'x': 4.6, 'z': 0.9},
                                             'rate_hz': 20.0}], None),
)


def _scene(entries, with_suite=True):
    world = World()
    for obstacle in COURSE.obstacles:
        world.add_obstacle(obstacle)
    params = load_car('Car')
    car = SimulatedCar(world, params, (0.0, 0.0, 0.0), name='Car')
    specs = merge_sensors(params.sensor_set, entries, 'bench')
    suite = SensorSuite(world, car.body, specs, COURSE.origin) if with_suite else None
    car.logic.set_cruising_speed_kmh(30.0)
    for _ in range(100):
        world.step()
    return world, car, suite


def _sample_cost(suite, samples):
    """Median cost of one sample of every mounted sensor of the suite, at its rate [s, share]."""
    costs = {}
    for name, spec in suite.specs.items():
        times = []
        for _ in range(samples):
            start = time.perf_counter()
            suite.sample(name)
            times.append(time.perf_counter() - start)
        costs[name] = (statistics.median(times), spec.rate_hz)
    return costs


def _step_cost(world, steps):
    start = time.perf_counter()
    for _ in range(steps):
        world.step()
    return (time.perf_counter() - start) / steps


def measure_scheduled_share(entries, blocks, steps):
    """
    Extra wall time per simulated second of the suite sampling on its schedule.

    Blocks of steps with the sensors scheduled and stopped alternate; the median difference
    counts.
    """
    world, _, suite = _scene(entries)
    extra = []
    for _ in range(blocks):
        suite.close()
        plain = _step_cost(world, steps)
        suite.start()
        extra.append(_step_cost(world, steps) - plain)
    world.close()
    return statistics.median(extra) / world.time_step_s


def measure_sensors_off(blocks, steps):
    """Step cost of a car with unmounted default sensors and a suite vs the same car without."""
    bare_world, _, _ = _scene([], with_suite=False)
    off_world, _, off_suite = _scene([])
    off_suite.start()                 # nothing mounted: no hook is registered
    ratios = []
    for block in range(blocks):
        if block % 2:
            bare_s = _step_cost(bare_world, steps)
            off_s = _step_cost(off_world, steps)
        else:
            off_s = _step_cost(off_world, steps)
            bare_s = _step_cost(bare_world, steps)
        ratios.append(off_s / bare_s)
    bare_world.close()
    off_world.close()
    return statistics.median(ratios)


def measure_collisions(steps):
    """Cost of the collision monitor per basic step (it runs every step) [s]."""
    world, car, _ = _scene([])
    plain = _step_cost(world, steps)
    CollisionMonitor(world, car.body)
    monitored = _step_cost(world, steps)
    world.close()
    return monitored - plain


def _verdict(share, target):
    if target is None:
        return 'reported'
    if share <= target:
        return f'meets the target (<= {target:.0%})'
    return f'MISSES the target (<= {target:.0%}) by {100 * (share / target - 1):.0f} %'


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[1])
    parser.add_argument('--samples', type=int, default=200)
    parser.add_argument('--blocks', type=int, default=9)
    parser.add_argument('--steps', type=int, default=300)
    args = parser.parse_args(argv)

    print('vehicle_sim sensor benchmark (Car at 30 km/h in the obstacle course, 10 ms step)')
    for label, entries, target in CASES:
        world, _, suite = _scene(entries)
        costs = _sample_cost(suite, args.samples)
        world.close()
        share = sum(cost * rate for cost, rate in costs.values())
        scheduled = measure_scheduled_share(entries, args.blocks, args.steps)
        per_sample = ', '.join(f'{name} {cost * 1e3:.3f} ms' for name, (cost, _) in
                               costs.items())
        print(f'  {label:38s}: {per_sample}; share of one core {share:6.2%} '
              f'(scheduled in the world: {scheduled:6.2%}): {_verdict(share, target)}')
    collision_s = measure_collisions(args.steps)
    print(f'  collision monitor (every step)        : {collision_s * 1e6:.1f} us per step, '
          f'share {collision_s / 0.01:.2%}')
    ratio = measure_sensors_off(args.blocks, args.steps)
    print(f'  sensors off (defaults unmounted) / bare car step cost: {ratio:.3f}x '
          '(nothing is scheduled, no hook runs)')
    return 0


if __name__ == '__main__':
    raise SystemExit(main())
