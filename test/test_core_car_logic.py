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

"""CarLogic: start state, modes, step actuation and the strict setter API (docs/core.md)."""

import copy
import dataclasses
import math

import numpy as np
import pytest

from vehicle_sim.config import load_car
from vehicle_sim.core.car.ackermann import ackermann_angles
from vehicle_sim.core.car.drivetrain import CarType, ControlMode
from vehicle_sim.core.car.engines import EngineType
from vehicle_sim.core.car.logic import CarLogic, CarStatus
from vehicle_sim.core.car.params import DEFAULT_CAR
from vehicle_sim.core.car.signals import Indicator, WiperMode
from vehicle_sim.core.car.vehicle_io import Measurement, Wheel, WheelMode
from vehicle_sim.core.specs.errors import InvalidCommandError

DT_S = 0.01
FREE, VELOCITY, TORQUE = WheelMode.FREE, WheelMode.VELOCITY, WheelMode.TORQUE


def _spinning(car, speed_radps, steps, start_s=0.0, speeds=None):
    """Step ``car`` with all wheels turning at a constant speed; return the last actuation."""
    measurement = Measurement()
    rates = np.full(4, speed_radps) if speeds is None else np.asarray(speeds, dtype=float)
    actuation = None
    for k in range(steps):
        measurement.wheel_position_rad = rates * (k * DT_S)
        actuation = car.step(measurement, start_s + k * DT_S, DT_S)
    return actuation


def test_car_starts_undefined_with_driven_wheels_held():
    car = CarLogic(DEFAULT_CAR)     # traction: front wheels driven
    status = car.status()
    assert status.control_mode == ControlMode.UNDEFINED
    assert (status.gear, status.throttle, status.brake_intensity, status.rpm) == (0, 0, 0, 0)
    assert status.indicator == Indicator.OFF and status.wiper_mode == WiperMode.DOWN
    assert status.limited_slip_differential and status.indicator_auto_disabling
    assert status.indicator_period_s == 0.34
    actuation = car.step(Measurement(), 0.0, DT_S)
    assert list(actuation.wheel_mode) == [VELOCITY, VELOCITY, FREE, FREE]
    np.testing.assert_array_equal(actuation.wheel_velocity_radps, 0.0)
    np.testing.assert_array_equal(actuation.brake_torque_nm, 0.0)


def test_step_returns_the_same_preallocated_actuation():
    car = CarLogic(DEFAULT_CAR)
    assert car.step(Measurement(), 0.0, DT_S) is car.step(Measurement(), DT_S, DT_S)


def test_speed_mode_ramps_driven_wheels_at_time0to100_rate():
    # Car: r = 0.4 m, time0To100 = 10 s → a = (100/3.6)/10/0.4 = 6.944 rad/s², i.e. 0.06944 rad/s
    # per 10 ms step; 36 km/h = 10 m/s → target 25 rad/s, reached after 360 steps.
    car = CarLogic(DEFAULT_CAR)
    car.set_cruising_speed_kmh(36.0)
    assert car.control_mode == ControlMode.SPEED
    per_step = 100.0 / 3.6 / 10.0 / 0.4 * DT_S
    actuation = car.step(Measurement(), 0.0, DT_S)
    assert list(actuation.wheel_mode) == [VELOCITY, VELOCITY, FREE, FREE]
    np.testing.assert_allclose(actuation.wheel_velocity_radps, [per_step, per_step, 0, 0],
                               rtol=1e-12)
    for k in range(1, 100):
        car.step(Measurement(), k * DT_S, DT_S)
    np.testing.assert_allclose(actuation.wheel_velocity_radps[:2], 100 * per_step, rtol=1e-9)
    for k in range(100, 400):
        car.step(Measurement(), k * DT_S, DT_S)
    np.testing.assert_allclose(actuation.wheel_velocity_radps[:2], 25.0, rtol=1e-12)
    # Slowing down is limited by the same rate.
    car.set_cruising_speed_kmh(0.0)
    car.step(Measurement(), 4.0, DT_S)
    np.testing.assert_allclose(actuation.wheel_velocity_radps[:2], 25.0 - per_step, rtol=1e-12)


