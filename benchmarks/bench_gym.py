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
Speed of the Gymnasium environment (docs/gym.md), with highway-env's beside it.

Figures, each in env steps per second (one step = one action, action_repeat 1, 10 ms):

1. one ``vehicle_sim/Drive-v0`` (``gymnasium.make``, world obstacle_course, a car), state
   observations only (target >= 3000/s), and with a 1080-ray lidar (target >= 500/s); and on
   the highway world (3 + 3 lanes, 2.33 km) with its lane observations, lane progress and lane
   penalty (target >= 3000/s, as state-only; the ratio to the state-only figure beside);
2. the in-process vector environment with 1, 8 and 32 worlds: its steps of all worlds per
   CPU second of this process over the single environment's, short blocks of the two
   interleaved, every world taking the lone environment's actions and stepping as often in
   each block, in a world without episode ends (target >= 0.9x: a world in the vector costs
   no more than a lone environment); wall-clock rates printed beside; and with 8 and 32
   worlds, the vector env over the same worlds held as Gymnasium's SyncVectorEnv of lone
   environments (no target);
3. Gymnasium's AsyncVectorEnv with 2 processes (steps of both per second);
4. creating an environment (16 in a row, each with its own physics client; target <= 0.2 s),
   and a reset;
5. highway-env's ``highway-fast-v0`` and ``racetrack-v0`` (if the package is installed:
   ``pip install 'vehicle_sim[bench]'``; skipped with a line otherwise).

