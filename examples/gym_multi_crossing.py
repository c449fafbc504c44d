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
Four agents at a crossing (vehicle_sim.gym.multi): a random policy each, until all have left.

The world config/worlds/crossing4.yaml: two streets crossing without signals, a car waiting on
each arm. Each agent draws its actions at random from its own action space (seeded); an agent
whose car collides leaves the episode (its car stays braked where it stopped) and the others go
on, until every agent has left or the episode's time is up.

Run: ``.venv/bin/python examples/gym_multi_crossing.py [--episodes 2] [--seed 0]
[--max-seconds 20]``. Needs the ``multi`` extra (``pip install 'vehicle_sim[multi]'``). Each
episode prints, per agent, its steps, its return, each reward term's sum and why it left.
"""

import argparse

from vehicle_sim.gym.multi import MultiDriveEnv


def _why(info, terminated):
    if info['collision']:
        return f'collision with {info["collided_with"]}'
    if info['goal_reached']:
        return 'goal reached'
    return 'terminated' if terminated else 'time limit'


def rollout(episodes=2, seed=0, max_seconds=20.0):
    """Run the random policy; return [{agent: (steps, return, {term: sum}, why)}] per episode."""
    env = MultiDriveEnv(world='crossing4', agents=4, action_repeat=10, max_episode_s=max_seconds)
    try:
        for i, agent in enumerate(env.possible_agents):
            env.action_space(agent).seed(seed + i)
        results = []
        for episode in range(episodes):
            env.reset(seed=seed + episode)
            steps = dict.fromkeys(env.agents, 0)
            returns = dict.fromkeys(env.agents, 0.0)
            terms = {agent: {} for agent in env.agents}
            ended = {}
            while env.agents:
                actions = {agent: env.action_space(agent).sample() for agent in env.agents}
                _, rewards, terminations, truncations, infos = env.step(actions)
                for agent, reward in rewards.items():
                    steps[agent] += 1
                    returns[agent] += reward
                    for name, value in infos[agent]['reward_terms'].items():
                        terms[agent][name] = terms[agent].get(name, 0.0) + value
                    if terminations[agent] or truncations[agent]:
                        ended[agent] = _why(infos[agent], terminations[agent])
            results.append({agent: (steps[agent], returns[agent], terms[agent], ended[agent])
                            for agent in env.possible_agents})
        return results
    finally:
        env.close()


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0].strip())
    parser.add_argument('--episodes', type=int, default=2)
    parser.add_argument('--seed', type=int, default=0)
    parser.add_argument('--max-seconds', type=float, default=20.0)
    args = parser.parse_args(argv)
    for episode, result in enumerate(rollout(args.episodes, args.seed, args.max_seconds)):
        print(f'episode {episode}:')
        for agent, (steps, total, terms, why) in result.items():
            print(f'  {agent}: {steps} steps, return {total:.2f} '
                  f'({", ".join(f"{k} {v:.2f}" for k, v in terms.items())}); {why}')


if __name__ == '__main__':
    main()