def test_speed_mode_steering_reissues_differential_targets():
    # Propulsion car: rear targets 2v·ratio_r / r with ratio_r = 0.5 − Tr·tan δ / (4L).
    params = load_car('TeslaModel3')
    car = CarLogic(params)
    car.set_cruising_speed_kmh(36.0)
    car.set_steering_angle(0.2)
    for k in range(2000):
        actuation = car.step(Measurement(), k * DT_S, DT_S)
    ratio = 0.5 - params.track_rear_m * math.tan(0.2) / (4.0 * params.wheelbase_m)
    radius = params.rear_tire_radius_m
    assert list(actuation.wheel_mode) == [FREE, FREE, VELOCITY, VELOCITY]
    np.testing.assert_allclose(actuation.wheel_velocity_radps,
                               [0.0, 0.0, 20.0 * ratio / radius, 20.0 * (1 - ratio) / radius],
                               rtol=1e-12)


def test_speed_mode_targets_saturate_at_motor_max_velocity():
    # Full speed in a tight turn: the outer wheel would exceed maxVelocity / r and saturates.
    car = CarLogic(DEFAULT_CAR)
    car.set_steering_angle(-0.8)
    car.set_cruising_speed_kmh(car.max_cruising_speed_kmh)
    actuation = _spinning(car, 0.0, 3000)
    limit = DEFAULT_CAR.max_velocity_mps / DEFAULT_CAR.front_tire_radius_m
    assert actuation.wheel_velocity_radps[Wheel.FRONT_RIGHT] == pytest.approx(limit, rel=1e-12)
    assert actuation.wheel_velocity_radps[Wheel.FRONT_LEFT] < limit


@pytest.mark.parametrize('speed_kmh', [300.0, -250.0, 1.7e308])
def test_cruising_speed_beyond_top_is_stored_and_the_motors_use_the_top_speed(speed_kmh):
    # driver.c stores the argument as given; the wheel motors saturate at maxVelocity / r.
    # Car: 50 m/s = 180 km/h, r = 0.4 m → 125 rad/s on the driven front wheels.
    car = CarLogic(DEFAULT_CAR)
    car.set_cruising_speed_kmh(speed_kmh)
    top_kmh = math.copysign(180.0, speed_kmh)
    assert car.target_cruising_speed_kmh == speed_kmh
    assert car.status().target_cruising_speed_kmh == speed_kmh
    assert car.effective_cruising_speed_kmh == top_kmh
    assert car.status().effective_cruising_speed_kmh == top_kmh
    actuation = _spinning(car, 0.0, 2000)   # 20 s: the ramp (6.94 rad/s² here) is done
    np.testing.assert_allclose(actuation.wheel_velocity_radps,
                               [math.copysign(125.0, speed_kmh)] * 2 + [0.0, 0.0], rtol=1e-12)
    assert car.target_cruising_speed_kmh == speed_kmh
    assert car.backwards_lights is (speed_kmh < 0)


def test_cruising_speed_beyond_top_in_a_turn_saturates_each_wheel_like_webots():
    # Each wheel target is computed from the stored speed, then clamped alone (WbMotor): at
    # 300 km/h both front wheels of the Car saturate even in a turn, as in Webots.
    car = CarLogic(DEFAULT_CAR)
    car.set_steering_angle(0.2)
    car.set_cruising_speed_kmh(300.0)
    actuation = _spinning(car, 0.0, 2000)
    np.testing.assert_allclose(actuation.wheel_velocity_radps[:2], [125.0, 125.0], rtol=1e-12)


def test_torque_mode_distributes_engine_torque_on_driven_wheels():
    # Car (traction, combustion a=150, b=0.1): all wheels at 10 rad/s, gear 1 (ratio 10):
    # rpm = 10·60/(2π)·10 = 954.9 < 1000 → engine at idle: 150 + 0.1·1000 = 250 N·m;
    # T = 250 · throttle 0.8 · 10 = 2000 N·m, split 0.5/0.5 (equal speeds: slip stays 0).
    car = CarLogic(DEFAULT_CAR)
    car.set_gear(1)
    car.set_throttle(0.8)
    actuation = _spinning(car, 10.0, 3)   # step 1: speeds 0; step 2: limiter; step 3: steady
    assert car.control_mode == ControlMode.TORQUE
    assert car.rpm == pytest.approx(10.0 * 60.0 / (2.0 * math.pi) * 10.0, rel=1e-9)
    assert list(actuation.wheel_mode) == [TORQUE, TORQUE, FREE, FREE]
    np.testing.assert_allclose(actuation.wheel_torque_nm, [1000.0, 1000.0, 0.0, 0.0],
                               rtol=1e-9)


