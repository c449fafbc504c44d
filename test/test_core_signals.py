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

"""Indicators, hazard flashers, wipers and automatic lights (Webots' driver.c and car.c)."""

import math

import pytest

from vehicle_sim.core.car.drivetrain import ControlMode
from vehicle_sim.core.car.logic import CarLogic
from vehicle_sim.core.car.params import DEFAULT_CAR
from vehicle_sim.core.car.signals import (
    auto_disable_indicator,
    backwards_light_on,
    Indicator,
    indicator_lamps,
    indicator_phase_on,
    MIN_INDICATOR_PERIOD_S,
    Wiper,
    WIPER_MAX_ANGLE_RAD,
    WiperMode,
)
from vehicle_sim.core.car.vehicle_io import Measurement
from vehicle_sim.core.specs.errors import InvalidCommandError

DT_S = 0.01


@pytest.mark.parametrize('time_s, on', [
    (0.0, True), (0.33, True),     # int(t/0.34) = 0
    (0.35, False), (0.67, False),  # = 1
    (0.69, True),                  # = 2
    (1.03, False),                 # = 3
])
def test_indicator_phase_toggles_every_period(time_s, on):
    assert indicator_phase_on(time_s, 0.34) is on


@pytest.mark.parametrize('period_s', [0.34, 0.5, 0.3, 0.07, DT_S, MIN_INDICATOR_PERIOD_S])
def test_indicator_phase_equals_driver_c_formula_at_every_step(period_s):
    # driver.c: (int)(t / period) % 2 == 0, bit for bit, including the steps where t / period
    # rounds onto an integer (a remainder-based phase differs there); 2e5 steps of 10 ms.
    times = [k * DT_S for k in range(200_000)]
    assert [indicator_phase_on(t, period_s) for t in times] == \
        [int(t / period_s) % 2 == 0 for t in times]


@pytest.mark.parametrize('period_s', [5e-324, 1e-300, 1e-3, 0.34, 1e300, 1.7e308])
@pytest.mark.parametrize('time_s', [0.0, 0.01, 1.0, 1.8e8, 1e9, 1e300, 1.7e308])
def test_indicator_phase_is_defined_for_any_finite_positive_period_at_any_time(time_s,
                                                                            period_s):
    # Regression: 5e-324 made t / period overflow and int(inf) raised OverflowError.
    on = indicator_phase_on(time_s, period_s)
    assert on is True or on is False
    # Whatever branch is taken, the answer is the exact phase where that is representable.
    if time_s / period_s < 2.0 ** 53:
        assert on == (int(time_s / period_s) % 2 == 0)
    else:
        assert on == (math.fmod(time_s, 2.0 * period_s) < period_s)


@pytest.mark.parametrize('time_s, period_s, on', [
    (3.0, 5e-324, True),               # 3 s is an even number of 5e-324 s phases
    (3 * 5e-324, 5e-324, False),       # third phase: OFF
    (2.0 ** 60 + 2.0 ** 8, 2.0 ** 7, True),   # quotient 2^53 + 2: even
    (1.0, 1.7e308, True),              # 2·period overflows to inf: still the first phase
    (-0.35, 0.34, False),              # C truncation toward zero: symmetric in t
])
def test_indicator_phase_beyond_the_exact_quotient_uses_the_exact_remainder(time_s, period_s,
                                                                             on):
    assert indicator_phase_on(time_s, period_s) is on


def test_indicator_lamps_blink_only_the_selected_side():
    assert indicator_lamps(Indicator.RIGHT, False, 0.1, 0.34) == (True, False)
    assert indicator_lamps(Indicator.LEFT, False, 0.1, 0.34) == (False, True)
    assert indicator_lamps(Indicator.RIGHT, False, 0.4, 0.34) == (False, False)
    assert indicator_lamps(Indicator.OFF, False, 0.1, 0.34) == (False, False)


@pytest.mark.parametrize('indicator', list(Indicator))
def test_hazard_flashers_blink_both_sides_whatever_the_indicator(indicator):
    assert indicator_lamps(indicator, True, 0.1, 0.34) == (True, True)
    assert indicator_lamps(indicator, True, 0.4, 0.34) == (False, False)


def test_indicator_right_tracks_extreme_then_cancels_after_returning_0_1_rad():
    # Binary-exact angles: 0.5 − 0.4375 = 0.0625 < 0.1 keeps it; 0.5 − 0.375 = 0.125 cancels.
    state = (Indicator.RIGHT, 0.0)
    state = auto_disable_indicator(*state, 0.5)
    assert state == (Indicator.RIGHT, 0.5)
    state = auto_disable_indicator(*state, 0.4375)
    assert state == (Indicator.RIGHT, 0.5)
    state = auto_disable_indicator(*state, 0.375)
    assert state[0] == Indicator.OFF


