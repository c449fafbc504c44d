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

"""Webots facade: a round trip of every setter/getter and every odd-input row, from one table."""

import math
import os
from pathlib import Path
import subprocess
import sys
import warnings

import pytest

from vehicle_sim.config import load_car
from vehicle_sim.physics import World
from vehicle_sim.webots import Car, Driver, WebotsWarning
from vehicle_sim.webots.api_table import API, CAR_WHEEL_API, DRIVER_API, UNSUPPORTED_ROBOT_API

REPO = Path(__file__).resolve().parent.parent
ROUND_TRIP_ROWS = [row for row in API if row.setter and row.samples]


@pytest.fixture
def car():
    with Car('BmwX5') as instance:
        yield instance


def _snapshot(car):
    """Every getter of the table, plus the core values behind setter-only rows."""
    values = {}
    for row in API:
        if row.getter:
            with warnings.catch_warnings():
                warnings.simplefilter('ignore', WebotsWarning)
                values[row.getter] = getattr(car, row.getter)()
        elif row.core_getter:
            values[row.core_getter] = getattr(car.logic, row.core_getter)
    return values


def _read(car, row):
    if row.getter:
        return getattr(car, row.getter)()
    return getattr(car.logic, row.core_getter)


@pytest.mark.parametrize('row', ROUND_TRIP_ROWS, ids=lambda row: row.setter)
def test_facade_setter_getter_round_trip(car, row):
    if row.getter in ('getGear',):
        car.setThrottle(0.0)   # TORQUE mode: getGear() reads 0 with a warning in SPEED mode
    for value in row.samples:
        getattr(car, row.setter)(value)
        for _ in range(max(1, row.settle_steps)):
            car.step()
        assert _read(car, row) == pytest.approx(value, abs=row.tolerance), (row.setter, value)


@pytest.mark.parametrize('row', [r for r in ROUND_TRIP_ROWS if r.prop],
                         ids=lambda row: row.prop)
def test_facade_snake_case_property_round_trip(car, row):
    if row.prop == 'gear':
        car.throttle = 0.0
    value = row.samples[0]
    setattr(car, row.prop, value)
    for _ in range(max(1, row.settle_steps)):
        car.step()
    assert getattr(car, row.prop) == pytest.approx(value, abs=row.tolerance)


def test_facade_read_only_properties_match_their_getters(car):
    car.step()
    for row in API:
        if row.prop and not row.setter:
            assert getattr(car, row.prop) == getattr(car, row.getter)()


def test_facade_getters_report_the_preset(car):
    params = load_car('BmwX5')
    assert car.getGearNumber() == len(params.gear_ratio) == 6
    assert car.getTrackFront() == params.track_front_m
    assert car.getTrackRear() == params.track_rear_m
    assert car.getWheelbase() == params.wheelbase_m
    assert car.getFrontWheelRadius() == params.front_tire_radius_m
    assert car.getRearWheelRadius() == params.rear_tire_radius_m
    assert car.getType() == Car.TRACTION
    assert car.getEngineType() == Car.COMBUSTION_ENGINE
    assert car.getControlMode() is None     # UNDEFINED before any command (Webots Python)
    car.setCruisingSpeed(10.0)
    assert car.getControlMode() == Driver.SPEED
    car.setThrottle(0.2)
    assert car.getControlMode() == Driver.TORQUE


def test_facade_constants_have_the_webots_values():
    assert (Driver.INDICATOR_OFF, Driver.INDICATOR_RIGHT, Driver.INDICATOR_LEFT) == (0, 1, 2)
    assert (Driver.SPEED, Driver.TORQUE) == (0, 1)
    assert (Driver.DOWN, Driver.SLOW, Driver.NORMAL, Driver.FAST) == (0, 1, 2, 3)
    assert (Car.TRACTION, Car.PROPULSION, Car.FOUR_BY_FOUR) == (0, 1, 2)
    assert (Car.COMBUSTION_ENGINE, Car.ELECTRIC_ENGINE, Car.PARALLEL_HYBRID_ENGINE,
            Car.POWER_SPLIT_HYBRID_ENGINE) == (0, 1, 2, 3)
    assert (Car.WHEEL_FRONT_RIGHT, Car.WHEEL_FRONT_LEFT, Car.WHEEL_REAR_RIGHT,
            Car.WHEEL_REAR_LEFT, Car.WHEEL_NB) == (0, 1, 2, 3, 4)


