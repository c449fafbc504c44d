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
Training on Ray: examples/train_highway_ray.py (RLlib's PPO on train_highway.py's task).

The smoke run (one per module) runs the shipped script as a user would, for two small training
iterations on the highway world with traffic and one evaluation episode per policy, and the
tests read what it wrote: a learning curve of finite returns over growing environment steps,
RLlib's checkpoint with train_highway.py's policy card beside it, the evaluation; then
``vehicle-sim policy`` reads the checkpoint as it reads a stable-baselines3 model. They need
the ``learn-ray`` extra (Ray's RLlib and PyTorch) and are skipped, with that reason, without
it. The script's clear errors (the extra missing, a bad budget) and the task's environment need
neither.
"""

import csv
from dataclasses import replace
import json
import math
from pathlib import Path
import shutil
import subprocess
import sys

import pytest
from script_helpers import load_script

from vehicle_sim.gym.policy_card import load_card, save_card

SCRIPT = Path(__file__).resolve().parents[1] / 'examples' / 'train_highway_ray.py'
ROOT = SCRIPT.parents[1]
# Generous bound: Ray's start, an EnvRunner process building the highway, two iterations, an
# evaluation episode per policy (60 s of simulated time at most each).
TIMEOUT_S = 1200
EVAL_SEED = 1_000_000           # train_highway.EVAL_SEED_BASE: the evaluation's first seed
LEARN_RAY = "training on Ray needs the 'learn-ray' extra (pip install 'vehicle_sim[learn-ray]')"


def _script():
    return load_script(SCRIPT)


def _run(*args, prelude='', cwd=None):
    code = (f'{prelude}import runpy, sys; sys.argv = {[str(SCRIPT), *args]!r}; '
            f'runpy.run_path({str(SCRIPT)!r}, run_name="__main__")')
    return subprocess.run([sys.executable, '-c', code], capture_output=True, text=True,
                          timeout=TIMEOUT_S, cwd=cwd)


def test_without_rllib_the_script_names_the_extra():
    # ray.rllib made unimportable, as on a machine without the learn-ray extra
    done = _run('--iterations', '1', prelude="import sys; sys.modules['ray.rllib'] = None; ")
    assert done.returncode != 0
    assert 'training on Ray needs RLlib and PyTorch' in done.stderr
    assert "pip install 'vehicle_sim[learn-ray]'" in done.stderr


@pytest.mark.parametrize('option, value, said', [('--budget-s', '0', '0.0: must be > 0'),
                                                  ('--iterations', '-1', '-1: must be > 0'),
                                                  ('--runners', '-2', '-2: must be >= 0'),
                                                  ('--batch', '0', '0: must be > 0'),
                                                  ('--eval-episodes', '-1', '-1: must be >= 0')])
def test_a_bad_option_is_refused_naming_it(tmp_path, option, value, said):
    done = _run(option, value, '--out', str(tmp_path / 'out'))
    assert done.returncode == 2
    assert f'{option} {said}' in done.stderr
    assert not (tmp_path / 'out').exists()


def test_evaluate_only_needs_a_finished_run(tmp_path):
    done = _run('--evaluate-only', '--out', str(tmp_path))
    assert done.returncode == 2
    assert f"--evaluate-only: {tmp_path / 'checkpoint'}: no such checkpoint" in done.stderr
    assert not (tmp_path / 'summary.json').exists()


def test_the_env_runners_build_train_highway_s_task():
    # the environment every EnvRunner builds is train_highway's: its card, judged by its
    # scenario (episodes end on the scenario's criteria), the same spaces
    script = _script()
    train_highway = script.train_highway
    env = script._task_env(script.env_config(train_highway.card()))
    reference = train_highway.make_task_env(train_highway.card())
    try:
        assert env.observation_space == reference.observation_space
        assert env.action_space == reference.action_space
        env.reset(seed=EVAL_SEED)
        _, _, _, _, info = env.step(env.action_space.sample() * 0.0)
        assert set(info['criteria']) == {'no_collision', 'stay_in_lane', 'mean_speed'}
        assert env.unwrapped.sim.options['max_steering'] == 0.02
    finally:
        env.close()
        reference.close()


def test_a_slow_env_runner_s_samples_are_kept():
    pytest.importorskip('ray.rllib', reason=LEARN_RAY)
    train_highway_ray = _script()
    config = train_highway_ray.make_config(train_highway_ray.train_highway.card(), seed=0,
                                           runners=2)
    # RLlib's default, 60 s, discards what a slower EnvRunner sampled: 0 steps per iteration
    # on a loaded machine
    assert config.sample_timeout_s is None
    assert config.num_env_runners == 2 and config.seed == 0
    # train_highway's PPO, in RLlib's names
    ppo = train_highway_ray.train_highway.PPO_OPTIONS
    assert (config.lr, config.gamma, config.lambda_, config.clip_param, config.num_epochs) == (
        ppo['learning_rate'], ppo['gamma'], ppo['gae_lambda'], ppo['clip_range'], ppo['n_epochs'])


@pytest.fixture(scope='module')
def ray_run(tmp_path_factory):
    """Run the shipped script's smoke run once; return (its folder, the finished process)."""
    for module in ('ray.rllib', 'torch'):
        pytest.importorskip(module, reason=LEARN_RAY)
    folder = tmp_path_factory.mktemp('ray')
    # a relative --out, as docs/learning.md runs it (RLlib's save_to_path takes a relative path
    # for a URI without a scheme: the script gives it the absolute one)
    done = _run('--iterations', '2', '--batch', '200', '--runners', '1', '--seed', '3',
                '--eval-episodes', '1', '--eval-workers', '1', '--out', 'run', cwd=folder)
    assert done.returncode == 0, done.stderr[-3000:]
    return folder / 'run', done


def test_two_iterations_on_the_highway_give_a_finite_learning_curve(ray_run):
    out, done = ray_run
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
    # RLlib's checkpoint, and the card saying which environment it was trained on:
    # train_highway.py's, the same task
    assert (out / 'checkpoint' / 'rllib_checkpoint.json').is_file()
    assert load_card(out / 'checkpoint') == _script().train_highway.card()
    assert f'{steps[1]} env steps in' in done.stdout
    # the run's summary, as docs/learning.md shows a committed one
    summary = json.loads((out / 'summary.json').read_text(encoding='utf-8'))
    assert summary['env_steps'] == steps[1] and summary['runners'] == 1
    assert summary['seed'] == 3 and summary['batch'] == 200
    assert summary['card'] == _script().train_highway.card().as_dict()
    assert summary['marks'][-1]['env_steps'] == steps[1]
    assert f'| {steps[1]} |' in _script().results_markdown(summary)


def test_the_trained_policy_is_evaluated_as_train_highway_s(ray_run):
    # train_highway's evaluation: its first seed, its figures, the trained policy beside a
    # random one, each episode in evaluation.csv
    out, _ = ray_run
    summary = json.loads((out / 'summary.json').read_text(encoding='utf-8'))
    assert summary['eval_seeds'] == [EVAL_SEED, EVAL_SEED]
    with open(out / 'evaluation.csv', encoding='utf-8') as stream:
        rows = list(csv.DictReader(stream))
    assert [(row['policy'], int(row['seed'])) for row in rows] == [('trained', EVAL_SEED),
                                                                   ('random', EVAL_SEED)]
    for row in rows:
        figures = summary['evaluation'][row['policy']]
        assert figures['episodes'] == 1
        assert figures['success_rate'] == float(row['success'] == 'True')
        assert figures['mean_speed_mps'] == pytest.approx(float(row['mean_speed_mps']),
                                                          abs=1e-3)
        assert 0.0 < float(row['time_s']) <= 60.0 + 1e-6
    table = _script().results_markdown(summary)
    rate = summary['evaluation']['trained']['success_rate']
    assert f'| RLlib PPO (deterministic) | {rate:.0%} |' in table


def test_evaluate_only_evaluates_a_finished_run_again_with_the_same_figures(ray_run, tmp_path):
    # the evaluation is deterministic for its seeds: a finished run's evaluation, made again
    # by --evaluate-only (on a copy), gives the same figures and episodes
    out, _ = ray_run
    again = tmp_path / 'run'
    shutil.copytree(out, again)
    (again / 'evaluation.csv').unlink()
    done = _run('--evaluate-only', '--eval-episodes', '1', '--eval-workers', '1', '--out',
                str(again))
    assert done.returncode == 0, done.stderr[-3000:]
    first = json.loads((out / 'summary.json').read_text(encoding='utf-8'))
    second = json.loads((again / 'summary.json').read_text(encoding='utf-8'))
    assert second['evaluation'] == first['evaluation']
    assert second['env_steps'] == first['env_steps']       # the training's figures kept
    assert ((again / 'evaluation.csv').read_text(encoding='utf-8')
            == (out / 'evaluation.csv').read_text(encoding='utf-8'))


def test_the_checkpoint_is_a_policy_with_frozen_input_statistics(ray_run):
    from vehicle_sim.tools.policy_loader import load_model
    out, _ = ray_run
    policy = load_model(out / 'checkpoint')
    train_highway = _script().train_highway
    env = train_highway.make_task_env(load_card(out / 'checkpoint'))
    try:
        assert policy.observation_space == env.observation_space
        assert policy.action_space == env.action_space
        first, _ = env.reset(seed=EVAL_SEED)
        action, state = policy.predict(first, deterministic=True)
        assert state is None and action.shape == (2,) and env.action_space.contains(action)
        # other observations go through the MeanStdFilter, its statistics stay: the same
        # observation gives the same action
        obs = first
        for _ in range(5):
            obs, *_ = env.step(policy.predict(obs)[0])
        again, _ = policy.predict(first, deterministic=True)
        assert again.tolist() == action.tolist()
    finally:
        env.close()


def _vehicle_sim(*args, cwd=ROOT):
    command = Path(sys.executable).with_name('vehicle-sim')
    return subprocess.run([str(command), *args], capture_output=True, text=True,
                          timeout=TIMEOUT_S, cwd=cwd)


def test_policy_evaluate_reads_the_checkpoint_with_the_script_s_verdict(ray_run):
    # the installed command takes the checkpoint folder as it takes a model.zip: the same
    # episode (seed, scenario, deterministic policy) gets the script's evaluation's verdict
    out, _ = ray_run
    done = _vehicle_sim('policy', 'evaluate', str(out / 'checkpoint'), '--only', 'in-process',
                        '--episodes', '1', '--first-seed', str(EVAL_SEED))
    assert done.returncode == 0, done.stderr[-3000:]
    with open(out / 'evaluation.csv', encoding='utf-8') as stream:
        trained = next(row for row in csv.DictReader(stream) if row['policy'] == 'trained')
    verdict = 'PASS' if trained['success'] == 'True' else 'FAIL'
    assert f'in-process seed {EVAL_SEED}: {verdict}' in done.stdout
    assert f"in-process success rate {100.0 * (verdict == 'PASS'):5.1f} %" in done.stdout


def test_policy_evaluate_drives_the_node_with_the_checkpoint_as_in_process(ray_run):
    # over the wire (the automobile node, policy run, lockstep) the checkpoint, given by a
    # relative path as docs/learning.md gives it, gets the verdict it gets in process
    # (5 s of the evaluation scenario's highway traffic: a 60 s episode over the wire takes
    # minutes on a loaded machine)
    out, _ = ray_run
    (out.parent / 'short.yaml').write_text(
        'name: short\nworld: highway_traffic\nduration: 5.0\nseed: 0\n'
        'driver: {commands: [{t: 0.0, cruising_speed: 100.0}]}\n'
        'criteria:\n  - kind: no_collision\n  - kind: stay_in_lane\n', encoding='utf-8')
    done = _vehicle_sim('policy', 'evaluate', 'run/checkpoint', '--scenario', 'short.yaml',
                        '--episodes', '1', '--first-seed', str(EVAL_SEED), cwd=out.parent)
    assert done.returncode == 0, done.stderr[-3000:]
    verdicts = {}
    for path in ('in-process', 'wire'):
        line = next(line for line in done.stdout.splitlines()
                    if line.strip().startswith(f'{path} seed {EVAL_SEED}: '))
        verdicts[path] = line.split(': ')[1].split()[0]
    assert verdicts['wire'] == verdicts['in-process'] in ('PASS', 'FAIL'), done.stdout
    rate = 100.0 * (verdicts['wire'] == 'PASS')
    assert f'in-process success rate {rate:5.1f} %' in done.stdout
    assert f'wire       success rate {rate:5.1f} %' in done.stdout


def test_policy_run_refuses_a_checkpoint_of_another_observation_space(ray_run, tmp_path):
    out, _ = ray_run
    other = tmp_path / 'checkpoint'
    shutil.copytree(out / 'checkpoint', other)
    card = load_card(out / 'checkpoint')
    save_card(replace(card, options=dict(card.options, objects=dict(card.options['objects'],
                                                                    count=5))), other)
    done = _vehicle_sim('policy', 'run', str(other), '--timeout', '5')
    assert done.returncode == 2
    assert ("observation space differs: 'objects': (8, 7) in the model, (5, 7) in the "
            'environment') in done.stderr
    assert str(other) in done.stderr


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
