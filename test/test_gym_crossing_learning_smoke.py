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
The shared-policy pipeline of the 4-agent crossing end to end (docs/learning.md), a few steps.

examples/train_crossing_shared.py's ``train`` (SuperSuit's vector env over the PettingZoo
agents, one stable-baselines3 PPO policy for all four) for a few thousand agent steps on a
trivial version of the crossing: 3 s episodes, too short for any car to reach the crossing, so
driving fast along the lane is all there is to learn; the trained policy must score well above a
random one on the same seeds. And the script's BlackDeath wrapper: a world whose agents leave
at different times ends, every slot at once, at the step the last one leaves. Seeded; bounded by
steps, not by time. Skipped, saying why, without the ``learn`` extra (stable-baselines3,
PyTorch, SuperSuit), which CI does not install.
"""

import argparse
import csv

import numpy as np
import pytest
from script_helpers import load_script

pytest.importorskip('pettingzoo', reason="needs the 'multi' extra (pettingzoo)")
pytest.importorskip('stable_baselines3',
                    reason="needs the 'learn' extra (stable-baselines3 and PyTorch): "
                           "pip install 'vehicle_sim[learn]', docs/learning.md")
pytest.importorskip('torch', reason="needs the 'learn' extra (PyTorch): docs/learning.md")
pytest.importorskip('supersuit', reason="needs the 'learn' extra (SuperSuit): "
                                        "pip install 'vehicle_sim[learn]', docs/learning.md")

SHORT = {'max_episode_s': 3.0}      # 15 decisions; the fastest car is 7 m short of the crossing
SEEDS = range(100, 104)


def _script():
    return load_script('examples/train_crossing_shared.py')


def _mean_return(outcomes, agents):
    return float(np.mean([o[f'return_{a}'] for o in outcomes for a in agents]))


@pytest.mark.timeout(600)
def test_the_shared_policy_learns_to_drive_faster_than_a_random_one(tmp_path):
    script = _script()
    args = argparse.Namespace(minutes=60.0, timesteps=4096, seed=0, worlds=2, processes=0,
                              threads=1, vehicle_model=script.VEHICLE_MODEL)
    model_path, rows, episodes, facts = script.train(
        args, tmp_path, ppo_options={'n_steps': 64, 'batch_size': 128, 'learning_rate': 1e-3},
        env_options=SHORT)
    script.write_curve(tmp_path, rows, episodes)
    # 8 slots (2 worlds x 4 agents) of 64 steps per update; a world's episode is 15 steps
    assert facts['agent_steps'] == 4096 and facts['episodes'] == len(episodes) > 0
    assert all(len([k for k in e if k.startswith('return_')]) == 4 for e in episodes)
    with open(tmp_path / 'learning_curve.csv', encoding='utf-8') as stream:
        curve = list(csv.DictReader(stream))
    # a row per update whose rollout ended (the last stops at the step budget, before its end)
    assert [int(r['agent_steps']) for r in curve] == [512 * k for k in range(1, 8)]
    assert [int(r['world_steps']) for r in curve] == [128 * k for k in range(1, 8)]

    agents = ['car_east', 'car_north', 'car_west', 'car_south']
    trained = script._evaluate(str(model_path), SEEDS, script.VEHICLE_MODEL, SHORT)
    random = script._evaluate(None, SEEDS, script.VEHICLE_MODEL, SHORT)
    assert [o['seed'] for o in trained] == list(SEEDS)
    assert not any(o['collision'] or o['success'] for o in trained + random)
    # 0.1 per metre: full speed drives 12-23 m in 3 s (the four cars' accelerations), about
    # 1.7 on average; a random speed about half of that
    assert _mean_return(trained, agents) > _mean_return(random, agents) + 0.3, (trained, random)


def test_a_world_ends_when_its_last_agent_leaves_every_slot_at_once():
    # SuperSuit 3.11.0's black_death ANDs terminations and truncations: a world whose last
    # agents are truncated at the time limit ends a step late (51 steps, the 50th not done) or
    # raises; the script's BlackDeath ends it at its 50th step, zeroing the agents that left.
    script = _script()
    env = script.black_death_class()(script.policy_env())
    try:
        env.reset(seed=3)
        full = np.array([0.0, 1.0], dtype=np.float32)     # straight on at the top speed
        left, steps = {}, 0
        while env.agents:
            obs, rewards, terminations, truncations, infos = env.step(
                dict.fromkeys(env.agents, full))
            steps += 1
            for agent in env.possible_agents:
                if agent in left:
                    assert rewards[agent] == 0.0 and infos[agent] == {}
                    assert all(not value.any() for value in obs[agent].values())
                elif infos[agent]['collision']:
                    left[agent] = steps
            assert len(set(terminations.values())) == 1 == len(set(truncations.values()))
        # the 10 s episode ran to its end; two cars collided in the crossing before it
        assert steps == 50 and all(terminations.values())
        assert sorted(left) == ['car_north', 'car_west'] and max(left.values()) < 50
    finally:
        env.close()