def test_torque_mode_limits_torque_when_a_wheel_jumps():
    # Step 2 sees the wheels go from 0 to 10 rad/s in 10 ms: 1000 rad/s² → torque · 50/1000.
    car = CarLogic(DEFAULT_CAR)
    car.set_gear(1)
    car.set_throttle(0.8)
    actuation = _spinning(car, 10.0, 2)
    np.testing.assert_allclose(actuation.wheel_torque_nm[:2], 1000.0 * 50.0 / 1000.0, rtol=1e-9)


def test_torque_mode_lsd_gives_faster_wheel_less_torque():
    car = CarLogic(load_car('TeslaModel3'))
    car.set_gear(1)
    car.set_throttle(1.0)
    actuation = _spinning(car, 0.0, 3, speeds=[0.0, 0.0, 11.0, 9.0])
    assert actuation.wheel_torque_nm[Wheel.REAR_RIGHT] < actuation.wheel_torque_nm[
        Wheel.REAR_LEFT]
    car.enable_limited_slip_differential(False)
    actuation = _spinning(car, 0.0, 3, speeds=[0.0, 0.0, 11.0, 9.0])
    assert actuation.wheel_torque_nm[Wheel.REAR_RIGHT] == pytest.approx(
        actuation.wheel_torque_nm[Wheel.REAR_LEFT], rel=1e-12)


def test_torque_to_speed_mode_ramp_starts_from_wheel_speeds():
    car = CarLogic(DEFAULT_CAR)
    car.set_throttle(0.0)
    _spinning(car, 20.0, 3)
    car.set_cruising_speed_kmh(0.0)
    actuation = car.step(Measurement(), 1.0, DT_S)
    per_step = 100.0 / 3.6 / 10.0 / 0.4 * DT_S
    np.testing.assert_allclose(actuation.wheel_velocity_radps[:2], 20.0 - per_step, rtol=1e-12)


def _car_in_mode(mode, cruising_kmh, throttle):
    # A new car left in 'undefined' mode, or switched by a cruising speed or a throttle.
    car = CarLogic(DEFAULT_CAR)
    if mode == 'speed':
        car.set_cruising_speed_kmh(cruising_kmh)
    elif mode == 'torque':
        car.set_throttle(throttle)
    return car


@pytest.mark.parametrize('mode', ['undefined', 'speed', 'torque'])
def test_brake_torque_is_intensity_times_coefficient_on_all_wheels(mode):
    car = _car_in_mode(mode, 10.0, 0.5)
    car.set_brake_intensity(0.5)
    actuation = car.step(Measurement(), 0.0, DT_S)
    np.testing.assert_allclose(actuation.brake_torque_nm, 0.5 * 700.0, rtol=1e-12)


@pytest.mark.parametrize('mode', ['undefined', 'speed', 'torque'])
def test_brake_in_speed_mode_is_taken_and_returns_a_note_saying_what_to_do(mode):
    # Webots' driver.c takes the brake in any mode without a word; in SPEED mode the driven
    # wheels' motors hold the cruising speed, so the call says why nothing slows down.
    car = _car_in_mode(mode, 20.0, 0.0)
    note = car.set_brake_intensity(1.0)
    assert car.brake_intensity == 1.0 and car.status().brake_lights
    if mode == 'speed':
        assert note == ('brake intensity 1 has no effect while cruise control holds 20 km/h (the '
                        'driven wheels follow the cruising speed): set the cruising speed to 0 '
                        'to slow down, or set the throttle (TORQUE mode) so that the brake acts')
    else:
        assert note is None
    assert car.set_brake_intensity(0.0) is None
    car.set_cruising_speed_kmh(0.0)             # stopping with cruise control: nothing to say
    assert car.set_brake_intensity(1.0) is None


