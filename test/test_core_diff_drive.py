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

"""Tests of the bridge kinematics (core/diffdrive, core/bridge) and the command watchdog."""

import math

import pytest

from vehicle_sim.core.bridge.ackermann_mapping import (
    ackermann_to_wheel_speeds,
    equivalent_steering_rad,
    STEERING_REPORT_SPEED_EPS_MPS,
    turn_in_place_yaw_rate,
    wheel_base_plausibility,
)
from vehicle_sim.core.bridge.converter import AckermannToDifferential, STOP_COMMAND
from vehicle_sim.core.bridge.params import (
    BRIDGE_PARAM_SPECS,
    bridge_params_from_dict,
    DEFAULT_BRIDGE_PARAMS,
)
from vehicle_sim.core.commands.watchdog import CommandWatchdog
from vehicle_sim.core.diffdrive.kinematics import (
    integrate_pose,
    twist_from_wheel_speeds,
    wheel_mps_from_radps,
    wheel_radps_from_mps,
    wheel_speeds_from_twist,
    yaw_rate_from_steering,
)
from vehicle_sim.core.diffdrive.speed_limiter import limit_wheel_speeds, SpeedLimiter
from vehicle_sim.core.specs.errors import InvalidCommandError, InvalidParameterError

TOL = 1e-12
# tan(STEER_RAD) = 0.25 exactly enough for closed forms.
STEER_RAD = math.atan(0.25)


def make_bridge(**overrides):
    return AckermannToDifferential(bridge_params_from_dict(overrides, source='test'))


# --- conversion -------------------------------------------------------------------------------

def test_conversion_left_turn_right_wheel_faster():
    # ω = v·tanδ/L = 2·0.25/0.5 = 1 rad/s; turn radius R = v/ω = 2 m; wheels on radii
    # R ∓ t/2 = 1.8 m and 2.2 m at ω = 1 rad/s: v_l = 1.8 m/s, v_r = 2.2 m/s.
    left, right = ackermann_to_wheel_speeds(2.0, STEER_RAD, 0.5, 0.4)
    assert left == pytest.approx(1.8, abs=TOL)
    assert right == pytest.approx(2.2, abs=TOL)
    assert right > left


def test_conversion_right_turn_left_wheel_faster():
    left, right = ackermann_to_wheel_speeds(2.0, -STEER_RAD, 0.5, 0.4)
    assert left == pytest.approx(2.2, abs=TOL)
    assert right == pytest.approx(1.8, abs=TOL)


@pytest.mark.parametrize('mode', ['kinematic', 'literal'])
@pytest.mark.parametrize('speed_mps', [-1.5, 0.0, 0.7])
def test_conversion_zero_steering_equal_wheel_speeds(mode, speed_mps):
    left, right = ackermann_to_wheel_speeds(speed_mps, 0.0, 0.5, 0.4, mode=mode)
    assert left == right == speed_mps


def test_conversion_reverse_with_left_steer_turns_clockwise():
    # Bicycle model in reverse: ω = v·tanδ/L < 0 for v < 0, δ > 0 (the rear swings right).
    assert yaw_rate_from_steering(-1.0, STEER_RAD, 0.5) == pytest.approx(-0.5, abs=TOL)
    left, right = ackermann_to_wheel_speeds(-1.0, STEER_RAD, 0.5, 0.4)
    assert right - left == pytest.approx(-0.5 * 0.4, abs=TOL)


@pytest.mark.parametrize('speed_mps, steering_rad', [(1.0, 0.3), (0.0, -0.2), (-2.0, 0.5)])
def test_conversion_literal_mode_equals_seed_formula(speed_mps, steering_rad):
    # Seed snippet: left = speed - steering_tire_angle * tread / 2, right = speed + ... / 2.
    tread_m = 0.4
    left, right = ackermann_to_wheel_speeds(speed_mps, steering_rad, 0.5, tread_m, mode='literal')
    assert left == pytest.approx(speed_mps - steering_rad * tread_m / 2, abs=TOL)
    assert right == pytest.approx(speed_mps + steering_rad * tread_m / 2, abs=TOL)


@pytest.mark.parametrize('steering', [math.nan, math.inf, -math.inf, math.pi / 2, -2.0, '0.1'])
def test_conversion_invalid_steering_raises_naming_value(steering):
    with pytest.raises(InvalidCommandError, match='steering_tire_angle'):
        ackermann_to_wheel_speeds(1.0, steering, 0.5, 0.4)


