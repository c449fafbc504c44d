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
Train stable-baselines3's PPO to drive around the wall of the obstacle course (optional).

The task: the car starts at the origin facing the wall (config/worlds/obstacle_course.yaml: a
1 x 6 m wall at x = 19.5 .. 20.5 m, a pole at (10, 5)); the goal region is a 2 m circle at
(30, 0), behind the wall. Reward: progress toward the goal [1/m], -10 for a collision (which
ends the episode), +10 at the goal. Observations: pose, twist and a 36-ray lidar; actions:
steering angle and speed (rescaled to [-1, 1] for the policy), held for 0.1 s (action_repeat
10). Driving straight scores about +5 (15 m of progress, then the wall); going around about
+40.

Not run in CI. Needs ``pip install stable-baselines3`` (and PyTorch) besides the ``gym`` extra.
Run: ``.venv/bin/python examples/gym_train_ppo.py [--timesteps 200000] [--out DIR]``; it writes
``DIR/monitor*.csv`` (one row per episode), ``DIR/learning_curve.csv`` and, with matplotlib,
``DIR/learning_curve.png``, and prints the trained policy's deterministic episode. docs/gym.md
shows a curve of this script.
"""

import argparse
import csv
import glob
import os

import gymnasium
import numpy as np

import vehicle_sim.gym  # noqa: F401  (registers vehicle_sim/Drive-v0)

GOAL = [30.0, 0.0]
ENV_OPTIONS = dict(world='obstacle_course', goal=GOAL, goal_radius=2.0, action_repeat=10,
                   max_episode_s=20.0, max_speed=10.0, max_reverse_speed=2.0,
                   lidar={'horizontal_resolution': 36, 'fov': 6.2, 'max_range': 20.0})


def make_env():
    env = gymnasium.make('vehicle_sim/Drive-v0', **ENV_OPTIONS)
    return gymnasium.wrappers.RescaleAction(env, -1.0, 1.0)


def learning_curve(folder, window=50):
    """Return [(timesteps, mean return of the last ``window`` episodes)] from the monitors."""
    rows = []
    for path in glob.glob(os.path.join(folder, '*monitor.csv')):
        with open(path, encoding='utf-8') as stream:
            next(stream)        # the monitor's JSON header line
            rows.extend((float(r['t']), float(r['r']), int(r['l']))
                        for r in csv.DictReader(stream))
    rows.sort()
    curve, returns, steps = [], [], 0
    for _, episode_return, length in rows:
        steps += length
        returns.append(episode_return)
        curve.append((steps, float(np.mean(returns[-window:]))))
    return curve


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--timesteps', type=int, default=200_000)
    parser.add_argument('--envs', type=int, default=8)
    parser.add_argument('--seed', type=int, default=0)
    parser.add_argument('--out', default='ppo_obstacle_course')
    args = parser.parse_args(argv)
    try:
        from stable_baselines3 import PPO
        from stable_baselines3.common.env_util import make_vec_env
    except ImportError:
        raise SystemExit('this example needs stable-baselines3: pip install stable-baselines3')
    os.makedirs(args.out, exist_ok=True)
    envs = make_vec_env(make_env, n_envs=args.envs, seed=args.seed, monitor_dir=args.out)
    model = PPO('MultiInputPolicy', envs, n_steps=256, batch_size=256, learning_rate=3e-4,
                gamma=0.99, ent_coef=0.005, seed=args.seed, verbose=0)
    model.learn(total_timesteps=args.timesteps)
    envs.close()
    model.save(os.path.join(args.out, 'ppo_policy'))
    curve = learning_curve(args.out)
    with open(os.path.join(args.out, 'learning_curve.csv'), 'w', encoding='utf-8') as stream:
        stream.write('timesteps,mean_return_last_50_episodes\n')
        stream.writelines(f'{steps},{value:.3f}\n' for steps, value in curve)
    try:
        import matplotlib
        matplotlib.use('Agg')
        import matplotlib.pyplot as plt
        figure, axes = plt.subplots(figsize=(6, 3.5))
        axes.plot([s for s, _ in curve], [v for _, v in curve])
        axes.axhline(5.0, color='grey', linestyle=':', label='straight into the wall')
        axes.set_xlabel('environment steps (0.1 s each)')
        axes.set_ylabel('mean return, last 50 episodes')
        axes.set_title('PPO on vehicle_sim/Drive-v0: around the wall to (30, 0)')
        axes.legend(loc='lower right')
        figure.tight_layout()
        figure.savefig(os.path.join(args.out, 'learning_curve.png'), dpi=100)
    except ImportError:
        pass
    env = make_env()
    obs, _ = env.reset(seed=123)
    total = 0.0
    while True:
        action, _ = model.predict(obs, deterministic=True)
        obs, reward, terminated, truncated, info = env.step(action)
        total += reward
        if terminated or truncated:
            break
    env.close()
    print(f'trained policy: return {total:.2f}, ended at x = {obs["pose"][0]:.1f} m, '
          f'y = {obs["pose"][1]:.1f} m after {info["time_s"]:.1f} s; goal reached: '
          f'{info["goal_reached"]}, collision: {info["collision"]}')
    print(f'curve: {len(curve)} episodes, last mean return '
          f'{curve[-1][1] if curve else float("nan"):.2f}; files in {args.out}')


if __name__ == '__main__':
    main()
