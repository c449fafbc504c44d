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
         [with a lane map:] - off_lane_penalty * (the step's duration [s] if it ends off
         every lane) - solid_line_penalty * (solid lines crossed in the step)
         - lane_centre_penalty * (|offset| / half the lane's width, on a lane) * the step's
         duration [s]

Each term is reported separately (:func:`reward_terms`), so that a user's reward can reuse
them and a learning curve can be read term by term. The ``lane`` term (:func:`lane_term`) is
there only when the world has lanes (LANE_TERMS).
"""

from dataclasses import dataclass
import math
from typing import Dict

from vehicle_sim.core.map.lane_graph import SOLID_TYPES
from vehicle_sim.core.specs.errors import InvalidParameterError

# The names of the terms, in the order info['reward_terms'] lists them (LANE_TERMS: a world
# with a lane map).
TERMS = ('progress', 'collision', 'goal')
LANE_TERMS = TERMS + ('lane',)
_PENALTIES = ('collision_penalty', 'off_lane_penalty', 'solid_line_penalty',
              'lane_centre_penalty')


@dataclass(frozen=True)
class RewardWeights:
    """
    Weights of the default reward.

    :param progress_weight: reward per metre of progress [1/m].
    :param collision_penalty: subtracted on a step with a new collision [-], >= 0.
    :param goal_reward: added on the step the goal is reached [-].
    :param off_lane_penalty: subtracted per second off every lane [1/s], >= 0.
    :param solid_line_penalty: subtracted per solid line crossed [-], >= 0.
    :param lane_centre_penalty: subtracted per second on a lane, times the distance from its
        centreline over half its width (0 at the centre, 1 at its edge) [1/s], >= 0.
    """

    progress_weight: float = 1.0
    collision_penalty: float = 10.0
    goal_reward: float = 10.0
    off_lane_penalty: float = 10.0
    solid_line_penalty: float = 1.0
    lane_centre_penalty: float = 0.0

    def __post_init__(self):
        for name in ('progress_weight', 'goal_reward') + _PENALTIES:
            value = getattr(self, name)
            if not math.isfinite(value):
                raise InvalidParameterError(f'{name} = {value!r}: must be finite')
        for name in _PENALTIES:
            if getattr(self, name) < 0.0:
                raise InvalidParameterError(f'{name} = {getattr(self, name)!r}: must be >= 0 '
                                            '(it is subtracted)')


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


def solid_crossings(invasions) -> int:
    """Return how many of a step's LaneInvasions (core/map/lane_invasion.py) were solid lines."""
    return sum(1 for event in invasions if event.line_type in SOLID_TYPES)


def lane_term(weights: RewardWeights, on_lane: bool, solid_lines: int, step_s: float,
              centre_fraction: float = 0.0) -> float:
    """
    Return the weighted ``lane`` term of one step (0 or negative).

    :param on_lane: the step ended on a lane (LaneState.on_lane: within half the lane's width
        of a lane's centreline, between its ends).
    :param solid_lines: solid lines crossed during the step (:func:`solid_crossings`).
    :param step_s: the step's duration [s] (an env step: action_repeat basic steps).
    :param centre_fraction: on a lane, |offset from its centreline| / half its width at the
        step's end (0 .. 1).
    """
    if on_lane:
        penalty = weights.lane_centre_penalty * float(centre_fraction) * float(step_s) \
            if weights.lane_centre_penalty else 0.0
    else:
        penalty = weights.off_lane_penalty * float(step_s)
    if solid_lines:
        penalty += weights.solid_line_penalty * solid_lines
    return -penalty if penalty else 0.0


def total(terms: Dict[str, float]) -> float:
    """Return the reward: the sum of the terms."""
    return float(sum(terms.values()))