def test_facade_driver_has_no_car_library_functions():
    assert not hasattr(Driver, 'getWheelEncoder')
    assert not hasattr(Driver, 'setIndicatorPeriod')
    assert all(hasattr(Driver, row.setter or row.getter) for row in DRIVER_API)


def test_facade_deprecated_aliases_warn_and_delegate(car):
    with pytest.warns(WebotsWarning, match='Deprecated setBrake'):
        car.setBrake(0.4)
    assert car.getBrakeIntensity() == 0.4
    with pytest.warns(WebotsWarning, match='Deprecated (set|get)WipersMode'):
        car.setWipersMode(Driver.FAST)
        assert car.getWipersMode() == Driver.FAST


# ------------------------------------------------------------------------ odd input
# (docs/deviations.md)
NUMERIC_ROWS = [row for row in API if row.setter and row.kind in ('float', 'int', 'enum')]


@pytest.mark.parametrize('bad', [math.nan, math.inf, -math.inf])
@pytest.mark.parametrize('row', NUMERIC_ROWS, ids=lambda row: row.setter)
def test_facade_non_finite_value_warns_and_changes_nothing(car, row, bad):
    before = _snapshot(car)
    with pytest.warns(WebotsWarning, match='invalid argument'):
        getattr(car, row.setter)(bad)
    assert _snapshot(car) == before


def _above_and_below(car, row):
    low, high = row.limits(car.logic)
    if row.kind == 'int':
        return [(high + 5, high), (low - 5, low)]
    cases = [(low - 1.0, low)]
    if math.isfinite(high):
        cases.append((high + 1.0, high))
    return cases


@pytest.mark.parametrize('row', [r for r in API if r.limits and r.out_of_range == 'clamp'],
                         ids=lambda row: row.setter)
def test_facade_out_of_range_value_warns_and_is_clamped(car, row):
    for value, expected in _above_and_below(car, row):
        with pytest.warns(WebotsWarning, match='outside the valid range'):
            getattr(car, row.setter)(value)
        for _ in range(max(1, row.settle_steps)):
            car.step()
        if row.getter == 'getSteeringAngle':
            # The measured mean of two clamped Ackermann angles is not the command: read the
            # stored command instead.
            core_value = car.logic.commanded_steering_angle_rad
        else:
            core_value = _read(car, row)
        assert core_value == pytest.approx(expected, abs=max(1e-9, row.tolerance)), (row.setter,
                                                                                 value)


@pytest.mark.parametrize('row', [r for r in API if r.limits and r.out_of_range == 'store'],
                         ids=lambda row: row.setter)
def test_facade_out_of_range_value_warns_and_is_stored_as_given(car, row):
    low, high = row.limits(car.logic)
    for value in (high + 120.0, low - 120.0, 1e300):
        with pytest.warns(WebotsWarning, match='outside the valid range .* stored as given'):
            getattr(car, row.setter)(value)
        car.step()
        assert _read(car, row) == value


def test_facade_cruising_speed_above_top_speed_is_returned_and_driven_at_top_speed():
    # Webots' driver.c stores the speed; only the wheel motors clamp (BmwX5: 180 km/h).
    with Car('BmwX5') as car:
        with pytest.warns(WebotsWarning, match='motors saturate at 180'):
            car.setCruisingSpeed(300.0)
        assert car.getTargetCruisingSpeed() == 300.0
        assert car.cruising_speed == 300.0
        assert car.logic.effective_cruising_speed_kmh == 180.0
        car.step(1000)
        assert car.getTargetCruisingSpeed() == 300.0


