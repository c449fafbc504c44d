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
A random policy in vehicle_sim/Drive-v0: one car, a 1080-ray lidar, episodes until a crash.

Run: ``.venv/bin/python examples/gym_random_rollout.py [--episodes 3] [--render out.png]
[--world highway]`` (a world with lanes adds the ``lane`` observation and reward term).
Needs the ``gym`` extra (``pip install 'vehicle_sim[gym]'``). Each episode prints its length,
its return, each reward term's sum and why it ended; ``--render`` saves the last chase-camera
picture (matplotlib).
"""

import argparse

import gymnasium
import numpy as np

import vehicle_sim.gym  # noqa: F401  (registers vehicle_sim/Drive-v0)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--episodes', type=int, default=3)
    parser.add_argument('--seed', type=int, default=0)
    parser.add_argument('--render', metavar='PNG', help='save the last picture here')
    parser.add_argument('--world', default='obstacle_course',
                        help='a world name or file (default obstacle_course)')
    args = parser.parse_args(argv)
    env = gymnasium.make('vehicle_sim/Drive-v0', world=args.world, lidar=True,
                         action_repeat=10, max_episode_s=20.0,
                         render_mode='rgb_array' if args.render else None)
    env.action_space.seed(args.seed)
    obs, info = env.reset(seed=args.seed)
    print(f'observations: {env.observation_space}\nactions: {env.action_space}')
    for episode in range(args.episodes):
        steps, total, terms = 0, 0.0, {}
        while True:
            obs, reward, terminated, truncated, info = env.step(env.action_space.sample())
            steps += 1
            total += reward
            for name, value in info['reward_terms'].items():
                terms[name] = terms.get(name, 0.0) + value
            if terminated or truncated:
                break
        why = (f'collision with {info["collided_with"]}' if info['collision'] else
               'goal reached' if info['goal_reached'] else
               'time limit' if truncated else 'terminated')
        nearest = float(np.min(obs['lidar']))
        lane = (f'; lane {int(obs["lane_id"][0])}, offset {obs["lane"][1]:.2f} m'
                if 'lane' in obs else '')
        print(f'episode {episode}: {steps} steps, {info["time_s"]:.1f} s, return {total:.2f} '
              f'({", ".join(f"{k} {v:.2f}" for k, v in terms.items())}); {why}; '
              f'nearest lidar return {nearest:.2f} m{lane}')
        if args.render and episode == args.episodes - 1:
            import matplotlib
            matplotlib.use('Agg')
            import matplotlib.pyplot as plt
            plt.imsave(args.render, env.render())
            print(f'picture: {args.render}')
        obs, info = env.reset()
    env.close()


if __name__ == '__main__':
    main()
