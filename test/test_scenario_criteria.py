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

"""Scenario criteria and the waypoint follower, fed by hand: verdicts and measured values."""

import math
from types import SimpleNamespace

import pytest

from vehicle_sim.core.world.collision import CollisionEvent
from vehicle_sim.scenarios.actors import WaypointFollower
from vehicle_sim.scenarios.criteria import (
    CRITERIA,
    distance_to_polyline,
    field_value,
    Sample,
    validate_criterion,
)
from vehicle_sim.scenarios.schema import ActorSpec, Waypoint

DURATION_S = 10.0


def _criterion(kind, **data):
    return CRITERIA[kind](kind, 'ego', validate_criterion(kind, data), DURATION_S)


def _feed(criterion, points, dt_s=0.5):
    # points: (x, y, speed) per sample, one sample every dt_s from t = 0
    for index, (x, y, speed) in enumerate(points):
        criterion.observe(Sample(index * dt_s, x, y, 0.0, speed))
    return criterion.result()


def test_distance_to_polyline_is_the_perpendicular_or_the_nearest_end():
    path = [(0.0, 0.0), (10.0, 0.0), (10.0, 10.0)]
    assert distance_to_polyline(5.0, 2.0, path) == pytest.approx(2.0, abs=1e-12)
    assert distance_to_polyline(12.0, 5.0, path) == pytest.approx(2.0, abs=1e-12)
    # beyond the end: the distance to the end point, sqrt(3² + 4²) = 5
    assert distance_to_polyline(-3.0, 4.0, path) == pytest.approx(5.0, abs=1e-12)


def test_reach_goal_reports_the_first_time_inside_the_region():
    result = _feed(_criterion('reach_goal', goal=[4.0, 0.0], radius=1.0),
                   [(0.0, 0.0, 2.0), (2.0, 0.0, 2.0), (3.5, 0.0, 2.0), (5.0, 0.0, 2.0)])
    assert result.passed
    assert result.value == pytest.approx(1.0)          # third sample, t = 2 × 0.5 s
    assert result.unit == 's'


def test_reach_goal_after_its_deadline_fails_with_the_time():
    result = _feed(_criterion('reach_goal', goal=[4.0, 0.0], radius=1.0, within=0.75),
                   [(0.0, 0.0, 2.0), (2.0, 0.0, 2.0), (3.5, 0.0, 2.0)])
    assert not result.passed
    assert result.value == pytest.approx(1.0)


def test_reach_goal_with_max_speed_counts_only_a_slow_enough_visit():
    result = _feed(_criterion('reach_goal', goal=[4.0, 0.0], radius=1.0, max_speed=0.1),
                   [(3.5, 0.0, 2.0), (4.0, 0.0, 1.0), (4.2, 0.0, 0.05)])
    assert result.passed
    assert result.value == pytest.approx(1.0)


def test_reach_goal_never_reached_fails_and_names_the_closest_distance():
    result = _feed(_criterion('reach_goal', goal=[10.0, 0.0], radius=1.0),
                   [(0.0, 0.0, 1.0), (6.0, 0.0, 1.0)])
    assert not result.passed
    assert result.value is None
    assert 'closest 4.000 m' in result.detail


def test_reach_goal_passed_through_too_fast_says_it_was_reached_and_by_how_much():
    # Inside the circle at t = 0.5 s (3.5 m) and 1.0 s (4.2 m), never below 0.1 m/s there: the
    # slowest inside is 1.5 m/s at 1.0 s, 1.4 m/s above the limit.
    result = _feed(_criterion('reach_goal', goal=[4.0, 0.0], radius=1.0, max_speed=0.1),
                   [(2.0, 0.0, 2.0), (3.5, 0.0, 2.0), (4.2, 0.0, 1.5), (6.0, 0.0, 1.0)])
    assert not result.passed
    assert result.value is None
    assert result.detail == ('goal (4, 0) r=1 m below 0.1 m/s entered at 0.50 s but never below '
                             'the limit there (slowest 1.5 m/s at 1.00 s, 1.4 m/s above it); '
                             'deadline 10 s')


def test_no_collision_says_one_collision_in_the_singular():
    criterion = _criterion('no_collision')
    criterion.collision(CollisionEvent(1.25, 'wall', 10.0))
    result = criterion.result()
    assert (result.value, result.unit) == (1, 'collision')
    assert result.detail == '1 collision: wall at 1.25 s'
    criterion.collision(CollisionEvent(1.5, 'wall', 10.0))
    assert criterion.result().unit == 'collisions'


def test_no_collision_counts_events_except_the_ignored_bodies():
    criterion = _criterion('no_collision', ignore=['cone'])
    assert criterion.result().passed and criterion.result().value == 0
    criterion.collision(CollisionEvent(1.25, 'cone', 10.0))
    assert criterion.result().passed
    criterion.collision(CollisionEvent(2.5, 'wall', 900.0))
    result = criterion.result()
    assert not result.passed
    assert result.value == 1
    assert 'wall at 2.50 s' in result.detail


def test_stay_on_path_measures_the_largest_lateral_distance():
    criterion = _criterion('stay_on_path', path=[[0.0, 0.0], [20.0, 0.0]], max_distance=0.5)
    result = _feed(criterion, [(0.0, 0.1, 1.0), (5.0, -0.4, 1.0), (10.0, 0.2, 1.0)])
    assert result.passed
    assert result.value == pytest.approx(0.4)
    result = _feed(criterion, [(12.0, 0.7, 1.0)])
    assert not result.passed
    assert result.value == pytest.approx(0.7)


