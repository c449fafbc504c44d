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
The learning pipeline end to end on a trivial task (docs/learning.md): a few thousand PPO steps.

examples/train_highway.py's ``train`` and ``write_curve`` on a flat world without traffic: the
car starts at rest, the reward is the distance driven along its heading (Drive-v0's progress
term), so driving fast is all there is to learn. The trained policy, saved with its card and
loaded back as ``vehicle-sim policy run`` would, must score well above a random policy on the
same seeds. Seeded; bounded by steps, not by time. Skipped, saying why, without the ``learn``
extra (stable-baselines3 and PyTorch), which CI does not install.
"""

import argparse
import csv
import json

import numpy as np
import pytest
from script_helpers import load_script

pytest.importorskip('gymnasium', reason="needs the 'gym' extra (gymnasium)")
pytest.importorskip('stable_baselines3',
                    reason="needs the 'learn' extra (stable-baselines3 and PyTorch): "
                           "pip install 'vehicle_sim[learn]', docs/learning.md")
pytest.importorskip('torch', reason="needs the 'learn' extra (PyTorch): docs/learning.md")

from stable_baselines3 import PPO  # noqa: E402

from vehicle_sim.gym.policy_card import load_card, make_env, PolicyCard  # noqa: E402

ROOT = __import__('pathlib').Path(__file__).resolve().parents[1]
OPTIONS = {'world': 'default', 'action_repeat': 10, 'max_episode_s': 4.0, 'max_speed': 10.0,
           'max_reverse_speed': 0.0, 'max_steering': 0.05, 'progress_weight': 0.1}
EPISODES = 4


def _script():
    return load_script('examples/train_highway.py')


def _mean_return(env, policy, seeds):
    returns = []
    for seed in seeds:
        obs, _ = env.reset(seed=seed)
        env.action_space.seed(seed)
        total, done = 0.0, False
        while not done:
            action = policy(obs, env)
            obs, reward, terminated, truncated, _ = env.step(action)
            total += reward
            done = terminated or truncated
        returns.append(total)
    return float(np.mean(returns))


@pytest.mark.timeout(600)
def test_ppo_learns_to_drive_faster_than_a_random_policy(tmp_path):
    script = _script()
    card = PolicyCard('vehicle_sim/Drive-v0', OPTIONS, ('twist',), (-1.0, 1.0))
    args = argparse.Namespace(minutes=60.0, timesteps=3072, seed=0, envs=2, threads=1)
    model_path, rows, episodes, facts = script.train(
        args, card, tmp_path, scenario=None,
        ppo_options={'n_steps': 128, 'batch_size': 64, 'learning_rate': 1e-3},
        scales={'twist': [0.1, 1.0, 1.0]})
    script.write_curve(tmp_path, rows, episodes)
    assert facts['env_steps'] >= 3072 and facts['episodes'] == len(episodes) > 0
    with open(tmp_path / 'learning_curve.csv', encoding='utf-8') as stream:
        curve = list(csv.DictReader(stream))
    assert [int(r['env_steps']) for r in curve] == [r['env_steps'] for r in rows]
    assert json.loads((tmp_path / 'model.card.json').read_text())['observation_keys'] == \
        ['twist']

    loaded = load_card(model_path)             # as `vehicle-sim policy run` reads it
    assert loaded == card
    model = PPO.load(model_path, device='cpu')
    env = make_env(loaded)
    seeds = range(100, 100 + EPISODES)
    trained = _mean_return(env, lambda obs, _: model.predict(obs, deterministic=True)[0], seeds)
    random = _mean_return(env, lambda _, e: e.action_space.sample(), seeds)
    env.close()
    # full speed (10 m/s from rest in 4 s) drives about 25 m: 2.5; a random speed about half
    assert trained > random + 0.3, (trained, random)
