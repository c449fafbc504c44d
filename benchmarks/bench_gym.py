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
   ``pip install 'vehicle_sim[bench]'``; skipped with a line otherwise);
6. equal work against highway-env (with the package): simulated seconds per CPU second of a
   highway with 20 traffic vehicles, decisions at 1 Hz (highway-fast-v0: 20 vehicles, 5 Hz
   simulation, 1 Hz policy) and at 5 Hz (the same with policy_frequency 5), against ours on
   highway_traffic with 20 vehicles updated at 5 Hz (update_period 0.2 s, as highway-fast-v0's
   simulation): with full physics at 10 ms steps (the default, Webots' city worlds;
   action_repeat 100 or 20) and at 20 ms steps (the coarsest step at which the physics car's
   checks run, docs/physics.md; action_repeat 50 or 10), target >= 3x, and with a kinematic
   ``vehicle_model: DELAY_STEER_ACC`` (200 ms steps, highway-fast-v0's; target >= 10x). Short
   blocks of the four interleaved; per block the ratio of simulated seconds
   per CPU second of this process; the median printed, the blocks' range beside it. highway-env
   takes random meta-actions; ours a lane keeper (steering from the lane observation) at a
   random speed of 20 to 33 m/s, so that both drive on the road among the traffic; both reset
   at episode ends.

Every environment takes the same fixed sequence of random actions (seeded) and is reset when its
episode ends, so resets count in the figures as in training. Run:
``.venv/bin/python benchmarks/bench_gym.py [--quick] [--equal] [--profile]`` (``--equal``: only
the equal-work rows) (``--profile``: the top
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
TARGET_EQUAL_PHYSICS = 3.0      # x highway-fast-v0, simulated s per CPU s, full physics
TARGET_EQUAL_KINEMATIC = 10.0   # the same with a kinematic vehicle_model
EQUAL_VEHICLES = 20
EQUAL_TRAFFIC_PERIOD_S = 0.2    # highway-fast-v0's simulation_frequency 5 Hz
EQUAL_KINEMATIC_MODEL = 'DELAY_STEER_ACC'
EQUAL_KINEMATIC_STEP_MS = 200   # highway-fast-v0's simulation step
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


class _LaneKeeper:
    """
    Our side of the equal-work race: decisions at ``policy_hz`` on highway_traffic.

    Steering from the lane observation (heading error and lateral offset, gains scaled to the
    decision period, the same on every model), a seeded random speed of 20 to 33 m/s; reset at
    episode ends.
    """

    # (heading gain, offset gain) per decision rate: they keep the car in its lane at 1 and 5 Hz
    GAINS = {1.0: (1.5, 0.4), 5.0: (0.6, 0.15)}

    def __init__(self, policy_hz, vehicle_model=None, step_ms=None):
        import yaml

        from vehicle_sim.config import world_path
        from vehicle_sim.core.specs.simulation import TIME_STEP_MS
        gymnasium = _gym()
        with open(world_path('highway_traffic'), encoding='utf-8') as stream:
            world = yaml.safe_load(stream)
        world['traffic']['vehicles'] = EQUAL_VEHICLES
        world['traffic']['update_period'] = EQUAL_TRAFFIC_PERIOD_S
        step_ms = TIME_STEP_MS.default if step_ms is None else step_ms
        if vehicle_model is not None:
            world['vehicles'][0]['vehicle_model'] = vehicle_model
            step_ms = EQUAL_KINEMATIC_STEP_MS
        self.period_s = 1.0 / policy_hz
        self.env = gymnasium.make(ENV_ID, world=world, time_step_ms=step_ms, max_speed=33.3,
                                  action_repeat=int(round(self.period_s * 1000.0 / step_ms)))
        self.gains = self.GAINS[policy_hz]
        self.rng = np.random.default_rng(0)
        self.episodes = 0
        self.obs, _ = self.env.reset(seed=0)

    def block(self, seconds):
        """Drive ``seconds`` simulated seconds; return them."""
        env, (k_heading, k_offset), period = self.env, self.gains, self.period_s
        decisions = int(round(seconds / period))
        for _ in range(decisions):
            _, offset, heading, _, _, on_lane = self.obs['lane']
            speed = max(5.0, float(self.obs['twist'][0]))
            lever = 2.8 / (speed * period)       # wheelbase over the distance of one decision
            steer = -(k_heading * heading * lever + k_offset * offset * lever / (speed * period)
                      ) if on_lane else 0.0
            action = np.array([min(0.2, max(-0.2, steer)), self.rng.uniform(20.0, 33.0)],
                              dtype=np.float32)
            self.obs, _, terminated, truncated, _ = env.step(action)
            if terminated or truncated:
                self.episodes += 1
                self.obs, _ = env.reset()
        return decisions * period


class _HighwayEnvSide:
    """highway-env's side: highway-fast-v0 (20 vehicles, 5 Hz simulation) at ``policy_hz``."""

    def __init__(self, policy_hz):
        gymnasium = _gym()
        self.env = gymnasium.make('highway-fast-v0',
                                  config={'vehicles_count': EQUAL_VEHICLES,
                                          'policy_frequency': int(policy_hz)})
        config = self.env.unwrapped.config
        assert config['simulation_frequency'] == 1.0 / EQUAL_TRAFFIC_PERIOD_S
        self.period_s = 1.0 / config['policy_frequency']
        self.actions = _actions(self.env.action_space)
        self.index = 0
        self.episodes = 0
        self.env.reset(seed=0)

    def block(self, seconds):
        env, actions = self.env, self.actions
        decisions = int(round(seconds / self.period_s))
        for _ in range(decisions):
            _, _, terminated, truncated, _ = env.step(actions[self.index % len(actions)])
            self.index += 1
            if terminated or truncated:
                self.episodes += 1
                env.reset()
        return decisions * self.period_s


def equal_work(policy_hz, blocks, seconds):
    """
    Return {side: (sim s per CPU s, sim s per wall s, ratios, mean episode [s])}.

    ratios: (median, lowest, highest) of the blocks' ratios to highway-env. Sides 'highway-env',
    'physics 10 ms' and 'physics 20 ms' (the full physics car at each step of
    CHECKED_TIME_STEPS_MS) and 'kinematic', stepped ``seconds`` simulated seconds each in turn,
    ``blocks`` times; None without highway-env.
    """
    try:
        import highway_env  # noqa: F401
    except ImportError:
        return None
    from vehicle_sim.core.specs.simulation import CHECKED_TIME_STEPS_MS
    sides = {'highway-env': _HighwayEnvSide(policy_hz)}
    for step_ms in CHECKED_TIME_STEPS_MS:      # the full physics car's checked steps
        sides[f'physics {step_ms} ms'] = _LaneKeeper(policy_hz, step_ms=step_ms)
    sides['kinematic'] = _LaneKeeper(policy_hz, EQUAL_KINEMATIC_MODEL)
    try:
        for side in sides.values():         # warm up (first episode, caches)
            side.block(2.0)
        start_episodes = {key: side.episodes for key, side in sides.items()}
        per_block = {key: [] for key in sides}
        totals = {key: [0.0, 0.0, 0.0] for key in sides}
        for _ in range(blocks):
            for key, side in sides.items():
                wall, cpu = time.perf_counter(), time.process_time()
                done = side.block(seconds)
                cpu, wall = time.process_time() - cpu, time.perf_counter() - wall
                per_block[key].append(done / cpu)
                for index, value in enumerate((done, cpu, wall)):
                    totals[key][index] += value
        result = {}
        for key in sides:
            ratios = [ours / theirs for ours, theirs in zip(per_block[key],
                                                              per_block['highway-env'])]
            done, cpu, wall = totals[key]
            episodes = max(1, sides[key].episodes - start_episodes[key])
            result[key] = (done / cpu, done / wall,
                           (statistics.median(ratios), min(ratios), max(ratios)), done / episodes)
        return result
    finally:
        for side in sides.values():
            side.env.close()


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


def equal_figures(quick=False):
    """Only the equal-work rows (``--equal``); (rows, context lines) as :func:`figures`."""
    rows, context = [], []
    _equal_rows({hz: equal_work(hz, 3 if quick else 7, 20.0 if quick else 60.0)
                 for hz in (1.0, 5.0)}, rows, context)
    return rows, context


def _equal_rows(equal, rows, context):
    if all(result is None for result in equal.values()):
        context.append("gym: highway-env not installed (pip install 'vehicle_sim[bench]'): "
                       'the equal-work rows skipped')
    for hz, result in equal.items():
        if result is None:
            continue
        ours = [(key, TARGET_EQUAL_PHYSICS, f'full physics, {key.split()[1]} ms steps')
                for key in result if key.startswith('physics ')]
        ours.append(('kinematic', TARGET_EQUAL_KINEMATIC, f'{EQUAL_KINEMATIC_MODEL} model'))
        for key, target, what in ours:
            rows.append((f'gym: equal work, {hz:.0f} Hz decisions, ours ({what}) / '
                         'highway-fast-v0, sim s per CPU s', result[key][2][0], '>=', target,
                         'x'))
        theirs = result['highway-env']
        context.append(
            f'gym: equal work at {hz:.0f} Hz decisions, {EQUAL_VEHICLES} traffic vehicles, '
            f'simulated s per CPU s (per wall s) [mean episode s]: highway-fast-v0 '
            f'{theirs[0]:.1f} ({theirs[1]:.1f}) [{theirs[3]:.0f}]; ' + '; '.join(
                f'ours ({what}) {result[key][0]:.1f} ({result[key][1]:.1f}) '
                f'[{result[key][3]:.0f}], blocks {result[key][2][1]:.2f}-{result[key][2][2]:.2f}x'
                for key, _, what in ours))


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
    equal = {hz: equal_work(hz, 3 if quick else 7, 20.0 if quick else 60.0) for hz in (1.0, 5.0)}
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
        context.append('gym: those are steps, not equal work: one of ours is 10 ms of '
                       "simulation, one of highway-fast-v0's 1 s (5 substeps); the equal-work "
                       'rows compare simulated seconds')
    _equal_rows(equal, rows, context)
    return rows, context


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--quick', action='store_true', help='fewer samples')
    parser.add_argument('--equal', action='store_true',
                        help='only the equal-work rows against highway-env')
    parser.add_argument('--profile', action='store_true',
                        help='print where a single environment spends its time')
    options = parser.parse_args(argv)
    load = '/'.join(f'{x:.1f}' for x in os.getloadavg())
    rows, context = (equal_figures if options.equal else figures)(options.quick)
    width = max((len(row[0]) for row in rows), default=0)
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
