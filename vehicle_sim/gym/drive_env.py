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
``vehicle_sim/Drive-v0``: one ego vehicle in a world or scenario, as a Gymnasium environment.

In process (no ROS, no DDS): the world is built by the scene builder in a PyBullet DIRECT client
of this process (render_mode 'human': the PyBullet window). Actions, observations, reward and
episode ends: docs/gym.md; the options: gym/options.py.

An environment's ``metadata['render_modes']`` are the modes it can render here: 'human' only
where PyBullet's window can open (physics/gui.py), so that Gymnasium's ``check_env``, which
opens every declared mode, passes on a machine without a display.
"""

import numpy as np

from vehicle_sim.gym.drive_sim import DriveSim
from vehicle_sim.gym.require import gymnasium
from vehicle_sim.gym.spaces import action_space, observation_space
from vehicle_sim.physics.gui import gui_unavailable_reason

RENDER_MODES = ('human', 'rgb_array')


def render_modes_here(render_mode=None):
    """Return the render modes an environment can give here: 'human' where a window opens."""
    if render_mode == 'human' or gui_unavailable_reason() is None:
        return list(RENDER_MODES)
    return [mode for mode in RENDER_MODES if mode != 'human']


class DriveEnv(gymnasium.Env):
    """
    One ego vehicle driven by actions (docs/gym.md).

    :param world: world name, path, mapping or WorldSpec (None: 'obstacle_course' unless a
        scenario is given).
    :param scenario: scenario path or ScenarioSpec.
    :param render_mode: None, 'rgb_array' (a chase-camera picture from ``render()``) or
        'human' (the PyBullet window, one per process).
    :param reward_fn: None = the default reward (the sum of ``info['reward_terms']``); else
        ``reward_fn(obs, action, info) -> float`` (``info`` has the default terms).
    :param observation_parts: more observation parts (observations.py).
    :param options: the environment's options (gym/options.py).
    :raises InvalidParameterError: for a bad option, world or scenario (nothing is built).
    """

    metadata = {'render_modes': list(RENDER_MODES), 'render_fps': 30}

    def __init__(self, world=None, scenario=None, render_mode=None, reward_fn=None,
                 observation_parts=(), **options):
        if render_mode is not None and render_mode not in RENDER_MODES:
            raise ValueError(f'render_mode = {render_mode!r}: one of None, '
                             + ', '.join(repr(m) for m in RENDER_MODES))
        if reward_fn is not None and not callable(reward_fn):
            raise ValueError(f'reward_fn = {reward_fn!r}: must be callable '
                             '(obs, action, info) -> float')
        self.render_mode = render_mode
        self.reward_fn = reward_fn
        self.sim = DriveSim(world, scenario, options, gui=render_mode == 'human',
                            observation_parts=observation_parts)
        self.action_space = action_space(self.sim.control)
        self.observation_space = observation_space(self.sim.spaces)
        self.metadata = dict(self.metadata, render_modes=render_modes_here(render_mode),
                             render_fps=round(1.0 / (self.sim.world.time_step_s
                                                     * self.sim.options['action_repeat'])))
        self._image = None
        self._chase = None
        if render_mode == 'human':
            from vehicle_sim.physics.gui import ChaseCamera
            self._chase = ChaseCamera(self.sim.world, [self.sim.ego.vehicle])

    def reset(self, *, seed=None, options=None):
        """Start an episode (see DriveSim.reset); ``options`` is not used."""
        super().reset(seed=seed)
        return self.sim.reset(self.np_random)

    def step(self, action):
        obs, terms, terminated, truncated, info = self.sim.step(action)
        if self.reward_fn is None:
            reward = info['reward_default']
        else:
            reward = float(self.reward_fn(obs, np.asarray(action), info))
        return obs, reward, terminated, truncated, info

    def render(self):
        """'rgb_array': the chase-camera picture (height, width, 3) uint8; 'human': None."""
        if self.render_mode != 'rgb_array':
            return None
        if self._image is None:
            from vehicle_sim.physics.chase_image import ChaseImage
            self._image = ChaseImage(self.sim.world, self.sim.ego.body,
                                     self.sim.options['render_width'],
                                     self.sim.options['render_height'])
        return self._image.render()

    def close(self):
        if getattr(self, 'sim', None) is not None:
            self.sim.close()
