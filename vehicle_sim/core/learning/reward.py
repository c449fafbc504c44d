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
The default reward of the Gym environment, term by term.

reward = progress_weight * progress [m] - collision_penalty * (1 if a new collision this step)
         + goal_reward * (1 on the step the goal is reached)

Each term is reported separately (:func:`reward_terms`), so that a user's reward can reuse
them and a learning curve can be read term by term. Leaving the lane adds a term once lanes
exist (the maps issue); it goes here, next to the others.
"""

from dataclasses import dataclass
import math
from typing import Dict

from vehicle_sim.core.specs.errors import InvalidParameterError

# The names of the terms, in the order info['reward_terms'] lists them.
TERMS = ('progress', 'collision', 'goal')


@dataclass(frozen=True)
class RewardWeights:
    """
    Weights of the default reward.

    :param progress_weight: reward per metre of progress [1/m].
    :param collision_penalty: subtracted on a step with a new collision [-], >= 0.
    :param goal_reward: added on the step the goal is reached [-].
    """

    progress_weight: float = 1.0
    collision_penalty: float = 10.0
    goal_reward: float = 10.0

    def __post_init__(self):
        for name in ('progress_weight', 'collision_penalty', 'goal_reward'):
            value = getattr(self, name)
            if not math.isfinite(value):
                raise InvalidParameterError(f'{name} = {value!r}: must be finite')
        if self.collision_penalty < 0.0:
            raise InvalidParameterError(f'collision_penalty = {self.collision_penalty!r}: '
                                        'must be >= 0 (it is subtracted)')


def reward_terms(weights: RewardWeights, progress_m: float, collided: bool,
                 reached_goal: bool) -> Dict[str, float]:
    """
    Return the weighted terms of one step: {'progress', 'collision', 'goal'}.

    :param progress_m: the step's progress [m] (core/learning/progress.py).
    :param collided: a new collision happened during the step.
    :param reached_goal: the goal was reached on this step (not before).
    """
    return {
        'progress': weights.progress_weight * float(progress_m),
        'collision': -weights.collision_penalty if collided else 0.0,
        'goal': weights.goal_reward if reached_goal else 0.0,
    }


def total(terms: Dict[str, float]) -> float:
    """Return the reward: the sum of the terms."""
    return float(sum(terms.values()))