Every environment takes the same fixed sequence of random actions (seeded) and is reset when its
episode ends, so resets count in the figures as in training. Run:
``.venv/bin/python benchmarks/bench_gym.py [--quick] [--profile]`` (``--profile``: the top
functions of a single environment's steps, to see where the time goes).
"""

import argparse
import cProfile
import io
import os
import pstats
import statistics
import sys
import time
import warnings

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))

TARGET_STATE = 3000.0
TARGET_LIDAR = 500.0
TARGET_VECTOR = 0.9
TARGET_CREATE_S = 0.2
ENV_ID = 'vehicle_sim/Drive-v0'
# The vector ratio's world: the default world (one car, nothing to hit), no time limit.
RATIO_WORLD = {'world': 'default', 'max_episode_s': 1.0e6}


def _gym():
    import gymnasium

    import vehicle_sim.gym  # noqa: F401  (registers the id)
    warnings.filterwarnings('ignore', module='gymnasium')
    return gymnasium


def _actions(space, count=256, seed=0):
    space.seed(seed)
    return [space.sample() for _ in range(count)]


class _Runner:
    """Steps one environment (reset at episode ends) with a fixed action sequence."""

    def __init__(self, env):
        self.env = env
        self.actions = _actions(env.action_space)
        self.index = 0
        env.reset(seed=0)

    def block(self, steps):
        env, actions = self.env, self.actions
        start = time.perf_counter()
        for _ in range(steps):
            _, _, terminated, truncated, _ = env.step(actions[self.index % len(actions)])
            self.index += 1
            if terminated or truncated:
                env.reset()
        return steps / (time.perf_counter() - start)


class _VectorRunner:
    """
    Steps a vector environment (autoreset) with the single environment's action sequence.

    Every world takes the lone environment's actions: the same episodes and the same resets
    (a reset costs as much as some 30 steps), so the two sides do the same work and the ratio
    is the cost of a world in the vector over a lone one.
    """

    def __init__(self, env):
        self.env = env
        n = env.num_envs
        self.actions = [np.stack([action] * n) for action in _actions(env.single_action_space)]
        self.index = 0
        env.reset(seed=[0] * n)

    def block(self, steps):
        env, actions = self.env, self.actions
        start = time.perf_counter()
        for _ in range(steps):
            env.step(actions[self.index % len(actions)])
            self.index += 1
        return steps * env.num_envs / (time.perf_counter() - start)


def single_rate(blocks, steps, **options):
    """Return the median steps/s of one environment over ``blocks`` blocks."""
    gymnasium = _gym()
    env = gymnasium.make(ENV_ID, **options)
    try:
        runner = _Runner(env)
        runner.block(50)        # warm up
        return statistics.median(runner.block(steps) for _ in range(blocks))
    finally:
        env.close()


def lane_ratio(blocks, steps):
    """
    Return (with lanes, without, ratio) of the highway world and the same car without roads.

    The highway world's steps/s over the same car on a world without its roads (no lane map:
    no lane observation, tracker or lane reward), short blocks of the two interleaved, so that
    the ratio is the lanes' cost.
    """
    gymnasium = _gym()
    bare = {'vehicles': [{'name': 'Car', 'model': 'ToyotaPrius',
                          'pose': {'x': 20.0, 'y': -5.625, 'yaw': 0.0}}]}
    envs = [gymnasium.make(ENV_ID, world='highway'), gymnasium.make(ENV_ID, world=bare)]
    try:
        runners = [_Runner(env) for env in envs]
        for runner in runners:
            runner.block(50)
        rates = [[], []]
        for _ in range(blocks):
            for rate, runner in zip(rates, runners):
                rate.append(runner.block(steps))
        ratio = statistics.median(a / b for a, b in zip(*rates))
        return statistics.median(rates[0]), statistics.median(rates[1]), ratio
    finally:
        for env in envs:
            env.close()


def _cpu_block(runner, steps):
    # (world steps, CPU seconds of this process): CPU time moves much less than wall time
    # with other people's processes on the machine's cores.
    start = time.process_time()
    rate = runner.block(steps)
    cpu_s = time.process_time() - start
    worlds = getattr(runner.env, 'num_envs', 1)
    return steps * worlds, cpu_s, rate


def _interleaved(first, first_steps, second, second_steps, blocks):
    """Return (median wall rate of each, first's world steps per CPU second ÷ second's)."""
    totals = {'first': [0, 0.0, []], 'second': [0, 0.0, []]}
    for _ in range(blocks):
        for key, runner, count in (('first', first, first_steps),
                                   ('second', second, second_steps)):
            done, cpu_s, rate = _cpu_block(runner, count)
            totals[key][0] += done
            totals[key][1] += cpu_s
            totals[key][2].append(rate)
    per_cpu = {key: done / cpu_s for key, (done, cpu_s, _) in totals.items()}
    return statistics.median(totals['first'][2]), statistics.median(totals['second'][2]), \
        per_cpu['first'] / per_cpu['second']


def vector_ratio(num_envs, blocks, steps):
    """
    Return (vector world steps/s, single steps/s, ratio) from interleaved blocks.

    Each block steps both sides ``steps`` times (the vector: ``steps`` steps of all its
    worlds), so that every world of the vector and the lone environment drive the same stretch
    of the same trajectory in each block: a step's cost depends on where the car is in it (the
    first 500 steps from rest cost up to 1.4 times the later ones), and blocks of ``steps /
    num_envs`` vector steps kept the vector's worlds in that dearer start while the lone
    environment drove on. The ratio is that of the world steps per CPU second of this process,
    summed over the blocks; the rates are the median wall-clock ones. Both sides drive in
    RATIO_WORLD, where no episode ends during the blocks: resets run the same code on both
    sides, but the vector's worlds (all taking the same actions) would end together, a burst
    that short blocks sample unevenly.
    """
    gymnasium = _gym()
    return _vector_over(num_envs, gymnasium.make(ENV_ID, **RATIO_WORLD), _Runner, blocks, steps)


def sync_ratio(num_envs, blocks, steps):
    """
    Return (vector world steps/s, SyncVectorEnv world steps/s, ratio) from interleaved blocks.

    The same N worlds held in this process the way Gymnasium does it without a native vector
    env: ``SyncVectorEnv`` of N ``gymnasium.make`` environments, stepped one after another.
    Both pay for N worlds sharing one core's cache; the ratio (world steps per CPU second, as
    :func:`vector_ratio`) is what the native vector env itself costs or saves.
    """
    gymnasium = _gym()
    sync = gymnasium.vector.SyncVectorEnv(
        [lambda: gymnasium.make(ENV_ID, **RATIO_WORLD) for _ in range(num_envs)])
    return _vector_over(num_envs, sync, _VectorRunner, blocks, steps)


def _vector_over(num_envs, other, runner, blocks, steps):
    """_interleaved() of DriveVectorEnv(num_envs) and ``other`` (stepped by ``runner``)."""
    from vehicle_sim.gym import DriveVectorEnv
    try:
        vector = DriveVectorEnv(num_envs, **RATIO_WORLD)
    except BaseException:
        other.close()
        raise
    try:
        return _interleaved(_VectorRunner(vector), steps, runner(other), steps, blocks)
    finally:
        other.close()
        vector.close()


def async_rate(steps, processes=2):
    """Return steps/s (all worlds) of Gymnasium's AsyncVectorEnv with ``processes`` workers."""
    gymnasium = _gym()

    def factory():
        import gymnasium as gym

        import vehicle_sim.gym  # noqa: F401
        return gym.make(ENV_ID)

    env = gymnasium.vector.AsyncVectorEnv([factory] * processes)
    try:
        runner = _VectorRunner(env)
        runner.block(50)
        return runner.block(steps)
    finally:
        env.close()


