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
What drawing a lane map's rules and traffic lights costs (docs/maps.md): bodies, steps, frames.

A world with traffic lights (config/worlds/city_block_signals.yaml by default: five signalised
intersections, a light per approach) is built by the scene builder with and without its lamps
(the ``signal_lamps`` part replaced by one that builds nothing), without traffic; the ego car
without sensors for the steps, with a camera (320 x 240) for the frames. Printed:

- the bodies the rules' drawing adds to the lane layer (one per area kind: all white paint is
  one mesh) and those of the lamps (one per lamp, the housings' and the poles' meshes), and the
  time to build the lamps (their bodies made, as when the world is first drawn);
- a lamp update when no state changed (what every step pays: a dict of states compared), and
  per lamp recoloured when the states change (PyBullet's changeVisualShape);
- ``World.step`` with the lamps over without, interleaved blocks, CPU time (the plan runs:
  states change at their times), the lamps' world drawn once first (``World.prepare_render``:
  a world that nothing draws has no lamp bodies);
- a camera frame with the lamps over without (the renderer draws their spheres and boxes).

Run: ``.venv/bin/python benchmarks/bench_signal_lamps.py [--world NAME] [--quick]``.
"""

import argparse
import copy
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))

from vehicle_sim.config import read_yaml, world_from_data, world_path  # noqa: E402
from vehicle_sim.core.map.lane_rules import SIGNAL_STATES  # noqa: E402
from vehicle_sim.physics import World  # noqa: E402
from vehicle_sim.physics.scene import build_scene, mount_suite  # noqa: E402
from vehicle_sim.physics.signal_lamps import SignalLampsPart  # noqa: E402

CAMERA = {'type': 'camera', 'name': 'camera', 'pose': {'x': 1.5, 'y': 0.0, 'z': 1.3},
          'width': 320, 'height': 240, 'fov': 1.1, 'rate_hz': 1.0}


class NoLamps:
    """The signal_lamps part replaced by one that builds nothing."""

    name = 'signal_lamps'

    def build(self, world, spec):
        return None


def world_spec(name, camera):
    data = copy.deepcopy(read_yaml(world_path(name)))
    data.pop('traffic', None)
    for vehicle in data['vehicles']:
        vehicle['sensors'] = [CAMERA] if camera else []
    return world_from_data(data, f'{name}.yaml')


def _best_us(call, count, repeat=5):
    best = float('inf')
    for _ in range(repeat):
        start = time.perf_counter()
        for _ in range(count):
            call()
        best = min(best, (time.perf_counter() - start) / count)
    return best * 1e6


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[1])
    parser.add_argument('--world', default='city_block_signals')
    parser.add_argument('--quick', action='store_true', help='fewer steps and frames')
    args = parser.parse_args(argv)
    steps, frames = (200, 5) if args.quick else (1000, 20)
    spec = world_spec(args.world, camera=False)
    start = time.perf_counter()
    lit = build_scene(spec)
    build_s = time.perf_counter() - start
    lit.world.prepare_render()      # the lamp bodies are made when the world is first drawn
    dark = build_scene(spec, parts=(NoLamps(),))
    seen = [build_scene(world_spec(args.world, camera=True), mount=mount_suite, parts=parts)
            for parts in ((), (NoLamps(),))]
    try:
        lamps = lit.parts['signal_lamps']
        roads = lit.parts.get('roads') or lit.parts.get('map')
        rules = lit.lanes.rules
        print(f'load average {"/".join(f"{x:.1f}" for x in os.getloadavg())}; world '
              f'{args.world}: {len(rules.groups)} groups, {len(lamps.lamps)} lamps, '
              f'{len(lamps.poles)} poles, {len(rules.stop_lines)} stop lines, '
              f'{len(rules.areas)} areas')
        with World() as alone:
            start = time.perf_counter()
            part = SignalLampsPart(lamps.controller).build(alone, lit.spec)  # the lamps alone
            part.make_lamp_bodies()     # (made when first drawn)
            lamps_build_ms = (time.perf_counter() - start) * 1e3
        print('| figure | value |\n|---|---|')
        print(f'| lane layer bodies (surface, areas, paint) | {len(roads.visual_ids)} |')
        print(f'| lamp bodies (lamps, housings, poles) | {lamps.visual_shape_count} |')
        print(f'| building the lamps [ms] | {lamps_build_ms:.1f} (the whole scene '
              f'{build_s * 1e3:.0f} ms) |')
        print(f'| lamp update, no state changed [us] | {_best_us(lamps.refresh, 20000):.2f} |')
        controller = lamps.controller
        groups = [group.id for group in rules.groups if group.bulbs]
        spent, changed = float('inf'), 0
        for turn in range(30):
            for group in groups:
                controller.force(group, SIGNAL_STATES[turn % 3])
            begin = time.perf_counter()
            changed = lamps.refresh()
            spent = min(spent, time.perf_counter() - begin)
        print(f'| recolouring, per lamp changed [us] | {spent * 1e6 / max(changed, 1):.2f} '
              f'(every group changed: {changed} lamps) |')
        controller.release()
        ratios, step_us = [], []
        for _ in range(15):
            times = []
            for scene in (lit, dark):
                begin = time.process_time()
                for _ in range(steps // 5):
                    scene.world.step()
                times.append(time.process_time() - begin)
            ratios.append(times[0] / times[1])
            step_us.append([t / (steps // 5) * 1e6 for t in times])
        ratios.sort()
        with_us, without_us = (sorted(t[k] for t in step_us)[7] for k in (0, 1))
        print(f'| World.step with lamps / without (CPU time, median of 15 blocks; the car, no '
              f'sensors: {with_us:.0f} us / {without_us:.0f} us) | {ratios[7]:.3f} |')
        frame_ratio = []
        for _ in range(frames):
            times = []
            for scene in seen:
                camera = scene.vehicles[next(iter(scene.vehicles))].sensors
                begin = time.perf_counter()
                camera.sample('camera')
                times.append(time.perf_counter() - begin)
            frame_ratio.append(times[0] / times[1])
        frame_ratio.sort()
        print(f'| camera frame 320 x 240 with lamps / without (median) | '
              f'{frame_ratio[len(frame_ratio) // 2]:.3f} |')
    finally:
        for scene in [lit, dark] + seen:
            scene.world.close()


if __name__ == '__main__':
    main()
