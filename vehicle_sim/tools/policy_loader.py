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
A trained policy and what drives the ROS node with it: the model, its card, the checks.

:func:`load_model` is the thin loader (stable-baselines3's ``PPO.load``, or the algorithm the
caller names; an RLlib checkpoint folder through tools/rllib_policy.py); :func:`drive_setup`
checks a model against its card's environment (the observation space, key by key, and the
action space) and returns the observation builder, the action writer and the period the node
runs it with. Anything with ``predict(obs, deterministic=True)`` and the two spaces serves as
a policy (the tests' scripted ones).
"""

from dataclasses import dataclass
import math
from pathlib import Path

import numpy as np

from vehicle_sim.core.learning.actions import CAR, DEFAULT_LAYOUT, ROBOT
from vehicle_sim.core.specs.errors import InvalidParameterError

ALGORITHMS = ('PPO', 'A2C', 'SAC', 'TD3', 'DDPG')


def load_model(path, algorithm='PPO'):
    """
    Load a stable-baselines3 model file (``model.zip``) or an RLlib checkpoint, on the CPU.

    An RLlib checkpoint folder (``Algorithm.save_to_path``) says its own algorithm:
    ``algorithm`` names the stable-baselines3 class of a model file only.

    :raises InvalidParameterError: naming the file: missing, not a model of ``algorithm``, or
        stable-baselines3 (the ``learn`` extra) or RLlib (``learn-ray``) not installed.
    """
    from vehicle_sim.tools.rllib_policy import CHECKPOINT_FILE, is_rllib_checkpoint, RllibPolicy
    path = Path(path)
    if is_rllib_checkpoint(path):
        return RllibPolicy.load(path)
    if path.is_dir():
        raise InvalidParameterError(f'{path}: a folder without {CHECKPOINT_FILE}: neither an '
                                    'RLlib checkpoint nor a model file')
    if not path.is_file():
        raise InvalidParameterError(f'{path}: no such model file')
    if algorithm not in ALGORITHMS:
        raise InvalidParameterError(f'--algorithm {algorithm!r}: one of {", ".join(ALGORITHMS)}')
    try:
        import stable_baselines3
    except ImportError:
        raise InvalidParameterError(
            f'{path}: loading a model needs stable-baselines3 (pip install '
            "'vehicle_sim[learn]')") from None
    try:
        return getattr(stable_baselines3, algorithm).load(str(path), device='cpu')
    except Exception as error:  # noqa: BLE001 - a zip of anything: say what it is not
        raise InvalidParameterError(
            f'{path}: not a stable-baselines3 {algorithm} model: {type(error).__name__}: '
            f'{error}') from None


def _shapes(space):
    spaces = getattr(space, 'spaces', None)
    if spaces is None:
        return {'': tuple(space.shape)}
    return {key: tuple(sub.shape) for key, sub in spaces.items()}


def space_mismatch(model_space, env_space, what='observation'):
    """
    Return a message naming what differs between a model's space and the environment's, or None.

    Per Dict key: a key only one has, or the two shapes.
    """
    model, env = _shapes(model_space), _shapes(env_space)
    if model == env:
        return None
    parts = []
    for key in sorted(set(model) | set(env)):
        name = repr(key) if key else 'the space'
        if key not in env:
            parts.append(f'{name}: {model[key]} in the model, not in the environment')
        elif key not in model:
            parts.append(f'{name}: {env[key]} in the environment, not in the model')
        elif model[key] != env[key]:
            parts.append(f'{name}: {model[key]} in the model, {env[key]} in the environment')
    return f'{what} space differs: ' + '; '.join(parts)


@dataclass(frozen=True)
class DriveSetup:
    """What the policy node needs of a card: keys, table, action layout and bounds, period."""

    keys: tuple
    objects_spec: object
    control: str
    low: tuple
    high: tuple
    action_range: tuple
    period_s: float
    steering_bounds: tuple = None        # (low, high) [rad], + = left; None for a robot


def drive_setup(card, model, rate_hz=None, source='the model'):
    """
    Check ``model`` against its card's environment; return its DriveSetup.

    :param rate_hz: the policy's rate instead of the card's (1 / (action_repeat x time_step)).
    :raises InvalidParameterError: naming both shapes, per key, for a model of another
        observation (or action) space; a rate that is not a positive number.
    """
    from vehicle_sim.gym.policy_card import make_env
    env = make_env(card)
    try:
        for what, model_space, env_space in (
                ('observation', model.observation_space, env.observation_space),
                ('action', model.action_space, env.action_space)):
            mismatch = space_mismatch(model_space, env_space, what)
            if mismatch:
                raise InvalidParameterError(
                    f'{source}: {mismatch} (the card says the policy was trained on '
                    f'{card.env_id} with {card.options}; card keys '
                    f'{list(card.observation_keys)})')
        sim = env.unwrapped.sim
        options = sim.options
        control = options['control']
        if control == 'auto':
            control = DEFAULT_LAYOUT[CAR if sim.scene.vehicles[sim.ego_name].car is not None
                                     else ROBOT]
        space = env.unwrapped.action_space
        steering = getattr(sim.control, 'steering_bounds', None)
        step_ms = sim.world.time_step_s * 1000.0
        period_s = options['action_repeat'] * step_ms / 1000.0
        objects = _objects_spec(card)
    finally:
        env.close()
    if rate_hz is not None:
        if not (math.isfinite(rate_hz) and rate_hz > 0.0):
            raise InvalidParameterError(f'--rate {rate_hz!r}: must be a number > 0 [Hz]')
        period_s = 1.0 / rate_hz
    keys = tuple(card.observation_keys) or tuple(_shapes(model.observation_space))
    return DriveSetup(keys, objects, control, tuple(np.asarray(space.low, dtype=float)),
                      tuple(np.asarray(space.high, dtype=float)), tuple(card.action_range),
                      period_s, None if steering is None else tuple(float(b) for b in steering))


def _objects_spec(card):
    from vehicle_sim.gym.objects import objects_spec
    return objects_spec(card.options.get('objects'), card.env_id)