def creation_s(count=16):
    """Return (seconds per environment made by gymnasium.make, per world of a vector env)."""
    gymnasium = _gym()
    from vehicle_sim.gym import DriveVectorEnv
    start = time.perf_counter()
    envs = [gymnasium.make(ENV_ID) for _ in range(count)]
    each = (time.perf_counter() - start) / count
    for env in envs:
        env.close()
    start = time.perf_counter()
    vector = DriveVectorEnv(count)
    per_world = (time.perf_counter() - start) / count
    vector.close()
    return each, per_world


def reset_ms(count=100, **kwargs):
    """Return the milliseconds of one reset (in place: every body reloaded, same client)."""
    gymnasium = _gym()
    env = gymnasium.make(ENV_ID, **(kwargs or {'lidar': True}))
    try:
        env.reset(seed=0)
        start = time.perf_counter()
        for seed in range(count):
            env.reset(seed=seed)
        return (time.perf_counter() - start) / count * 1000.0
    finally:
        env.close()


def highway_rates(seconds):
    """Return {id: steps/s} of highway-env's environments, or None without the package."""
    try:
        import highway_env  # noqa: F401
    except ImportError:
        return None
    gymnasium = _gym()
    rates = {}
    for env_id in ('highway-fast-v0', 'racetrack-v0'):
        env = gymnasium.make(env_id)
        try:
            runner = _Runner(env)
            runner.block(5)
            steps, start = 0, time.perf_counter()
            while time.perf_counter() - start < seconds:
                runner.block(10)
                steps += 10
            rates[env_id] = steps / (time.perf_counter() - start)
        finally:
            env.close()
    return rates


def profile_text(steps=2000, top=15, **options):
    """Return the top functions (internal time) of a single environment's steps."""
    gymnasium = _gym()
    env = gymnasium.make(ENV_ID, **options)
    try:
        runner = _Runner(env)
        profiler = cProfile.Profile()
        profiler.enable()
        runner.block(steps)
        profiler.disable()
    finally:
        env.close()
    out = io.StringIO()
    pstats.Stats(profiler, stream=out).sort_stats('tottime').print_stats(top)
    return out.getvalue()


