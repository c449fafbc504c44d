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
The multi-agent environment (vehicle_sim.gym.multi): N ego vehicles in one world.

PettingZoo's own parallel API and seed tests; two seeded runs bit-identical; an agent that
crashes leaves while the others go on (and its reward and info are those of the single-agent
environment's terms); more agents than the world has places for, unknown agent names and
actions of unknown or departed agents are refused with the value named.
"""

from pathlib import Path
import re
import subprocess
import sys

import numpy as np
import pytest

pytest.importorskip('gymnasium', reason="needs the 'gym' extra (gymnasium)")
pytest.importorskip('pettingzoo', reason="needs the 'multi' extra (pettingzoo)")

from pettingzoo.test import parallel_api_test  # noqa: E402

from vehicle_sim.core.specs.errors import InvalidParameterError  # noqa: E402
from vehicle_sim.gym.multi import MultiDriveEnv  # noqa: E402

FAST = np.array([0.0, 10.0], dtype=np.float32)
STAND = np.array([0.0, 0.0], dtype=np.float32)


@pytest.fixture
def make_env():
    made = []

    def _make(**kwargs):
        kwargs.setdefault('agents', 4)
        env = MultiDriveEnv(**kwargs)
        made.append(env)
        return env

    yield _make
    for env in made:
        env.close()


def test_parallel_api_test_passes(make_env):
    env = make_env(max_episode_s=3.0, action_repeat=10)
    parallel_api_test(env, num_cycles=400)
    assert env.possible_agents == ['car_east', 'car_north', 'car_west', 'car_south']


def test_parallel_seed_test_passes():
    seed_test = pytest.importorskip('pettingzoo.test').parallel_seed_test
    envs = []

    def env_fn():
        env = MultiDriveEnv(agents=4, max_episode_s=2.0, action_repeat=10)
        envs.append(env)
        return env

    try:
        seed_test(env_fn, num_cycles=30)
    finally:
        for env in envs:
            env.close()


def _run(env, seed, steps):
    obs, _ = env.reset(seed=seed)
    rng = np.random.default_rng(seed)
    trace = [obs]
    for _ in range(steps):
        if not env.agents:
            break
        actions = {a: rng.uniform(env.action_space(a).low, env.action_space(a).high)
                   .astype(np.float32) for a in env.agents}
        obs, rewards, _, _, _ = env.step(actions)
        trace.append((obs, rewards))
    return trace


def _flat(trace):
    out = []
    for item in trace:
        obs, rewards = item if isinstance(item, tuple) else (item, {})
        for agent in sorted(obs):
            out.extend(np.concatenate([np.ravel(obs[agent][k]).astype(np.float64)
                                       for k in sorted(obs[agent])]))
        out.extend(rewards[a] for a in sorted(rewards))
    return np.array(out)


def test_two_seeded_runs_are_identical_with_traffic_and_start_noise(make_env):
    kwargs = dict(world='crossing4', agents=4, action_repeat=10, max_episode_s=5.0,
                  start_noise=[0.5, 0.2, 0.05])
    first = _flat(_run(make_env(**kwargs), 7, 40))
    second = _flat(_run(make_env(**kwargs), 7, 40))
    other = _flat(_run(make_env(**kwargs), 8, 40))
    assert first.size > 1000
    assert np.array_equal(first, second)
    assert not np.array_equal(first[:first.size // 2], other[:first.size // 2])


def test_a_crashed_agent_leaves_and_the_others_go_on(make_env):
    env = make_env(max_episode_s=12.0, action_repeat=10)
    env.reset(seed=0)
    # car_north and car_west race into the crossing; car_east and car_south stand
    plan = {'car_east': STAND, 'car_north': FAST, 'car_west': FAST, 'car_south': STAND}
    crashed = None
    for _ in range(200):
        obs, rewards, terminated, truncated, infos = env.step(
            {a: plan[a] for a in env.agents})
        if any(terminated.values()):
            crashed = {a for a, t in terminated.items() if t}
            break
    assert crashed == {'car_north', 'car_west'}
    for agent in crashed:
        assert infos[agent]['collision']
        assert infos[agent]['collided_with'] == ({'car_north', 'car_west'} - {agent}).pop()
        assert rewards[agent] == pytest.approx(sum(infos[agent]['reward_terms'].values()))
        assert infos[agent]['reward_terms']['collision'] == -10.0
    assert not terminated['car_east'] and not terminated['car_south']
    assert env.agents == ['car_east', 'car_south']
    with pytest.raises(ValueError, match=r"'car_west'.*left the episode; live agents: "
                                         r'car_east, car_south'):
        env.step({'car_west': STAND, 'car_east': STAND, 'car_south': STAND})
    # the others go on until the episode's time
    time_s = infos['car_east']['time_s']
    for _ in range(3):
        obs, rewards, terminated, truncated, infos = env.step(
            {'car_east': FAST, 'car_south': STAND})
    assert set(obs) == {'car_east', 'car_south'}
    assert infos['car_east']['time_s'] == pytest.approx(time_s + 0.3)
    assert obs['car_east']['twist'][0] > 0.5
    while env.agents:
        _, _, terminated, truncated, _ = env.step({a: STAND for a in env.agents})
    assert env.agents == []
    with pytest.raises(RuntimeError, match='every agent has left'):
        env.step({})


def test_more_agents_than_places_is_refused():
    with pytest.raises(InvalidParameterError,
                       match=r"agents = 5: more agents than the world 'crossing4' has places "
                             r'for: its 4 vehicles \(car_east, car_north, car_west, car_south\)'):
        MultiDriveEnv(world='crossing4', agents=5)
    with pytest.raises(InvalidParameterError, match=r"agents = 3: more agents than the world "
                                                    r"'two_cars' has places for: its 2"):
        MultiDriveEnv(world='two_cars', agents=3)
    with pytest.raises(InvalidParameterError, match='agents = 0: at least 1 agent'):
        MultiDriveEnv(agents=0)
    with pytest.raises(InvalidParameterError, match=r"agents = 'car_east': give a number of "
                                                    r"agents or a list of vehicle names of the "
                                                    r"world 'crossing4'"):
        MultiDriveEnv(agents='car_east')
    world = {'vehicles': [{'name': 'solo', 'pose': {'x': 0.0, 'y': 0.0, 'yaw': 0.0}}]}
    with pytest.raises(InvalidParameterError, match=r'agents = 2: more agents than the world '
                                                    r'given has places for: its 1 vehicles '
                                                    r'\(solo\)'):
        MultiDriveEnv(world=world, agents=np.int64(2))


def test_unknown_and_repeated_agent_names_are_refused():
    with pytest.raises(InvalidParameterError,
                       match=r"'car_up': no such vehicle in the world 'crossing4'; its "
                             r'vehicles: car_east, car_north, car_west, car_south'):
        MultiDriveEnv(agents=['car_east', 'car_up'])
    with pytest.raises(InvalidParameterError, match=r"'car_east' named more than once"):
        MultiDriveEnv(agents=['car_east', 'car_east'])
    with pytest.raises(InvalidParameterError, match=r"option 'vehicle' = 'car_east': names "
                                                    'one ego'):
        MultiDriveEnv(vehicle='car_east')


def test_named_agents_and_bad_actions(make_env):
    env = make_env(world='two_cars', agents=['car2'], action_repeat=5)
    assert env.possible_agents == ['car2']
    obs, _ = env.reset(seed=3)
    pose = obs['car2']['pose'].copy()
    assert pose[1] == pytest.approx(6.0, abs=1e-3)
    with pytest.raises(ValueError, match=r"actions for 'car1': no such agent; agents: car2"):
        env.step({'car1': STAND, 'car2': STAND})
    with pytest.raises(ValueError, match=r"no action for the live agents 'car2'"):
        env.step({})
    with pytest.raises(ValueError, match=r"agent 'car2': action\[1\] \(speed\) = 99.0"):
        env.step({'car2': np.array([0.0, 99.0], dtype=np.float32)})
    assert env.sim.elapsed_s == 0.0       # nothing was stepped
    obs, *_ = env.step({'car2': STAND})
    assert env.sim.elapsed_s == pytest.approx(0.05)


def test_the_shipped_crossing_example_runs_four_agents():
    script = Path(__file__).resolve().parents[1] / 'examples' / 'gym_multi_crossing.py'
    done = subprocess.run([sys.executable, str(script), '--episodes', '1', '--max-seconds',
                           '3'], capture_output=True, text=True, timeout=300, check=True)
    rows = re.findall(r'^  (\w+): (\d+) steps, return (-?[\d.]+) \((.*)\); (.*)$',
                      done.stdout, re.MULTILINE)
    assert [row[0] for row in rows] == ['car_east', 'car_north', 'car_west', 'car_south']
    for _, steps, total, terms, why in rows:
        assert 1 <= int(steps) <= 30          # 3 s of 0.1 s steps at most
        assert why == 'time limit' if int(steps) == 30 else why.startswith('collision with')
        parts = [float(part.rsplit(' ', 1)[1]) for part in terms.split(', ')]
        assert sum(parts) == pytest.approx(float(total), abs=0.03)


def test_the_docs_example_runs_as_written():
    # docs/gym.md's multi-agent block, as written, then what it left behind: every agent gone,
    # each with a final observation in its space
    text = (Path(__file__).resolve().parents[1] / 'docs' / 'gym.md').read_text(encoding='utf-8')
    block = [b for b in re.findall(r'```python\n(.*?)```', text, re.S)
             if 'MultiDriveEnv(' in b][0]
    scope = {}
    exec(compile(block, 'docs/gym.md', 'exec'), scope)   # noqa: S102
    env = scope['env']
    try:
        assert env.agents == []
        assert set(scope['obs']) <= set(env.possible_agents) and scope['obs']
        for agent, obs in scope['obs'].items():
            assert env.observation_space(agent).contains(obs)
            assert scope['terminations'][agent] or scope['truncations'][agent]
    finally:
        env.close()
