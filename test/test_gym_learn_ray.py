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
Training on Ray: examples/train_highway_ray.py (RLlib's PPO on the highway with traffic).

The smoke test runs the shipped script as a user would, for two small training iterations on
the highway world with traffic, and reads what it wrote: a learning curve of finite returns
over growing environment steps, RLlib's checkpoint and the policy card beside it. It needs the
``learn-ray`` extra (Ray's RLlib and PyTorch) and is skipped, with that reason, without it. The
script's clear errors (the extra missing, a bad budget) need neither.
"""

import csv
import json
import math
from pathlib import Path
import subprocess
import sys

import pytest
from script_helpers import load_script

from vehicle_sim.gym.policy_card import load_card

SCRIPT = Path(__file__).resolve().parents[1] / 'examples' / 'train_highway_ray.py'
ROOT = SCRIPT.parents[1]
# Generous bound: Ray's start, an EnvRunner process building the highway, two iterations.
TIMEOUT_S = 540


def _script():
    return load_script(SCRIPT)


def _run(*args, prelude=''):
    code = (f'{prelude}import runpy, sys; sys.argv = {[str(SCRIPT), *args]!r}; '
            f'runpy.run_path({str(SCRIPT)!r}, run_name="__main__")')
    return subprocess.run([sys.executable, '-c', code], capture_output=True, text=True,
                          timeout=TIMEOUT_S)


def test_without_rllib_the_script_names_the_extra():
    # ray.rllib made unimportable, as on a machine without the learn-ray extra
    done = _run('--iterations', '1', prelude="import sys; sys.modules['ray.rllib'] = None; ")
    assert done.returncode != 0
    assert 'training on Ray needs RLlib and PyTorch' in done.stderr
    assert "pip install 'vehicle_sim[learn-ray]'" in done.stderr


@pytest.mark.parametrize('option, value, said', [('--budget-s', '0', '0.0: must be > 0'),
                                                  ('--iterations', '-1', '-1: must be > 0'),
                                                  ('--runners', '-2', '-2: must be >= 0'),
                                                  ('--batch', '0', '0: must be > 0')])
def test_a_bad_option_is_refused_naming_it(tmp_path, option, value, said):
    done = _run(option, value, '--out', str(tmp_path / 'out'))
    assert done.returncode == 2
    assert f'{option} {said}' in done.stderr
    assert not (tmp_path / 'out').exists()


def test_a_slow_env_runner_s_samples_are_kept():
    pytest.importorskip('ray.rllib', reason="training on Ray needs the 'learn-ray' extra "
                                            "(pip install 'vehicle_sim[learn-ray]')")
    train_highway_ray = _script()
    config = train_highway_ray.make_config(train_highway_ray.highway_card(), seed=0, runners=2)
    # RLlib's default, 60 s, discards what a slower EnvRunner sampled: 0 steps per iteration
    # on a loaded machine
    assert config.sample_timeout_s is None
    assert config.num_env_runners == 2 and config.seed == 0


def test_two_iterations_on_the_highway_give_a_finite_learning_curve(tmp_path):
    for module in ('ray.rllib', 'torch'):
        pytest.importorskip(module, reason="training on Ray needs the 'learn-ray' extra "
                                           "(pip install 'vehicle_sim[learn-ray]')")
    out = tmp_path / 'run'
    done = _run('--iterations', '2', '--batch', '200', '--runners', '1', '--seed', '3',
                '--out', str(out))
    assert done.returncode == 0, done.stderr[-3000:]
    with open(out / 'learning_curve.csv', encoding='utf-8') as stream:
        rows = list(csv.DictReader(stream))
    assert [int(row['iteration']) for row in rows] == [1, 2]
    # each iteration samples at least its batch of environment steps
    steps = [int(row['env_steps']) for row in rows]
    assert 200 <= steps[0] < steps[1]
    for row in rows:
        assert math.isfinite(float(row['mean_return']))
        assert float(row['mean_length']) > 0
        assert 0.0 <= float(row['success_rate']) <= 1.0
        assert int(row['episodes']) >= 1
    # RLlib's checkpoint, and the card saying which environment it was trained on
    assert (out / 'checkpoint' / 'rllib_checkpoint.json').is_file()
    card = load_card(out / 'checkpoint')
    assert card.env_id == 'vehicle_sim/Drive-v0'
    assert card.observation_keys == ('lane', 'twist', 'objects')
    assert card.options['objects'] is True and card.options['max_speed'] == 40.0
    assert f'{steps[1]} env steps in' in done.stdout
    # the run's summary, as docs/learning.md shows a committed one
    summary = json.loads((out / 'summary.json').read_text(encoding='utf-8'))
    assert summary['env_steps'] == steps[1] and summary['runners'] == 1
    assert summary['seed'] == 3 and summary['batch'] == 200
    assert summary['marks'][-1]['env_steps'] == steps[1]
    assert f'| {steps[1]} |' in _script().results_markdown(summary)


def test_the_docs_show_the_committed_ray_runs_figures():
    # docs/learning.md's "Training with Ray" figures are the script's results_markdown of the
    # committed run's summary (not typed in), beside its curve
    run = ROOT / 'docs' / 'learning'
    summary = json.loads((run / 'highway_ray_summary.json').read_text(encoding='utf-8'))
    text = (ROOT / 'docs' / 'learning.md').read_text(encoding='utf-8')
    assert _script().results_markdown(summary) in text
    with open(run / 'highway_ray_curve.csv', encoding='utf-8') as stream:
        rows = list(csv.DictReader(stream))
    assert int(rows[-1]['env_steps']) == summary['env_steps']
    assert float(rows[-1]['wall_s']) == summary['train_wall_s']
    assert (ROOT / 'docs' / 'highway_ray_learning_curve.png').is_file()