def test_indicator_left_tracks_extreme_then_cancels_after_returning_0_1_rad():
    state = (Indicator.LEFT, 0.0)
    state = auto_disable_indicator(*state, -0.5)
    assert state == (Indicator.LEFT, -0.5)
    state = auto_disable_indicator(*state, -0.4375)
    assert state == (Indicator.LEFT, -0.5)
    assert auto_disable_indicator(*state, -0.375)[0] == Indicator.OFF


def test_car_indicator_auto_cancel_only_runs_in_set_steering_angle():
    car = CarLogic(DEFAULT_CAR)
    car.set_steering_angle(0.125)
    car.set_indicator(Indicator.RIGHT)      # remembers 0.125 as the start angle
    car.set_steering_angle(0.5)
    car.set_steering_angle(0.4375)
    assert car.indicator == Indicator.RIGHT
    car.step(Measurement(), 0.0, DT_S)
    assert car.indicator == Indicator.RIGHT
    car.set_steering_angle(0.375)
    assert car.indicator == Indicator.OFF


def test_car_indicator_auto_cancel_can_be_disabled():
    car = CarLogic(DEFAULT_CAR)
    car.enable_indicator_auto_disabling(False)
    car.set_indicator(Indicator.LEFT)
    car.set_steering_angle(-0.5)
    car.set_steering_angle(0.5)
    assert car.indicator == Indicator.LEFT


def test_car_indicator_lamps_use_time_before_the_step():
    car = CarLogic(DEFAULT_CAR)
    car.set_hazard_flashers(True)
    car.step(Measurement(), 0.0, DT_S)
    assert (car.right_indicator_light, car.left_indicator_light) == (True, True)
    car.step(Measurement(), 0.35, DT_S)
    assert (car.right_indicator_light, car.left_indicator_light) == (False, False)
    car.set_indicator_period_s(1.0)
    car.set_hazard_flashers(False)
    car.set_indicator(Indicator.RIGHT)
    car.step(Measurement(), 0.35, DT_S)
    assert (car.right_indicator_light, car.left_indicator_light) == (True, False)


@pytest.mark.parametrize('period_s', [5e-324, 1e-300, 9.99e-4, 0.0])
def test_car_refuses_an_indicator_period_below_one_millisecond(period_s):
    car = CarLogic(DEFAULT_CAR)
    car.set_hazard_flashers(True)
    with pytest.raises(InvalidCommandError, match=r'indicator period = .* s is outside the '
                                                  r'valid range \[0\.001, inf\) s'):
        car.set_indicator_period_s(period_s)
    assert car.indicator_period_s == 0.34
    car.step(Measurement(), 0.0, DT_S)
    car.step(Measurement(), DT_S, DT_S)
    assert (car.right_indicator_light, car.left_indicator_light) == (True, True)


def test_car_blinks_with_the_shortest_period_at_any_time():
    car = CarLogic(DEFAULT_CAR)
    car.set_hazard_flashers(True)
    car.set_indicator_period_s(MIN_INDICATOR_PERIOD_S)
    times = (0.0, 0.001, 1e9, 1e15, 1e300, 1.7e308)
    lamps = []
    for time_s in times:
        car.step(Measurement(), time_s, DT_S)
        lamps.append((car.right_indicator_light, car.left_indicator_light))
    assert lamps[:2] == [(True, True), (False, False)]
    assert lamps == [(on, on) for on in (indicator_phase_on(t, 1e-3) for t in times)]


def _run_wiper(mode, duration_s, wiper=None):
    wiper = wiper or Wiper()
    wiper.set_mode(mode)
    angles = []
    for k in range(round(duration_s / DT_S)):
        angles.append(wiper.step(k * DT_S, DT_S))
    return wiper, angles