@pytest.mark.parametrize('row', [r for r in API if r.limits and r.out_of_range == 'ignore'],
                         ids=lambda row: row.setter)
def test_facade_out_of_range_value_warns_and_is_ignored(car, row):
    low, high = row.limits(car.logic)
    values = [low / 2.0, 5e-324, 0.0, -1.0] + ([high * 2.0] if math.isfinite(high) else [])
    for value in values:
        before = _snapshot(car)
        with pytest.warns(WebotsWarning, match='outside the valid range .*; ignored'):
            getattr(car, row.setter)(value)
        assert _snapshot(car) == before


def test_facade_tiny_indicator_period_with_hazard_flashers_keeps_stepping():
    # Regression: setIndicatorPeriod(5e-324) was stored and the next step raised OverflowError.
    with Car() as car:
        car.setHazardFlashers(True)
        with pytest.warns(WebotsWarning, match=r'setIndicatorPeriod\(5e-324\)'):
            car.setIndicatorPeriod(5e-324)
        assert car.step() == 0
        assert car.step() == 0
        assert car.getIndicatorPeriod() == 0.34
        assert car.logic.right_indicator_light and car.logic.left_indicator_light


@pytest.mark.parametrize('row, value', [
    (next(r for r in API if r.setter == 'setIndicator'), 7),
    (next(r for r in API if r.setter == 'setIndicator'), -1),
    (next(r for r in API if r.setter == 'setWiperMode'), 9),
    (next(r for r in API if r.setter == 'setIndicatorPeriod'), 0.0),
    (next(r for r in API if r.setter == 'setIndicatorPeriod'), -0.5),
], ids=['indicator 7', 'indicator -1', 'wiper 9', 'period 0', 'period -0.5'])
def test_facade_undefined_value_warns_and_is_ignored(car, row, value):
    before = _snapshot(car)
    with pytest.warns(WebotsWarning):
        getattr(car, row.setter)(value)
    assert _snapshot(car) == before


@pytest.mark.parametrize('name, method', CAR_WHEEL_API)
@pytest.mark.parametrize('index', [-1, 4, 7])
def test_facade_wheel_index_outside_range_warns_and_returns_zero(car, name, method, index):
    with pytest.warns(WebotsWarning, match='maximum wheel index'):
        assert getattr(car, name)(index) == 0.0


@pytest.mark.parametrize('getter', ['getRpm', 'getGear'])
def test_facade_rpm_and_gear_in_speed_mode_warn_and_return_zero(car, getter):
    car.setGear(2)
    car.setCruisingSpeed(20.0)
    for _ in range(50):
        car.step()
    with pytest.warns(WebotsWarning, match='cruise control'):
        assert getattr(car, getter)() == 0


@pytest.mark.parametrize('setter, value', [
    ('setThrottle', 'full'), ('setGear', 1.5), ('setGear', True), ('setDippedBeams', 'on'),
    ('setSteeringAngle', None), ('setIndicator', 1.0)])
def test_facade_wrong_type_raises_type_error_and_changes_nothing(car, setter, value):
    before = _snapshot(car)
    with pytest.raises(TypeError, match=setter):
        getattr(car, setter)(value)
    assert _snapshot(car) == before


@pytest.mark.parametrize('name', UNSUPPORTED_ROBOT_API[:5])
def test_facade_devices_raise_not_implemented_naming_what_is_supported(car, name):
    with pytest.raises(NotImplementedError, match='driver and car library'):
        getattr(car, name)('camera')


def test_facade_unknown_attribute_is_an_attribute_error(car):
    with pytest.raises(AttributeError):
        car.noSuchFunction()


# ------------------------------------------------------------------------ stepping and worlds
def test_facade_step_with_a_duration_advances_that_many_basic_steps(car):
    assert car.getBasicTimeStep() == pytest.approx(10.0)
    assert car.step(30) == 0
    assert car.getTime() == pytest.approx(0.03, abs=1e-12)
    car.step()
    assert car.getTime() == pytest.approx(0.04, abs=1e-12)
    with pytest.raises(ValueError, match='multiple of the basic time step'):
        car.step(15)