def test_conversion_nonpositive_lengths_and_unknown_mode_raise():
    with pytest.raises(InvalidParameterError, match='wheel_base'):
        ackermann_to_wheel_speeds(1.0, 0.1, 0.0, 0.4)
    with pytest.raises(InvalidParameterError, match='wheel_tread'):
        ackermann_to_wheel_speeds(1.0, 0.1, 0.5, -0.4)
    with pytest.raises(InvalidParameterError, match='bicycle'):
        ackermann_to_wheel_speeds(1.0, 0.1, 0.5, 0.4, mode='bicycle')
    with pytest.raises(InvalidCommandError, match='speed'):
        ackermann_to_wheel_speeds(math.nan, 0.1, 0.5, 0.4)


# --- inverse ----------------------------------------------------------------------------------

@pytest.mark.parametrize('speed_mps', [-2.0, -0.3, 0.05, 0.3, 4.0])
@pytest.mark.parametrize('steering_rad', [-1.2, -0.3, 0.0, 0.1, 1.4])
def test_inverse_of_forward_is_identity(speed_mps, steering_rad):
    wheel_base_m, tread_m = 0.6, 0.45
    left, right = ackermann_to_wheel_speeds(speed_mps, steering_rad, wheel_base_m, tread_m)
    twist = twist_from_wheel_speeds(left, right, tread_m)
    assert twist.speed_mps == pytest.approx(speed_mps, abs=1e-12)
    assert twist.yaw_rate_radps == pytest.approx(
        speed_mps * math.tan(steering_rad) / wheel_base_m, rel=1e-12, abs=1e-12)
    # |v| >= v_eps: the reported steering is the exact inverse.
    steering = equivalent_steering_rad(twist.speed_mps, twist.yaw_rate_radps, wheel_base_m)
    assert steering == pytest.approx(steering_rad, abs=1e-9)


def test_inverse_steering_is_zero_at_standstill_and_continuous_through_zero_speed():
    wheel_base_m, yaw_rate_radps = 0.5, 0.4
    eps = STEERING_REPORT_SPEED_EPS_MPS
    assert equivalent_steering_rad(0.0, yaw_rate_radps, wheel_base_m) == 0.0
    # At |v| = v_eps the regularised law meets the exact inverse atan(ω·L/v).
    assert equivalent_steering_rad(eps, yaw_rate_radps, wheel_base_m) == pytest.approx(
        math.atan(yaw_rate_radps * wheel_base_m / eps), abs=TOL)
    # Sweep v from -4 v_eps to +4 v_eps: no jump larger than the Lipschitz bound of the law
    # (|dδ/dv| <= ω·L/v_eps² inside the band, smaller outside) times the sample step.
    step_mps = eps / 1000.0
    speeds = [-4 * eps + i * step_mps for i in range(8001)]
    values = [equivalent_steering_rad(v, yaw_rate_radps, wheel_base_m) for v in speeds]
    bound = yaw_rate_radps * wheel_base_m / eps ** 2 * step_mps
    assert max(abs(b - a) for a, b in zip(values, values[1:])) <= bound
    assert all(abs(value) < math.pi / 2 for value in values)


def test_wheel_angular_speed_helpers_round_trip():
    # 1.5 m/s on a 0.1 m wheel = 15 rad/s.
    assert wheel_radps_from_mps(1.5, 0.1) == pytest.approx(15.0, abs=TOL)
    assert wheel_mps_from_radps(15.0, 0.1) == pytest.approx(1.5, abs=TOL)
    with pytest.raises(InvalidParameterError, match='wheel_radius'):
        wheel_radps_from_mps(1.0, 0.0)


# --- limits -----------------------------------------------------------------------------------

def test_wheel_limit_scales_both_wheels_and_keeps_curvature():
    # (1.8, 2.2) with a 1.1 m/s limit: s = 1.1/2.2 = 0.5 -> (0.9, 1.1).
    left, right = limit_wheel_speeds(1.8, 2.2, 1.1)
    assert (left, right) == (pytest.approx(0.9, abs=TOL), pytest.approx(1.1, abs=TOL))
    before = twist_from_wheel_speeds(1.8, 2.2, 0.4)
    after = twist_from_wheel_speeds(left, right, 0.4)
    assert after.yaw_rate_radps / after.speed_mps == pytest.approx(
        before.yaw_rate_radps / before.speed_mps, rel=1e-12)


