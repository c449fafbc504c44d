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
Train stable-baselines3's PPO to drive the highway in traffic, then evaluate it (docs/learning.md).

The task is scenarios/highway_policy.yaml: 60 s on the motorway of
config/worlds/highway_traffic.yaml (3 + 3 lanes, 60 traffic cars, limit 33.3 m/s), starting at
rest; a success is no collision, no lane departure (stay_in_lane) and a mean speed of at least
80 % of the limit. Training episodes end on the scenario's criteria (Drive-v0's ``scenario=``).

Observations (the keys a running ROS node gives too): ``lane`` (the lane state), ``twist``
(base_link velocity) and ``objects`` (the 8 nearest traffic cars as highway-env's Kinematics
table), scaled inside the policy (vehicle_sim/gym/scaled_inputs.py; ``--derived-inputs closing
lane_lateral`` adds each row's closing rate and its lateral position in lane widths). Actions
(``guarded_speed_steering``): steering angle within +-0.02 rad and cruising speed 0 .. 33.3
m/s, rescaled to [-1, 1], at 5 Hz; the speed is capped by a headway guard (no faster than the
car can stop behind the car ahead in its lane), and a speed more than 1 m/s below the car's
brakes. Reward
(Drive-v0's terms, weights in ENV_OPTIONS): progress along the lanes x 0.03 /m (one per
second at the limit), -10 for a collision, -10 per second off the lanes, -5 per solid line
crossed, -0.3 per second times the distance from the lane's centre over half its width, and
the gap term (a time headway under 1 s, a time to collision under 4 s, a side clearance under
1 m); a collision or a lane departure also ends the episode, losing the progress to come.
Every second training environment runs denser traffic with a wider spread of speeds
(TRAINING_TRAFFIC); the evaluation runs the scenario's own.

Run: ``python examples/train_highway.py [--minutes 30] [--seed 0] [--out DIR]``; it writes
``DIR/learning_curve.csv`` (a row per PPO update: env steps, wall time, mean return and success
rate of the last 50 training episodes), ``DIR/learning_curve.png``, ``DIR/episodes.csv`` (every
training episode), ``DIR/model.zip`` with its card ``DIR/model.card.json``
(vehicle_sim/gym/policy_card.py), and ``DIR/summary.json``: 100 evaluation episodes on seeds
disjoint from training's, the trained policy (deterministic) beside a random one.
Needs the ``learn`` extra (stable-baselines3, PyTorch) and matplotlib (the ``plot`` extra).
"""

import argparse
import json
import multiprocessing
import os
from pathlib import Path
import time
import warnings

import numpy as np

from vehicle_sim.core.learning.actions import CAR, LAYOUTS, layouts_of
from vehicle_sim.gym.learning_curve import plot_curve, write_evaluation, write_rows
from vehicle_sim.gym.policy_card import load_card, make_env, PolicyCard, save_card

ROOT = Path(__file__).resolve().parents[1]
SCENARIO = ROOT / 'scenarios' / 'highway_policy.yaml'
LIMIT_MPS = 33.3                # the motorway's speed limit (config/worlds/highway_traffic.yaml)
MIN_MEAN_FRACTION = 0.8         # the scenario's mean_speed criterion: 26.64 m/s
OBSERVATION_KEYS = ('lane', 'objects', 'twist')
ENV_ID = 'vehicle_sim/Drive-v0'
ENV_OPTIONS = {
    'world': 'highway_traffic',
    'objects': {'count': 8, 'range': 80.0, 'speed_scale': 40.0},
    'action_repeat': 20,                # 0.2 s per action: 5 Hz decisions
    # braking_speed_steering (a speed well below the car's brakes, up to 5.4 m/s^2) under the
    # headway guard (core/learning/headway_guard.py: no faster than it can stop behind the car
    # ahead in its lane); it reads the objects table, so 'objects' stays
    'control': 'guarded_speed_steering',
    'max_speed': LIMIT_MPS,             # never faster than the limit
    'max_reverse_speed': 0.0,
    'max_steering': 0.02,               # rad: 0.02 rad at 33 m/s is 8 m/s^2 lateral
    'max_episode_s': 60.0,
    'progress_weight': 0.03,            # 1 per second at the limit
    'collision_penalty': 10.0,
    'off_lane_penalty': 10.0,
    'solid_line_penalty': 5.0,
    'lane_centre_penalty': 0.3,         # per second at a lane's edge: keep to the centre
    # the gap term (core/learning/gap.py, docs/gym.md): per second, in proportion, a time
    # headway under 1 s, a time to collision under 4 s (x 2), a side clearance under 1 m
    'headway_penalty': 1.0,
    'headway_s': 1.0,
    'ttc_penalty': 2.0,
    'ttc_s': 4.0,
    'side_gap_penalty': 1.0,
    'gap_margin': 1.0,
}
# Input factors (ScaledInputs): each entry to about [-1, 1] where it matters.
SCALES = {
    # s [m], offset [m], heading error [rad], width [m], speed limit [m/s], on_lane
    'lane': [1.0 / 600.0, 1.0 / 1.875, 10.0, 1.0 / 3.75, 1.0 / LIMIT_MPS, 1.0],
    # forward [m/s], left [m/s], yaw rate [rad/s]
    'twist': [1.0 / LIMIT_MPS, 1.0, 5.0],
    # presence, x, y (over 80 m: a lane is 0.047, x 10 makes it 0.47), vx, vy, cos_h, sin_h
    'objects': [1.0, 2.0, 10.0, 2.0, 5.0, 1.0, 1.0],
}
# ScaledInputs' derived inputs (--derived-inputs; none by default: docs/learning.md, "Tried:
# inputs derived inside the policy"), each one more input per row of the objects table.
# closing: the row's closing rate (inverse time to collision) x 4 s, so that a time to collision
# of 4 s (the gap term's ttc_s) reads 1 and one of 0.8 s reads 5.
# lane_lateral: the row's lateral position in the ego's lane widths, from the lane state (0: in
# the ego's lane, +-1: the next lane): the table's y alone moves by a lane's width when the
# ego's heading is a degree or two off its lane's.
DERIVED_INPUTS = {
    'closing': {'key': 'objects', 'range': ENV_OPTIONS['objects']['range'],
                'speed_scale': ENV_OPTIONS['objects']['speed_scale'], 'min_distance': 5.0,
                'factor': 4.0},
    'lane_lateral': {'key': 'objects', 'lane_key': 'lane',
                     'range': ENV_OPTIONS['objects']['range']},
}
PPO_OPTIONS = {
    'n_steps': 256, 'batch_size': 256, 'n_epochs': 10, 'learning_rate': 3e-4, 'gamma': 0.99,
    'gae_lambda': 0.95, 'clip_range': 0.2, 'ent_coef': 0.0,
}
NET_ARCH = [128, 128]
LOG_STD_INIT = -0.5
POLICY_OPTIONS = {}             # more keywords of the policy (e.g. squash_output with use_sde)
# The traffic of every TRAINING_TRAFFIC_EVERY-th training environment (1, 1 + k, ...; 0: none)
# replaced by these TrafficSpec fields (core/traffic/params.py): the training worlds only, the
# evaluation keeps the scenario's traffic.
# Every second one gets 80 cars whose desired speeds spread twice as wide (a factor 0.667 +- 2 x
# 0.15 of the limit: 12 to 32 m/s, against 17 to 28 m/s): more cars much slower than the ego.
TRAINING_TRAFFIC = {'vehicles': 80, 'speed_factor_std': 0.15}
TRAINING_TRAFFIC_EVERY = 2
EVAL_SEED_BASE = 1_000_000      # evaluation seeds: EVAL_SEED_BASE + k; training's are seed + i
WINDOW = 50                     # training episodes per curve point
# --control: the car's layouts with a speed entry (max_speed bounds it), from core's table.
SPEED_CONTROLS = tuple(name for name in layouts_of(CAR) if 'speed' in LAYOUTS[name].names)
# The columns of learning_curve.csv.
CURVE_FIELDS = ['env_steps', 'wall_s', 'episodes', 'mean_return', 'success_rate',
                'mean_episode_s']
# RescaleAction's float64 bounds are cast to the float32 Box: expected, not news.
warnings.filterwarnings('ignore', message='.*precision lowered by casting to float32.*')


def card(control=None):
    """
    Return the policy card of this task (the environment the policy reads and drives).

    :param control: the action layout instead of ENV_OPTIONS' (``--control``), or None.
    """
    options = dict(ENV_OPTIONS)
    if control is not None:
        options['control'] = control
    return PolicyCard(ENV_ID, options, OBSERVATION_KEYS, (-1.0, 1.0))


def make_task_env(policy_card, scenario=SCENARIO):
    """
    Return the card's environment judging the evaluation scenario (episodes end on it).

    The scenario's world is the card's (highway_traffic): the scenario replaces it. None: the
    card's environment as it is.
    """
    if scenario is None:
        return make_env(policy_card)
    return make_env(policy_card, world=None, scenario=str(scenario))


def episode_outcome(info, sim):
    """Return {success, collision, lane_departure, mean_speed_mps, time_s} of an ended episode."""
    verdicts = info['criteria']
    results = sim.criteria_results()
    mean = results['mean_speed'].value
    return {'success': all(v == 'passed' for v in verdicts.values()),
            'collision': verdicts['no_collision'] == 'failed',
            'lane_departure': verdicts['stay_in_lane'] == 'failed',
            'mean_speed_mps': float(mean) if mean is not None else 0.0,
            'time_s': float(info['time_s'])}


def scenario_with_traffic(scenario, traffic):
    """Return the scenario file's ScenarioSpec with its world's traffic fields replaced."""
    from dataclasses import replace

    from vehicle_sim.scenarios.schema import load_scenario
    spec = load_scenario(scenario)
    world = replace(spec.world, traffic=replace(spec.world.traffic, **traffic))
    return replace(spec, world=world)


class _EnvFactory:
    """
    A picklable env maker for SubprocVecEnv (the card travels, not a closure).

    With ``rank`` it makes what stable-baselines3's ``make_vec_env`` makes for that rank: the
    environment in a Monitor, its action space seeded ``seed + rank``; with ``traffic`` the
    scenario's traffic fields replaced (scenario_with_traffic).
    """

    def __init__(self, policy_card, scenario, traffic=None, rank=None, seed=None):
        self.card = policy_card
        self.scenario = scenario
        self.traffic = traffic
        self.rank = rank
        self.seed = seed

    def __call__(self):
        if self.traffic and self.scenario is not None:
            env = make_env(self.card, world=None,
                           scenario=scenario_with_traffic(self.scenario, self.traffic))
        else:
            env = make_task_env(self.card, self.scenario)
        if self.rank is None:
            return env
        from stable_baselines3.common.monitor import Monitor
        if self.seed is not None:
            env.action_space.seed(self.seed + self.rank)
        return Monitor(env)


def derived_inputs(policy_card, names):
    """
    Return ScaledInputs' keywords for the derived inputs ``names`` (of DERIVED_INPUTS).

    :raises SystemExit: naming an input whose observation keys the card does not read.
    """
    keys = set(policy_card.observation_keys)
    chosen = {}
    for name in names:
        value = DERIVED_INPUTS[name]
        needed = {value['key'], value.get('lane_key', value['key'])}
        if not needed <= keys:
            raise SystemExit(f'derived input {name!r} reads the keys {sorted(needed)}; the '
                             f'policy reads {sorted(keys)}')
        chosen[name] = value
    return chosen


def train(args, policy_card, out, scenario=SCENARIO, ppo_options=None, scales=None,
          derived=()):
    """
    Train PPO within the wall-clock budget; return (model path, curve rows, episodes, facts).

    :param args: the command line's (minutes, timesteps, seed, envs, threads).
    :param scenario: the scenario judging the episodes (None: the card's environment alone).
    :param ppo_options: PPO keywords replacing PPO_OPTIONS' (a smoke test's smaller batches).
    :param scales: ScaledInputs' factors for the card's keys (None: SCALES).
    :param derived: the names of ScaledInputs' derived inputs (DERIVED_INPUTS) to add.
    """
    from stable_baselines3 import PPO
    from stable_baselines3.common.callbacks import BaseCallback
    from stable_baselines3.common.vec_env import DummyVecEnv, SubprocVecEnv
    import torch

    from vehicle_sim.gym.scaled_inputs import ScaledInputs

    torch.set_num_threads(args.threads)
    vec_cls = SubprocVecEnv if args.envs > 1 else DummyVecEnv
    every = TRAINING_TRAFFIC_EVERY
    envs = vec_cls([_EnvFactory(policy_card, scenario,
                                TRAINING_TRAFFIC if every and i % every == 1 % every else None,
                                rank=i, seed=args.seed)
                    for i in range(args.envs)])
    envs.seed(args.seed)
    model = PPO('MultiInputPolicy', envs, seed=args.seed, device='cpu', verbose=0,
                policy_kwargs=dict({'net_arch': NET_ARCH, 'log_std_init': LOG_STD_INIT,
                                    'features_extractor_class': ScaledInputs,
                                    'features_extractor_kwargs': {
                                        'scales': SCALES if scales is None else scales,
                                        **derived_inputs(policy_card, derived)}},
                                   **POLICY_OPTIONS),
                **dict(PPO_OPTIONS, **(ppo_options or {})))
    episodes, rows = [], []
    start = time.monotonic()
    budget_s = args.minutes * 60.0

    class Curve(BaseCallback):
        def _on_step(self):
            for info, done in zip(self.locals['infos'], self.locals['dones']):
                if done and 'episode' in info:
                    verdicts = info.get('criteria', {})
                    outcome = {'env_steps': self.num_timesteps,
                               'wall_s': time.monotonic() - start,
                               'return': float(info['episode']['r']),
                               'length': int(info['episode']['l']),
                               'time_s': float(info['time_s']),
                               'success': bool(verdicts) and all(
                                   v == 'passed' for v in verdicts.values()),
                               'collision': bool(info['collision']),
                               'lane_departure': verdicts.get('stay_in_lane') == 'failed'}
                    episodes.append(outcome)
            if args.timesteps and self.num_timesteps >= args.timesteps:
                return False
            return time.monotonic() - start < budget_s

        def _on_rollout_end(self):
            last = episodes[-WINDOW:]
            if last:
                rows.append({'env_steps': self.num_timesteps,
                             'wall_s': round(time.monotonic() - start, 1),
                             'episodes': len(episodes),
                             'mean_return': round(float(np.mean([e['return'] for e in last])), 3),
                             'success_rate': round(float(np.mean([e['success'] for e in last])),
                                                   3),
                             'mean_episode_s': round(float(np.mean([e['time_s'] for e in last])),
                                                     2)})
                row = rows[-1]
                print(f"{row['env_steps']:>8} steps {row['wall_s']:>7.0f} s  return "
                      f"{row['mean_return']:7.2f}  success {row['success_rate']:.2f}  "
                      f"episode {row['mean_episode_s']:.1f} s", flush=True)

    model.learn(total_timesteps=10 ** 9, callback=Curve())
    facts = {'env_steps': int(model.num_timesteps), 'train_wall_s': time.monotonic() - start,
             'episodes': len(episodes)}
    envs.close()
    model_path = out / 'model.zip'
    model.save(model_path)
    save_card(policy_card, model_path)
    return model_path, rows, episodes, facts


def _evaluate_chunk(job):
    """
    Run evaluation episodes in a worker.

    :param job: (model path, or None for the random policy; seeds; PyTorch's threads; the
        random policy's action layout, None: ENV_OPTIONS').
    """
    model_path, seeds, threads, control = job
    import torch
    torch.set_num_threads(threads)
    if model_path is None:
        policy_card, model = card(control), None
    else:
        from vehicle_sim.tools.policy_loader import load_model
        policy_card = load_card(model_path)
        model = load_model(model_path)  # PPO's model.zip, or train_highway_ray's checkpoint
    env = make_task_env(policy_card)
    outcomes = []
    for seed in seeds:
        obs, info = env.reset(seed=seed)
        env.action_space.seed(seed)
        while True:
            if model is None:
                action = env.action_space.sample()
            else:
                action, _ = model.predict(obs, deterministic=True)
            obs, _, terminated, truncated, info = env.step(action)
            if terminated or truncated:
                break
        outcomes.append(dict(episode_outcome(info, env.unwrapped.sim), seed=seed))
    env.close()
    return outcomes


def evaluate(model_path, seeds, workers, control=None):
    """
    Return the outcomes of one episode per seed.

    :param model_path: the model, or None for the random policy (in ``control``'s action
        layout, None: ENV_OPTIONS').
    """
    chunks = [seeds[i::workers] for i in range(workers)]
    context = multiprocessing.get_context('forkserver')
    with context.Pool(workers) as pool:
        parts = pool.map(_evaluate_chunk, [(model_path, chunk, 1, control) for chunk in chunks])
    return sorted((o for part in parts for o in part), key=lambda o: o['seed'])


def figures(outcomes):
    """Return the evaluation's figures: rates and mean speed over the episodes."""
    n = len(outcomes)
    mean = float(np.mean([o['mean_speed_mps'] for o in outcomes]))
    return {'episodes': n,
            'success_rate': sum(o['success'] for o in outcomes) / n,
            'collision_rate': sum(o['collision'] for o in outcomes) / n,
            'lane_departure_rate': sum(o['lane_departure'] for o in outcomes) / n,
            'mean_speed_mps': round(mean, 3),
            'mean_speed_fraction_of_limit': round(mean / LIMIT_MPS, 4),
            'mean_episode_s': round(float(np.mean([o['time_s'] for o in outcomes])), 2)}


def results_markdown(summary):
    """Return the run's figures as docs/learning.md shows them (a table, from summary.json)."""
    lines = [
        f"Seed {summary['seed']}, {summary['envs']} environments, PyTorch on "
        f"{summary['torch_threads']} thread(s): {summary['env_steps']} env steps "
        f"({summary['episodes']} training episodes) in {summary['train_wall_s'] / 60.0:.1f} "
        f"min of training; evaluation: {summary['evaluation']['trained']['episodes']} episodes "
        f"of 60 s per policy, seeds {summary['eval_seeds'][0]} .. {summary['eval_seeds'][1]}.",
        '',
        '| policy | success | collision | lane departure | mean speed [m/s] | of the limit '
        '| mean episode [s] |',
        '|---|---|---|---|---|---|---|',
    ]
    learner = summary.get('algorithm', 'PPO')      # PPO where the summary does not say
    for name, label in (('trained', f'{learner} (deterministic)'), ('random', 'random')):
        f = summary['evaluation'][name]
        lines.append(f"| {label} | {f['success_rate']:.0%} | {f['collision_rate']:.0%} | "
                     f"{f['lane_departure_rate']:.0%} | {f['mean_speed_mps']:.2f} | "
                     f"{f['mean_speed_fraction_of_limit']:.1%} | {f['mean_episode_s']:.1f} |")
    return '\n'.join(lines) + '\n'


def write_curve(out, rows, episodes):
    """Write learning_curve.csv, episodes.csv and learning_curve.png."""
    write_rows(out / 'learning_curve.csv', rows, CURVE_FIELDS)
    if episodes:
        write_rows(out / 'episodes.csv', episodes)
    plot_curve(out / 'learning_curve.png', rows,
               'PPO on Drive-v0, highway_traffic (training episodes, stochastic policy)',
               WINDOW, steps_label='environment steps (0.2 s each)')


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--minutes', type=float, default=30.0,
                        help='wall-clock budget of the training [min]')
    parser.add_argument('--timesteps', type=int, default=0,
                        help='stop after this many env steps too (0: the budget only)')
    parser.add_argument('--seed', type=int, default=0)
    parser.add_argument('--envs', type=int, default=8, help='environments (processes)')
    parser.add_argument('--threads', type=int, default=1, help="PyTorch's CPU threads")
    parser.add_argument('--eval-episodes', type=int, default=100,
                        help='evaluation episodes per policy (0: none)')
    parser.add_argument('--eval-workers', type=int, default=2)
    parser.add_argument('--evaluate', metavar='MODEL',
                        help='evaluate this model.zip (with its card) instead of training')
    parser.add_argument('--out', default='train_highway_out')
    parser.add_argument('--derived-inputs', nargs='*', default=[], choices=sorted(DERIVED_INPUTS),
                        metavar='NAME',
                        help='inputs the policy derives from the objects table: '
                             f'{", ".join(sorted(DERIVED_INPUTS))} (default: none)')
    parser.add_argument('--control', default=ENV_OPTIONS['control'],
                        choices=SPEED_CONTROLS,
                        help='the action layout (docs/gym.md, Actions; default: %(default)s)')
    args = parser.parse_args(argv)
    try:
        import vehicle_sim.gym.learn_require  # noqa: F401
    except ImportError as error:
        raise SystemExit(str(error)) from None
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    summary = {'algorithm': 'PPO', 'seed': args.seed, 'minutes': args.minutes, 'envs': args.envs,
               'torch_threads': args.threads, 'cpu_count': os.cpu_count(),
               'env_id': ENV_ID, 'env_options': card(args.control).options,
               'scenario': SCENARIO.name,
               'observation_keys': list(OBSERVATION_KEYS), 'scales': SCALES,
               'ppo': dict(PPO_OPTIONS, net_arch=NET_ARCH, log_std_init=LOG_STD_INIT,
                           **POLICY_OPTIONS)}
    if args.derived_inputs:
        summary['derived_inputs'] = derived_inputs(card(args.control), args.derived_inputs)
    if TRAINING_TRAFFIC_EVERY:
        summary['training_traffic'] = dict(TRAINING_TRAFFIC, every=TRAINING_TRAFFIC_EVERY)
    if args.evaluate:
        model_path = Path(args.evaluate)
    else:
        model_path, rows, episodes, facts = train(args, card(args.control), out,
                                                  derived=args.derived_inputs)
        write_curve(out, rows, episodes)
        summary.update(facts)
        summary['final_training_row'] = rows[-1] if rows else None
        print(f"trained {facts['env_steps']} env steps ({facts['episodes']} episodes) in "
              f"{facts['train_wall_s']:.0f} s; model {model_path}", flush=True)
    if args.eval_episodes <= 0:         # training only (a reproducibility check)
        (out / 'summary.json').write_text(json.dumps(summary, indent=2) + '\n',
                                          encoding='utf-8')
        return
    seeds = [EVAL_SEED_BASE + k for k in range(args.eval_episodes)]
    start = time.monotonic()
    # the random policy in the trained one's action layout
    control = load_card(model_path).options.get('control')
    results = {'trained': evaluate(str(model_path), seeds, args.eval_workers),
               'random': evaluate(None, seeds, args.eval_workers, control)}
    summary['eval_wall_s'] = round(time.monotonic() - start, 1)
    summary['eval_seeds'] = [seeds[0], seeds[-1]]
    summary['evaluation'] = {name: figures(outcomes) for name, outcomes in results.items()}
    summary['target'] = {'success_rate': 0.9, 'mean_speed_fraction_of_limit': MIN_MEAN_FRACTION}
    write_evaluation(out / 'evaluation.csv', results)
    (out / 'summary.json').write_text(json.dumps(summary, indent=2) + '\n', encoding='utf-8')
    for name, values in summary['evaluation'].items():
        print(f"{name:>8}: success {values['success_rate']:.2f}, collision "
              f"{values['collision_rate']:.2f}, lane departure "
              f"{values['lane_departure_rate']:.2f}, mean speed {values['mean_speed_mps']:.2f} "
              f"m/s ({values['mean_speed_fraction_of_limit']:.1%} of the limit), episode "
              f"{values['mean_episode_s']:.1f} s")
    print(f"evaluation: {len(seeds)} episodes each in {summary['eval_wall_s']:.0f} s; "
          f'files in {out}')


if __name__ == '__main__':
    main()
