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

"""Drivetrain math: differential ratios, ramp, speeds, rpm, LSD (Webots' driver.c)."""

import math

import numpy as np
import pytest

from vehicle_sim.core.car.ackermann import ackermann_angles
from vehicle_sim.core.car.drivetrain import (
    central_ratio,
    cruise_wheel_targets,
    current_speed_mps,
    Differential,
    distribute_torque,
    engine_rpm,
    front_ratio,
    max_signed_acceleration,
    ramp_toward,
    rear_ratio,
    update_slip_ratios,
    wheel_acceleration_radps2,
    wheel_speeds,
)
from vehicle_sim.core.car.vehicle_io import Wheel

L_M = 2.94      # wheelbase
TF_M = 1.64     # front track
TR_M = 1.6      # rear track
GEARS = (-12.0, 10.0, 6.5, 4.5, 3.5, 2.75)
CAR_TYPES = ('traction', 'propulsion', '4x4')


def test_ratios_are_exactly_one_half_when_not_steering():
    assert front_ratio(0.0, 0.0, 0.0) == 0.5
    assert rear_ratio(0.0, TR_M, L_M) == 0.5
    assert central_ratio(0.0, 0.3, 0.4) == 0.5


@pytest.mark.parametrize('delta', [-0.5, -0.1, 0.2, 0.6])
def test_ratios_match_webots_turning_radius_formulas(delta):
    right, left = ackermann_angles(delta, TF_M, L_M)
    # driver.c: R = L/sin θ (front), R = L/tan δ ∓ Tr/2 (rear), R = L/sin δ and L/tan δ (central,
    # times k = rr/rf); ratio = R_right / (R_left + R_right), central k·R_front/(R_front+R_rear).
    r_r, r_l = L_M / math.sin(right), L_M / math.sin(left)
    assert front_ratio(delta, right, left) == pytest.approx(r_r / (r_l + r_r), rel=1e-12)
    r_r = L_M / math.tan(delta) - TR_M / 2.0
    r_l = L_M / math.tan(delta) + TR_M / 2.0
    assert rear_ratio(delta, TR_M, L_M) == pytest.approx(r_r / (r_l + r_r), rel=1e-12)
    r_front, r_rear = L_M / math.sin(delta), L_M / math.tan(delta)
    k = 0.4 / 0.35
    assert central_ratio(delta, 0.35, 0.4) == pytest.approx(
        k * r_front / (r_front + r_rear), rel=1e-12)


@pytest.mark.parametrize('car_type', CAR_TYPES)
def test_cruise_targets_straight_are_speed_over_radius_on_driven_wheels(car_type):
    # 10 m/s on 0.4 m (front) and 0.5 m (rear) tyres: 25 and 20 rad/s; undriven wheels 0.
    targets = cruise_wheel_targets(10.0, car_type, 0.5, 0.5, 0.5, 0.4, 0.5)
    front = 25.0 if car_type != 'propulsion' else 0.0
    rear = 20.0 if car_type != 'traction' else 0.0
    np.testing.assert_allclose(targets, [front, front, rear, rear], rtol=1e-12)


@pytest.mark.parametrize('delta', [0.3, -0.3])
def test_cruise_targets_in_a_turn_outer_wheel_faster(delta):
    right, left = ackermann_angles(delta, TF_M, L_M)
    ratios = (front_ratio(delta, right, left), rear_ratio(delta, TR_M, L_M),
              central_ratio(delta, 0.35, 0.35))
    targets = cruise_wheel_targets(8.0, '4x4', *ratios, 0.35, 0.35)
    outer_sign = 1.0 if delta > 0 else -1.0    # right turn: the left wheels are outside
    assert outer_sign * (targets[Wheel.FRONT_LEFT] - targets[Wheel.FRONT_RIGHT]) > 0.0
    assert outer_sign * (targets[Wheel.REAR_LEFT] - targets[Wheel.REAR_RIGHT]) > 0.0


def test_cruise_targets_rear_axle_speeds_follow_turning_radii():
    # Rear wheels turn about the same centre at radii R ∓ Tr/2, R = L/tan δ, so their speeds
    # are in that ratio and average to v.
    delta = 0.25
    targets = cruise_wheel_targets(6.0, 'propulsion', 0.5, rear_ratio(delta, TR_M, L_M), 0.5,
                                   0.3, 0.3)
    radius = L_M / math.tan(delta)
    assert targets[Wheel.REAR_RIGHT] / targets[Wheel.REAR_LEFT] == pytest.approx(
        (radius - TR_M / 2.0) / (radius + TR_M / 2.0), rel=1e-12)
    assert 0.5 * (targets[Wheel.REAR_RIGHT] + targets[Wheel.REAR_LEFT]) * 0.3 == \
        pytest.approx(6.0, rel=1e-12)