def test_wheel_limit_leaves_speeds_below_limit_or_disabled_unchanged():
    assert limit_wheel_speeds(-0.5, 0.9, 1.0) == (-0.5, 0.9)
    assert limit_wheel_speeds(-5.0, 9.0, 0.0) == (-5.0, 9.0)


def test_bridge_saturated_turn_keeps_commanded_curvature():
    bridge = make_bridge(wheel_base=0.5, wheel_tread=0.4, max_wheel_speed_mps=1.1,
                         max_accel_mps2=0.0, max_decel_mps2=0.0)
    command = bridge.step(2.0, STEER_RAD, 0.1)
    assert max(abs(command.left_mps), abs(command.right_mps)) == pytest.approx(1.1, abs=TOL)
    assert command.yaw_rate_radps / command.speed_mps == pytest.approx(0.25 / 0.5, rel=1e-12)


def test_speed_limiter_sign_change_brakes_then_accelerates():
    # From +0.1 at 2 m/s² decel: zero after 0.05 s; the remaining 0.05 s at 1 m/s² -> -0.05.
    limiter = SpeedLimiter(max_accel=1.0, max_decel=2.0)
    assert limiter.limit(-1.0, 0.1, 0.1) == pytest.approx(-0.05, abs=TOL)
    assert limiter.limit(-1.0, 1.0, 0.1) == pytest.approx(0.8, abs=TOL)
    assert SpeedLimiter().limit(-3.0, 2.0, 0.1) == -3.0


def test_bridge_acceleration_limit_respected_over_a_sequence():
    accel, decel, dt_s = 1.0, 2.0, 0.1
    bridge = make_bridge(max_accel_mps2=accel, max_decel_mps2=decel, max_wheel_speed_mps=0.0)
    targets = [1.0] * 15 + [0.2] * 5 + [-1.0] * 15 + [0.0] * 10
    previous = 0.0
    for target in targets:
        speed = bridge.step(target, 0.2, dt_s).speed_mps
        grows = abs(speed) > abs(previous) and speed * previous >= 0.0
        limit = (accel if grows else decel) * dt_s
        assert abs(speed - previous) <= limit + 1e-12
        previous = speed
    assert previous == pytest.approx(0.0, abs=TOL)
    # Closed form: 5 steps of 0.1 s at 1 m/s² from rest reach 0.5 m/s.
    bridge = make_bridge(max_accel_mps2=accel)
    for _ in range(5):
        command = bridge.step(1.0, 0.0, dt_s)
    assert command.speed_mps == pytest.approx(0.5, abs=1e-12)


def test_bridge_ramp_keeps_commanded_curvature_in_kinematic_mode():
    bridge = make_bridge(wheel_base=0.5, max_accel_mps2=0.5, max_wheel_speed_mps=0.0)
    for _ in range(10):
        command = bridge.step(2.0, STEER_RAD, 0.1)
        assert command.yaw_rate_radps == pytest.approx(command.speed_mps * 0.25 / 0.5, abs=TOL)


def test_bridge_rejected_command_leaves_state_unchanged():
    bridge = make_bridge()
    bridge.step(1.0, 0.1, 0.2)
    before = bridge.applied_twist
    for speed, steering, dt_s in [(math.nan, 0.0, 0.1), (1.0, 2.0, 0.1), (1.0, 0.0, -0.1)]:
        with pytest.raises(InvalidCommandError):
            bridge.step(speed, steering, dt_s)
        assert bridge.applied_twist == before


def test_bridge_wheel_radps_follow_wheel_radius():
    bridge = make_bridge(wheel_radius=0.2, max_accel_mps2=0.0, max_wheel_speed_mps=0.0)
    command = bridge.step(1.0, STEER_RAD, 0.1)
    assert command.left_radps == pytest.approx(command.left_mps / 0.2, abs=TOL)
    assert command.right_radps == pytest.approx(command.right_mps / 0.2, abs=TOL)


# --- watchdog ---------------------------------------------------------------------------------

LAST = 'last command'
BRAKE = 'brake command'


