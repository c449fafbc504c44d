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
Radar cost (docs/sensors.md, "radar"): microseconds per reading with 60 traffic cars around.

The shipped highway (config/worlds/highway.yaml) with 60 traffic cars (seeded) and a radar on
the ego car that sees all around (horizontal fov 2 pi, vertical 0.5 rad, 200 m): the world is
stepped (10 ms steps, traffic updated every 100 ms) and the radar read after each step; only
the readings are timed (their mean, best of 3 runs). Target: <= 50 us per reading.

Run: ``.venv/bin/python benchmarks/bench_radar.py [--quick]``.
"""

import argparse
import time

from bench_traffic import highway_spec

from vehicle_sim.core.sensors.params import sensor_from_dict
from vehicle_sim.physics.scene import build_scene
from vehicle_sim.physics.sensors import SensorSuite

TARGET_US = 50.0
RADAR = {'type': 'radar', 'name': 'radar', 'pose': {'x': 2.0, 'z': 0.6},
         'horizontal_fov': 6.283, 'vertical_fov': 0.5, 'max_range': 200.0}


def per_reading_us(count=60, steps=500, repeats=3):
    """Return (mean us per reading, mean targets per reading), best of ``repeats`` runs."""
    best = (float('inf'), 0.0)
    for _ in range(repeats):
        scene = build_scene(highway_spec(count))
        try:
            car = scene.vehicles['Car'].car
            car.logic.set_cruising_speed_kmh(90.0)
            suite = SensorSuite(scene.world, car.body, [sensor_from_dict(RADAR, 'bench')])
            radar = suite.sensors['radar']
            world = scene.world
            for _ in range(50):
                world.step()
            wall, targets = 0.0, 0
            for _ in range(steps):
                world.step()
                start = time.perf_counter()
                reading = radar.sample(world.time_s)
                wall += time.perf_counter() - start
                targets += len(reading.targets)
            best = min(best, (wall / steps * 1e6, targets / steps))
        finally:
            scene.world.close()
    return best


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[1])
    parser.add_argument('--quick', action='store_true')
    args = parser.parse_args()
    us, targets = per_reading_us(steps=200 if args.quick else 500,
                                 repeats=1 if args.quick else 3)
    print(f'radar with 60 traffic cars: {us:.1f} us per reading ({targets:.1f} targets a '
          f'reading; target <= {TARGET_US:g} us)')


if __name__ == '__main__':
    main()