def figures(quick=False):
    """Run every measurement; return (rows, context lines) in run_all.py's row form."""
    blocks = 3 if quick else 7
    steps = 400 if quick else 1000
    vector_blocks = 6 if quick else 20
    vector_steps = 50 if quick else 100     # per block, on each side (vector_ratio)
    state = single_rate(blocks, steps)
    lidar = single_rate(blocks, max(100, steps // 4), lidar=True)
    lanes = single_rate(blocks, steps, world='highway')
    laned, bare, lane_cost = lane_ratio(2 * blocks, max(200, steps // 2))
    # One world: three times the blocks (they are short, and its ratio sits near the target,
    # where the run-to-run spread of 20 blocks, about ±0.015, decides what is printed).
    vectors = {n: vector_ratio(n, vector_blocks * (3 if n == 1 else 1), vector_steps)
               for n in (1, 8, 32)}
    syncs = {n: sync_ratio(n, vector_blocks // 2, vector_steps) for n in (8, 32)}
    asynchronous = async_rate(200 if quick else 1000)
    each_s, per_world_s = creation_s()
    reset = reset_ms(30 if quick else 100)
    traffic_reset = reset_ms(30 if quick else 100, world='highway_traffic')
    highway = highway_rates(2.0 if quick else 5.0)
    rows = [
        ('gym: one Drive-v0, state observations (obstacle_course car)', state, '>=',
         TARGET_STATE, 'steps/s'),
        ('gym: one Drive-v0 with a 1080-ray lidar', lidar, '>=', TARGET_LIDAR, 'steps/s'),
        ('gym: one Drive-v0, highway world with lane observations', lanes, '>=',
         TARGET_STATE, 'steps/s'),
    ]
    for n, (many, lone, ratio) in vectors.items():
        rows.append((f'gym: vector env of {n} worlds in one process / one env, steps/s', ratio,
                     '>=', TARGET_VECTOR, 'x'))
    rows.append(('gym: creating one Drive-v0 (gymnasium.make, 16 in a row)', each_s, '<=',
                 TARGET_CREATE_S, 's'))
    context = [f'gym: highway with lanes {lanes:.0f} steps/s beside state-only obstacle_course '
               f'{state:.0f} steps/s: {lanes / state:.2f}x; interleaved with the same car on '
               f'a world without roads: {laned:.0f} / {bare:.0f} steps/s = {lane_cost:.2f}x']
    context += [f'gym: vector env of {n} worlds: {many:.0f} world steps/s ({many / n:.0f} per '
               f'world), one env alone in the same blocks {lone:.0f} steps/s'
               for n, (many, lone, _) in vectors.items()]
    context += [f'gym: the same {n} worlds as a SyncVectorEnv of {n} gymnasium.make '
                f'environments: {standard:.0f} world steps/s; the vector env {many:.0f}: '
                f'{ratio:.2f}x per CPU second' for n, (many, standard, ratio) in syncs.items()]
    context.append(f'gym: AsyncVectorEnv, 2 processes: {asynchronous:.0f} steps/s of both')
    context.append(f'gym: a world of DriveVectorEnv(16): {per_world_s * 1000:.1f} ms to create; '
                   f"a reset (with the lidar's first scan) {reset:.1f} ms; in "
                   f'highway_traffic (its 60 traffic vehicles started afresh) {traffic_reset:.1f} '
                   'ms')
    if highway is None:
        context.append("gym: highway-env not installed (pip install 'vehicle_sim[bench]'): "
                       'its figures skipped')
    else:
        context.extend(f'gym: highway-env {env_id}: {rate:.0f} steps/s'
                       for env_id, rate in highway.items())
    return rows, context


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--quick', action='store_true', help='fewer samples')
    parser.add_argument('--profile', action='store_true',
                        help='print where a single environment spends its time')
    options = parser.parse_args(argv)
    load = '/'.join(f'{x:.1f}' for x in os.getloadavg())
    rows, context = figures(options.quick)
    width = max(len(row[0]) for row in rows)
    for name, value, relation, target, unit in rows:
        met = value >= target if relation == '>=' else value <= target
        print(f'{name:<{width}} | {value:>10.2f} {unit:<7} | {relation} {target:g} | '
              f'{"met" if met else "MISSED"}')
    for line in context:
        print('  ' + line)
    print(f'  load average before {load}, after '
          f'{"/".join(f"{x:.1f}" for x in os.getloadavg())} on {os.cpu_count()} cores')
    if options.profile:
        print(profile_text())
        print(profile_text(500, lidar=True))
    return 0


if __name__ == '__main__':
    sys.exit(main())
