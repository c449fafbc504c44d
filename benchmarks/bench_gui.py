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
PyBullet's window with traffic: how long a GUI world takes to start, and what a step costs.

Needs an X display; without one, run it under a virtual one (Debian/Ubuntu package xvfb)::

    xvfb-run -a -s '-screen 0 1280x1024x24' .venv/bin/python benchmarks/bench_gui.py

Xvfb draws with Mesa's software renderer (llvmpipe), as a machine without a GPU does. Each
figure comes from a fresh process (PyBullet allows one window per process):

- start: ``World(gui=True)`` (the window opens), ``build_scene`` of the world file, then its
  first 20 steps (the first frames draw the whole scene), for ``highway`` and
  ``highway_traffic`` (the same road with 50 traffic cars). ``--compare-build`` builds
  ``highway_traffic`` once more with the window drawing while the bodies are added (as before
  the scene builder paused its rendering): minutes under a software renderer, so not by default.
- step: ``highway_traffic`` in the window, interleaved blocks of 30 steps with the traffic boxes
  placed for the window once a frame (``gui.FRAME_PERIOD_S`` of simulated time, the default)
  and after every step; wall and CPU time (all of the process's threads: the window draws in
  its own) per step, median of the blocks; the real-time factor is 10 ms over the wall time.

Wall times move with the machine's load (benchmarks/README.md); run it on a quiet machine.
Run: ``.venv/bin/python benchmarks/bench_gui.py [--blocks N] [--compare-build]``.
"""

import argparse
from contextlib import nullcontext
import json
import os
import statistics
import subprocess
import sys
import time

BLOCK_STEPS = 30
FIRST_STEPS = 20


def _start(world_name, rendering):
    from vehicle_sim.config import load_world
    from vehicle_sim.physics.scene import build_scene
    from vehicle_sim.physics.world import World
    if rendering == 'on':       # the window draws while bodies are added
        World.rendering_paused = lambda self: nullcontext()
    spec = load_world(world_name, 'ToyotaPrius')
    start = time.perf_counter()
    world = World(gui=True)
    opened = time.perf_counter()
    build_scene(spec, world=world)
    built = time.perf_counter()
    for _ in range(FIRST_STEPS):
        world.step()
    stepped = time.perf_counter()
    world.close()
    return {'open_s': opened - start, 'build_s': built - opened,
            'first_steps_s': stepped - built}


def _steps(blocks):
    from vehicle_sim.config import load_world
    from vehicle_sim.physics import traffic_bodies
    from vehicle_sim.physics.gui import FRAME_PERIOD_S
    from vehicle_sim.physics.scene import build_scene
    scene = build_scene(load_world('highway_traffic', 'ToyotaPrius'), gui=True)
    world = scene.world
    scene.vehicles['Car'].car.logic.set_cruising_speed_kmh(90.0)
    for _ in range(FIRST_STEPS):
        world.step()
    periods = {'once a frame': FRAME_PERIOD_S, 'every step': 0.0}
    times = {name: ([], []) for name in periods}
    for _ in range(blocks):
        for name, period in periods.items():
            traffic_bodies.FRAME_PERIOD_S = period
            wall, cpu = time.perf_counter(), time.process_time()
            for _ in range(BLOCK_STEPS):
                world.step()
            times[name][0].append((time.perf_counter() - wall) / BLOCK_STEPS)
            times[name][1].append((time.process_time() - cpu) / BLOCK_STEPS)
    world.close()
    return {name: {'wall_ms': 1000.0 * statistics.median(w),
                   'cpu_ms': 1000.0 * statistics.median(c),
                   'rtf': world.time_step_s / statistics.median(w)}
            for name, (w, c) in times.items()}


def _in_process(*args):
    # One measurement in a fresh process (one window each); its last line is the JSON.
    result = subprocess.run([sys.executable, __file__, '--one', *args], capture_output=True,
                            text=True, timeout=3600)
    if result.returncode != 0:
        raise RuntimeError(f'{args}: exit {result.returncode}: {result.stderr[-2000:]}')
    return json.loads(result.stdout.strip().splitlines()[-1])


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--blocks', type=int, default=10, help='blocks of 30 steps per side')
    parser.add_argument('--compare-build', action='store_true',
                        help='also build highway_traffic with the window drawing (slow)')
    parser.add_argument('--one', nargs='+', help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.one:
        kind, *rest = args.one
        out = _start(*rest) if kind == 'start' else _steps(int(rest[0]))
        print(json.dumps(out))
        return 0
    from vehicle_sim.physics.gui import gui_unavailable_reason
    reason = gui_unavailable_reason()
    if reason is not None:
        print(f'bench_gui: skipped: {reason}')
        return 0
    print(f'load average {os.getloadavg()[0]:.1f}')
    cases = [('highway', 'paused'), ('highway_traffic', 'paused')]
    if args.compare_build:
        cases.append(('highway_traffic', 'on'))
    starts = {}
    for world_name, rendering in cases:
        starts[world_name, rendering] = s = _in_process('start', world_name, rendering)
        print(f'start {world_name:16s} rendering {rendering:6s} during the build: window '
              f'{s["open_s"]:6.2f} s, build {s["build_s"]:7.2f} s, first {FIRST_STEPS} steps '
              f'{s["first_steps_s"]:6.2f} s', flush=True)
    if args.compare_build:
        on, off = starts['highway_traffic', 'on'], starts['highway_traffic', 'paused']
        print(f'build with the window drawing / paused: {on["build_s"] / off["build_s"]:.1f}x')
    steps = _in_process('steps', str(args.blocks))
    for name, s in steps.items():
        print(f'step highway_traffic in the window, boxes placed {name:12s}: wall '
              f'{s["wall_ms"]:6.1f} ms, CPU {s["cpu_ms"]:6.1f} ms, real-time factor '
              f'{s["rtf"]:.3f}')
    print(f'load average {os.getloadavg()[0]:.1f}')
    return 0


if __name__ == '__main__':
    sys.exit(main())
