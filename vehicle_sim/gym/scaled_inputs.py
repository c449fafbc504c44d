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
A policy's input scaling, inside the policy: a stable-baselines3 features extractor.

Drive-v0's observations are in physical units (docs/gym.md): a lane's arc length runs to
hundreds of metres while a heading error that matters is a hundredth of a radian. A network
learns badly from inputs of such different sizes; :class:`ScaledInputs` multiplies each entry
of each Dict key by a fixed factor, clips the result to [-clip, clip] and concatenates the keys
(stable-baselines3's CombinedExtractor without learned parts). The factors are the policy's
``features_extractor_kwargs``, saved in the model file: a policy loaded elsewhere (``vehicle-sim
policy run``, reading the same keys from ROS topics) scales its inputs the same way, and the
observations themselves stay in the units the environment and the topics give.

Needs the ``learn`` extra (stable-baselines3 and PyTorch).
"""

import numpy as np

from vehicle_sim.gym.learn_require import BaseFeaturesExtractor, torch


class ScaledInputs(BaseFeaturesExtractor):
    """
    Each Dict key flattened, times its fixed factors, clipped, concatenated.

    :param observation_space: the policy's Dict of Boxes.
    :param scales: {key: factor}: a number, or an array broadcast to the key's shape (one
        factor per column of a table: ``[1, 2, 10, ...]``); a key left out keeps factor 1.
    :param clip: the scaled entries are clipped to [-clip, clip].
    :raises ValueError: naming a key of ``scales`` not in the space, or factors whose shape
        does not fit the key's.
    """

    def __init__(self, observation_space, scales=None, clip=5.0):
        spaces = observation_space.spaces
        scales = dict(scales or {})
        unknown = sorted(set(scales) - set(spaces))
        if unknown:
            raise ValueError(f'scales for keys {unknown}: not in the observation space '
                             f'(keys {sorted(spaces)})')
        self.keys = list(spaces)
        factors = []
        for key in self.keys:
            shape = spaces[key].shape
            try:
                factor = np.broadcast_to(np.asarray(scales.get(key, 1.0), dtype=np.float32),
                                         shape)
            except ValueError:
                raise ValueError(f'scales[{key!r}] of shape '
                                 f"{np.shape(scales[key])} does not fit the key's shape "
                                 f'{shape}') from None
            factors.append(factor.reshape(-1))
        super().__init__(observation_space, features_dim=int(sum(f.size for f in factors)))
        self.clip = float(clip)
        for i, factor in enumerate(factors):
            self.register_buffer(f'factor_{i}', torch.as_tensor(np.array(factor)))

    def forward(self, observations):
        parts = []
        for i, key in enumerate(self.keys):
            value = observations[key].reshape(observations[key].shape[0], -1)
            parts.append(torch.clamp(value * getattr(self, f'factor_{i}'),
                                     -self.clip, self.clip))
        return torch.cat(parts, dim=1)