def test_cruise_targets_4x4_front_axle_faster_by_one_over_cos_delta():
    # Front axle centre runs on L/sin δ, rear on L/tan δ: speed ratio 1/cos δ (equal radii).
    delta = 0.4
    right, left = ackermann_angles(delta, TF_M, L_M)
    targets = cruise_wheel_targets(5.0, '4x4', front_ratio(delta, right, left),
                                   rear_ratio(delta, TR_M, L_M), central_ratio(delta, 0.3, 0.3),
                                   0.3, 0.3)
    front = targets[Wheel.FRONT_RIGHT] + targets[Wheel.FRONT_LEFT]
    rear = targets[Wheel.REAR_RIGHT] + targets[Wheel.REAR_LEFT]
    assert front / rear == pytest.approx(1.0 / math.cos(delta), rel=1e-12)


def test_wheel_acceleration_is_100_kmh_over_time0to100_over_radius():
    # (100/3.6) m/s / 10 s / 0.4 m = 6.9444 rad/s².
    assert wheel_acceleration_radps2(10.0, 0.4) == pytest.approx(100.0 / 3.6 / 10.0 / 0.4,
                                                                 rel=1e-12)


def test_ramp_toward_is_symmetric_and_lands_on_target():
    current = np.array([0.0, 10.0, 4.5, -3.0])
    target = np.array([10.0, 0.0, 5.0, -10.0])
    result = ramp_toward(current, target, 1.0)
    np.testing.assert_allclose(result, [1.0, 9.0, 5.0, -4.0], rtol=0, atol=1e-12)
    ramp_toward(current, target, np.array([2.0, 2.0, 2.0, 0.5]), out=current)
    np.testing.assert_allclose(current, [2.0, 8.0, 5.0, -3.5], rtol=0, atol=1e-12)


def test_wheel_speeds_are_backward_differences():
    speeds = wheel_speeds(np.array([1.0, 2.0, -3.0, 4.0]), np.zeros(4), 0.5)
    np.testing.assert_allclose(speeds, [2.0, 4.0, -6.0, 8.0], rtol=1e-12)


def test_wheel_speeds_of_lists_are_a_list_equal_bit_for_bit_to_the_array_path():
    # The car logic's per-step path hands lists; the result must not depend on the path.
    now = [12.345678901, -0.1, 3.0e-9, 1.0e6 + 0.3]
    before = [12.3, 0.2, -7.0e-9, 1.0e6]
    listed = wheel_speeds(now, before, 0.01)
    assert type(listed) is list
    assert listed == wheel_speeds(np.array(now), np.array(before), 0.01).tolist()


def test_max_signed_acceleration_keeps_the_sign_of_the_largest_magnitude():
    # Accelerations (now − before)/0.01: [100, −300, 200, 0] → −300.
    now = [1.0, -3.0, 2.0, 0.0]
    assert max_signed_acceleration(now, [0.0] * 4, 0.01) == pytest.approx(-300.0, rel=1e-12)
    assert max_signed_acceleration([1.0] * 4, [1.0] * 4, 0.01) == 0.0


def test_engine_rpm_is_mean_wheel_speed_times_gear_ratio():
    # mean(10, 10, 10, 10) rad/s = 95.49 rev/min; × 10 (gear 1) = 954.93 rpm.
    assert engine_rpm([10.0] * 4, 1, GEARS, 4500.0) == pytest.approx(
        10.0 * 60.0 / (2.0 * math.pi) * 10.0, rel=1e-12)


def test_engine_rpm_uses_all_four_wheels():
    # Only the front wheels turn: the mean is halved.
    assert engine_rpm([10.0, 10.0, 0.0, 0.0], 2, GEARS, 4500.0) == pytest.approx(
        5.0 * 60.0 / (2.0 * math.pi) * 6.5, rel=1e-12)


def test_engine_rpm_reverse_is_positive_for_backward_wheels():
    assert engine_rpm([-2.0] * 4, -1, GEARS, 4500.0) == pytest.approx(
        2.0 * 60.0 / (2.0 * math.pi) * 12.0, rel=1e-12)


def test_engine_rpm_neutral_is_zero():
    assert engine_rpm([50.0] * 4, 0, GEARS, 4500.0) == 0.0