@pytest.mark.parametrize('action, expected', [('brake', BRAKE), ('coast', None), ('hold', LAST)])
def test_watchdog_stale_command_gives_action_output(action, expected):
    watchdog = CommandWatchdog(timeout_s=0.5, action=action)
    watchdog.feed(10.0)
    assert not watchdog.is_stale(10.5)            # age equal to the timeout is still fresh
    assert watchdog.output(10.5, LAST, BRAKE) == LAST
    assert watchdog.is_stale(10.51)
    assert watchdog.output(10.51, LAST, BRAKE) == expected
    watchdog.feed(11.0)
    assert watchdog.output(11.2, LAST, BRAKE) == LAST


def test_watchdog_defaults_are_half_second_brake():
    watchdog = CommandWatchdog()
    assert (watchdog.timeout_s, watchdog.action) == (0.5, 'brake')


def test_watchdog_timeout_zero_never_stale():
    watchdog = CommandWatchdog(timeout_s=0.0, action='brake')
    assert not watchdog.is_stale(1e9)
    assert watchdog.output(1e9, LAST, BRAKE) == LAST


def test_watchdog_before_first_command_and_after_clock_jump_back_is_stale():
    watchdog = CommandWatchdog(timeout_s=0.5)
    assert watchdog.is_stale(0.0)
    assert watchdog.output(0.0, None, BRAKE) == BRAKE
    watchdog.feed(100.0)
    assert watchdog.is_stale(5.0)


def test_watchdog_rejected_command_does_not_feed():
    # The node feeds only after the bridge accepted the command.
    bridge, watchdog = make_bridge(), CommandWatchdog(timeout_s=0.5, action='brake')
    bridge.step(1.0, 0.0, 0.1)
    watchdog.feed(1.0)
    with pytest.raises(InvalidCommandError):
        bridge.step(math.nan, 0.0, 0.1)
        watchdog.feed(1.4)                        # not reached
    assert watchdog.last_feed_s == 1.0
    assert watchdog.output(1.6, LAST, STOP_COMMAND) == STOP_COMMAND


@pytest.mark.parametrize('timeout_s, action', [(-0.1, 'brake'), (math.nan, 'brake'),
                                               (0.5, 'stop')])
def test_watchdog_bad_parameters_raise(timeout_s, action):
    with pytest.raises(InvalidParameterError):
        CommandWatchdog(timeout_s, action)


# --- turn in place ----------------------------------------------------------------------------

def test_turn_in_place_law_is_proportional_then_capped():
    assert turn_in_place_yaw_rate(0.3, 1.0, 0.5) == pytest.approx(0.3, abs=TOL)
    assert turn_in_place_yaw_rate(-1.0, 1.0, 0.5) == pytest.approx(-0.5, abs=TOL)
    assert turn_in_place_yaw_rate(0.0, 1.0, 0.5) == 0.0


def test_turn_in_place_enabled_at_standstill_rotates_about_the_centre():
    # ω = min(0.3·1, 0.5) = 0.3 rad/s; wheels ∓ω·t/2 = ∓0.3·0.5/2 = ∓0.075 m/s.
    bridge = make_bridge(turn_in_place=True, wheel_tread=0.5)
    command = bridge.step(0.01, 0.3, 0.1)
    assert command.speed_mps == pytest.approx(0.0, abs=TOL)
    assert command.yaw_rate_radps == pytest.approx(0.3, abs=TOL)
    assert command.left_mps == pytest.approx(-0.075, abs=TOL)
    assert command.right_mps == pytest.approx(0.075, abs=TOL)


def test_turn_in_place_off_by_default_gives_no_motion_at_standstill():
    assert DEFAULT_BRIDGE_PARAMS.turn_in_place is False
    command = make_bridge().step(0.0, 0.3, 0.1)
    assert (command.left_mps, command.right_mps) == (0.0, 0.0)


def test_turn_in_place_not_applied_above_speed_threshold():
    bridge = make_bridge(turn_in_place=True, max_accel_mps2=0.0, wheel_base=0.5)
    command = bridge.step(0.2, STEER_RAD, 0.1)
    assert command.yaw_rate_radps == pytest.approx(0.2 * 0.25 / 0.5, abs=TOL)


# --- pose integration and end to end ------------------------------------------------------------

