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

"""Ackermann steering geometry (Webots' driver.c)."""

import math

import pytest

from vehicle_sim.core.car.ackermann import ackermann_angles

TRACK_M = 1.628    # Toyota Prius trackFront
WHEELBASE_M = 2.8  # Toyota Prius wheelbase


def _spec_formula(delta, track, wheelbase):
    # driver.c: cot = 1/tan δ; θR = atan(1/(cot − Tf/(2L))); θL = atan(1/(cot + Tf/(2L))).
    cot = 1.0 / math.tan(delta)
    return (math.atan(1.0 / (cot - track / (2.0 * wheelbase))),
            math.atan(1.0 / (cot + track / (2.0 * wheelbase))))


@pytest.mark.parametrize('delta', [-0.9, -0.5, -0.1, -1e-6, 1e-6, 0.05, 0.3, 0.6])
def test_ackermann_matches_webots_formula(delta):
    right, left = ackermann_angles(delta, TRACK_M, WHEELBASE_M)
    expected_right, expected_left = _spec_formula(delta, TRACK_M, WHEELBASE_M)
    assert right == pytest.approx(expected_right, abs=1e-9)
    assert left == pytest.approx(expected_left, abs=1e-9)


def test_ackermann_zero_steering_gives_zero_angles_without_division_error():
    assert ackermann_angles(0.0, TRACK_M, WHEELBASE_M) == (0.0, 0.0)


def test_ackermann_right_turn_inner_right_wheel_steers_more():
    right, left = ackermann_angles(0.3, TRACK_M, WHEELBASE_M)
    assert right > 0.3 > left > 0.0


def test_ackermann_left_turn_inner_wheel_steers_more():
    right, left = ackermann_angles(-0.3, TRACK_M, WHEELBASE_M)
    assert left < -0.3 < right < 0.0


def test_ackermann_left_and_right_turns_are_mirror_images():
    right, left = ackermann_angles(0.4, TRACK_M, WHEELBASE_M)
    mirrored_right, mirrored_left = ackermann_angles(-0.4, TRACK_M, WHEELBASE_M)
    assert mirrored_right == pytest.approx(-left, abs=1e-12)
    assert mirrored_left == pytest.approx(-right, abs=1e-12)


@pytest.mark.parametrize('delta', [0.2, -0.35])
def test_ackermann_wheel_axes_meet_on_the_rear_axle_line(delta):
    # The turn centre lies on the rear axle at R = L/tan δ to the right of the centre line
    # (negative: to the left); each front wheel's axis passes through it:
    # L/tan θR = R − Tf/2 and L/tan θL = R + Tf/2.
    right, left = ackermann_angles(delta, TRACK_M, WHEELBASE_M)
    radius = WHEELBASE_M / math.tan(delta)
    assert WHEELBASE_M / math.tan(right) == pytest.approx(radius - TRACK_M / 2.0, rel=1e-9)
    assert WHEELBASE_M / math.tan(left) == pytest.approx(radius + TRACK_M / 2.0, rel=1e-9)
