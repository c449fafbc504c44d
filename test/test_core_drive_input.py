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
cmd_vel and drive -> a car and a differential robot, ROS-free (core/commands/drive_input.py).

Closed forms: the bicycle model ω = v·tan(δ)/L and its inverse δ = atan(ω·L/v); REP 103 steering
(+ left) is the opposite of Webots' (+ right); the rear axle of a front-driven car runs at
cos δ times the front axle's speed on a turn. Time is injected (``now_s``), no sleeps.
"""

import math

import pytest

from vehicle_sim.config import load_car
from vehicle_sim.core.car.drivetrain import ControlMode
from vehicle_sim.core.car.logic import CarLogic
from vehicle_sim.core.car.params import DEFAULT_CAR
from vehicle_sim.core.commands.drive_input import (
    CarDriveInput,
    DiffDriveInput,
    rear_axle_speed_ratio,
    STANDSTILL_SPEED_MPS,
    steering_from_yaw_rate,
)
from vehicle_sim.core.diffdrive.kinematics import yaw_rate_from_steering
from vehicle_sim.core.specs.errors import InvalidCommandError
from vehicle_sim.core.specs.units import kmh_to_mps, ros_steering_to_webots, webots_steering_to_ros

# ------------------------------------------------------------------------------ conversions

@pytest.mark.parametrize('angle', [0.3, -0.12, 0.0, 1.0])
def test_rep103_steering_is_webots_steering_negated_both_ways(angle):
    # A left turn is + in REP 103 and − in Webots (+ = right).
    assert ros_steering_to_webots(angle) == -angle
    assert webots_steering_to_ros(angle) == -angle
    assert webots_steering_to_ros(ros_steering_to_webots(angle)) == angle


@pytest.mark.parametrize('speed', [3.0, 0.5, -2.0, 25.0])
@pytest.mark.parametrize('steering', [0.3, -0.1, 0.0, 0.6])
def test_steering_from_yaw_rate_inverts_the_bicycle_model(speed, steering):
    wheelbase = 2.94
    yaw_rate = yaw_rate_from_steering(speed, steering, wheelbase)   # ω = v·tan δ / L
    assert steering_from_yaw_rate(speed, yaw_rate, wheelbase) == pytest.approx(
        steering, abs=1e-12)


def test_steering_from_yaw_rate_in_reverse_steers_the_other_way():
    # Backing with a left yaw rate (+ω) needs the wheels turned right: δ < 0.
    assert steering_from_yaw_rate(-2.0, 0.5, 3.0) == pytest.approx(math.atan(-0.75))


def test_steering_from_yaw_rate_at_a_standstill_is_undefined():
    assert steering_from_yaw_rate(0.0, 0.5, 3.0) is None
    assert steering_from_yaw_rate(STANDSTILL_SPEED_MPS / 2, 0.5, 3.0) is None
    assert steering_from_yaw_rate(STANDSTILL_SPEED_MPS, 0.5, 3.0) is not None


@pytest.mark.parametrize('steering', [0.0, 0.3, -0.4])
def test_rear_axle_speed_ratio_follows_the_driven_axle(steering):
    # traction: front axle at the cruising speed, rear axle cos δ of it; propulsion: rear axle
    # driven; 4x4 with equal radii: 2(1 − 1/(1 + cos δ)) = 2 cos δ / (1 + cos δ).
    cos = math.cos(steering)
    assert rear_axle_speed_ratio('traction', steering) == pytest.approx(cos)
    assert rear_axle_speed_ratio('propulsion', steering) == 1.0
    assert rear_axle_speed_ratio('4x4', steering, 0.35, 0.35) == pytest.approx(
        2.0 * cos / (1.0 + cos))


# ------------------------------------------------------------------------------ the car

def _car(timeout_s=0.5, model=None):
    logic = CarLogic(load_car(model) if model else DEFAULT_CAR)
    return logic, CarDriveInput(logic, timeout_s)


def test_car_cmd_vel_left_turn_sets_webots_right_negative_steering_and_cruising_speed():
    logic, drive = _car()
    wheelbase = logic.wheelbase_m
    target = drive.twist(5.0, 0.2, now_s=1.0)
    delta = math.atan(0.2 * wheelbase / 5.0)      # REP 103, + left
    assert target.notes == ()
    assert logic.commanded_steering_angle_rad == pytest.approx(-delta)
    # Front-driven 'Car': the front axle runs 1/cos δ faster than base_link.
    assert kmh_to_mps(logic.target_cruising_speed_kmh) == pytest.approx(5.0 / math.cos(delta))
    assert logic.control_mode == ControlMode.SPEED
    assert logic.brake_intensity == 0.0


def test_car_drive_takes_rep103_steering_and_propulsion_speed_unscaled():
    logic, drive = _car(model='TeslaModel3')
    assert logic.params.car_type == 'propulsion'
    drive.ackermann(4.0, 0.25, now_s=0.0)
    assert logic.commanded_steering_angle_rad == pytest.approx(-0.25)
    assert kmh_to_mps(logic.target_cruising_speed_kmh) == pytest.approx(4.0)


def test_car_negative_speed_cruises_in_reverse():
    logic, drive = _car()
    drive.ackermann(-2.0, 0.0, now_s=0.0)
    assert kmh_to_mps(logic.target_cruising_speed_kmh) == pytest.approx(-2.0)


def test_car_steering_beyond_the_limit_saturates_with_a_note():
    logic, drive = _car()
    high = webots_steering_to_ros(logic.min_steering_angle_rad)   # most to the left
    target = drive.ackermann(3.0, high + 0.5, now_s=0.0)
    assert logic.commanded_steering_angle_rad == logic.min_steering_angle_rad
    assert len(target.notes) == 1 and 'saturated' in target.notes[0]
    assert 'steering limits' in target.notes[0]


def test_car_yaw_rate_needing_too_much_steering_saturates_with_a_note():
    logic, drive = _car()
    target = drive.twist(0.5, 5.0, now_s=0.0)   # atan(5·L/0.5) ≈ 88°
    assert logic.commanded_steering_angle_rad == logic.min_steering_angle_rad
    assert 'saturated' in target.notes[0]


def test_car_speed_beyond_top_speed_saturates_with_a_note():
    logic, drive = _car()
    top_mps = kmh_to_mps(logic.max_cruising_speed_kmh)
    target = drive.ackermann(-2 * top_mps, 0.0, now_s=0.0)
    assert kmh_to_mps(logic.target_cruising_speed_kmh) == pytest.approx(-top_mps)
    assert 'top speed' in target.notes[0]


@pytest.mark.parametrize('bad', [(math.nan, 0.0), (1.0, math.inf), (-math.inf, 0.1)])
def test_car_non_finite_command_is_refused_and_changes_nothing(bad):
    logic, drive = _car()
    drive.twist(2.0, 0.1, now_s=0.0)
    before = (logic.target_cruising_speed_kmh, logic.commanded_steering_angle_rad,
              drive.watchdog.last_feed_s)
    for apply in (drive.twist, drive.ackermann):
        with pytest.raises(InvalidCommandError, match='finite'):
            apply(*bad, now_s=0.3)
    assert (logic.target_cruising_speed_kmh, logic.commanded_steering_angle_rad,
            drive.watchdog.last_feed_s) == before


def test_car_yaw_rate_at_a_standstill_keeps_the_steering_and_says_so():
    logic, drive = _car()
    drive.ackermann(1.0, 0.2, now_s=0.0)
    target = drive.twist(0.0, 0.4, now_s=0.1)
    assert logic.commanded_steering_angle_rad == pytest.approx(-0.2)
    assert logic.target_cruising_speed_kmh == 0.0
    assert 'cannot turn in place' in target.notes[0]
    assert drive.twist(0.0, 0.0, now_s=0.2).notes == ()


def test_car_watchdog_brakes_once_after_the_timeout_and_not_before():
    logic, drive = _car(timeout_s=0.5)
    drive.twist(3.0, 0.0, now_s=1.0)
    assert not drive.tick(1.5)                    # an age equal to the timeout is fresh
    assert logic.brake_intensity == 0.0
    assert drive.tick(1.51)
    # a safety stop: cruise control off (throttle 0, TORQUE mode, its target 0) and full brake
    assert logic.target_cruising_speed_kmh == 0.0
    assert (logic.control_mode, logic.throttle) == (ControlMode.TORQUE, 0.0)
    assert logic.brake_intensity == 1.0
    assert not drive.tick(2.0)                    # once per staleness
    drive.twist(1.0, 0.0, now_s=2.0)             # the next command drives again
    assert logic.brake_intensity == 0.0 and logic.target_cruising_speed_kmh > 0.0


def test_car_service_after_a_command_holds_past_the_timeout():
    logic, drive = _car(timeout_s=0.5)
    drive.twist(3.0, 0.0, now_s=0.0)
    logic.set_cruising_speed_kmh(20.0)
    drive.service_override()
    assert not drive.tick(5.0)
    assert logic.target_cruising_speed_kmh == 20.0


def test_car_watchdog_timeout_zero_never_acts():
    logic, drive = _car(timeout_s=0.0)
    drive.twist(3.0, 0.0, now_s=0.0)
    assert not drive.tick(1e6)
    assert logic.brake_intensity == 0.0


# ------------------------------------------------------------------------------ the robot

def test_robot_twist_gives_the_differential_wheel_speeds():
    robot = DiffDriveInput(tread_m=0.4, wheel_radius_m=0.1, max_wheel_speed_radps=20.0)
    left, right, notes = robot.twist(0.5, 1.0, now_s=0.0)
    # v_l = v − ω·b/2 = 0.3 m/s, v_r = 0.7 m/s; divided by r = 0.1 m.
    assert (left, right, notes) == (pytest.approx(3.0), pytest.approx(7.0), ())


def test_robot_turns_in_place_at_zero_speed():
    robot = DiffDriveInput(0.4, 0.1, 20.0)
    left, right, _ = robot.twist(0.0, 2.0, now_s=0.0)
    assert left == pytest.approx(-4.0) and right == pytest.approx(4.0)


def test_robot_wheel_speeds_beyond_the_limit_scale_together_with_a_note():
    robot = DiffDriveInput(0.4, 0.1, 10.0)                     # 1 m/s
    left, right, notes = robot.twist(1.5, 2.5, now_s=0.0)   # v_l = 1.0, v_r = 2.0 m/s
    assert right == pytest.approx(10.0) and right <= 10.0
    assert left / right == pytest.approx(0.5)                # curvature kept
    assert 'saturated' in notes[0]


@pytest.mark.parametrize('radius, speed, yaw_rate, limit', [
    (0.267, 18.1, 0.78, 18.9), (0.202, 18.81, 4.09, 12.5), (0.351, -12.87, -0.67, 7.2)])
def test_robot_saturated_wheel_speed_never_exceeds_the_limit_by_rounding(radius, speed,
                                                                         yaw_rate, limit):
    # Cases where scaling in m/s and dividing by r lands one bit above the limit in rad/s,
    # which the robot body refuses.
    robot = DiffDriveInput(0.4, radius, limit)
    left, right, notes = robot.twist(speed, yaw_rate, now_s=0.0)
    assert max(abs(left), abs(right)) <= limit and notes


def test_robot_non_finite_twist_is_refused_without_feeding_the_watchdog():
    robot = DiffDriveInput(0.4, 0.1, 10.0)
    with pytest.raises(InvalidCommandError):
        robot.twist(math.nan, 0.0, now_s=0.0)
    assert robot.watchdog.last_feed_s is None and not robot.armed


def test_robot_watchdog_acts_once_and_override_stands_it_down():
    robot = DiffDriveInput(0.4, 0.1, 10.0, timeout_s=0.5)
    robot.twist(0.2, 0.0, now_s=0.0)
    assert not robot.tick(0.5) and robot.tick(0.51) and not robot.tick(0.6)
    robot.twist(0.2, 0.0, now_s=1.0)
    robot.override()
    assert not robot.tick(3.0)