def test_facade_step_returns_minus_one_after_the_duration():
    with Driver(duration_s=0.05) as driver:
        results = [driver.step() for _ in range(6)]
    assert results == [0, 0, 0, 0, -1, -1]


def test_facade_car_is_chosen_by_argument_or_environment(monkeypatch):
    with Driver(car='ToyotaPrius') as driver:
        assert driver.getGearNumber() == 2
    monkeypatch.setenv('VEHICLE_SIM_CAR', 'LincolnMKZ')
    with Car() as car:
        assert car.getType() == Car.FOUR_BY_FOUR
    monkeypatch.delenv('VEHICLE_SIM_CAR')
    with Driver() as driver:
        assert driver.getGearNumber() == 6 and driver.logic.params.model == 'Car'


def test_facade_drivers_sharing_a_world_advance_it_once_per_tick():
    with World() as world:
        first = Driver(car='BmwX5', world=world, position=(0.0, 0.0, 0.0))
        second = Driver(car='ToyotaPrius', world=world, position=(0.0, 10.0, 0.0))
        for _ in range(5):
            first.step()
            second.step()
        assert world.step_count == 5
        # A loop that steps only one of them still advances time.
        for _ in range(3):
            first.step()
        assert world.step_count == 8
        assert first.getTime() == second.getTime() == pytest.approx(0.08)


def test_facade_example_controller_runs_unchanged_apart_from_the_import():
    source = (REPO / 'examples' / 'webots_controller.py').read_text()
    assert 'from vehicle_sim.webots import Driver' in source
    webots_source = source.replace('from vehicle_sim.webots import Driver',
                                   'from vehicle import Driver')
    assert 'vehicle_sim' not in webots_source.split('"""')[-1]   # nothing else is ours
    env = dict(os.environ, VEHICLE_SIM_CAR='BmwX5')
    result = subprocess.run([sys.executable, str(REPO / 'examples' / 'webots_controller.py')],
                            capture_output=True, text=True, env=env, timeout=120)
    assert result.returncode == 0, result.stderr
    speeds = [float(line.split('speed=')[1].split()[0])
              for line in result.stdout.splitlines() if 'speed=' in line]
    assert len(speeds) >= 9
    assert speeds[3] == pytest.approx(30.0, abs=0.5)   # cruise control reached 30 km/h
    assert speeds[-1] < speeds[7]                      # and slowed down after t = 8 s


def test_facade_brake_while_cruising_warns_once_and_acts_after_set_throttle():
    # Webots' driver.c takes a brake in SPEED mode without a word and the driven wheels keep the
    # cruising speed; the facade takes it too and says, once, what to do instead.
    driver = Driver()
    try:
        driver.setCruisingSpeed(20.0)
        while driver.getTime() < 4.5:
            driver.step()
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter('always')
            for _ in range(3):
                driver.setBrakeIntensity(1.0)
        assert [str(w.message) for w in caught if w.category is WebotsWarning] == [
            'setBrakeIntensity(1.0): brake intensity 1 has no effect while cruise control holds '
            '20 km/h (the driven wheels follow the cruising speed): set the cruising speed to 0 '
            'to slow down, or set the throttle (TORQUE mode) so that the brake acts']
        assert driver.getBrakeIntensity() == 1.0
        for _ in range(100):
            driver.step()
        assert driver.getCurrentSpeed() == pytest.approx(20.0, abs=0.1)   # cruise holds it
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter('always')
            driver.setThrottle(0.0)
            driver.setBrakeIntensity(1.0)
        assert caught == []
        while driver.getTime() < 9.5:
            driver.step()
        assert driver.getCurrentSpeed() == pytest.approx(0.0, abs=0.01)
    finally:
        driver.close()
