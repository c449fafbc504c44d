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


"""The learning math of core/learning: progress along a path, toward a goal, along the heading."""

import math

import pytest

from vehicle_sim.core.learning.progress import GoalProgress, HeadingProgress, PathProgress
from vehicle_sim.core.learning.reward import reward_terms, RewardWeights, TERMS, total
from vehicle_sim.core.specs.errors import InvalidParameterError


def test_path_progress_is_the_change_of_the_arc_length_of_the_nearest_point():
    path = PathProgress([[0.0, 0.0], [10.0, 0.0], [10.0, 10.0]])
    assert path.length_m == 20.0
    assert path.project(4.0, 1.5) == (4.0, 1.5)
    assert path.project(12.0, 6.0) == (16.0, 2.0)          # on the second leg
    assert path.project(-3.0, 4.0) == (0.0, 5.0)           # before the start: the first point
    path.start(1.0, 0.5)
    assert path.advance(10.5, 3.0) == pytest.approx(12.0)  # 1 -> 13 m around the corner
    assert path.lateral_m == pytest.approx(0.5)
    assert path.advance(10.5, 1.0) == pytest.approx(-2.0)  # backwards is negative
    assert not path.done
    path.advance(10.0, 12.0)
    assert path.done


@pytest.mark.parametrize('points, message', [
    ([[0.0, 0.0]], 'at least two'),
    ([[0.0, 0.0], [1.0, math.nan]], 'finite'),
    ([[1.0, 1.0], [1.0, 1.0]], 'no length'),
])
def test_a_bad_path_is_refused(points, message):
    with pytest.raises(InvalidParameterError, match=message):
        PathProgress(points)


def test_goal_progress_is_how_much_closer_and_done_inside_the_radius():
    goal = GoalProgress((10.0, 0.0), 2.0)
    goal.start(0.0, 0.0)
    assert goal.advance(3.0, 4.0) == pytest.approx(10.0 - math.hypot(7.0, 4.0))
    assert not goal.done
    goal.advance(8.5, 0.0)
    assert goal.done
    with pytest.raises(InvalidParameterError, match='radius'):
        GoalProgress((0.0, 0.0), 0.0)


def test_heading_progress_projects_the_displacement_on_the_start_heading():
    heading = HeadingProgress()
    heading.start(1.0, 1.0, math.pi / 2)
    assert heading.advance(2.0, 4.0, 0.0) == pytest.approx(3.0)
    assert heading.advance(0.0, 4.0, 0.0) == pytest.approx(-2.0)     # now along x, reversing


def test_the_reward_terms_and_their_sum():
    weights = RewardWeights(progress_weight=2.0, collision_penalty=5.0, goal_reward=7.0)
    terms = reward_terms(weights, 0.25, True, True)
    assert list(terms) == list(TERMS)
    assert terms == {'progress': 0.5, 'collision': -5.0, 'goal': 7.0}
    assert total(terms) == 2.5
    assert total(reward_terms(weights, 0.25, False, False)) == 0.5
    with pytest.raises(InvalidParameterError, match='collision_penalty'):
        RewardWeights(collision_penalty=-1.0)
    with pytest.raises(InvalidParameterError, match='progress_weight'):
        RewardWeights(progress_weight=math.inf)