def test_mode_changes_only_through_cruising_speed_and_throttle():
    car = CarLogic(DEFAULT_CAR)
    car.set_brake_intensity(1.0)
    car.set_gear(2)
    car.set_steering_angle(0.1)
    assert car.control_mode == ControlMode.UNDEFINED
    car.set_cruising_speed_kmh(20.0)
    assert car.control_mode == ControlMode.SPEED
    car.set_throttle(0.2)
    assert car.control_mode == ControlMode.TORQUE


def test_rpm_and_gear_read_zero_in_speed_mode():
    car = CarLogic(DEFAULT_CAR)
    car.set_gear(2)
    car.set_cruising_speed_kmh(20.0)
    _spinning(car, 10.0, 3)
    assert car.rpm == 0.0 and car.gear == 0
    assert car.selected_gear == 2


def test_steering_targets_are_ackermann_angles_clamped_per_wheel():
    # Car: δ = 1.0 rad (the limit) asks θR = 1.165 rad for the inner wheel → clamped to 1.0.
    car = CarLogic(DEFAULT_CAR)
    car.set_steering_angle(1.0)
    actuation = car.step(Measurement(), 0.0, DT_S)
    right, left = ackermann_angles(1.0, DEFAULT_CAR.track_front_m, DEFAULT_CAR.wheelbase_m)
    assert right > 1.0
    assert actuation.steer_right_rad == 1.0
    assert actuation.steer_left_rad == pytest.approx(left, abs=1e-12)


def test_single_wheel_steering_overrides_that_side_only():
    car = CarLogic(DEFAULT_CAR)
    car.set_steering_angle(0.2)
    car.set_right_steering_angle(-0.1)
    actuation = car.step(Measurement(), 0.0, DT_S)
    assert actuation.steer_right_rad == -0.1
    assert actuation.steer_left_rad == pytest.approx(
        ackermann_angles(0.2, DEFAULT_CAR.track_front_m, DEFAULT_CAR.wheelbase_m)[1], abs=1e-12)
    assert car.commanded_steering_angle_rad == 0.2


def test_steering_angle_getters_report_measured_angles():
    car = CarLogic(DEFAULT_CAR)
    car.set_steering_angle(0.3)
    measurement = Measurement()
    measurement.steer_right_rad, measurement.steer_left_rad = 0.2, 0.1
    car.step(measurement, 0.0, DT_S)
    assert car.steering_angle_rad == pytest.approx(0.15, abs=1e-15)
    assert (car.right_steering_angle_rad, car.left_steering_angle_rad) == (0.2, 0.1)


def test_wheel_speeds_are_zero_on_first_step_then_finite_differences():
    car = CarLogic(DEFAULT_CAR)
    measurement = Measurement()
    measurement.wheel_position_rad[:] = [5.0, 5.0, 5.0, 5.0]
    car.step(measurement, 0.0, DT_S)
    assert [car.wheel_speed_radps(i) for i in range(4)] == [0.0] * 4
    measurement.wheel_position_rad[:] = [5.1, 5.2, 4.9, 5.0]
    car.step(measurement, DT_S, DT_S)
    speeds = [car.wheel_speed_radps(i) for i in range(4)]
    np.testing.assert_allclose(speeds, [10.0, 20.0, -10.0, 0.0], rtol=1e-9, atol=1e-9)
    assert car.wheel_encoder_rad(Wheel.FRONT_LEFT) == 5.2
    # Traction: current speed = ½(10 + 20)·0.4 m/s = 6 m/s = 21.6 km/h.
    assert car.current_speed_kmh == pytest.approx(21.6, rel=1e-9)


@pytest.mark.parametrize('index', [-1, 4, 1.0, True, None])
def test_wheel_getters_reject_index_outside_0_to_3(index):
    car = CarLogic(DEFAULT_CAR)
    with pytest.raises(InvalidCommandError, match='wheel index'):
        car.wheel_encoder_rad(index)
    with pytest.raises(InvalidCommandError, match='wheel index'):
        car.wheel_speed_radps(index)


