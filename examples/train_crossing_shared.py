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
Train one PPO policy shared by the 4 agents of a crossing, then evaluate it (docs/learning.md).

The task: config/worlds/crossing4.yaml, two streets crossing without signals, a car on each arm
36 m from the centre (a Tesla Model 3, a BMW X5, a Toyota Prius and a Citroen C-Zero: four
accelerations), all four agents of vehicle_sim.gym.multi's PettingZoo ParallelEnv, each driving
straight across. An agent that collides leaves; the episode lasts 10 s. A **success** is all
four cars through the crossing (base_link 12 m past its centre) without a collision.

Parameter sharing: PettingZoo's env becomes a vector env with one slot per agent
(SuperSuit's ``pettingzoo_env_to_vec_env_v1``), several worlds are concatenated in processes
(SuperSuit's ``concat_vec_envs_v1`` constructor) and stable-baselines3's PPO learns one policy
from every agent's steps. Agents that left get zero observations and rewards until the world's
episode ends (SuperSuit's ``black_death``, here with the fix of its released version's done test:
:class:`BlackDeath`).

Each agent sees its lane state, its twist, the other three cars as a Kinematics table
(``agents``: :class:`AgentsPart`) and the crossing's centre in its own frame (``crossing``),
scaled inside the policy (vehicle_sim/gym/scaled_inputs.py). Actions: steering within +-0.1 rad
and cruising speed 0 .. 10 m/s, rescaled to [-1, 1], at 5 Hz. Reward (Drive-v0's terms, weights
in ENV_OPTIONS): 0.1 per metre along the lanes, -10 for a collision (which also ends the
agent's episode), -2 per second off the lanes, -0.3 per second times the distance from the
lane's centre over half its width. The cars are moved by Autoware's DELAY_STEER_ACC model
(docs/physics.md, ``vehicle_model:``) at 100 ms steps, several times cheaper than the physics car;
``--vehicle-model none`` trains on the physics car (10 ms steps).

Run: ``python examples/train_crossing_shared.py [--minutes 15] [--seed 0] [--out DIR]``; it
writes ``DIR/learning_curve.csv`` (a row per PPO update: agent steps, world steps, wall time,
mean return per agent, success and collision rates of the last 50 training episodes),
``DIR/learning_curve.png``, ``DIR/model.zip`` and ``DIR/summary.json`` with an evaluation of the
trained policy (deterministic) beside a random one on seeds disjoint from training's: success
rate, collision rate, each agent's mean return and share through the crossing.
Needs the ``learn`` extra (stable-baselines3, PyTorch, SuperSuit) and PettingZoo (``multi``).
"""

import argparse
import json
import math
import multiprocessing
import os
from pathlib import Path
import time

import numpy as np
import yaml

from vehicle_sim.core.learning.objects_table import Neighbour, objects_table, ObjectsTableSpec
from vehicle_sim.gym import learning_curve as lc

ROOT = Path(__file__).resolve().parents[1]
WORLD_FILE = ROOT / 'config' / 'worlds' / 'crossing4.yaml'
AGENTS = 4
VEHICLE_MODEL = 'DELAY_STEER_ACC'
THROUGH_M = 48.0        # along its start heading: base_link 12 m past the crossing's centre
CENTRE = (0.0, 0.0)     # the crossing's centre (crossing4.yaml)
ENV_OPTIONS = {
    'action_repeat': 2,                 # 0.2 s per action at 100 ms steps: 5 Hz decisions
    'time_step_ms': 100,
    'max_episode_s': 10.0,
    'max_speed': 10.0,                  # m/s (the limit is 13.9): 10 s stay on the road
    'max_reverse_speed': 0.0,
    'max_steering': 0.1,                # rad
    'start_noise': (1.0, 1.0, 0.03),    # m, m, rad (world axes): along and across the lane
    'progress_weight': 0.1,             # 4.8 for crossing
    'collision_penalty': 10.0,
    'off_lane_penalty': 2.0,
    'lane_centre_penalty': 0.3,
}
PHYSICS_OPTIONS = {'action_repeat': 20, 'time_step_ms': 10}     # --vehicle-model none
TABLE = ObjectsTableSpec(count=AGENTS - 1, range_m=60.0, speed_scale_mps=20.0)
OBSERVATION_KEYS = ('lane', 'twist', 'agents', 'crossing')
# Input factors (ScaledInputs): each entry to about [-1, 1] where it matters.
SCALES = {
    # s [m], offset [m], heading error [rad], width [m], speed limit [m/s], on_lane
    'lane': [1.0 / 50.0, 1.0 / 1.75, 5.0, 1.0 / 3.5, 1.0 / 13.9, 1.0],
    # forward [m/s], left [m/s], yaw rate [rad/s]
    'twist': [0.1, 1.0, 2.0],
    # presence, x, y (over 60 m), vx, vy (over 20 m/s), cos_h, sin_h
    'agents': [1.0, 2.0, 2.0, 2.0, 2.0, 1.0, 1.0],
    # the crossing's centre in the agent's axes, over 60 m
    'crossing': [2.0, 2.0],
}
PPO_OPTIONS = {
    'n_steps': 64, 'batch_size': 256, 'n_epochs': 10, 'learning_rate': 3e-4, 'gamma': 0.99,
    'gae_lambda': 0.95, 'clip_range': 0.2, 'ent_coef': 0.0,
}
NET_ARCH = [64, 64]
LOG_STD_INIT = -0.5
EVAL_SEED_BASE = 1_000_000      # evaluation seeds: EVAL_SEED_BASE + k; training's: seed + world
WINDOW = 50                     # training episodes (worlds) per curve point
# The columns of learning_curve.csv.
CURVE_FIELDS = ['agent_steps', 'world_steps', 'wall_s', 'episodes', 'mean_return',
                'success_rate', 'collision_rate']


def crossing_world(vehicle_model=VEHICLE_MODEL):
    """Return crossing4.yaml as a mapping, each car moved by ``vehicle_model`` (None: physics)."""
    world = yaml.safe_load(WORLD_FILE.read_text(encoding='utf-8'))
    if vehicle_model is not None:
        for vehicle in world['vehicles']:
            vehicle['vehicle_model'] = vehicle_model
    return world


class AgentsPart:
    """
    The other agents' cars as a Kinematics table (``agents``) and the crossing's centre.

    An observation part (vehicle_sim/gym/observations.py) of one agent: the objects table of
    core/learning/objects_table.py over the other agents' cars (those that left too: they stay
    where they stopped), and ``crossing``, the centre of the crossing in the agent's axes over
    the table's range. ``sim`` is set once the environment is built (:func:`make_crossing_env`).
    """

    def __init__(self, name):
        self.name = name
        self.sim = None

    def spaces(self):
        return {'agents': (-1.0, 1.0, TABLE.shape, np.float32),
                'crossing': (-np.inf, np.inf, (2,), np.float32)}

    def reset(self):
        pass

    def read(self, out):
        egos = self.sim.egos
        body = egos[self.name].body
        x, y, yaw = egos[self.name].state()
        (vx, vy, _), _ = body.world.base_link_velocity(body.body_id, body.pose()[:3])
        c, s = math.cos(yaw), math.sin(yaw)
        others = [Neighbour(*ego.state(), ego.body.forward_speed_mps())
                  for name, ego in egos.items() if name != self.name]
        out['agents'] = objects_table(TABLE, x, y, yaw, c * vx + s * vy, -s * vx + c * vy,
                                      others)
        dx, dy = CENTRE[0] - x, CENTRE[1] - y
        out['crossing'] = np.array(((c * dx + s * dy) / TABLE.range_m,
                                    (-s * dx + c * dy) / TABLE.range_m), dtype=np.float32)


def task_options(vehicle_model=VEHICLE_MODEL, options=None):
    """Return the environment's options: ENV_OPTIONS (physics: its steps), then ``options``."""
    return dict(ENV_OPTIONS, **({} if vehicle_model is not None else PHYSICS_OPTIONS),
                **(options or {}))


def make_crossing_env(vehicle_model=VEHICLE_MODEL, options=None):
    """
    Return the 4 agents' MultiDriveEnv of the task, with :class:`AgentsPart` on each.

    :param options: environment options replacing the task's (:func:`task_options`).
    """
    from vehicle_sim.gym.multi import MultiDriveEnv

    parts = {}

    def observation_parts(name):
        parts[name] = AgentsPart(name)
        return [parts[name]]

    env = MultiDriveEnv(world=crossing_world(vehicle_model), agents=AGENTS,
                        observation_parts=observation_parts,
                        **task_options(vehicle_model, options))
    for part in parts.values():
        part.sim = env.sim
    return env


def through(env, agent):
    """Return whether an agent's car is through the crossing (THROUGH_M along its start)."""
    ego = env.unwrapped.sim.egos[agent]
    x0, y0, yaw0 = ego.body.spawn[:3]
    x, y, _ = ego.state()
    return (x - x0) * math.cos(yaw0) + (y - y0) * math.sin(yaw0) >= THROUGH_M


def _keep_keys(obs, space, agent):
    return {key: obs[key] for key in OBSERVATION_KEYS}


def _keep_spaces(space, agent):
    from gymnasium.spaces import Dict
    return Dict({key: space[key] for key in OBSERVATION_KEYS})


def _from_unit(action, space, agent):
    # [-1, 1] -> the agent's Box (steering, speed)
    unit = np.clip(np.asarray(action, dtype=np.float32), -1.0, 1.0)
    return (space.low + 0.5 * (unit + 1.0) * (space.high - space.low)).astype(np.float32)


def _unit_space(space, agent):
    from gymnasium.spaces import Box
    return Box(-1.0, 1.0, space.shape, np.float32)


def policy_env(vehicle_model=VEHICLE_MODEL, options=None):
    """Return the task's ParallelEnv as the policy sees it: its keys, actions in [-1, 1]."""
    import supersuit

    env = make_crossing_env(vehicle_model, options)
    env = supersuit.observation_lambda_v0(env, _keep_keys, _keep_spaces)
    return supersuit.action_lambda_v1(env, _from_unit, _unit_space)


def black_death_class():
    """
    Return :class:`BlackDeath`: SuperSuit's black_death for this task (imported lazily).

    SuperSuit 3.11.0 (its latest release) ends the world's episode only when every agent is
    terminated *and* truncated at once; fixed upstream (Farama-Foundation/SuperSuit#265, an
    OR), not released. When the last agents are truncated at the time limit, no slot is done:
    on MultiDriveEnv itself the next step then raises (every agent has left), behind the
    lambda wrappers it ends the world a step late, on a step of zero observations for every
    slot, the time limit's truncation lost. It also takes Box observations only; an agent that
    left reads zeros of each key of the Dict here.
    """
    from supersuit.multiagent_wrappers.black_death import black_death_par

    class BlackDeath(black_death_par):
        def _check_valid_for_black_death(self):
            pass

        def _zeros(self, agent):
            return {key: np.zeros(space.shape, space.dtype)
                    for key, space in self.observation_space(agent).spaces.items()}

        def step(self, actions):
            active = {agent: actions[agent] for agent in self.env.agents}
            obs, rewards, terms, truncs, infos = self.env.step(active)
            for agent in obs:
                infos[agent]['through'] = through(self.env, agent)
            for agent in self.agents:
                if agent not in obs:
                    obs[agent], rewards[agent], infos[agent] = self._zeros(agent), 0.0, {}
            done = all(terms[a] or truncs[a] for a in terms)
            dones = {agent: done for agent in self.agents}
            if done:
                self.agents = []
            return obs, rewards, dones, dict(dones), infos

    return BlackDeath


class _WorldFactory:
    """A world of the vector env: the policy env, seeded, zeroing agents that left."""

    def __init__(self, seed, vehicle_model, options=None):
        self.seed = seed
        self.vehicle_model = vehicle_model
        self.options = options

    def __call__(self):
        import supersuit
        env = black_death_class()(policy_env(self.vehicle_model, self.options))
        env.reset(seed=self.seed)       # later resets draw from this generator
        return supersuit.pettingzoo_env_to_vec_env_v1(env)


def train(args, out, ppo_options=None, env_options=None):
    """
    Train the shared policy within the budget; return (model path, curve rows, episodes, facts).

    :param args: the command line's (minutes, timesteps, seed, worlds, processes, threads,
        vehicle_model).
    :param ppo_options: PPO keywords replacing PPO_OPTIONS' (a smoke test's smaller batches).
    :param env_options: environment options replacing the task's (a smoke test's shorter
        episodes).
    """
    from stable_baselines3 import PPO
    from stable_baselines3.common.callbacks import BaseCallback
    from stable_baselines3.common.vec_env import VecMonitor
    from supersuit.vector import MakeCPUAsyncConstructor
    from supersuit.vector.sb3_vector_wrapper import SB3VecEnvWrapper
    import torch

    from vehicle_sim.gym.scaled_inputs import ScaledInputs

    torch.set_num_threads(args.threads)
    # SuperSuit's concat_vec_envs_v1 copies one built world by pickling it (a physics client
    # does not pickle); its constructor takes a factory per world instead.
    factories = [_WorldFactory(args.seed + i, args.vehicle_model, env_options)
                 for i in range(args.worlds)]
    probe = factories[0]()
    spaces = probe.observation_space, probe.action_space
    names = list(probe.par_env.possible_agents)
    probe.close()
    concat = MakeCPUAsyncConstructor(args.processes)(factories, *spaces)

    class SeededWorlds(SB3VecEnvWrapper):
        # PPO(seed=...) calls the VecEnv's seed(), which SuperSuit's concatenated worlds lack
        # (an AttributeError): the worlds were seeded when built (seed + world), and each
        # reset after draws from its world's generator.
        def seed(self, seed=None):
            return [None] * self.num_envs

    envs = VecMonitor(SeededWorlds(concat))
    model = PPO('MultiInputPolicy', envs, seed=args.seed, device='cpu', verbose=0,
                policy_kwargs={'net_arch': NET_ARCH, 'log_std_init': LOG_STD_INIT,
                               'features_extractor_class': ScaledInputs,
                               'features_extractor_kwargs': {'scales': SCALES}},
                **dict(PPO_OPTIONS, **(ppo_options or {})))
    episodes, rows = [], []
    start = time.monotonic()
    budget_s = args.minutes * 60.0
    slots = AGENTS * args.worlds

    class Curve(BaseCallback):
        def _on_training_start(self):
            self.returns = [None] * slots
            self.crashed = [False] * slots
            self.passed = [False] * slots

        def _on_step(self):
            infos, dones = self.locals['infos'], self.locals['dones']
            for slot, info in enumerate(infos):
                self.crashed[slot] |= bool(info.get('collision', False))
                self.passed[slot] |= bool(info.get('through', False))
                if dones[slot]:
                    self.returns[slot] = float(info['episode']['r'])
            for world in range(args.worlds):
                group = range(world * AGENTS, (world + 1) * AGENTS)
                if not all(dones[s] for s in group):
                    continue
                episode = {'agent_steps': self.num_timesteps,
                           'wall_s': round(time.monotonic() - start, 1),
                           'success': all(self.passed[s] and not self.crashed[s]
                                          for s in group),
                           'collision': any(self.crashed[s] for s in group)}
                for i, s in enumerate(group):
                    episode[f'return_{names[i]}'] = self.returns[s]
                    self.crashed[s] = self.passed[s] = False
                episodes.append(episode)
            if args.timesteps and self.num_timesteps >= args.timesteps:
                return False
            return time.monotonic() - start < budget_s

        def _on_rollout_end(self):
            last = episodes[-WINDOW:]
            if not last:
                return
            returns = [e[f'return_{n}'] for e in last for n in names]
            rows.append({'agent_steps': self.num_timesteps,
                         'world_steps': self.num_timesteps // AGENTS,
                         'wall_s': round(time.monotonic() - start, 1),
                         'episodes': len(episodes),
                         'mean_return': round(float(np.mean(returns)), 3),
                         'success_rate': round(float(np.mean([e['success'] for e in last])), 3),
                         'collision_rate': round(float(np.mean([e['collision'] for e in last])),
                                                 3)})
            row = rows[-1]
            print(f"{row['agent_steps']:>8} agent steps {row['wall_s']:>7.0f} s  return "
                  f"{row['mean_return']:6.2f}  success {row['success_rate']:.2f}  collision "
                  f"{row['collision_rate']:.2f}", flush=True)

    model.learn(total_timesteps=10 ** 9, callback=Curve())
    facts = {'agent_steps': int(model.num_timesteps), 'train_wall_s': time.monotonic() - start,
             'episodes': len(episodes)}
    envs.close()
    model_path = out / 'model.zip'
    model.save(model_path)
    return model_path, rows, episodes, facts


def _evaluate(model_path, seeds, vehicle_model, options=None):
    """
    Run one episode per seed (model_path None: the random policy); return the outcomes.

    Each outcome: the seed, success (all through, none collided), collision (any), and per
    agent its return and whether it went through without a collision.
    """
    model = None
    if model_path is not None:
        from stable_baselines3 import PPO
        model = PPO.load(model_path, device='cpu')
    env = policy_env(vehicle_model, options)
    outcomes = []
    try:
        for seed in seeds:
            obs, _ = env.reset(seed=seed)
            for i, agent in enumerate(env.possible_agents):
                env.action_space(agent).seed(seed * AGENTS + i)
            returns = dict.fromkeys(env.possible_agents, 0.0)
            crashed = dict.fromkeys(env.possible_agents, False)
            passed = dict.fromkeys(env.possible_agents, False)
            while env.agents:
                live = list(env.agents)
                if model is None:
                    actions = {agent: env.action_space(agent).sample() for agent in live}
                else:
                    batch = {key: np.stack([obs[a][key] for a in live])
                             for key in OBSERVATION_KEYS}
                    chosen, _ = model.predict(batch, deterministic=True)
                    actions = dict(zip(live, chosen))
                obs, rewards, _, _, infos = env.step(actions)
                for agent in live:
                    returns[agent] += rewards[agent]
                    crashed[agent] |= bool(infos[agent]['collision'])
                    passed[agent] |= through(env, agent)
            outcome = {'seed': seed,
                       'success': all(passed[a] and not crashed[a] for a in returns),
                       'collision': any(crashed.values())}
            for agent in env.possible_agents:
                outcome[f'return_{agent}'] = round(returns[agent], 4)
                outcome[f'through_{agent}'] = passed[agent] and not crashed[agent]
            outcomes.append(outcome)
    finally:
        env.close()
    return outcomes


def _evaluate_job(job):
    import torch
    torch.set_num_threads(1)
    return _evaluate(*job)


def figures(outcomes, agents):
    """Return the evaluation's figures: rates and each agent's mean return and share through."""
    n = len(outcomes)
    found = {'episodes': n,
             'success_rate': sum(o['success'] for o in outcomes) / n,
             'collision_rate': sum(o['collision'] for o in outcomes) / n,
             'mean_return': {}, 'through_rate': {}}
    for agent in agents:
        found['mean_return'][agent] = round(float(np.mean(
            [o[f'return_{agent}'] for o in outcomes])), 3)
        found['through_rate'][agent] = sum(o[f'through_{agent}'] for o in outcomes) / n
    return found


def results_markdown(summary):
    """Return the run's figures as docs/learning.md shows them (a table, from summary.json)."""
    agents = summary['agents']
    lines = [
        f"Seed {summary['seed']}, {summary['worlds']} worlds of {len(agents)} agents "
        f"({summary['processes']} processes), cars moved by {summary['vehicle_model']}, "
        f"PyTorch on {summary['torch_threads']} thread(s): {summary['agent_steps']} agent "
        f"steps ({summary['episodes']} training episodes) in "
        f"{summary['train_wall_s'] / 60.0:.1f} min of training; evaluation: "
        f"{summary['evaluation']['trained']['episodes']} episodes of 10 s per policy, seeds "
        f"{summary['eval_seeds'][0]} .. {summary['eval_seeds'][1]}.",
        '',
        '| policy | success (all 4 through, no collision) | an episode with a collision | '
        + ' | '.join(f'{a}: return, through' for a in agents) + ' |',
        '|---|---|---|' + '---|' * len(agents),
    ]
    for name, label in (('trained', 'PPO, shared (deterministic)'), ('random', 'random')):
        f = summary['evaluation'][name]
        cells = [f"{f['mean_return'][a]:.2f}, {f['through_rate'][a]:.0%}" for a in agents]
        lines.append(f"| {label} | {f['success_rate']:.0%} | {f['collision_rate']:.0%} | "
                     + ' | '.join(cells) + ' |')
    return '\n'.join(lines) + '\n'


def write_curve(out, rows, episodes):
    """Write learning_curve.csv, episodes.csv and learning_curve.png."""
    lc.write_rows(out / 'learning_curve.csv', rows, CURVE_FIELDS)
    if episodes:
        lc.write_rows(out / 'episodes.csv', episodes)
    lc.plot_curve(out / 'learning_curve.png', rows,
                  'PPO shared by the 4 agents of crossing4 (training episodes, stochastic '
                  'policy)', WINDOW, steps_key='agent_steps',
                  steps_label='agent steps (0.2 s each)', rates=(lc.SUCCESS, lc.COLLISION),
                  return_label='mean return per agent')


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--minutes', type=float, default=15.0,
                        help='wall-clock budget of the training [min]')
    parser.add_argument('--timesteps', type=int, default=0,
                        help='stop after this many agent steps too (0: the budget only)')
    parser.add_argument('--seed', type=int, default=0)
    parser.add_argument('--worlds', type=int, default=4, help='worlds of 4 agents')
    parser.add_argument('--processes', type=int, default=2,
                        help='processes stepping the worlds (0 or 1: in this one)')
    parser.add_argument('--threads', type=int, default=1, help="PyTorch's CPU threads")
    parser.add_argument('--vehicle-model', default=VEHICLE_MODEL,
                        help="the cars' vehicle_model (docs/physics.md); none: the physics car")
    parser.add_argument('--eval-episodes', type=int, default=100,
                        help='evaluation episodes per policy (0: none)')
    parser.add_argument('--eval-workers', type=int, default=1,
                        help='processes per policy evaluated (both policies at once)')
    parser.add_argument('--evaluate', metavar='MODEL',
                        help='evaluate this model.zip instead of training')
    parser.add_argument('--out', default='train_crossing_out')
    args = parser.parse_args(argv)
    if args.vehicle_model.lower() == 'none':
        args.vehicle_model = None
    try:
        import vehicle_sim.gym.learn_require  # noqa: F401
    except ImportError as error:
        raise SystemExit(str(error)) from None
    try:
        import supersuit  # noqa: F401
    except ImportError as error:
        raise SystemExit(f'training the crossing needs SuperSuit and PettingZoo ({error.name} '
                         f"is missing): pip install 'vehicle_sim[learn]'") from None
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    agents = [v['name'] for v in crossing_world()['vehicles']][:AGENTS]
    summary = {'seed': args.seed, 'minutes': args.minutes, 'worlds': args.worlds,
               'processes': args.processes, 'torch_threads': args.threads,
               'cpu_count': os.cpu_count(), 'vehicle_model': args.vehicle_model or 'physics',
               'agents': agents, 'env_options': dict(ENV_OPTIONS, **(
                   {} if args.vehicle_model else PHYSICS_OPTIONS)),
               'through_m': THROUGH_M, 'observation_keys': list(OBSERVATION_KEYS),
               'scales': SCALES, 'ppo': dict(PPO_OPTIONS, net_arch=NET_ARCH,
                                             log_std_init=LOG_STD_INIT),
               'load_average_start': os.getloadavg()}
    if args.evaluate:
        model_path = Path(args.evaluate)
    else:
        model_path, rows, episodes, facts = train(args, out)
        write_curve(out, rows, episodes)
        summary.update(facts)
        summary['final_training_row'] = rows[-1] if rows else None
        print(f"trained {facts['agent_steps']} agent steps ({facts['episodes']} episodes) in "
              f"{facts['train_wall_s']:.0f} s; model {model_path}", flush=True)
    if args.eval_episodes > 0:
        seeds = [EVAL_SEED_BASE + k for k in range(args.eval_episodes)]
        start = time.monotonic()
        workers = max(1, args.eval_workers)
        chunks = [seeds[i::workers] for i in range(workers)]
        jobs = [(path, chunk, args.vehicle_model) for path in (str(model_path), None)
                for chunk in chunks]
        with multiprocessing.get_context('forkserver').Pool(len(jobs)) as pool:
            parts = pool.map(_evaluate_job, jobs)
        results = {name: sorted((o for part in parts[k * workers:(k + 1) * workers]
                                 for o in part), key=lambda o: o['seed'])
                   for k, name in enumerate(('trained', 'random'))}
        summary['eval_wall_s'] = round(time.monotonic() - start, 1)
        summary['eval_seeds'] = [seeds[0], seeds[-1]]
        summary['evaluation'] = {name: figures(outcomes, agents)
                                 for name, outcomes in results.items()}
        lc.write_evaluation(out / 'evaluation.csv', results)
        for name, values in summary['evaluation'].items():
            print(f"{name:>8}: success {values['success_rate']:.2f}, collision "
                  f"{values['collision_rate']:.2f}, mean return {values['mean_return']}, "
                  f"through {values['through_rate']}")
    summary['load_average_end'] = os.getloadavg()
    (out / 'summary.json').write_text(json.dumps(summary, indent=2) + '\n', encoding='utf-8')
    print(f'files in {out}')


if __name__ == '__main__':
    main()
