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
SUMO-driven worlds in the Gymnasium vector environments: how worlds in one process share SUMO.

libsumo runs one SUMO per process, so in ``DriveVectorEnv`` (every world in this process) the
first world's SUMO is libsumo's and every other world's a sumo process over TraCI;
``AsyncVectorEnv`` runs each world in a process of its own, each with libsumo. Figures, in env
steps per second of all worlds (one env step = 0.1 s: action_repeat 10, one SUMO step), on a
netgenerate 4 x 4 signalised grid (two lanes each way, sidewalks, crossings) with 1200 vehicles
and 300 pedestrians an hour and a 120 s warmup (some 45 vehicles and 10 persons on the map):

1. one environment (libsumo), and the same with ``transport: traci`` (TraCI's cost) and with
   ``transport: worker`` (libsumo in a process of its own, stepping while the world runs);
2. ``DriveVectorEnv`` of N worlds (1 libsumo + N - 1 TraCI), and of N worlds each with a worker;
3. ``AsyncVectorEnv`` of N processes (N libsumo);
4. a reset (SUMO started again and warmed up; the demand's trips from the cache).

Run: ``.venv/bin/python benchmarks/bench_sumo_vector.py [--quick] [--worlds N]``.
"""

import argparse
import os
import subprocess
import sys
import tempfile
import time
import warnings

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))

ENV_ID = 'vehicle_sim/Drive-v0'
GRID = ('--grid', '--grid.number', '4', '--grid.length', '100', '--default.lanenumber', '2',
        '--tls.guess', '--sidewalks.guess', '--crossings.guess')


def _gym():
    import gymnasium

    import vehicle_sim.gym  # noqa: F401  (registers the id)
    warnings.filterwarnings('ignore', module='gymnasium')
    return gymnasium


def make_world(folder, transport='auto'):
    """Write the grid network and a world on it into ``folder``; return the world's path."""
    import sumo
    import yaml
    net = os.path.join(folder, 'grid.net.xml')
    if not os.path.exists(net):
        subprocess.run([os.path.join(sumo.SUMO_HOME, 'bin', 'netgenerate'), *GRID, '-o', net],
                       check=True, capture_output=True)
    world = {'vehicles': [{'name': 'ego', 'model': 'Car',
                           'pose': {'x': 4.8, 'y': 30.0, 'yaw': 1.5708}}],
             'map': {'type': 'sumo', 'net': 'grid.net.xml'},
             'traffic': {'engine': 'sumo', 'transport': transport, 'warmup': 120.0, 'seed': 1,
                         'demand': {'vehicles_per_hour': 1200, 'pedestrians_per_hour': 300,
                                    'seed': 1}}}
    path = os.path.join(folder, f'sumo_grid_{transport}.yaml')
    with open(path, 'w', encoding='utf-8') as handle:
        yaml.safe_dump(world, handle)
    return path


OPTIONS = {'action_repeat': 10, 'max_episode_s': 1.0e6, 'terminate_on_collision': False}


def _actions(space, count=64):
    space.seed(0)
    return [space.sample() * 0.2 for _ in range(count)]


def single_rate(world, steps):
    """Return env steps/s of one environment and its agents' count at the end."""
    env = _gym().make(ENV_ID, world=world, **OPTIONS)
    try:
        env.reset(seed=0)
        actions = _actions(env.action_space)
        start = time.perf_counter()
        for i in range(steps):
            env.step(actions[i % len(actions)])
        rate = steps / (time.perf_counter() - start)
        return rate, len(env.unwrapped.sim.scene.parts['traffic'].agents())
    finally:
        env.close()


def _vector_rate(env, steps):
    n = env.num_envs
    actions = [np.stack([a] * n) for a in _actions(env.single_action_space)]
    env.reset(seed=list(range(n)))
    env.step(actions[0])
    start = time.perf_counter()
    for i in range(steps):
        env.step(actions[i % len(actions)])
    return steps * n / (time.perf_counter() - start)


def in_process_rate(world, steps, worlds):
    """Return env steps/s of all worlds of DriveVectorEnv, and each world's transport."""
    from vehicle_sim.gym import DriveVectorEnv
    _gym()
    env = DriveVectorEnv(worlds, world=world, **OPTIONS)
    try:
        transports = [sim.scene.parts['traffic'].session.transport for sim in env.sims]
        return _vector_rate(env, steps), transports
    finally:
        env.close()


def async_rate(world, steps, worlds):
    """Return env steps/s of all worlds of AsyncVectorEnv (a process per world)."""
    gymnasium = _gym()

    def factory():
        import gymnasium as gym

        import vehicle_sim.gym  # noqa: F401
        return gym.make(ENV_ID, world=world, **OPTIONS)

    env = gymnasium.vector.AsyncVectorEnv([factory] * worlds)
    try:
        return _vector_rate(env, steps)
    finally:
        env.close()


def reset_s(world, count):
    """Return the seconds of a reset (SUMO started again and warmed up)."""
    env = _gym().make(ENV_ID, world=world, **OPTIONS)
    try:
        env.reset(seed=0)
        start = time.perf_counter()
        for _ in range(count):
            env.reset()
        return (time.perf_counter() - start) / count
    finally:
        env.close()


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[1])
    parser.add_argument('--quick', action='store_true', help='fewer steps')
    parser.add_argument('--worlds', type=int, default=4, help='worlds of the vector envs')
    args = parser.parse_args(argv)
    steps = 100 if args.quick else 400
    with tempfile.TemporaryDirectory() as folder:
        os.environ.setdefault('XDG_CACHE_HOME', os.path.join(folder, 'cache'))
        world = make_world(folder)
        traci_world = make_world(folder, 'traci')
        single, agents = single_rate(world, steps)
        print(f'load average {os.getloadavg()[0]:.1f}; {agents} SUMO vehicles and persons '
              'in the world')
        print(f'one env (libsumo):              {single:7.0f} env steps/s')
        single_traci, _ = single_rate(traci_world, steps)
        print(f'one env (transport: traci):     {single_traci:7.0f} env steps/s '
              f'({single_traci / single:.2f}x)')
        worker_world = make_world(folder, 'worker')
        single_worker, _ = single_rate(worker_world, steps)
        print(f'one env (transport: worker):    {single_worker:7.0f} env steps/s '
              f'({single_worker / single:.2f}x)')
        vector, transports = in_process_rate(world, steps // 2, args.worlds)
        print(f'DriveVectorEnv of {args.worlds} ({transports.count("libsumo")} libsumo + '
              f'{transports.count("traci")} traci): {vector:7.0f} env steps/s of all '
              f'({vector / single:.2f}x one env)')
        vector, transports = in_process_rate(worker_world, steps // 2, args.worlds)
        print(f'DriveVectorEnv of {args.worlds} ({transports.count("worker")} workers): '
              f'{vector:7.0f} env steps/s of all ({vector / single:.2f}x one env)')
        asynchronous = async_rate(world, steps // 2, args.worlds)
        print(f'AsyncVectorEnv of {args.worlds} processes (libsumo each): {asynchronous:7.0f} '
              f'env steps/s of all ({asynchronous / single:.2f}x one env)')
        reset = reset_s(world, 3 if args.quick else 5)
        print(f'a reset (SUMO again, 120 s warmup): {reset:.2f} s')


if __name__ == '__main__':
    main()