@pytest.mark.parametrize('model, car_type, engine_type', [
    ('Car', CarType.TRACTION, EngineType.COMBUSTION),
    ('ToyotaPrius', CarType.TRACTION, EngineType.POWER_SPLIT_HYBRID),
    ('TeslaModel3', CarType.PROPULSION, EngineType.ELECTRIC),
    ('LincolnMKZ', CarType.FOUR_BY_FOUR, EngineType.COMBUSTION),
])
def test_car_and_engine_types_are_webots_ints(model, car_type, engine_type):
    car = CarLogic(load_car(model))
    assert car.car_type == car_type and car.engine_type == engine_type


def test_dimensions_and_gear_number_come_from_params():
    params = load_car('ToyotaPrius')
    car = CarLogic(params)
    dims = car.dimensions()
    assert (dims.track_front_m, dims.track_rear_m, dims.wheelbase_m, dims.front_wheel_radius_m,
            dims.rear_wheel_radius_m) == (params.track_front_m, params.track_rear_m,
                                          params.wheelbase_m, params.front_tire_radius_m,
                                          params.rear_tire_radius_m)
    assert car.gear_number == len(params.gear_ratio) == 2


# ---------------------------------------------------------------------------------------------
# Strict API: every bad value raises InvalidCommandError and changes nothing.

NAN, INF = float('nan'), float('inf')
BAD_NUMBERS = [NAN, INF, -INF, None, 'x', True]

# Car defaults: steering ±1 rad, maxVelocity 50 m/s = 180 km/h, 6 gear ratios → gears −1..5.
STRICT_CASES = [
    ('set_steering_angle', BAD_NUMBERS + [1.0 + 1e-9, -1.5]),
    ('set_right_steering_angle', BAD_NUMBERS + [1.01, -1.01]),
    ('set_left_steering_angle', BAD_NUMBERS + [1.01, -1.01]),
    ('set_cruising_speed_kmh', BAD_NUMBERS),
    ('set_cruising_speed_within_top_kmh', BAD_NUMBERS + [180.001, -181.0, 1e300]),
    ('set_throttle', BAD_NUMBERS + [-0.01, 1.01]),
    ('set_brake_intensity', BAD_NUMBERS + [-0.01, 1.01]),
    ('set_indicator_period_s', BAD_NUMBERS + [0.0, -0.34, 5e-324, 1e-300, 9.99e-4]),
    ('set_gear', [NAN, None, True, 1.0, 6, -2, np.float64(2.0)]),
    ('set_indicator', [NAN, None, True, 1.0, 3, -1]),
    ('set_wiper_mode', [NAN, None, False, 2.0, 4, -1]),
    ('set_hazard_flashers', [NAN, None, 2, -1, 0.0, 1.0, 'true']),
    ('set_dipped_beams', [NAN, None, 2, 1.0, 'on']),
    ('set_antifog_lights', [None, 2, 0.5]),
    ('enable_limited_slip_differential', [None, 2, 1.0]),
    ('enable_indicator_auto_disabling', [None, -1, 0.0]),
]


def _busy_car():
    """Return a car with non-default state everywhere, after a few steps."""
    car = CarLogic(DEFAULT_CAR)
    car.set_gear(2)
    car.set_cruising_speed_kmh(30.0)
    car.set_steering_angle(0.2)
    car.set_indicator(Indicator.LEFT)
    car.set_brake_intensity(0.25)
    car.set_wiper_mode(WiperMode.NORMAL)
    car.set_dipped_beams(True)
    car.set_indicator_period_s(0.5)
    _spinning(car, 3.0, 5)
    return car


def _actuation_values(actuation):
    return (actuation.steer_right_rad, actuation.steer_left_rad, list(actuation.wheel_mode),
            actuation.wheel_velocity_radps.tolist(), actuation.wheel_torque_nm.tolist(),
            actuation.brake_torque_nm.tolist())


def test_status_fills_every_field_of_a_frozen_car_status():
    status = _busy_car().status()
    assert set(vars(status)) == {f.name for f in dataclasses.fields(CarStatus)}
    assert status == CarStatus(**vars(status))
    with pytest.raises(dataclasses.FrozenInstanceError):
        status.gear = 3
    assert all(type(v) is float for v in status.wheel_encoders_rad + status.wheel_speeds_radps)