def test_max_speed_measures_the_top_absolute_speed():
    result = _feed(_criterion('max_speed', limit=5.0), [(0, 0, 4.0), (0, 0, -4.5), (0, 0, 3.0)])
    assert result.passed
    assert result.value == pytest.approx(4.5)
    result = _feed(_criterion('max_speed', limit=5.0), [(0, 0, 5.25)])
    assert not result.passed
    assert result.value == pytest.approx(5.25)


def _msg(value):
    return SimpleNamespace(header=SimpleNamespace(stamp=SimpleNamespace(sec=1)), data=value)


def _topic(op, value, mode, values):
    criterion = _criterion('topic', topic='/automobile/current_speed',
                           type='vehicle_msgs/msg/Float64Stamped', field='data', op=op,
                           value=value, mode=mode)
    for index, item in enumerate(values):
        criterion.message(_msg(item), 0.1 * index)
    return criterion.result()


@pytest.mark.parametrize('op, value, mode, values, passed, measured', [
    ('<=', 30.0, 'always', [10.0, 29.0, 30.0, 5.0], True, 30.0),  # the closest to failing
    ('>', 1.0, 'always', [10.0, 2.0, 30.0], True, 2.0),
    ('<=', 30.0, 'always', [10.0, 31.0, 40.0], False, 31.0),     # the first that fails
    ('>', 20.0, 'eventually', [10.0, 21.0, 25.0], True, 21.0),   # the first that passes
    ('>', 20.0, 'eventually', [10.0, 15.0], False, 15.0),        # none: the last
    ('==', 0.0, 'final', [5.0, 0.0], True, 0.0),
    ('!=', 0.0, 'final', [5.0, 0.0], False, 0.0),
])
def test_topic_predicate_modes_give_verdict_and_value(op, value, mode, values, passed,
                                                      measured):
    result = _topic(op, value, mode, values)
    assert result.passed is passed
    assert result.value == pytest.approx(measured)


def test_topic_predicate_without_messages_fails():
    result = _topic('<', 1.0, 'always', [])
    assert not result.passed
    assert 'no message received' in result.detail


def test_topic_predicate_with_a_missing_field_fails_naming_it():
    criterion = _criterion('topic', topic='/x', type='std_msgs/msg/Float64',
                           field='twist.linear.x', op='<', value=1.0)
    criterion.message(_msg(0.0), 0.0)
    result = criterion.result()
    assert not result.passed
    assert "no 'twist'" in result.detail


def test_field_value_follows_dotted_names():
    assert field_value(_msg(3.5), 'header.stamp.sec') == 1


def _follower(points, lookahead_m=2.0, loop=False):
    spec = ActorSpec('car', tuple(Waypoint(x, y, 3.0) for x, y in points), lookahead_m, loop)
    return WaypointFollower(spec, wheelbase_m=2.5)


def test_waypoint_follower_curvature_is_pure_pursuit():
    follower = _follower([(10.0, 0.0), (10.0, 10.0)])
    # aim point (10, 0) from (0, 0) heading +y: α = -π/2, L_d = 10: κ = 2 sin α / L_d = -0.2
    speed, curvature = follower.command(0.0, 0.0, math.pi / 2)
    assert speed == 3.0
    assert curvature == pytest.approx(-0.2, rel=1e-12)


def test_waypoint_follower_moves_on_within_lookahead_and_stops_at_the_last_point():
    follower = _follower([(10.0, 0.0), (20.0, 0.0)])
    follower.command(8.5, 0.0, 0.0)            # 1.5 m from the first point: aim at the second
    assert follower.index == 1
    assert follower.command(18.5, 0.0, 0.0) is not None   # last point: 1.5 m > ARRIVE_M
    assert follower.command(19.5, 0.0, 0.0) is None
    assert follower.done


def test_waypoint_follower_loops_back_to_the_first_point():
    follower = _follower([(10.0, 0.0), (20.0, 0.0)], loop=True)
    follower.command(8.5, 0.0, 0.0)
    follower.command(19.0, 0.0, 0.0)
    assert follower.index == 0 and not follower.done


def test_mean_speed_is_the_time_average_of_the_speed():
    from vehicle_sim.scenarios.criteria import MeanSpeed, Sample
    crit = MeanSpeed('mean_speed', '', {'min_mps': 7.0}, 10.0)
    # 0 -> 10 m/s over 2 s (ramp, mean 5), then 10 m/s for 2 s: 30 m in 4 s = 7.5 m/s
    for t, v in ((0.0, 0.0), (1.0, 5.0), (2.0, 10.0), (3.0, 10.0), (4.0, 10.0)):
        crit.observe(Sample(t, 0.0, 0.0, 0.0, v))
    result = crit.result()
    assert result.passed and abs(result.value - 7.5) < 1e-12
    slow = MeanSpeed('mean_speed', '', {'min_mps': 7.6}, 10.0)
    for t, v in ((0.0, 0.0), (1.0, 5.0), (2.0, 10.0), (3.0, 10.0), (4.0, 10.0)):
        slow.observe(Sample(t, 0.0, 0.0, 0.0, v))
    assert not slow.result().passed
    assert not MeanSpeed('mean_speed', '', {'min_mps': 0.0}, 10.0).result().passed