def test_engine_rpm_clamps_at_max_and_maps_nan_to_zero():
    assert engine_rpm([100.0] * 4, 1, GEARS, 4500.0) == 4500.0
    assert engine_rpm([math.nan] * 4, 1, GEARS, 4500.0) == 0.0


@pytest.mark.parametrize('car_type', CAR_TYPES)
def test_distribute_torque_without_lsd_sums_to_total(car_type):
    torque = distribute_torque(1000.0, car_type, 0.45, 0.55, 0.6)
    assert torque.sum() == pytest.approx(1000.0, rel=1e-12)
    if car_type == 'traction':
        np.testing.assert_allclose(torque, [450.0, 550.0, 0.0, 0.0], rtol=1e-12)
    elif car_type == 'propulsion':
        np.testing.assert_allclose(torque, [0.0, 0.0, 550.0, 450.0], rtol=1e-12)
    else:
        # FR = T·rf·rc, FL = T·(1−rf)·rc, RR = T·rr·(1−rc), RL = T·(1−rr)·(1−rc).
        np.testing.assert_allclose(torque, [270.0, 330.0, 220.0, 180.0], rtol=1e-12)


def test_distribute_torque_with_lsd_gives_faster_side_less_torque():
    # s_f = 0.2 (right faster): ratio 0.5·(1 − 0.2) = 0.4 → FR 400, FL 600; total kept.
    slip = np.array([0.2, 0.0, 0.0])
    torque = distribute_torque(1000.0, 'traction', 0.5, 0.5, 0.5, slip=slip)
    np.testing.assert_allclose(torque, [400.0, 600.0, 0.0, 0.0], rtol=1e-12)


def test_slip_ratio_integrates_right_left_imbalance():
    # ω_FR = 12, ω_FL = 8: 12/20·2 − 1 = 0.2 per step, clamped at 1.
    slip = np.zeros(3)
    speeds = [12.0, 8.0, 5.0, 5.0]
    update_slip_ratios(slip, speeds, 'traction')
    assert slip[Differential.FRONT] == pytest.approx(0.2, rel=1e-12)
    update_slip_ratios(slip, speeds, 'traction')
    assert slip[Differential.FRONT] == pytest.approx(0.4, rel=1e-12)
    assert slip[Differential.REAR] == 0.0 and slip[Differential.CENTRAL] == 0.0
    for _ in range(10):
        update_slip_ratios(slip, speeds, 'traction')
    assert slip[Differential.FRONT] == 1.0


def test_slip_ratio_of_faster_right_wheel_lowers_its_torque():
    slip = np.zeros(3)
    update_slip_ratios(slip, [0.0, 0.0, 11.0, 9.0], 'propulsion')
    torque = distribute_torque(500.0, 'propulsion', 0.5, 0.5, 0.5, slip=slip)
    assert slip[Differential.REAR] > 0.0
    assert torque[Wheel.REAR_RIGHT] < torque[Wheel.REAR_LEFT]


def test_slip_ratio_4x4_updates_front_rear_and_central():
    # Front sum 20, rear 10: central 20/30·2 − 1 = 1/3; front 0.2 (12 vs 8); rear −0.2 (4 vs 6).
    slip = update_slip_ratios(np.zeros(3), [12.0, 8.0, 4.0, 6.0], '4x4')
    np.testing.assert_allclose(slip, [0.2, -0.2, 1.0 / 3.0], rtol=1e-12)


def test_slip_ratio_resets_on_wheels_at_rest_and_saturates_on_opposite_wheels():
    slip = np.array([0.5, 0.0, 0.0])
    update_slip_ratios(slip, [0.0, 0.0, 0.0, 0.0], 'traction')    # 0/0 = NaN → 0
    assert slip[Differential.FRONT] == 0.0
    update_slip_ratios(slip, [3.0, -3.0, 0.0, 0.0], 'traction')   # 3/0 = +inf → clamp 1
    assert slip[Differential.FRONT] == 1.0


@pytest.mark.parametrize('car_type, expected', [
    ('traction', 0.5 * (10.0 + 12.0) * 0.3),                        # 3.3 m/s
    ('propulsion', 0.5 * (20.0 + 22.0) * 0.4),                      # 8.4 m/s
    ('4x4', 0.25 * (10.0 + 12.0) * 0.3 + 0.25 * (20.0 + 22.0) * 0.4),  # 5.85 m/s
])
def test_current_speed_uses_driven_wheels_only(car_type, expected):
    speeds = [10.0, 12.0, 20.0, 22.0]
    assert current_speed_mps(speeds, car_type, 0.3, 0.4) == pytest.approx(expected, rel=1e-12)
