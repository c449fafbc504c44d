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
``vehicle_sim.gym.multi``: several ego vehicles in one world, as a PettingZoo ``ParallelEnv``.

Needs PettingZoo (the ``multi`` extra: ``pip install 'vehicle_sim[multi]'``)::

    from vehicle_sim.gym.multi import MultiDriveEnv
    env = MultiDriveEnv(world='crossing4', agents=4, max_episode_s=20.0)
    obs, infos = env.reset(seed=1)
    while env.agents:
        actions = {a: env.action_space(a).sample() for a in env.agents}
        obs, rewards, terminations, truncations, infos = env.step(actions)

Each agent is a vehicle of the world file and has the single-agent environment's action Box,
observation Dict, reward terms and episode ends (docs/gym.md); an agent that crashes leaves
(``env.agents``) and its car stays braked where it stopped, the others go on. The simulator
part: multi_sim.py.
"""

import numpy as np

from vehicle_sim.gym.multi_sim import MultiDriveSim, SOURCE
from vehicle_sim.gym.require import gymnasium
from vehicle_sim.gym.spaces import action_space, observation_space

try:
    from pettingzoo import ParallelEnv
except ImportError as error:      # pragma: no cover - the 'gym' extra is missing
    raise ImportError('vehicle_sim.gym.multi needs PettingZoo: '
                      "pip install 'vehicle_sim[multi]'") from error


class MultiDriveEnv(ParallelEnv):
    """
    N ego vehicles in one world, each driven by its agent's actions (see the module text).

    :param world: world name, path, mapping or WorldSpec (None: 'crossing4').
    :param agents: the number of agents (the world's first vehicles) or their vehicle names;
        more than the world's vehicles, an unknown or repeated name is refused.
    :param reward_fn: None = the default reward (the sum of ``info['reward_terms']``); else
        ``reward_fn(agent, obs, action, info) -> float``.
    :param observation_parts: a function (agent name) -> more observation parts of that agent
        (observations.py).
    :param options: the single-agent environment's options (gym/options.py) but 'vehicle',
        'robot' and 'start'; every agent gets the same.
    :raises InvalidParameterError: for a bad option, world or agents (nothing is built).
    """

    metadata = {'name': 'vehicle_sim_multi_drive_v0', 'render_modes': [],
                'is_parallelizable': True}

    def __init__(self, world=None, agents=2, render_mode=None, reward_fn=None,
                 observation_parts=None, **options):
        if render_mode is not None:
            raise ValueError(f'render_mode = {render_mode!r}: {SOURCE} renders nothing; '
                             'give None')
        if reward_fn is not None and not callable(reward_fn):
            raise ValueError(f'reward_fn = {reward_fn!r}: must be callable '
                             '(agent, obs, action, info) -> float')
        self.render_mode = None
        self.reward_fn = reward_fn
        self.sim = MultiDriveSim(world, agents, options, observation_parts=observation_parts)
        self.possible_agents = list(self.sim.agents)
        self.agents = []
        self.observation_spaces = {name: observation_space(ego.spaces)
                                   for name, ego in self.sim.egos.items()}
        self.action_spaces = {name: action_space(ego.control)
                              for name, ego in self.sim.egos.items()}
        self.metadata = dict(self.metadata, render_fps=round(
            1.0 / (self.sim.world.time_step_s * self.sim.options['action_repeat'])))
        self.np_random = None

    def observation_space(self, agent):
        """Return an agent's observation Dict (the single-agent environment's)."""
        return self.observation_spaces[agent]

    def action_space(self, agent):
        """Return an agent's action Box (the single-agent environment's)."""
        return self.action_spaces[agent]

    def reset(self, seed=None, options=None):
        """Start an episode with every agent: ({agent: obs}, {agent: info}); see MultiDriveSim."""
        if seed is not None or self.np_random is None:
            self.np_random, _ = gymnasium.utils.seeding.np_random(seed)
        self.agents = []
        obs, infos = self.sim.reset(self.np_random)
        self.agents = list(self.sim.live)
        return obs, infos

    def step(self, actions):
        """
        Step every live agent with its action.

        :return: (observations, rewards, terminations, truncations, infos), each a dict over
            the agents live before the step; ``agents`` then holds those that go on.
        :raises ValueError: for an action of an unknown agent or one that left, a live agent
            without an action, or an action outside its space (nothing stepped).
        """
        obs, terms, terminated, truncated, infos = self.sim.step(actions)
        if self.reward_fn is None:
            rewards = {name: infos[name]['reward_default'] for name in obs}
        else:
            rewards = {name: float(self.reward_fn(name, obs[name], np.asarray(actions[name]),
                                                  infos[name])) for name in obs}
        self.agents = list(self.sim.live)
        return obs, rewards, terminated, truncated, infos

    def render(self):
        """Render nothing (no render modes)."""
        return None

    def close(self):
        if getattr(self, 'sim', None) is not None:
            self.sim.close()
