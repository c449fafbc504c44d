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
Traffic cost (docs/traffic.md): real-time factor in process with 0, 10, 50 and 200 traffic cars.

The shipped highway (config/worlds/highway.yaml) with its ego car (ToyotaPrius, cruising at
90 km/h, no sensors mounted) and N traffic cars (``traffic: {vehicles: N}``, seeded), built by
the scene builder and stepped with ``World.step`` (10 ms steps; traffic updated every 100 ms):
simulated seconds / wall seconds, best of ``repeats`` runs (targets: >= 100x with 50 cars,
>= 30x with 200). The core manager alone (no physics) is printed beside it.

Side by side, in the same run: highway-env's ``highway-fast-v0`` (IDM and MOBIL traffic on a
straight 4-lane road) with the same car count, stepped with the idle action: its simulation
steps per second (``simulation_frequency`` steps of 1/f s per policy step) against ours, and
both as simulated seconds per wall second. highway-env is a benchmark-only optional dependency
(``pip install 'vehicle_sim[bench]'``); without it that part is skipped with a printed line.

Run: ``.venv/bin/python benchmarks/bench_traffic.py [--quick]``.
"""

import argparse
import copy
import time

from vehicle_sim.config import read_yaml, world_from_data, world_path
from vehicle_sim.core.map.road_segments import lane_graph_from_roads
from vehicle_sim.core.traffic.manager import TrafficManager
from vehicle_sim.physics.scene import build_scene
from vehicle_sim.physics.traffic_bodies import model_dimensions

COUNTS = (0, 10, 50, 200)
TARGETS = {50: 100.0, 200: 30.0}
TARGET_HIGHWAY_ENV_RATIO = 10.0


def highway_spec(count, seed=1):
    data = copy.deepcopy(read_yaml(world_path('highway')))
    if count:
        data['traffic'] = {'vehicles': count, 'seed': seed,
                           'models': ['ToyotaPrius', 'BmwX5', 'TeslaModel3'],
                           'speed_factor': {'mean': 0.85, 'std': 0.1}}
    return world_from_data(data, 'highway.yaml')


def real_time_factor(count, sim_seconds, repeats=3):
    """Return (RTF, steps per second) of the highway with ``count`` traffic cars."""
    best = 0.0
    for _ in range(repeats):
        scene = build_scene(highway_spec(count))
        try:
            car = scene.vehicles['Car'].car
            car.logic.set_cruising_speed_kmh(90.0)
            world = scene.world
            steps = int(round(sim_seconds / world.time_step_s))
            for _ in range(50):                  # settle: not timed
                world.step()
            start = time.perf_counter()
            for _ in range(steps):
                world.step()
            wall = time.perf_counter() - start
            best = max(best, steps * world.time_step_s / wall)
        finally:
            scene.world.close()
    return best, best / 0.01


def manager_only(count, sim_seconds, dt=0.1):
    """Return the real-time factor of the core TrafficManager alone (no physics)."""
    spec = highway_spec(count)
    graph = lane_graph_from_roads(spec.roads)
    sizes = {m: model_dimensions(m)[:2] for m in spec.traffic.all_models}
    manager = TrafficManager(graph, spec.traffic, sizes)
    steps = int(round(sim_seconds / dt))
    start = time.perf_counter()
    for _ in range(steps):
        manager.step(dt)
    return steps * dt / (time.perf_counter() - start)


def highway_env_figures(count, policy_steps):
    """
    Return (simulation steps/s, simulated s per wall s) of highway-fast-v0, or None.

    None when highway-env is not installed (printed).
    """
    try:
        import gymnasium
        import highway_env  # noqa: F401  (registers the environments)
    except ImportError:
        print("highway-env: not installed, its side is skipped "
              "(pip install 'vehicle_sim[bench]')")
        return None
    env = gymnasium.make('highway-fast-v0')
    env.unwrapped.configure({'vehicles_count': count, 'duration': 10 ** 6})
    env.reset(seed=0)
    config = env.unwrapped.config
    per_policy = config['simulation_frequency'] // config['policy_frequency']
    idle = 1                                   # DiscreteMetaAction: IDLE
    start = time.perf_counter()
    done = 0
    for _ in range(policy_steps):
        _, _, terminated, truncated, _ = env.step(idle)
        done += 1
        if terminated or truncated:
            env.reset(seed=done)
    wall = time.perf_counter() - start
    env.close()
    sim_steps = done * per_policy
    return sim_steps / wall, done / config['policy_frequency'] / wall


def figures(quick=False):
    """Return {count: (RTF, steps/s)}, {count: core RTF}, highway-env's figures (or None)."""
    seconds = 5.0 if quick else 20.0
    ours = {n: real_time_factor(n, seconds, 1 if quick else 3) for n in COUNTS}
    core = {n: manager_only(n, seconds) for n in COUNTS if n}
    theirs = highway_env_figures(50, 50 if quick else 200)
    return ours, core, theirs


def _verdict(ok):
    return 'met' if ok else 'MISSED'


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[1])
    parser.add_argument('--quick', action='store_true', help='shorter runs')
    args = parser.parse_args(argv)
    ours, core, theirs = figures(args.quick)
    for n in COUNTS:
        rtf, steps = ours[n]
        target = TARGETS.get(n)
        verdict = f' (target >= {target:g}x: {_verdict(rtf >= target)})' if target else ''
        extra = f'; core manager alone {core[n]:.0f}x' if n else ''
        print(f'highway, {n:3d} traffic cars: {rtf:7.1f}x real time, {steps:8.0f} steps/s'
              f'{verdict}{extra}')
    if theirs is not None:
        their_steps, their_rtf = theirs
        ratio = ours[50][1] / their_steps
        print(f'highway-env highway-fast-v0, 50 vehicles: {their_steps:.0f} simulation steps/s '
              f'({their_rtf:.1f}x real time); ours with 50: {ours[50][1]:.0f} steps/s = '
              f'{ratio:.1f}x theirs (target >= {TARGET_HIGHWAY_ENV_RATIO:g}x: '
              f'{_verdict(ratio >= TARGET_HIGHWAY_ENV_RATIO)}); simulated time per wall time: '
              f'{ours[50][0] / their_rtf:.1f}x theirs')


if __name__ == '__main__':
    main()
