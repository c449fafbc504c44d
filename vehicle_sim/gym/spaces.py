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


"""Gymnasium spaces of a DriveSim: its action Box and its observation Dict."""

import numpy as np

from vehicle_sim.gym.require import gymnasium


def action_space(control):
    """Return the Box of a Control (controls.py): float32, its low and high."""
    return gymnasium.spaces.Box(control.low, control.high, dtype=control.low.dtype)


def observation_space(spaces):
    """
    Return the Dict of observation part spaces.

    :param spaces: {key: (low, high, shape, dtype)} (observations.py).
    """
    return gymnasium.spaces.Dict({
        key: gymnasium.spaces.Box(np.broadcast_to(np.asarray(low, dtype=dtype), shape),
                                  np.broadcast_to(np.asarray(high, dtype=dtype), shape),
                                  shape=shape, dtype=dtype)
        for key, (low, high, shape, dtype) in spaces.items()})
