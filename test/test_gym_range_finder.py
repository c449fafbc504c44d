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

"""The Gym ``depth`` key of option ``range_finder``: values, bounds, the render it shares."""

import warnings

import numpy as np
import pytest

gymnasium = pytest.importorskip('gymnasium', reason="needs the 'gym' extra (gymnasium)")

from gymnasium.utils.env_checker import check_env  # noqa: E402

import vehicle_sim.gym  # noqa: E402,F401  (registers the ids)
from vehicle_sim.physics.sensors import render  # noqa: E402


def test_gym_depth_key_is_the_depth_with_no_return_at_max_range(make):
    env = make(world='obstacle_course', range_finder={'width': 32, 'height': 24,
                                                      'max_range': 50.0,
                                                      'pose': {'x': 1.5, 'z': 1.3}})
    obs, _ = env.reset(seed=0)
    depth = obs['depth']
    assert depth.shape == (24, 32) and depth.dtype == np.float32
    assert env.observation_space['depth'].contains(depth)
    assert depth[12, 16] == pytest.approx(18.0, abs=0.02)         # the wall's face
    assert (depth[0] == 50.0).all()                                # the sky: max_range


def test_gym_camera_and_range_finder_defaults_pass_check_env_and_share_a_render(make,
                                                                              monkeypatch):
    env = make(world='obstacle_course', camera=True, range_finder=True)
    with warnings.catch_warnings():
        warnings.filterwarnings('ignore', message='.*(infinity|symmetric and normalized).*')
        check_env(env.unwrapped, skip_render_check=True)
    assert isinstance(env.observation_space['depth'], gymnasium.spaces.Box)
    renders = []
    real = render.Renderer._render
    monkeypatch.setattr(render.Renderer, '_render',
                        lambda self, *args: renders.append(args[0]) or real(self, *args))
    env.reset(seed=0)
    renders.clear()
    for _ in range(2):
        obs, *_ = env.step(env.action_space.sample())
    assert obs['depth'].shape == (84, 84) and obs['camera'].shape == (84, 84, 3)
    assert len(renders) == 2                     # one per step's observation, for the two
