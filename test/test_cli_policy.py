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
``vehicle-sim policy run|evaluate`` through the installed command: bad input, a saved model.

The bad model files and cards need nothing beyond the package. The tests that load a model
need stable-baselines3 (the ``learn`` extra): without it they are skipped, saying so; they
train a tiny PPO model (two updates) on the highway, save it with its card and run it.
"""

import json
import subprocess
import sys

from conftest import peer_env
import pytest

from vehicle_sim.gym.policy_card import PolicyCard, save_card

CLI_TIMEOUT_S = 600.0
CARD = PolicyCard('vehicle_sim/Drive-v0',
                  {'world': 'highway', 'control': 'speed_steering', 'action_repeat': 10,
                   'max_speed': 30.0, 'max_episode_s': 5.0},
                  ('lane', 'twist'), (-1.0, 1.0))


def vehicle_sim(*args, cwd=None):
    """Run the installed command; return the CompletedProcess (text)."""
    return subprocess.run([sys.executable, '-m', 'vehicle_sim', *args], env=peer_env(),
                          capture_output=True, text=True, timeout=CLI_TIMEOUT_S, cwd=cwd)


def test_a_model_without_a_card_is_refused_naming_the_card(tmp_path):
    model = tmp_path / 'model.zip'
    model.write_bytes(b'PK')
    result = vehicle_sim('policy', 'run', str(model))
    assert result.returncode == 2
    assert (f'{model}: no policy card beside it ({tmp_path / "model.card.json"}): the '
            'environment the policy was trained on is unknown') in result.stderr


def test_a_malformed_card_is_refused_naming_it(tmp_path):
    model = tmp_path / 'model.zip'
    model.write_bytes(b'PK')
    (tmp_path / 'model.card.json').write_text('{"version": 1, "env_id": ', encoding='utf-8')
    result = vehicle_sim('policy', 'run', str(model))
    assert result.returncode == 2
    assert f'{tmp_path / "model.card.json"}: not a policy card: ' in result.stderr


def test_a_card_without_its_model_file_is_refused(tmp_path):
    model = tmp_path / 'model.zip'
    save_card(CARD, model)
    result = vehicle_sim('policy', 'run', str(model))
    assert result.returncode == 2
    assert f'{model}: no such model file' in result.stderr


def test_a_folder_that_is_not_an_rllib_checkpoint_is_refused_naming_it(tmp_path):
    # a folder is read as an RLlib checkpoint (train_highway_ray's checkpoint/) only when it
    # holds RLlib's rllib_checkpoint.json
    folder = tmp_path / 'checkpoint'
    folder.mkdir()
    save_card(CARD, folder)
    result = vehicle_sim('policy', 'run', str(folder))
    assert result.returncode == 2
    assert (f'{folder}: a folder without rllib_checkpoint.json: neither an RLlib checkpoint '
            'nor a model file') in result.stderr


# ---------------------------------------------------------------- with stable-baselines3
def _require_sb3():
    try:
        import stable_baselines3  # noqa: F401
    except ImportError:
        pytest.skip('stable-baselines3 is not installed (the learn extra): no model to load')


@pytest.fixture(scope='module')
def tiny_model(tmp_path_factory):
    """Return a tiny PPO model of CARD (two updates of 32 steps), saved with its card."""
    _require_sb3()
    from stable_baselines3 import PPO

    from vehicle_sim.gym.policy_card import make_env
    path = tmp_path_factory.mktemp('policy') / 'tiny.zip'
    env = make_env(CARD)
    try:
        model = PPO('MultiInputPolicy', env, n_steps=32, batch_size=32, n_epochs=1, seed=0,
                    device='cpu')
        model.learn(64)
        model.save(str(path))
    finally:
        env.close()
    save_card(CARD, path)
    return path


def test_a_zip_that_is_not_a_model_is_refused_naming_it(tmp_path):
    _require_sb3()
    model = tmp_path / 'model.zip'
    model.write_bytes(b'not a zip')
    save_card(CARD, model)
    result = vehicle_sim('policy', 'run', str(model))
    assert result.returncode == 2
    assert f'{model}: not a stable-baselines3 PPO model: ' in result.stderr


def test_a_model_of_another_observation_space_is_refused_naming_both_shapes(tiny_model,
                                                                           tmp_path):
    other = tmp_path / 'other.zip'
    other.write_bytes(tiny_model.read_bytes())
    card = json.loads(tiny_model.with_name('tiny.card.json').read_text(encoding='utf-8'))
    card['options']['objects'] = {'count': 8}
    card['observation_keys'] = ['lane', 'objects', 'twist']
    (tmp_path / 'other.card.json').write_text(json.dumps(card), encoding='utf-8')
    result = vehicle_sim('policy', 'run', str(other))
    assert result.returncode == 2
    assert (f"{other}: observation space differs: 'objects': (8, 7) in the environment, not "
            'in the model') in result.stderr


def test_a_rate_that_is_not_a_number_is_refused_before_anything_runs(tiny_model):
    result = vehicle_sim('policy', 'run', str(tiny_model), '--rate', '-5')
    assert result.returncode == 2
    assert '--rate -5.0: must be a number > 0 [Hz]' in result.stderr


def test_a_saved_model_drives_the_scenario_over_the_wire_and_in_process(tiny_model, tmp_path):
    scenario = tmp_path / 'short.yaml'
    scenario.write_text('name: short\nworld: highway\nduration: 2.0\n'
                        'driver: {commands: [{t: 0.0, cruising_speed: 0.0}]}\n'
                        'criteria:\n  - kind: no_collision\n  - {kind: max_speed, limit: 40}\n',
                        encoding='utf-8')
    result = vehicle_sim('policy', 'evaluate', str(tiny_model), '--scenario', str(scenario),
                         '--episodes', '1', '--first-seed', '7')
    assert result.returncode == 0, result.stderr[-3000:]
    out = result.stdout
    assert 'in-process seed 7: PASS (every criterion passed)' in out
    assert 'wire seed 7: PASS (every criterion passed)' in out
    assert '  in-process success rate 100.0 %' in out
    assert '  wire       success rate 100.0 %' in out