@pytest.mark.parametrize('mode, speed', [(WiperMode.NORMAL, 2.0), (WiperMode.FAST, 4.0)])
def test_wiper_sweeps_continuously_at_mode_speed(mode, speed):
    # Up 1.6 rad and back at `speed`: one cycle lasts 2·1.6/speed (1.6 s NORMAL, 0.8 s FAST).
    cycle_steps = round(2.0 * WIPER_MAX_ANGLE_RAD / speed / DT_S)
    _, angles = _run_wiper(mode, 4.0)
    assert angles[0] == pytest.approx(speed * DT_S, abs=1e-12)
    assert max(angles) == pytest.approx(WIPER_MAX_ANGLE_RAD, abs=1e-9)
    assert angles[cycle_steps // 2 - 1] == pytest.approx(WIPER_MAX_ANGLE_RAD, abs=1e-9)
    assert angles[cycle_steps - 1] == pytest.approx(0.0, abs=1e-9)
    # ... and starts the next cycle at once.
    assert angles[cycle_steps] == pytest.approx(speed * DT_S, abs=1e-9)
    assert max(angles[cycle_steps:2 * cycle_steps]) == pytest.approx(WIPER_MAX_ANGLE_RAD,
                                                                     abs=1e-9)


def test_wiper_slow_sweeps_only_in_first_second_of_each_4_s_window():
    # Up at 2 rad/s until 0.8 s, down again until 1.6 s, parked until t = 4 s, then again.
    _, angles = _run_wiper(WiperMode.SLOW, 8.0)
    assert angles[79] == pytest.approx(WIPER_MAX_ANGLE_RAD, abs=1e-9)   # after 0.80 s
    assert angles[159] == pytest.approx(0.0, abs=1e-9)                  # after 1.60 s
    assert max(angles[160:400]) == 0.0                                 # 1.6 s .. 4.0 s
    assert angles[400] > 0.0                                           # sweeps at 4.0 s
    assert max(angles[400:500]) == pytest.approx(WIPER_MAX_ANGLE_RAD, abs=1e-9)


def test_wiper_slow_goes_down_when_window_closes_mid_sweep():
    # Starting the sweep at t = 0.5 s: at t = 1 s it has reached 1.0 rad and turns back.
    wiper = Wiper()
    wiper.set_mode(WiperMode.SLOW)
    angles = [wiper.step(0.5 + k * DT_S, DT_S) for k in range(100)]
    assert max(angles) == pytest.approx(1.0, abs=1e-9)
    assert angles[-1] == pytest.approx(0.0, abs=1e-9)


def test_wiper_down_parks_from_mid_sweep():
    wiper, _ = _run_wiper(WiperMode.NORMAL, 0.5)   # at 1.0 rad, going up
    assert wiper.angle_rad == pytest.approx(1.0, abs=1e-9)
    wiper, angles = _run_wiper(WiperMode.DOWN, 2.0, wiper)
    assert angles[0] == pytest.approx(1.0 - 2.0 * DT_S, abs=1e-9)
    assert angles[-1] == 0.0 and max(angles) < 1.0


@pytest.mark.parametrize('mode, gear, cruising, on', [
    (ControlMode.TORQUE, -1, 0.0, True),
    (ControlMode.TORQUE, 1, -10.0, False),
    (ControlMode.SPEED, -1, 10.0, False),
    (ControlMode.SPEED, 0, -10.0, True),
    (ControlMode.UNDEFINED, -1, -10.0, False),
])
def test_backwards_light_in_reverse_gear_or_negative_cruise(mode, gear, cruising, on):
    assert backwards_light_on(mode, gear, cruising) is on


def test_car_backwards_light_recomputed_each_step():
    car = CarLogic(DEFAULT_CAR)
    car.set_gear(-1)
    car.set_throttle(0.0)
    assert not car.backwards_lights                  # not before the step
    car.step(Measurement(), 0.0, DT_S)
    assert car.backwards_lights
    car.set_cruising_speed_kmh(-5.0)
    car.step(Measurement(), DT_S, DT_S)
    assert car.backwards_lights
    car.set_cruising_speed_kmh(5.0)
    car.step(Measurement(), 2 * DT_S, DT_S)
    assert not car.backwards_lights


def test_car_brake_light_follows_brake_intensity_immediately():
    car = CarLogic(DEFAULT_CAR)
    car.set_brake_intensity(0.3)
    assert car.brake_lights
    car.set_brake_intensity(0.0)
    assert not car.brake_lights


def test_car_dipped_beams_drive_front_and_rear_lights_and_antifog_is_separate():
    car = CarLogic(DEFAULT_CAR)
    car.set_dipped_beams(True)
    assert (car.dipped_beams, car.front_lights, car.rear_lights) == (True, True, True)
    assert not car.antifog_lights
    car.set_antifog_lights(True)
    car.set_dipped_beams(False)
    assert (car.front_lights, car.rear_lights, car.antifog_lights) == (False, False, True)


def test_car_wiper_moves_in_step():
    car = CarLogic(DEFAULT_CAR)
    car.set_wiper_mode(WiperMode.FAST)
    car.step(Measurement(), 0.0, DT_S)
    assert car.wiper_angle_rad == pytest.approx(4.0 * DT_S, abs=1e-12)
