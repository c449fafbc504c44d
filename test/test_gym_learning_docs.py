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
docs/learning.md shows the figures of the committed training run, as the script wrote them.

examples/train_highway.py wrote docs/learning/highway_ppo_summary.json and the curve files; the
table in docs/learning.md must be ``results_markdown`` of that summary (not typed in), and the
committed model's card must be the script's. The same for the earlier runs of the script whose
figures the page keeps (the committed run before the headway guard highway_ppo_unguarded_*,
highway_ppo_speed_steering_*, highway_ppo_braking_*,
highway_ppo_lane_speed_*, highway_ppo_more_steps_*, its second seed's highway_ppo_seed1_*,
highway_ppo_every4_* and its other seeds' highway_ppo_every4_seed1_* and _seed2_*,
highway_ppo_lr_decay_*, highway_ppo_lr_decay_c20_*, highway_ppo_lr_decay_ttc5_*,
highway_ppo_lane_choice_*, highway_ppo_lane_choice_box_*, highway_ppo_lane_choice_back_*,
highway_ppo_average_*, highway_ppo_curriculum_*, highway_ppo_20ms_*, the derived inputs'
highway_ppo_closing_*, highway_ppo_derived_*, highway_ppo_derived_every4_* and
highway_ppo_derived_seed1_*, and the SAC runs' highway_sac_*) and for
examples/train_crossing_shared.py's run (docs/learning/crossing_shared_*). Needs neither
stable-baselines3 nor PyTorch.
"""

import csv
import json
from pathlib import Path

import pytest
from script_helpers import load_script

ROOT = Path(__file__).resolve().parents[1]
RUN = ROOT / 'docs' / 'learning'


def _script():
    return load_script('examples/train_highway.py')


def test_the_docs_show_the_committed_runs_figures():
    summary = json.loads((RUN / 'highway_ppo_summary.json').read_text(encoding='utf-8'))
    text = (ROOT / 'docs' / 'learning.md').read_text(encoding='utf-8')
    assert _script().results_markdown(summary) in text
    assert summary['evaluation']['trained']['episodes'] == 100


def test_the_committed_curve_is_the_runs_and_the_model_has_the_scripts_card():
    summary = json.loads((RUN / 'highway_ppo_summary.json').read_text(encoding='utf-8'))
    with open(RUN / 'highway_ppo_curve.csv', encoding='utf-8') as stream:
        rows = list(csv.DictReader(stream))
    assert rows and summary['final_training_row'] == {
        key: type(value)(rows[-1][key]) for key, value in summary['final_training_row'].items()}
    assert (ROOT / 'docs' / 'highway_ppo_learning_curve.png').is_file()
    script = _script()
    card = json.loads((ROOT / 'examples' / 'models' / 'highway_ppo.card.json')
                      .read_text(encoding='utf-8'))
    assert card == script.card().as_dict()
    assert summary['env_options'] == script.ENV_OPTIONS
    assert summary['training_traffic'] == dict(script.TRAINING_TRAFFIC,
                                               every=script.TRAINING_TRAFFIC_EVERY)
    # the guard's run: no collision in the 100 evaluation episodes
    assert summary['env_options']['control'] == 'guarded_speed_steering'
    assert summary['evaluation']['trained']['collision_rate'] == 0.0


# The control of every run before the committed one (the script's until the headway guard).
UNGUARDED = {'control': 'braking_speed_steering'}


def _unguarded(script, **changed):
    # the script's environment options as an earlier run had them: braking_speed_steering,
    # and what that run changed
    return dict(script.ENV_OPTIONS, **dict(UNGUARDED, **changed))


# The options the braking run added to the first run's: the braking action and the gap term.
BRAKING_AND_GAP = {'control': 'braking_speed_steering', 'headway_penalty': 1.0,
                   'headway_s': 1.0, 'ttc_penalty': 2.0, 'ttc_s': 4.0, 'side_gap_penalty': 1.0,
                   'gap_margin': 1.0}


def _earlier_run(name):
    # An earlier run's summary: its table in docs/learning.md, its curve's last row its own
    summary = json.loads((RUN / f'{name}_summary.json').read_text(encoding='utf-8'))
    text = (ROOT / 'docs' / 'learning.md').read_text(encoding='utf-8')
    assert _script().results_markdown(summary) in text
    assert summary['evaluation']['trained']['episodes'] == 100
    with open(RUN / f'{name}_curve.csv', encoding='utf-8') as stream:
        rows = list(csv.DictReader(stream))
    assert summary['final_training_row'] == {
        key: type(value)(rows[-1][key]) for key, value in summary['final_training_row'].items()}
    return summary


def _ppo_options(script, **changed):
    # the PPO settings a run of the script records in its summary, with those changed
    return dict(script.PPO_OPTIONS, net_arch=script.NET_ARCH, log_std_init=script.LOG_STD_INIT,
                **dict(script.POLICY_OPTIONS, **changed))


def _shipped_task_run(name, seed=0, every=None):
    # a 30-minute run with the script's options and training traffic (whatever its learner;
    # ``every``: the training traffic in every so many worlds, the script's when None)
    script = _script()
    summary = _earlier_run(name)
    assert summary['seed'] == seed and summary['minutes'] == 30.0, name
    assert summary['env_options'] == _unguarded(script), name
    every = script.TRAINING_TRAFFIC_EVERY if every is None else every
    assert summary['training_traffic'] == dict(script.TRAINING_TRAFFIC, every=every), name
    return script, summary


def _shipped_settings_run(name, seed=0):
    # the same with the script's PPO settings
    script, summary = _shipped_task_run(name, seed)
    assert summary['ppo'] == _ppo_options(script), name
    return script, summary


def test_the_docs_show_the_braking_runs_figures_and_its_options_are_the_scripts():
    # the braking run: the script's options of today, its own traffic in every environment
    summary = _earlier_run('highway_ppo_braking')
    script = _script()
    assert summary['env_options'] == _unguarded(script, **BRAKING_AND_GAP)
    assert 'training_traffic' not in summary and script.TRAINING_TRAFFIC_EVERY


def test_the_docs_show_the_first_runs_figures_without_the_brakes_and_the_gap_term():
    summary = _earlier_run('highway_ppo_speed_steering')
    options = {key: value for key, value in _script().ENV_OPTIONS.items()
               if key not in BRAKING_AND_GAP}
    assert summary['env_options'] == options


def test_the_docs_show_the_lane_speed_runs_figures_and_its_options_are_the_scripts():
    # the lane-change actions tried: the script's options and training traffic but the
    # lane_speed layout (--control lane_speed)
    summary = _earlier_run('highway_ppo_lane_speed')
    script = _script()
    assert summary['env_options'] == dict(script.ENV_OPTIONS, control='lane_speed')
    assert summary['env_options'] == script.card('lane_speed').options
    assert summary['training_traffic'] == dict(script.TRAINING_TRAFFIC,
                                               every=script.TRAINING_TRAFFIC_EVERY)


def test_the_docs_show_the_shipped_scripts_later_runs_figures_and_options():
    # the committed run before the guard (its curve drawn beside it), its command again once
    # the env step no longer predicted the objects' paths (more env steps in the same 30
    # minutes), and the same with the second seed
    for name, seed in (('highway_ppo_unguarded', 0), ('highway_ppo_more_steps', 0),
                       ('highway_ppo_seed1', 1)):
        _shipped_settings_run(name, seed)
    assert (ROOT / 'docs' / 'highway_ppo_unguarded_learning_curve.png').is_file()
    assert _earlier_run('highway_ppo_more_steps')['env_steps'] > 1.5 * json.loads(
        (RUN / 'highway_ppo_unguarded_summary.json').read_text(encoding='utf-8'))['env_steps']


def test_the_docs_show_the_every4_runs_figures_and_their_options_are_the_scripts():
    # fewer training worlds in the denser traffic: the script's options, every fourth
    script = _script()
    for name, seed in (('highway_ppo_every4', 0), ('highway_ppo_every4_seed1', 1),
                       ('highway_ppo_every4_seed2', 2)):
        summary = _earlier_run(name)
        assert summary['seed'] == seed
        assert summary['env_options'] == _unguarded(script)
        assert summary['training_traffic'] == dict(script.TRAINING_TRAFFIC, every=4)


# The decaying learning rate's runs: PPO's learning rate from 3e-4 to 3e-5 over the first
# 400 000 env steps, alone and with one reward weight changed -> that run's options.
LR_DECAY_RUNS = {'highway_ppo_lr_decay': {},
                 'highway_ppo_lr_decay_c20': {'collision_penalty': 20.0},
                 'highway_ppo_lr_decay_ttc5': {'ttc_penalty': 5.0}}


def test_the_docs_show_the_lr_decay_runs_figures_and_their_options_are_the_scripts():
    script = _script()
    for name, changed in LR_DECAY_RUNS.items():
        summary = _earlier_run(name)
        assert summary['env_options'] == _unguarded(script, **changed), name
        assert summary['training_traffic'] == dict(script.TRAINING_TRAFFIC,
                                                   every=script.TRAINING_TRAFFIC_EVERY)
        assert summary['ppo'] == _ppo_options(script, learning_rate=[3e-4, 3e-5, 400_000]), name
        assert summary['seed'] == 0
    # the first ran past the end of the decay
    assert _earlier_run('highway_ppo_lr_decay')['env_steps'] > 400_000


# The lane-choice runs: a wrapper around the lane_speed environment whose lane choice (keep,
# left, right) is held until the lane is reached (or, in the last, called back by the opposite
# choice) -> what the run's summary says of its actions.
LANE_CHOICE_RUNS = {
    'highway_ppo_lane_choice': {'lane_choice_speeds': [0.0, 10.0, 18.0, 24.0, 28.0, 31.0, 33.3]},
    'highway_ppo_lane_choice_box': {'lane_choice_threshold': 1.0 / 3.0},
    'highway_ppo_lane_choice_back': {'lane_choice_threshold': 1.0 / 3.0,
                                     'lane_choice_call_back': True},
}


def test_the_docs_show_the_lane_choice_runs_figures_and_their_options_are_the_scripts():
    script = _script()
    for name, actions in LANE_CHOICE_RUNS.items():
        summary = _earlier_run(name)
        assert summary['env_options'] == dict(script.ENV_OPTIONS, control='lane_speed'), name
        assert {key: summary[key] for key in actions} == actions, name
        assert summary['training_traffic'] == dict(script.TRAINING_TRAFFIC,
                                                   every=script.TRAINING_TRAFFIC_EVERY)
        assert summary['ppo'] == _ppo_options(script), name
        assert summary['seed'] == 0 and summary['minutes'] == 30.0


def test_the_docs_show_the_averaged_and_last_policys_figures_of_one_training():
    # the average of the policies of the second half: the shipped script's training (its curve
    # the 499 736-step run's up to where it stopped), its last policy evaluated beside it
    _, summary = _shipped_settings_run('highway_ppo_average')
    assert summary['averaged_policies'] == 91
    text = (ROOT / 'docs' / 'learning.md').read_text(encoding='utf-8')
    for name in ('trained', 'last'):
        figures = summary['evaluation'][name]
        collisions = round(figures['collision_rate'] * figures['episodes'])
        assert (f"**{figures['success_rate'] * 100:.0f} %**, {collisions} collisions"
                in text), name
    with open(RUN / 'highway_ppo_average_curve.csv', encoding='utf-8') as stream:
        rows = list(csv.DictReader(stream))
    with open(RUN / 'highway_ppo_more_steps_curve.csv', encoding='utf-8') as stream:
        longer = {row['env_steps']: row for row in csv.DictReader(stream)}
    for row in rows:
        assert {key: row[key] for key in ('episodes', 'mean_return', 'success_rate')} == {
            key: longer[row['env_steps']][key] for key in ('episodes', 'mean_return',
                                                           'success_rate')}, row['env_steps']


def test_the_docs_show_the_curriculum_runs_figures_and_its_options_are_the_scripts():
    # sparse traffic first: the first third in 30 cars of the training traffic's spread, then
    # the script's own mix
    script, summary = _shipped_settings_run('highway_ppo_curriculum')
    assert summary['first_phase'] == {'vehicles': 30, 'fraction': 1.0 / 3.0,
                                      'speed_factor_std': script.TRAINING_TRAFFIC[
                                          'speed_factor_std']}
    assert 0 < summary['first_phase_env_steps'] < summary['env_steps'] / 2


def test_the_docs_show_the_20ms_runs_figures_and_it_trained_at_a_checked_step():
    # training at 20 ms steps (the same 5 Hz decisions) with twice the batch, evaluated on the
    # task as shipped (its summary's options are the script's card)
    from vehicle_sim.core.specs.simulation import CHECKED_TIME_STEPS_MS, TIME_STEP_MS
    script, summary = _shipped_task_run('highway_ppo_20ms')
    assert summary['ppo'] == _ppo_options(script, n_steps=512, batch_size=512)
    steps = summary['training_steps']
    assert steps['time_step_ms'] in CHECKED_TIME_STEPS_MS and steps['time_step_ms'] > 10
    assert (steps['time_step_ms'] * steps['action_repeat']
            == TIME_STEP_MS.default * script.ENV_OPTIONS['action_repeat'])
    text = ' '.join((ROOT / 'docs' / 'learning.md').read_text(encoding='utf-8').split())
    with open(RUN / 'highway_ppo_20ms_evaluation.csv', encoding='utf-8') as stream:
        rows = [row for row in csv.DictReader(stream) if row['policy'] == 'trained']
    slow = [float(row['mean_speed_mps']) for row in rows
            if row['success'] == 'False' and row['collision'] == 'False']
    collisions = sum(row['collision'] == 'True' for row in rows)
    assert (f"**{summary['evaluation']['trained']['success_rate'] * 100:.0f} %**: "
            f'{collisions} collisions and {len(slow)} episodes without one too slow for '
            f'`mean_speed` ({min(slow):.1f}–{max(slow):.1f} m/s)') in text
    assert f"**{summary['env_steps']:,} env steps**".replace(',', ' ') in text


# The runs with inputs derived inside the policy (docs/learning.md, "Tried: inputs derived
# inside the policy"): the derived inputs, the training traffic's every, the seed
DERIVED_RUNS = {'highway_ppo_closing': (('closing',), 2, 0),
                'highway_ppo_derived': (('closing', 'lane_lateral'), 2, 0),
                'highway_ppo_derived_every4': (('closing', 'lane_lateral'), 4, 0),
                'highway_ppo_derived_seed1': (('closing', 'lane_lateral'), 2, 1)}


def test_the_docs_show_the_derived_inputs_runs_figures_and_their_settings_are_the_scripts():
    script = _script()
    assert script.TRAINING_TRAFFIC_EVERY == 2
    for name, (names, every, seed) in DERIVED_RUNS.items():
        summary = _earlier_run(name)
        assert summary['seed'] == seed and summary['minutes'] == 30.0, name
        assert summary['env_options'] == _unguarded(script), name
        assert summary['training_traffic'] == dict(script.TRAINING_TRAFFIC, every=every), name
        assert summary['ppo'] == _ppo_options(script), name
        assert summary['derived_inputs'] == {n: script.DERIVED_INPUTS[n] for n in names}, name
        assert summary['derived_inputs'] == script.derived_inputs(script.card(), names)


def test_the_scripts_derived_inputs_need_the_keys_they_read():
    from vehicle_sim.gym.policy_card import PolicyCard
    script = _script()
    assert script.derived_inputs(script.card(), ()) == {}
    no_lane = PolicyCard(script.ENV_ID, script.ENV_OPTIONS, ('twist', 'objects'), (-1.0, 1.0))
    assert list(script.derived_inputs(no_lane, ['closing'])) == ['closing']
    with pytest.raises(SystemExit, match=r"'lane_lateral' reads the keys \['lane', 'objects'\]"):
        script.derived_inputs(no_lane, ['lane_lateral'])


# SAC's settings of the runs with another learner (docs/learning.md, "Tried: another learner"),
# and each run's gradient steps and training traffic (in every so many worlds; None: the
# script's)
SAC_SETTINGS = {'buffer_size': 1_000_000, 'learning_starts': 10_000, 'batch_size': 256,
                'learning_rate': 3e-4, 'gamma': 0.99, 'tau': 0.005, 'train_freq': 1,
                'ent_coef': 'auto', 'net_arch': [128, 128]}
SAC_RUNS = {'highway_sac': (2, None), 'highway_sac_g4': (4, None), 'highway_sac_g8': (8, None),
            'highway_sac_g4_e4': (4, 4)}


def test_the_docs_show_the_sac_runs_figures_and_their_task_is_the_scripts():
    # the same task, observations, reward and training traffic as the script, SAC's learner
    text = ' '.join((ROOT / 'docs' / 'learning.md').read_text(encoding='utf-8').split())
    for name, (gradient_steps, every) in SAC_RUNS.items():
        script, summary = _shipped_task_run(name, every=every)
        assert summary['algorithm'] == 'SAC' and 'ppo' not in summary, name
        assert summary['scales'] == script.SCALES, name
        assert summary['sac'] == dict(SAC_SETTINGS, gradient_steps=gradient_steps), name
        with open(RUN / f'{name}_evaluation.csv', encoding='utf-8') as stream:
            rows = [row for row in csv.DictReader(stream) if row['policy'] == 'trained']
        slow = [float(row['mean_speed_mps']) for row in rows
                if row['success'] == 'False' and row['collision'] == 'False']
        collisions = sum(row['collision'] == 'True' for row in rows)
        assert (f"**{summary['evaluation']['trained']['success_rate'] * 100:.0f} %**, with "
                f'**{collisions} collisions**') in text, name
        assert (f'{len(slow)} episodes without a collision were too slow for `mean_speed` '
                f'({min(slow):.1f}–{max(slow):.1f} m/s, {sum(v >= 26.0 for v in slow)} of them '
                'at 26.0 m/s or more)') in text, name


def test_the_docs_show_the_committed_crossing_runs_figures():
    # examples/train_crossing_shared.py's run: its summary, curve and table in docs/learning.md
    script = load_script('examples/train_crossing_shared.py')
    summary = json.loads((RUN / 'crossing_shared_summary.json').read_text(encoding='utf-8'))
    text = (ROOT / 'docs' / 'learning.md').read_text(encoding='utf-8')
    assert script.results_markdown(summary) in text
    assert summary['evaluation']['trained']['episodes'] == 100
    assert summary['env_options'] == json.loads(json.dumps(script.task_options()))
    with open(RUN / 'crossing_shared_curve.csv', encoding='utf-8') as stream:
        rows = list(csv.DictReader(stream))
    assert rows and summary['final_training_row'] == {
        key: type(value)(rows[-1][key]) for key, value in summary['final_training_row'].items()}
    assert (ROOT / 'docs' / 'crossing_shared_learning_curve.png').is_file()


def test_the_docs_show_the_policy_evaluations_verdicts_of_all_100_seeds():
    # `vehicle-sim policy evaluate` of the committed model on both paths: the table and the
    # failures in docs/learning.md are the CSV's (written from the command's printed lines)
    with open(RUN / 'highway_ppo_policy_evaluate.csv', encoding='utf-8') as stream:
        rows = list(csv.DictReader(stream))
    assert [int(row['seed']) for row in rows] == list(range(1000, 1100))
    text = (ROOT / 'docs' / 'learning.md').read_text(encoding='utf-8')
    passed = {path: sum(row[f'{path}_success'] == 'True' for row in rows)
              for path in ('in_process', 'wire')}
    assert (f"| in process | 100 | {passed['in_process']} | {passed['in_process']} % |\n"
            f"| over the wire | 100 | {passed['wire']} | {passed['wire']} % |") in text
    assert f"differ by **{abs(passed['in_process'] - passed['wire'])} point" in text
    verdicts = [row[f'{path}_verdict'] for row in rows for path in ('in_process', 'wire')
                if row[f'{path}_success'] == 'False']
    assert verdicts and all(v.startswith('mean_speed: ') for v in verdicts)   # no collision
    same = sum(row['in_process_success'] == row['wire_success'] for row in rows)
    assert f'The same verdict on {same} of the 100 seeds' in text
    assert not any('lockstep' in row['wire_verdict'] for row in rows)
