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
Train RLlib's PPO on train_highway.py's task, the highway with traffic, on Ray (docs/learning.md).

The task is examples/train_highway.py's, taken from it, not copied: its policy card
(``train_highway.card()``: ``vehicle_sim/Drive-v0`` in the traffic of
config/worlds/highway_traffic.yaml, its observation keys, reward weights, action bounds and
rate) and its scenario (``train_highway.make_task_env``: scenarios/highway_policy.yaml judges
every episode: 60 s, no collision, on the road, a mean speed of at least 80 % of the limit), so
that the returns, success rates and evaluations of the two scripts are on one scale. The
environment is registered with Ray's tune registry. Everything of learning is Ray's: RLlib's
PPO (torch, on the CPU), its EnvRunners (one per CPU of the Ray cluster by default, each a
process with its own worlds), its connectors (``FlattenObservations`` of the Dict,
``MeanStdFilter`` scaling the physical-unit inputs), its metrics, its checkpoint.

Needs the ``learn-ray`` extra: ``pip install 'vehicle_sim[learn-ray]'`` (Ray's RLlib and
PyTorch; a CPU build of PyTorch: docs/learning.md).
Run: ``python examples/train_highway_ray.py --budget-s 600 --seed 0 --out DIR``. It starts Ray on
this machine (``ray.init()``, shut down at the end) unless ``--address`` names a running cluster
(``auto``, ``head:6379``, ``ray://head:10001``). It trains until the wall-clock budget is spent
(or ``--iterations``), then writes ``DIR/learning_curve.csv`` (one row per training iteration:
environment steps, wall time, the mean return, length and success rate of the last
``--window`` episodes), ``DIR/learning_curve.png`` with matplotlib, ``DIR/checkpoint`` (RLlib's
``Algorithm.save_to_path``) and ``DIR/checkpoint.card.json`` (the policy card:
``vehicle-sim policy run DIR/checkpoint`` drives a node with it), and evaluates the trained
policy (deterministic) beside a random one as train_highway.py does (``--eval-episodes``:
its seeds, its criteria, its figures) into ``DIR/evaluation.csv`` and ``DIR/summary.json``
(``--evaluate-only``: that evaluation alone, of the finished run in ``DIR``).
"""

import argparse
import json
import math
import os
from pathlib import Path
import sys
import time

from vehicle_sim.gym.learning_curve import plot_curve, write_evaluation, write_rows
from vehicle_sim.gym.policy_card import PolicyCard, save_card

EXAMPLES = Path(__file__).resolve().parent
if str(EXAMPLES) not in sys.path:       # the task's module beside this script
    sys.path.insert(0, str(EXAMPLES))
import train_highway  # noqa: E402  (the task: its card, scenario, evaluation)

ENV_NAME = 'vehicle_sim_highway'
LEARN_RAY_HINT = ("pip install 'vehicle_sim[learn-ray]' (Ray's RLlib and PyTorch; a CPU build of "
                  'PyTorch: docs/learning.md)')
# env steps per PPO update: train_highway's, 256 steps in each of its 8 environments
BATCH = 2048
CURVE_FIELDS = ('iteration', 'env_steps', 'wall_s', 'episodes', 'mean_return', 'mean_length',
                'success_rate')


def require_rllib():
    """Import Ray's RLlib and PyTorch; raise ImportError naming the ``learn-ray`` extra."""
    try:
        import ray
        from ray.rllib.algorithms.ppo import PPOConfig
        import torch
    except ImportError as error:
        raise ImportError(f'training on Ray needs RLlib and PyTorch ({error.name} is missing): '
                          f'{LEARN_RAY_HINT}') from error
    return ray, PPOConfig, torch


def episode_success(last_info):
    """
    Return whether an episode met the scenario's criteria, from its last info.

    Every criterion of the scenario must have passed (``info['criteria']``); a criterion
    still undecided when the episode ended (a collision or a lane departure ended it first)
    counts as not met.
    """
    verdicts = last_info.get('criteria') or {}
    return bool(verdicts) and all(v == 'passed' for v in verdicts.values())


def _callbacks_class(window):
    from ray.rllib.callbacks.callbacks import RLlibCallback

    class SuccessRate(RLlibCallback):
        """Log each episode's success (:func:`episode_success`) beside RLlib's returns."""

        def on_episode_end(self, *, episode, metrics_logger=None, **kwargs):
            metrics_logger.log_value(
                'success_rate', float(episode_success(episode.get_infos(-1))),
                reduce='mean', window=window)

    return SuccessRate


def env_config(card):
    """Return the EnvRunners' ``env_config`` of a card: its fields (:func:`_task_env` reads)."""
    return {'env_id': card.env_id, 'options': dict(card.options),
            'observation_keys': tuple(card.observation_keys),
            'action_range': tuple(card.action_range)}


def _task_env(config, make_task_env=train_highway.make_task_env):
    """Return the task's environment of the card in ``config``, judged by the scenario."""
    return make_task_env(PolicyCard(**config))


def make_config(card, seed, runners, envs_per_runner=1, batch=BATCH, window=20):
    """
    Return RLlib's PPOConfig for the card's environment (registered as ``ENV_NAME``).

    :param runners: EnvRunner processes (0 = sample in this process).
    :param envs_per_runner: worlds per EnvRunner (a Gymnasium vector env in each).
    :param batch: environment steps per training iteration.
    :param window: episodes that the curve's means and success rate are taken over.
    """
    ray, PPOConfig, _ = require_rllib()
    from ray.rllib.connectors.env_to_module import FlattenObservations, MeanStdFilter
    from ray.rllib.core.rl_module.default_model_config import DefaultModelConfig
    from ray.tune.registry import register_env

    # the task's env maker travels to the EnvRunners by value: they need not import the
    # examples folder (a cluster's machines, Ray Client)
    ray.cloudpickle.register_pickle_by_value(train_highway)
    register_env(ENV_NAME, _task_env)
    ppo = train_highway.PPO_OPTIONS
    return (PPOConfig()
            .environment(ENV_NAME, env_config=env_config(card))
            .framework('torch')
            .env_runners(num_env_runners=runners, num_envs_per_env_runner=envs_per_runner,
                         num_cpus_per_env_runner=1,
                         # wait for every EnvRunner's steps: RLlib's default (60 s) drops the
                         # samples of an EnvRunner slower than that, on a loaded machine all
                         sample_timeout_s=None,
                         env_to_module_connector=lambda env, spaces=None, device=None: [
                             FlattenObservations(), MeanStdFilter()])
            .learners(num_learners=0, num_gpus_per_learner=0)
            # train_highway's PPO settings, in RLlib's names
            .training(train_batch_size_per_learner=batch,
                      minibatch_size=min(ppo['batch_size'], batch), num_epochs=ppo['n_epochs'],
                      lr=ppo['learning_rate'], gamma=ppo['gamma'], lambda_=ppo['gae_lambda'],
                      clip_param=ppo['clip_range'], entropy_coeff=ppo['ent_coef'])
            .rl_module(model_config=DefaultModelConfig(fcnet_hiddens=list(train_highway.NET_ARCH),
                                                       fcnet_activation='tanh'))
            .callbacks(_callbacks_class(window))
            .reporting(metrics_num_episodes_for_smoothing=window)
            .debugging(seed=seed))


def _row(iteration, result, wall_s):
    runners = result.get('env_runners', {})
    return {'iteration': iteration,
            'env_steps': int(result.get('num_env_steps_sampled_lifetime',
                                        runners.get('num_env_steps_sampled_lifetime', 0))),
            'wall_s': round(wall_s, 2),
            'episodes': int(runners.get('num_episodes_lifetime', 0)),
            'mean_return': float(runners.get('episode_return_mean', math.nan)),
            'mean_length': float(runners.get('episode_len_mean', math.nan)),
            'success_rate': float(runners.get('success_rate', math.nan))}


def train(out, budget_s=600.0, seed=0, runners=None, envs_per_runner=1, batch=BATCH,
          window=20, iterations=None, address=None, card=None, log=print):
    """
    Train PPO on Ray until ``budget_s`` of wall time (or ``iterations``) is spent.

    :param runners: EnvRunners; None = one per CPU of the Ray cluster.
    :param address: a running Ray cluster to join; None = start Ray on this machine.
    :return: (curve, facts): the learning curve, a list of :data:`CURVE_FIELDS` dicts (also
        written to ``out/learning_curve.csv``), and {runners, cluster_cpus, setup_s (Ray's
        start and the algorithm's build), load_start, load_mean (over the iterations),
        load_end (the machine's 1-minute load averages)}.
    """
    ray, _, _ = require_rllib()
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    card = card or train_highway.card()
    facts = {'load_start': round(os.getloadavg()[0], 2)}
    setup_start = time.perf_counter()
    started_here = not ray.is_initialized()
    if started_here:
        if address:
            ray.init(address=address, log_to_driver=False)
        else:
            ray.init(num_cpus=max(os.cpu_count() or 1, runners or 0), include_dashboard=False,
                     log_to_driver=False)
    algo = None
    try:
        cluster_cpus = int(ray.cluster_resources().get('CPU', 1))
        if runners is None:
            runners = max(1, cluster_cpus)
        algo = make_config(card, seed, runners, envs_per_runner, batch, window).build_algo()
        facts.update(runners=runners, cluster_cpus=cluster_cpus,
                     setup_s=round(time.perf_counter() - setup_start, 1))
        curve, loads = [], []       # loads: the 1-minute load average after each iteration
        start = time.perf_counter()
        while True:
            result = algo.train()
            row = _row(len(curve) + 1, result, time.perf_counter() - start)
            curve.append(row)
            loads.append(os.getloadavg()[0])
            write_rows(out / 'learning_curve.csv', curve, CURVE_FIELDS)
            log(f"iteration {row['iteration']}: {row['env_steps']} env steps in "
                f"{row['wall_s']:.0f} s, return {row['mean_return']:.2f}, length "
                f"{row['mean_length']:.1f}, success {row['success_rate']:.2f}")
            if (iterations is not None and len(curve) >= iterations) \
                    or row['wall_s'] >= budget_s:
                break
        facts['load_end'] = round(os.getloadavg()[0], 2)
        facts['load_mean'] = round(sum(loads) / len(loads), 2)
        checkpoint = out / 'checkpoint'
        # absolute: RLlib takes a relative path for a URI without a scheme (pyarrow refuses it)
        algo.save_to_path(str(checkpoint.resolve()))
        save_card(card, checkpoint)
        return curve, facts
    finally:
        if algo is not None:
            algo.stop()
        if started_here:
            ray.shutdown()


def evaluate(out, episodes, workers):
    """
    Evaluate the trained policy (deterministic) and a random one as train_highway.py does.

    train_highway's ``evaluate`` on its seeds (``EVAL_SEED_BASE`` ..), judged by its scenario,
    summed up by its ``figures``; the checkpoint is read by vehicle_sim's policy loader, as
    ``vehicle-sim policy run`` reads it. Writes ``out/evaluation.csv``; returns the summary's
    evaluation entries.
    """
    seeds = [train_highway.EVAL_SEED_BASE + k for k in range(episodes)]
    start = time.perf_counter()
    results = {'trained': train_highway.evaluate(str(out / 'checkpoint'), seeds, workers),
               'random': train_highway.evaluate(None, seeds, workers)}
    write_evaluation(out / 'evaluation.csv', results)
    evaluation = {name: train_highway.figures(outcomes) for name, outcomes in results.items()}
    for name, values in evaluation.items():
        print(f"{name:>8}: success {values['success_rate']:.2f}, collision "
              f"{values['collision_rate']:.2f}, lane departure "
              f"{values['lane_departure_rate']:.2f}, mean speed {values['mean_speed_mps']:.2f} "
              f"m/s ({values['mean_speed_fraction_of_limit']:.1%} of the limit)", flush=True)
    return {'eval_seeds': [seeds[0], seeds[-1]],
            'eval_wall_s': round(time.perf_counter() - start, 1), 'evaluation': evaluation}


MARKS_S = (60.0, 120.0, 300.0, 600.0, 1200.0, 1800.0)


def run_summary(args, curve, facts):
    """Return the run's summary (summary.json): its settings, throughput and curve marks."""
    last = curve[-1]
    # the first iteration at or past each wall-time mark, and the last
    marks = []
    for mark in MARKS_S:
        row = next((row for row in curve if row['wall_s'] >= mark), last)
        if row not in marks:
            marks.append(row)
    if marks[-1] is not last:
        marks.append(last)
    return dict(facts, seed=args.seed, budget_s=args.budget_s,
                envs_per_runner=args.envs_per_runner, batch=args.batch, window=args.window,
                card=train_highway.card().as_dict(), scenario=train_highway.SCENARIO.name,
                cpu_count=os.cpu_count(),
                env_steps=last['env_steps'], episodes=last['episodes'],
                train_wall_s=last['wall_s'],
                env_steps_per_s=round(last['env_steps'] / max(last['wall_s'], 1e-9), 2),
                marks=marks)


def _figure(value, digits=2):
    return 'n/a' if value is None or (isinstance(value, float) and math.isnan(value)) \
        else f'{value:.{digits}f}'


def results_markdown(summary):
    """Return the run's figures as docs/learning.md shows them (from summary.json)."""
    lines = [
        f"Seed {summary['seed']}, {summary['runners']} EnvRunner(s) x "
        f"{summary['envs_per_runner']} world(s) on a Ray cluster of {summary['cluster_cpus']} "
        f"CPU(s), PyTorch on the CPU, {summary['batch']} env steps per iteration: "
        f"{summary['env_steps']} env steps ({summary['episodes']} episodes) in "
        f"{summary['train_wall_s'] / 60.0:.1f} min of training, "
        f"{summary['env_steps_per_s']:.1f} env steps/s (Ray's start and the build before it: "
        f"{summary['setup_s']:.0f} s). Load average {summary['load_start']:.1f} at the start, "
        f"{summary['load_mean']:.1f} on average over the iterations, {summary['load_end']:.1f} "
        f"at the end, on {summary['cpu_count']} CPUs.",
        '',
        '| after [min] | env steps | env steps/s | mean return | mean length [steps] '
        '| success rate |',
        '|---|---|---|---|---|---|',
    ]
    for row in summary['marks']:
        lines.append(f"| {row['wall_s'] / 60.0:.1f} | {row['env_steps']} | "
                     f"{row['env_steps'] / max(row['wall_s'], 1e-9):.1f} | "
                     f"{_figure(row['mean_return'])} | {_figure(row['mean_length'], 1)} | "
                     f"{_figure(row['success_rate'])} |")
    evaluation = summary.get('evaluation')
    if evaluation:
        first, last = summary['eval_seeds']
        lines += [
            '',
            f"Evaluation (train_highway's): {evaluation['trained']['episodes']} episodes of 60 s "
            f'per policy, seeds {first} .. {last}, in {summary["eval_wall_s"] / 60.0:.1f} min.',
            '',
            '| policy | success | collision | lane departure | mean speed [m/s] | of the limit '
            '| mean episode [s] |',
            '|---|---|---|---|---|---|---|',
        ]
        for name, label in (('trained', 'RLlib PPO (deterministic)'), ('random', 'random')):
            f = evaluation[name]
            lines.append(f"| {label} | {f['success_rate']:.0%} | {f['collision_rate']:.0%} | "
                         f"{f['lane_departure_rate']:.0%} | {f['mean_speed_mps']:.2f} | "
                         f"{f['mean_speed_fraction_of_limit']:.1%} | "
                         f"{f['mean_episode_s']:.1f} |")
    return '\n'.join(lines) + '\n'


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[1].split('\n')[0])
    parser.add_argument('--budget-s', type=float, default=600.0,
                        help='wall-clock budget of training [s] (default 600)')
    parser.add_argument('--iterations', type=int, default=None,
                        help='stop after this many training iterations (default: the budget)')
    parser.add_argument('--seed', type=int, default=0)
    parser.add_argument('--runners', type=int, default=None,
                        help="EnvRunner processes (default: the Ray cluster's CPU count)")
    parser.add_argument('--envs-per-runner', type=int, default=1)
    parser.add_argument('--batch', type=int, default=BATCH,
                        help=f'environment steps per training iteration (default {BATCH})')
    parser.add_argument('--window', type=int, default=20,
                        help='episodes the means and the success rate are taken over')
    parser.add_argument('--eval-episodes', type=int, default=100,
                        help="evaluation episodes per policy, train_highway.py's (0: none)")
    parser.add_argument('--eval-workers', type=int, default=2)
    parser.add_argument('--address', default=None,
                        help='a running Ray cluster (auto, head:6379, ray://head:10001); '
                             'default: start Ray on this machine')
    parser.add_argument('--evaluate-only', action='store_true',
                        help='evaluate the finished run in --out (its checkpoint) instead of '
                             'training; its summary.json gets the evaluation')
    parser.add_argument('--out', default='ppo_highway_ray')
    args = parser.parse_args(argv)
    for name in ('budget_s', 'iterations', 'runners', 'envs_per_runner', 'batch', 'window',
                 'eval_episodes', 'eval_workers'):
        value = getattr(args, name)
        at_least_0 = name in ('runners', 'eval_episodes')
        if value is not None and not value > (-1 if at_least_0 else 0):
            parser.error(f"--{name.replace('_', '-')} {value}: must be "
                         f"{'>= 0' if at_least_0 else '> 0'}")
    out = Path(args.out)
    if args.evaluate_only:
        if not args.eval_episodes:
            parser.error('--evaluate-only with --eval-episodes 0: nothing to do')
        if not (out / 'checkpoint').is_dir():
            parser.error(f"--evaluate-only: {out / 'checkpoint'}: no such checkpoint (a run's "
                         '--out folder is expected)')
    try:
        require_rllib()
    except ImportError as error:
        raise SystemExit(str(error)) from None
    if args.evaluate_only:
        path = out / 'summary.json'
        summary = json.loads(path.read_text(encoding='utf-8')) if path.is_file() else {}
        summary.update(evaluate(out, args.eval_episodes, args.eval_workers))
        path.write_text(json.dumps(summary, indent=2) + '\n', encoding='utf-8')
        return
    curve, facts = train(args.out, args.budget_s, args.seed, args.runners,
                         args.envs_per_runner, args.batch, args.window, args.iterations,
                         args.address, train_highway.card())
    summary = run_summary(args, curve, facts)
    Path(args.out, 'summary.json').write_text(json.dumps(summary, indent=2) + '\n',
                                              encoding='utf-8')
    last = curve[-1]
    print(f"{last['env_steps']} env steps in {last['wall_s']:.0f} s "
          f"({last['env_steps'] / max(last['wall_s'], 1e-9):.1f} env steps/s); last "
          f"{args.window} episodes: return {last['mean_return']:.2f}, success rate "
          f"{last['success_rate']:.2f}; files in {args.out}")
    # without matplotlib the PNG is skipped, saying so (vehicle_sim/gym/learning_curve.py)
    plot_curve(os.path.join(args.out, 'learning_curve.png'), curve,
               'RLlib PPO on Drive-v0, highway_traffic (training episodes)', args.window)
    if args.eval_episodes:
        summary.update(evaluate(Path(args.out), args.eval_episodes, args.eval_workers))
        Path(args.out, 'summary.json').write_text(json.dumps(summary, indent=2) + '\n',
                                                  encoding='utf-8')


if __name__ == '__main__':
    main()
