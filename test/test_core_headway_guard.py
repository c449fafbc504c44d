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
The headway guard (core/learning/headway_guard.py): which rows are leads, and the speed.

Tables are built by core's own objects_table from world-frame neighbours, so that the guard is
checked on what the environment and the policy node give it; each expected speed is worked out
from the constant-deceleration stop the module states.
"""

import math
import pathlib

import pytest

from vehicle_sim.core.learning import headway_guard as hg
from vehicle_sim.core.learning.objects_table import Neighbour, objects_table, ObjectsTableSpec

SPEC = ObjectsTableSpec(count=5, range_m=80.0, speed_scale_mps=40.0)
B, TR, D0 = hg.DECELERATION_MPS2, hg.REACTION_S, hg.STANDSTILL_DISTANCE_M


def _guard(forward, others, ego_yaw=0.0, offset=0.0, heading_error=0.0):
    """Return the guard's speed for an ego at the origin, heading ego_yaw, at ``forward``."""
    table = objects_table(SPEC, 0.0, 0.0, ego_yaw, forward, 0.0, others)
    return hg.guard_speed(table, SPEC.range_m, SPEC.speed_scale_mps, forward, offset,
                          heading_error)


def _stop(forward, lead_speed, gap):
    """Return the speed from which braking at B after TR ends at lead_speed with D0 left."""
    closing = max(0.0, forward - lead_speed)
    return lead_speed + math.sqrt(2.0 * B * max(0.0, gap - D0 - TR * closing))


def test_no_lead_allows_any_speed():
    assert _guard(20.0, []) == math.inf
    # behind, in the next lane either side, or beyond the table's range: none is a lead
    assert _guard(20.0, [Neighbour(-15.0, 0.0, 0.0, 30.0), Neighbour(25.0, 3.75, 0.0, 5.0),
                         Neighbour(25.0, -3.75, 0.0, 5.0), Neighbour(85.0, 0.0, 0.0, 0.0)]) \
        == math.inf


@pytest.mark.parametrize('forward, lead_speed, gap', [
    (20.0, 14.0, 30.0),     # closing at 6 m/s: the reaction time eats 3 m of the gap
    (20.0, 25.0, 30.0),     # pulling away: no reaction distance
    (30.0, 0.0, 70.0),      # a car at rest
    (10.0, 0.0, 6.0),       # already inside the standstill distance: stop
])
def test_the_speed_is_the_constant_deceleration_stop(forward, lead_speed, gap):
    allowed = _guard(forward, [Neighbour(gap, 0.4, 0.0, lead_speed)])
    assert allowed == pytest.approx(_stop(forward, lead_speed, gap), abs=1e-4)
    # worked by hand for the first: 14 + sqrt(2 * 3 * (30 - 9 - 0.5 * 6)) = 24.39 m/s
    if (forward, lead_speed, gap) == (20.0, 14.0, 30.0):
        assert (B, TR, D0) == (3.0, 0.5, 9.0)
        assert allowed == pytest.approx(14.0 + math.sqrt(108.0), abs=1e-4)


def test_the_nearest_constraint_wins_and_the_allowed_speed_grows_with_the_gap():
    near, far = Neighbour(25.0, 0.0, 0.0, 10.0), Neighbour(60.0, 0.0, 0.0, 0.0)
    assert _guard(20.0, [near, far]) == pytest.approx(
        min(_stop(20.0, 10.0, 25.0), _stop(20.0, 0.0, 60.0)), abs=1e-4)
    speeds = [_guard(20.0, [Neighbour(gap, 0.0, 0.0, 0.0)]) for gap in (10, 20, 40, 79)]
    assert speeds == sorted(speeds) and speeds[0] < speeds[-1]


def test_the_lane_is_found_from_the_lane_state_not_the_ego_s_axis():
    # the ego 3.5 m left of its lane's centre (changing lanes): a car 3.6 m to its right is on
    # that centre line, so a lead; a car on the ego's own axis is 3.5 m off it, so not
    others_right = [Neighbour(30.0, -3.6, 0.0, 10.0)]
    assert _guard(20.0, others_right) == math.inf
    assert _guard(20.0, others_right, offset=3.5) == pytest.approx(_stop(20.0, 10.0, 30.0),
                                                                   abs=1e-3)
    assert _guard(20.0, [Neighbour(30.0, 0.0, 0.0, 10.0)], offset=3.5) == math.inf
    # the ego heading 0.1 rad left of its lane: a car 40 m ahead on the lane's centre line
    # lies 40 sin(0.1) = 4 m to the ego's right
    lane_yaw = -0.1     # the lane's direction in the world, the ego's yaw 0
    ahead = Neighbour(40.0 * math.cos(lane_yaw), 40.0 * math.sin(lane_yaw), lane_yaw, 15.0)
    assert _guard(20.0, [ahead]) == math.inf
    assert _guard(20.0, [ahead], heading_error=0.1) == pytest.approx(
        _stop(20.0, 15.0 * math.cos(0.1), 40.0 * math.cos(0.1)), abs=1e-3)


def test_a_car_half_over_the_line_counts():
    half = hg.PATH_HALF_WIDTH_M
    assert _guard(20.0, [Neighbour(30.0, half - 0.05, 0.0, 0.0)]) < 20.0
    assert _guard(20.0, [Neighbour(30.0, half + 0.05, 0.0, 0.0)]) == math.inf


def test_docs_state_the_guard_s_constants():
    root = pathlib.Path(__file__).resolve().parents[1]
    text = ' '.join((root / 'docs' / 'gym.md').read_text(encoding='utf-8').split())
    assert f'braking at {B:g} m/s² after a reaction time of {TR:g} s' in text
    assert f'with {D0:g} m between the vehicle' in text
    assert f'within {hg.PATH_HALF_WIDTH_M:g} m of the ego' in text
    at_rest = math.sqrt(2.0 * B * (SPEC.range_m - D0))
    assert f'{SPEC.range_m:g} m range a vehicle at rest is met in time from below ' \
           f'{at_rest:.1f} m/s' in text