@pytest.mark.parametrize('setter, value', [(setter, value) for setter, values in STRICT_CASES
                                           for value in values])
def test_strict_setter_rejects_bad_value_and_changes_nothing(setter, value):
    car = _busy_car()
    twin = copy.deepcopy(car)
    before = car.status()
    with pytest.raises(InvalidCommandError):
        getattr(car, setter)(value)
    assert car.status() == before
    # The future is unchanged too: the same measurements give the same commands.
    measurement = Measurement()
    measurement.wheel_position_rad[:] = [0.3, 0.31, 0.29, 0.3]
    assert _actuation_values(car.step(measurement, 1.0, DT_S)) == \
        _actuation_values(twin.step(measurement, 1.0, DT_S))
    assert car.status() == twin.status()


@pytest.mark.parametrize('setter, value, message', [
    ('set_throttle', 1.5, r'throttle = 1\.5 is outside the valid range \[0\.0, 1\.0\]'),
    ('set_steering_angle', -2.0, r'-2\.0 rad is outside the valid range \[-1\.0, 1\.0\]'),
    ('set_gear', 7, r'gear = 7 is outside the valid range -1\.\.5'),
    ('set_cruising_speed_kmh', NAN, r'cruising speed = nan is not a finite number'),
    ('set_cruising_speed_within_top_kmh', 300.0,
     r'cruising speed = 300\.0 km/h is outside the valid range \[-180\.0, 180\.0\] km/h'),
    ('set_indicator_period_s', 5e-324,
     r'indicator period = 5e-324 s is outside the valid range \[0\.001, inf\) s'),
    ('set_wiper_mode', 9, r'wiper mode = 9 .*0\.\.3 \(0 DOWN, 1 SLOW, 2 NORMAL, 3 FAST\)'),
])
def test_strict_setter_error_names_value_and_range(setter, value, message):
    with pytest.raises(InvalidCommandError, match=message):
        getattr(CarLogic(DEFAULT_CAR), setter)(value)


@pytest.mark.parametrize('setter, value, getter, expected', [
    ('set_throttle', 1, 'throttle', 1.0),
    ('set_throttle', np.float64(0.0), 'throttle', 0.0),
    ('set_brake_intensity', 1.0, 'brake_intensity', 1.0),
    ('set_cruising_speed_kmh', -180.0, 'target_cruising_speed_kmh', -180.0),
    ('set_cruising_speed_kmh', 300.0, 'target_cruising_speed_kmh', 300.0),
    ('set_cruising_speed_kmh', -1e300, 'target_cruising_speed_kmh', -1e300),
    ('set_cruising_speed_within_top_kmh', 180.0, 'target_cruising_speed_kmh', 180.0),
    ('set_gear', -1, 'selected_gear', -1),
    ('set_gear', np.int64(5), 'selected_gear', 5),
    ('set_indicator', Indicator.RIGHT, 'indicator', Indicator.RIGHT),
    ('set_wiper_mode', 3, 'wiper_mode', WiperMode.FAST),
    ('set_hazard_flashers', 1, 'hazard_flashers', True),
    ('set_dipped_beams', np.bool_(True), 'dipped_beams', True),
    ('enable_limited_slip_differential', 0, 'limited_slip_differential', False),
    ('set_indicator_period_s', 1e-3, 'indicator_period_s', 1e-3),
    ('set_steering_angle', -1.0, 'commanded_steering_angle_rad', -1.0),
])
def test_strict_setter_accepts_boundary_and_numpy_values(setter, value, getter, expected):
    car = CarLogic(DEFAULT_CAR)
    getattr(car, setter)(value)
    result = getattr(car, getter)
    assert result == expected and type(result) is type(expected)


@pytest.mark.parametrize('now_s, dt_s', [(NAN, DT_S), (0.0, 0.0), (0.0, -DT_S), (0.0, INF)])
def test_step_rejects_bad_time(now_s, dt_s):
    with pytest.raises(InvalidCommandError):
        CarLogic(DEFAULT_CAR).step(Measurement(), now_s, dt_s)
