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
Speed of the multi-agent environment (vehicle_sim.gym.multi, docs/gym.md).

Per-agent throughput with 8 agents in one world against a single-agent environment: 8 cars on
the highway world (3 forward lanes, 30 m apart; ``MultiDriveEnv``, lane observations, lane
progress and penalties, action_repeat 1, 10 ms) and one ``vehicle_sim/Drive-v0`` on the same
highway with its one car. The figure is agent steps per CPU second of this process (8 per
multi-agent env step) over the single environment's world steps per CPU second (target >=
0.8x). CPU time (``time.process_time``), not wall time: the machine's cores are shared, and
other people's processes move wall-clock rates much more. Short blocks of the two are
interleaved, both driving the same stretch from rest in each block (a step's cost depends on
the speed), every car taking small seeded random actions (no one leaves the road or crashes
during the blocks). The wall-clock rates are printed beside.

Run: ``.venv/bin/python benchmarks/bench_gym_multi.py [--quick]``.
"""

import argparse
import os
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))

TARGET_RATIO = 0.8
AGENTS = 8
LANES_Y = (-1.875, -5.625, -9.375)      # highway.yaml's forward lanes


def highway_world(agents=AGENTS):
    """Return highway.yaml as a mapping with ``agents`` cars, three abreast, 30 m apart."""
    from vehicle_sim.config import read_yaml, world_path
    data = read_yaml(world_path('highway'))
    data['vehicles'] = [{'name': f'car{i}', 'namespace': f'car{i}', 'model': 'ToyotaPrius',
                         'pose': {'x': 20.0 + 30.0 * (i // 3), 'y': LANES_Y[i % 3],
                                  'yaw': 0.0}}
                        for i in range(agents)]
    return data


def _actions(count, seed):
    rng = np.random.default_rng(seed)
    return np.stack([rng.uniform(-0.01, 0.01, count), rng.uniform(8.0, 12.0, count)],
                    axis=1).astype(np.float32)


class _Single:
    def __init__(self):
        import gymnasium

        import vehicle_sim.gym  # noqa: F401  (registers Drive-v0)
        self.env = gymnasium.make('vehicle_sim/Drive-v0', world='highway')
        self.agents = 1

    def block(self, steps):
        env = self.env
        env.reset(seed=0)
        actions = _actions(steps, 0)
        for i in range(steps):
            _, _, terminated, truncated, _ = env.step(actions[i])
            assert not (terminated or truncated)


class _Multi:
    def __init__(self, agents=AGENTS):
        from vehicle_sim.gym.multi import MultiDriveEnv
        self.env = MultiDriveEnv(world=highway_world(agents), agents=agents)
        self.agents = agents

    def block(self, steps):
        env = self.env
        env.reset(seed=0)
        actions = {agent: _actions(steps, i) for i, agent in enumerate(env.possible_agents)}
        for i in range(steps):
            env.step({agent: actions[agent][i] for agent in env.agents})
        assert len(env.agents) == self.agents, f'agents left: {env.agents}'


def measure(blocks=5, steps=400, agents=AGENTS):
    """
    Return {'ratio', 'multi_cpu', 'single_cpu', 'multi_wall', 'single_wall'}.

    ``*_cpu``: agent steps per CPU second (the multi-agent env: ``agents`` per env step);
    ``*_wall``: agent steps per wall second; ``ratio``: multi_cpu / single_cpu.
    """
    single, multi = _Single(), _Multi(agents)
    totals = {'single': [0, 0.0, 0.0], 'multi': [0, 0.0, 0.0]}
    try:
        for _ in range(blocks):
            for key, runner in (('multi', multi), ('single', single)):
                cpu0, wall0 = time.process_time(), time.perf_counter()
                runner.block(steps)
                totals[key][0] += steps * runner.agents
                totals[key][1] += time.process_time() - cpu0
                totals[key][2] += time.perf_counter() - wall0
    finally:
        single.env.close()
        multi.env.close()
    found = {f'{key}_cpu': done / cpu_s for key, (done, cpu_s, _) in totals.items()}
    found.update({f'{key}_wall': done / wall_s for key, (done, _, wall_s) in totals.items()})
    found['ratio'] = found['multi_cpu'] / found['single_cpu']
    return found


def figures(quick=False):
    """Return the rows of run_all.py (name, value, relation, target, unit)."""
    found = measure(3 if quick else 5, 200 if quick else 400)
    return [
        (f'gym.multi: {AGENTS} agents in one world, agent steps per CPU s / Drive-v0 steps '
         'per CPU s', found['ratio'], '>=', TARGET_RATIO, 'x'),
        (f'  same, {AGENTS} agents: agent steps per CPU second', found['multi_cpu'], None, None,
         '/CPU s'),
        ('  same, Drive-v0 alone: steps per CPU second', found['single_cpu'], None, None,
         '/CPU s'),
    ]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.strip().splitlines()[0])
    parser.add_argument('--quick', action='store_true', help='fewer, shorter blocks')
    options = parser.parse_args(argv)
    found = measure(3 if options.quick else 5, 200 if options.quick else 400)
    print(f'{AGENTS} agents in one highway world (MultiDriveEnv), per agent: '
          f'{found["multi_cpu"]:.0f} agent steps per CPU s ({found["multi_wall"]:.0f} per wall s)')
    print(f'one Drive-v0 on the same highway:          {found["single_cpu"]:.0f} steps per CPU s '
          f'({found["single_wall"]:.0f} per wall s)')
    print(f'ratio (CPU): {found["ratio"]:.2f}x  (target >= {TARGET_RATIO}x)  '
          f'load {"/".join(f"{x:.1f}" for x in os.getloadavg())}')


if __name__ == '__main__':
    main()