def test_integrate_pose_quarter_circle_in_one_step_is_exact():
    # v = 1, ω = pi/2, dt = 1: radius 2/pi, from the origin heading +x to (R, R) heading +y.
    radius_m = 2.0 / math.pi
    pose = integrate_pose(0.0, 0.0, 0.0, 1.0, math.pi / 2, 1.0)
    assert pose == (pytest.approx(radius_m, abs=TOL), pytest.approx(radius_m, abs=TOL),
                    pytest.approx(math.pi / 2, abs=TOL))


def test_integrate_pose_zero_yaw_rate_is_straight_line():
    pose = integrate_pose(1.0, 2.0, math.pi / 4, 2.0, 0.0, 0.5)
    assert pose.x_m == pytest.approx(1.0 + math.sqrt(0.5), abs=TOL)
    assert pose.y_m == pytest.approx(2.0 + math.sqrt(0.5), abs=TOL)
    assert pose.yaw_rad == pytest.approx(math.pi / 4, abs=TOL)


def test_integrate_pose_full_circle_returns_to_start():
    steps, yaw_rate_radps = 1000, 0.5
    dt_s = 2 * math.pi / yaw_rate_radps / steps
    pose = (1.0, -2.0, 0.3)
    for _ in range(steps):
        pose = integrate_pose(*pose, 1.0, yaw_rate_radps, dt_s)
    assert pose == (pytest.approx(1.0, abs=1e-9), pytest.approx(-2.0, abs=1e-9),
                    pytest.approx(0.3, abs=1e-9))


def test_bridge_applied_path_follows_bicycle_circle():
    # Kinematic mode, no wheel saturation: the applied path is a circle of radius L/tanδ = 2 m
    # about (0, 2), also while the speed ramps up.
    bridge = make_bridge(wheel_base=0.5, wheel_tread=0.4, max_wheel_speed_mps=0.0)
    pose = (0.0, 0.0, 0.0)
    for _ in range(300):
        command = bridge.step(1.0, STEER_RAD, 0.02)
        pose = integrate_pose(*pose, command.speed_mps, command.yaw_rate_radps, 0.02)
        assert math.hypot(pose[0], pose[1] - 2.0) == pytest.approx(2.0, abs=1e-9)


# --- parameters -------------------------------------------------------------------------------

def test_params_table_defaults_validate_and_have_units_and_docs():
    assert bridge_params_from_dict({}) == DEFAULT_BRIDGE_PARAMS
    for spec in BRIDGE_PARAM_SPECS:
        assert spec.doc
        assert spec.unit or spec.kind in ('enum', 'bool')


@pytest.mark.parametrize('key, value', [('wheel_base', 0.0), ('wheel_tread', math.nan),
                                        ('max_accel_mps2', -1.0), ('mode', 'seed'),
                                        ('turn_in_place', 1), ('command_timeout_s', -0.5)])
def test_params_bad_value_raises_naming_parameter_and_value(key, value):
    with pytest.raises(InvalidParameterError, match=key) as info:
        bridge_params_from_dict({key: value})
    assert repr(value) in str(info.value)


def test_params_unknown_name_raises_listing_valid_names():
    with pytest.raises(InvalidParameterError, match='wheel_base'):
        bridge_params_from_dict({'wheelbase': 0.5})


@pytest.mark.parametrize('wheel_base_m, warns', [(0.19, True), (0.2, False), (0.4, False),
                                                 (1.2, False), (1.21, True)])
def test_wheel_base_plausibility_warns_outside_half_to_three_treads(wheel_base_m, warns):
    warning = wheel_base_plausibility(wheel_base_m, 0.4)
    assert (warning is not None) == warns
    if warns:
        assert 'wheel_base' in warning


def test_wheel_speeds_from_twist_pure_rotation_is_antisymmetric():
    left, right = wheel_speeds_from_twist(0.0, 1.0, 0.4)
    assert (left, right) == (-0.2, 0.2)


def test_speed_limiter_disabled_with_zero_dt_passes_the_target_through():
    # An unlimited (0 = off) limiter must not compute inf * 0 = NaN when no time has passed.
    limiter = SpeedLimiter(max_accel=0.0, max_decel=0.0)
    assert limiter.limit(2.0, 1.0, 0.0) == 2.0
    assert limiter.limit(-2.0, 1.0, 0.0) == -2.0
    limited = SpeedLimiter(max_accel=1.0, max_decel=1.0)
    assert limited.limit(2.0, 1.0, 0.0) == 1.0
