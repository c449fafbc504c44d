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
An RLlib checkpoint as a policy: ``predict(obs, deterministic=True)`` through RLlib's own parts.

A checkpoint of RLlib's new API stack (``Algorithm.save_to_path``: examples/train_highway_ray.py)
holds the three things an action is made of, each restored by RLlib itself: the env-to-module
connector pipeline (``env_runner/env_to_module_connector``: the Dict flattened, the
``MeanStdFilter``'s statistics), the RLModule (``learner_group/learner/rl_module/
default_policy``) and the module-to-env pipeline (the action taken from the distribution,
unsquashed and clipped to the action space). :class:`RllibPolicy` runs them on a one-step
episode per call, the loop of RLlib's own inference example, and answers like a
stable-baselines3 model (``predict``, ``observation_space``, ``action_space``), so that
``vehicle-sim policy run|evaluate`` and the training scripts' evaluation take either.

The ``MeanStdFilter``'s statistics are frozen when loaded: a policy that is run changes no
more, and the same observation gives the same action whatever was seen before.
"""

from pathlib import Path

import numpy as np

from vehicle_sim.core.specs.errors import InvalidParameterError

CHECKPOINT_FILE = 'rllib_checkpoint.json'
LEARN_RAY_HINT = "pip install 'vehicle_sim[learn-ray]'"


def is_rllib_checkpoint(path) -> bool:
    """Return whether ``path`` is an RLlib checkpoint folder (it holds rllib_checkpoint.json)."""
    path = Path(path)
    return path.is_dir() and (path / CHECKPOINT_FILE).is_file()


class RllibPolicy:
    """
    A single-agent policy of an RLlib checkpoint.

    :ivar observation_space: the environment's observation space it reads (the Dict, before
        RLlib's connectors).
    :ivar action_space: the environment's action space it writes.
    """

    def __init__(self, env_to_module, module, module_to_env):
        self._env_to_module = env_to_module
        self._module = module
        self._module_to_env = module_to_env
        self.observation_space = env_to_module.input_observation_space
        self.action_space = module_to_env.action_space

    @classmethod
    def load(cls, path):
        """
        Restore the policy of the checkpoint folder ``path`` (on the CPU).

        :raises InvalidParameterError: naming the folder: Ray's RLlib missing (the
            ``learn-ray`` extra), or not a checkpoint of a single-agent RLlib algorithm.
        """
        path = Path(path)
        try:
            from ray.rllib.connectors.env_to_module import EnvToModulePipeline, MeanStdFilter
            from ray.rllib.connectors.module_to_env import ModuleToEnvPipeline
            from ray.rllib.core import (
                COMPONENT_ENV_RUNNER,
                COMPONENT_ENV_TO_MODULE_CONNECTOR,
                COMPONENT_LEARNER,
                COMPONENT_LEARNER_GROUP,
                COMPONENT_MODULE_TO_ENV_CONNECTOR,
                COMPONENT_RL_MODULE,
                DEFAULT_MODULE_ID,
            )
            from ray.rllib.core.rl_module.rl_module import RLModule
        except ImportError as error:
            raise InvalidParameterError(
                f"{path}: loading an RLlib checkpoint needs Ray's RLlib ({error.name} is "
                f'missing): {LEARN_RAY_HINT}') from None
        # absolute: RLlib reads a relative path as a URI without a scheme (pyarrow refuses it)
        folder = path.resolve()
        runner = folder / COMPONENT_ENV_RUNNER
        try:
            env_to_module = EnvToModulePipeline.from_checkpoint(
                runner / COMPONENT_ENV_TO_MODULE_CONNECTOR)
            module = RLModule.from_checkpoint(
                folder / COMPONENT_LEARNER_GROUP / COMPONENT_LEARNER / COMPONENT_RL_MODULE
                / DEFAULT_MODULE_ID)
            module_to_env = ModuleToEnvPipeline.from_checkpoint(
                runner / COMPONENT_MODULE_TO_ENV_CONNECTOR)
        except Exception as error:  # noqa: BLE001 - a folder of anything: say what it is not
            raise InvalidParameterError(
                f'{path}: not a checkpoint of a single-agent RLlib algorithm: '
                f'{type(error).__name__}: {error}') from None
        for piece in env_to_module.connectors:
            if isinstance(piece, MeanStdFilter):
                # RLlib's filter updates its statistics with each observation unless built
                # with update_stats=False, which a checkpoint's pipeline is not
                piece._update_stats = False
        module.eval()
        return cls(env_to_module, module, module_to_env)

    def predict(self, observation, deterministic=True):
        """
        Return (action, None) for one observation of the environment, as stable-baselines3 does.

        :param deterministic: the distribution's mode (RLlib's ``explore=False``); False
            samples it.
        """
        from ray.rllib.core.columns import Columns
        from ray.rllib.env.single_agent_episode import SingleAgentEpisode
        import torch

        episode = SingleAgentEpisode(observations=[observation],
                                     observation_space=self.observation_space,
                                     action_space=self.action_space)
        shared = {}
        explore = not deterministic
        batch = self._env_to_module(episodes=[episode], rl_module=self._module,
                                    explore=explore, shared_data=shared)
        with torch.no_grad():
            out = (self._module.forward_exploration(batch) if explore
                   else self._module.forward_inference(batch))
        to_env = self._module_to_env(batch=out, episodes=[episode], rl_module=self._module,
                                     explore=explore, shared_data=shared)
        return np.asarray(to_env[Columns.ACTIONS_FOR_ENV][0], dtype=self.action_space.dtype), None
