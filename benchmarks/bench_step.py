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
Simulation step cost (benchmarks/README.md), measured in one run and printed as ratios.

1. Overhead: ``Driver.step()`` with all Webots logic vs raw PyBullet ``stepSimulation`` of the
   same bodies with the same sub-steps and no Python logic (target <= 1.5x).
2. Real-time factor of one car stepped through ``Driver.step()`` (target >= 20x).
3. Per-car cost with 10 cars in one world relative to one car alone (target <= 1.2x).

Blocks of raw and full steps are interleaved and the median ratio is reported, so that load
from other processes hits both sides alike. Run: ``.venv/bin/python benchmarks/bench_step.py``.
"""

import argparse
import cProfile
import io
import pstats
import statistics
import time

import pybullet

from vehicle_sim.config import load_car
from vehicle_sim.physics import SimulatedCar, World
from vehicle_sim.webots import Car

TARGET_OVERHEAD = 1.5
TARGET_RTF = 20.0
TARGET_TEN_CARS = 1.2


def _time_block(function, count):
    start = time.perf_counter()
    for _ in range(count):
        function()
    return (time.perf_counter() - start) / count


def _driving_car(model='BmwX5'):
    car = Car(model)
    car.setCruisingSpeed(60.0)
    car.setSteeringAngle(0.05)
    car.step(2000)          # past the start transient, wheels turning, ramp active
    return car


def measure_overhead(blocks, steps):
    car = _driving_car()
    world = car.world
    cid = world.client_id

    def raw():
        for _ in range(world.substeps):
            pybullet.stepSimulation(physicsClientId=cid)

    ratios, raw_us, full_us = [], [], []
    for _ in range(blocks):
        raw_s = _time_block(raw, steps)
        full_s = _time_block(car.step, steps)
        ratios.append(full_s / raw_s)
        raw_us.append(raw_s * 1e6)
        full_us.append(full_s * 1e6)
    profile = cProfile.Profile()
    profile.enable()
    _time_block(car.step, steps)
    profile.disable()
    text = io.StringIO()
    pstats.Stats(profile, stream=text).sort_stats('tottime').print_stats(8)
    substeps = world.substeps
    car.close()
    return (statistics.median(ratios), statistics.median(raw_us), statistics.median(full_us),
            substeps, text.getvalue())


def measure_real_time_factor(sim_seconds):
    car = _driving_car()
    steps = int(sim_seconds / (car.getBasicTimeStep() / 1000.0))
    start = time.perf_counter()
    for _ in range(steps):
        car.step()
    wall_s = time.perf_counter() - start
    car.close()
    return sim_seconds / wall_s


def _world_with_cars(count):
    world = World()
    params = load_car('BmwX5')
    cars = [SimulatedCar(world, params, position=(0.0, 8.0 * index, 0.0))
            for index in range(count)]
    for car in cars:
        car.logic.set_cruising_speed_kmh(60.0)
        car.logic.set_steering_angle(0.05)
    for _ in range(200):
        world.step()
    return world


def measure_ten_cars(blocks, steps):
    one = _world_with_cars(1)
    ten = _world_with_cars(10)
    ratios = []
    for _ in range(blocks):
        one_s = _time_block(one.step, steps)
        ten_s = _time_block(ten.step, steps // 4)
        ratios.append(ten_s / 10.0 / one_s)
    one.close()
    ten.close()
    return statistics.median(ratios)


def _verdict(ok):
    return 'meets the target' if ok else 'MISSES the target'


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[1])
    parser.add_argument('--blocks', type=int, default=15)
    parser.add_argument('--steps', type=int, default=400)
    parser.add_argument('--sim-seconds', type=float, default=30.0)
    args = parser.parse_args(argv)

    ratio, raw_us, full_us, substeps, profile = measure_overhead(args.blocks, args.steps)
    rtf = measure_real_time_factor(args.sim_seconds)
    ten = measure_ten_cars(args.blocks, args.steps)

    print('vehicle_sim step benchmark (BmwX5 cruising at 60 km/h, 10 ms basic step, '
          f'{substeps} physics sub-step(s))')
    print(f'  raw PyBullet stepSimulation      : {raw_us:7.1f} us per basic step (median)')
    print(f'  Driver.step() with all logic     : {full_us:7.1f} us per basic step (median)')
    print(f'  overhead ratio (median of {args.blocks} interleaved blocks): {ratio:.2f}x '
          f'(target <= {TARGET_OVERHEAD}x): {_verdict(ratio <= TARGET_OVERHEAD)}')
    print(f'  real-time factor, one car        : {rtf:7.1f}x (target >= {TARGET_RTF}x): '
          f'{_verdict(rtf >= TARGET_RTF)}')
    print(f'  per-car cost, 10 cars / 1 car    : {ten:7.2f}x (target <= {TARGET_TEN_CARS}x): '
          f'{_verdict(ten <= TARGET_TEN_CARS)}')
    if ratio > TARGET_OVERHEAD:
        print(f'  overhead misses its target by {100 * (ratio / TARGET_OVERHEAD - 1):.0f} %; '
              'where the time goes (cProfile, one block):')
        print('\n'.join('    ' + line for line in profile.splitlines() if line.strip()))
    return 0


if __name__ == '__main__':
    raise SystemExit(main())
