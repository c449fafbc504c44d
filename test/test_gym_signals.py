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


"""The Gym environment's world keeps its one signal controller and resets it with the world."""

import numpy as np
import pytest

pytest.importorskip('gymnasium', reason="needs the 'gym' extra (gymnasium)")

import vehicle_sim.gym  # noqa: E402,F401  (registers the ids)

EAST = 4000100101           # city_block_signals: the ring's southern intersection, eastbound


def test_a_reset_starts_the_signal_plan_again_and_releases_forced_states(make):
    env = make(world='city_block_signals', action_repeat=10)
    env.reset(seed=1)
    part = env.unwrapped.sim.scene.parts['signals']
    controller = part.controller
    idle = np.zeros(env.action_space.shape, dtype=env.action_space.dtype)
    for _ in range(30):                     # 3 s
        env.step(idle)
    assert controller.time_s > 2.9
    controller.force(EAST, 'red')
    env.step(idle)
    assert controller.state(EAST) == 'red'
    env.reset(seed=2)
    assert controller.time_s == 0.0 and controller.state(EAST) == 'green'
    env.step(idle)
    assert controller.time_s > 0.0 and controller.state(EAST) == 'green'
