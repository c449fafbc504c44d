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
A policy's card: the environment a policy was trained on, saved beside its model file.

A trained policy reads observations of a given layout and writes actions of a given layout; to
run it again (an evaluation, the ROS node driven by it: ``vehicle-sim policy run``) the same
environment must be built. The card says which: the environment id, its keyword options
(``world`` included), the observation keys the policy reads and the range its actions were
rescaled to. It is a JSON file next to the model: ``model.zip`` -> ``model.card.json``
(:func:`card_path`).

:func:`make_env` builds the environment of a card, wrapped as the policy saw it:
``FilterObservation`` (the card's keys) and ``RescaleAction`` (the card's range).
"""

from dataclasses import dataclass, field
import json
from pathlib import Path
from typing import Dict, Tuple

from vehicle_sim.core.specs.errors import InvalidParameterError

CARD_SUFFIX = '.card.json'
CARD_VERSION = 1
_FIELDS = ('version', 'env_id', 'options', 'observation_keys', 'action_range')


@dataclass(frozen=True)
class PolicyCard:
    """
    The environment of a policy.

    :param env_id: the Gymnasium id (``vehicle_sim/Drive-v0``).
    :param options: its keyword options (``world``, ``scenario`` and docs/gym.md's options).
    :param observation_keys: the Dict keys the policy reads, in order.
    :param action_range: (low, high) every action entry was rescaled to for the policy.
    """

    env_id: str
    options: Dict = field(default_factory=dict)
    observation_keys: Tuple[str, ...] = ()
    action_range: Tuple[float, float] = (-1.0, 1.0)

    def as_dict(self):
        """Return the card as its JSON object."""
        return {'version': CARD_VERSION, 'env_id': self.env_id, 'options': dict(self.options),
                'observation_keys': list(self.observation_keys),
                'action_range': list(self.action_range)}


def card_path(model_path) -> Path:
    """Return the card file of a model file: ``model.zip`` -> ``model.card.json``."""
    path = Path(model_path)
    return path.with_name(path.name[:-len(path.suffix)] + CARD_SUFFIX if path.suffix
                          else path.name + CARD_SUFFIX)


def save_card(card: PolicyCard, model_path) -> Path:
    """Write the card beside ``model_path``; return its path."""
    path = card_path(model_path)
    path.write_text(json.dumps(card.as_dict(), indent=2, sort_keys=True) + '\n',
                    encoding='utf-8')
    return path


def load_card(model_path) -> PolicyCard:
    """
    Read the card beside ``model_path``.

    :raises InvalidParameterError: naming the file for a missing or malformed card.
    """
    path = card_path(model_path)
    try:
        data = json.loads(path.read_text(encoding='utf-8'))
    except FileNotFoundError:
        raise InvalidParameterError(
            f'{model_path}: no policy card beside it ({path}): the environment the policy was '
            'trained on is unknown (docs/learning.md)') from None
    except (OSError, ValueError) as error:
        raise InvalidParameterError(f'{path}: not a policy card: {error}') from None
    if not isinstance(data, dict):
        raise InvalidParameterError(f'{path}: not a policy card: a JSON object is expected')
    unknown = sorted(set(data) - set(_FIELDS))
    missing = sorted(set(_FIELDS) - set(data))
    if unknown or missing or data['version'] != CARD_VERSION:
        raise InvalidParameterError(
            f'{path}: not a policy card of version {CARD_VERSION}: '
            f'unknown fields {unknown}, missing fields {missing}, version '
            f'{data.get("version")!r}')
    rng = data['action_range']
    if (not isinstance(data['options'], dict) or not isinstance(data['observation_keys'], list)
            or not isinstance(rng, list) or len(rng) != 2):
        raise InvalidParameterError(
            f'{path}: options must be an object, observation_keys a list and action_range '
            '[low, high]')
    return PolicyCard(str(data['env_id']), dict(data['options']),
                      tuple(str(k) for k in data['observation_keys']),
                      (float(rng[0]), float(rng[1])))


def make_env(card: PolicyCard, **overrides):
    """
    Return the card's environment, wrapped as its policy saw it.

    :param overrides: options replacing the card's (``render_mode``, a ``scenario`` to judge).
    """
    import gymnasium

    import vehicle_sim.gym  # noqa: F401  (registers the ids)
    options = dict(card.options)
    options.update(overrides)
    env = gymnasium.make(card.env_id, **options)
    if card.observation_keys:
        env = gymnasium.wrappers.FilterObservation(env, list(card.observation_keys))
    low, high = card.action_range
    return gymnasium.wrappers.RescaleAction(env, low, high)
