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
stable-baselines3 and PyTorch, the optional dependencies of learning: imported with a clear error.

The ``learn`` extra installs them (docs/learning.md says how to get a CPU build of PyTorch).
"""

LEARN_HINT = ("pip install 'vehicle_sim[learn]' (stable-baselines3 and PyTorch; a CPU build of "
              'PyTorch: docs/learning.md)')

try:
    import stable_baselines3
    from stable_baselines3.common.torch_layers import BaseFeaturesExtractor
    import torch
except ImportError as error:      # pragma: no cover - the 'learn' extra is missing
    raise ImportError(f'learning with vehicle_sim needs stable-baselines3 and PyTorch '
                      f'({error.name} is missing): {LEARN_HINT}') from error

__all__ = ['BaseFeaturesExtractor', 'LEARN_HINT', 'stable_baselines3', 'torch']
