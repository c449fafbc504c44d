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
Indicators, hazard flashers, wipers and automatic lights (Webots' driver.c and car.c).

Pure functions of explicit inputs plus one small Wiper state machine; time is always passed in.
"""

from enum import IntEnum
import math

from vehicle_sim.core.car.drivetrain import ControlMode

# car.c default indicator_period: time of one ON (or OFF) phase, so a full cycle is 2×period.
DEFAULT_INDICATOR_PERIOD_S = 0.34
# Shortest accepted indicator period (ours; Webots accepts anything). A phase shorter than one
# basic step cannot be seen (the lamps are evaluated once per step), and 1 ms is the shortest
# basic step any vehicle_sim node runs (time_step_ms is an integer >= 1). The lamp phase itself
# is computed without overflow for any finite positive period (indicator_phase_on).
MIN_INDICATOR_PERIOD_S = 1.0e-3
# Every float at or above 2**53 is an even integer: a quotient that large carries no phase.
_EXACT_PARITY_LIMIT = 2.0 ** 53
# driver.c INDICATOR_AUTO_DISABLING_THRESHOLD.
INDICATOR_AUTO_DISABLING_THRESHOLD_RAD = 0.1

# No preset has wiper geometry, so each wiper is an angle in [0, WIPER_MAX_ANGLE_RAD] (ours,
# about a windscreen sweep of 92°), driven at Webots' motor speeds (driver.c set_wiper_mode).
WIPER_MIN_ANGLE_RAD = 0.0
WIPER_MAX_ANGLE_RAD = 1.6
WIPER_SLOW_SPEED_RADPS = 2.0    # DOWN, SLOW and NORMAL
WIPER_FAST_SPEED_RADPS = 4.0    # FAST
# SLOW mode sweeps only while (int)t % 4 == 0, i.e. in the first second of each 4 s window.
WIPER_SLOW_WINDOW_S = 4
# Webots compares the wiper sensor with the motor limits by exact float equality; the modelled
# wiper lands exactly on its limits, but a tolerance keeps the logic robust.
WIPER_LIMIT_TOLERANCE_RAD = 1e-9


class Indicator(IntEnum):
    """Webots WbuDriverIndicatorState values (driver.h)."""

    OFF = 0
    RIGHT = 1
    LEFT = 2


class WiperMode(IntEnum):
    """Webots WbuDriverWiperMode values (driver.h)."""

    DOWN = 0
    SLOW = 1
    NORMAL = 2
    FAST = 3


def indicator_phase_on(time_s, period_s):
    """
    Return whether the blinking lamps are in their ON phase (driver.c wbu_driver_step).

    driver.c evaluates ``(int)(t / period) % 2 == 0``, which is reproduced exactly while the
    quotient is below 2**53. Beyond that (a tiny period or a huge time) the quotient has no
    parity left, and overflows to inf for tiny periods, so the exact remainder is used instead:
    ON while ``fmod(|t|, 2·period) < period``. The result is defined for every finite time and
    every finite positive period.

    :param time_s: simulation time [s] (before the step being computed), finite.
    :param period_s: indicator period [s] > 0, the length of one ON or OFF phase, finite.
    :return: True in the ON phase (C truncation toward zero: the phase is symmetric in t).
    """
    time_s = abs(time_s)
    quotient = time_s / period_s
    if quotient < _EXACT_PARITY_LIMIT:
        return int(quotient) % 2 == 0
    # 2·period overflows to inf only for periods above 8.9e307 s, where fmod(t, inf) = t.
    return math.fmod(time_s, 2.0 * period_s) < period_s


# Enum members as plain names for the per-step functions below (each ``Enum.X`` lookup costs
# about 0.1 us on CPython 3.11).
_INDICATOR_OFF, _INDICATOR_RIGHT = Indicator.OFF, Indicator.RIGHT
_TORQUE, _SPEED = ControlMode.TORQUE, ControlMode.SPEED


def indicator_lamps(indicator, hazard_flashers, time_s, period_s):
    """
    Return the (right, left) indicator lamp states.

    :param indicator: Indicator value.
    :param hazard_flashers: True when the hazard flashers are on (both sides blink).
    :param time_s: simulation time [s].
    :param period_s: indicator period [s] > 0.
    :return: (right_on, left_on).
    """
    if not hazard_flashers and indicator == _INDICATOR_OFF:
        return False, False
    on = indicator_phase_on(time_s, period_s)
    if hazard_flashers:
        return on, on
    if indicator == _INDICATOR_RIGHT:
        return on, False
    return False, on


def auto_disable_indicator(indicator, indicator_angle_rad, steering_rad):
    """
    Apply the indicator auto-disabling rule of driver.c set_steering_angle.

    The extreme angle reached in the indicated direction is tracked; once the steering has come
    back by 0.1 rad from it, the indicator switches OFF.

    :param indicator: current Indicator value.
    :param indicator_angle_rad: extreme steering angle reached since set_indicator [rad].
    :param steering_rad: the new commanded steering angle [rad], positive = right.
    :return: (indicator, indicator_angle_rad) after the rule.
    """
    if indicator == Indicator.RIGHT:
        if steering_rad > indicator_angle_rad:
            return indicator, steering_rad
        if steering_rad - indicator_angle_rad <= -INDICATOR_AUTO_DISABLING_THRESHOLD_RAD:
            return Indicator.OFF, indicator_angle_rad
    elif indicator == Indicator.LEFT:
        if steering_rad < indicator_angle_rad:
            return indicator, steering_rad
        if indicator_angle_rad - steering_rad <= -INDICATOR_AUTO_DISABLING_THRESHOLD_RAD:
            return Indicator.OFF, indicator_angle_rad
    return indicator, indicator_angle_rad


def backwards_light_on(control_mode, gear, cruising_speed_kmh):
    """
    Return the backwards (reversing) light state, recomputed every step (driver.c).

    :param control_mode: ControlMode value.
    :param gear: engaged gear.
    :param cruising_speed_kmh: target cruising speed [km/h].
    :return: True in TORQUE mode with gear −1 or in SPEED mode with a negative cruising speed.
    """
    return ((control_mode == _TORQUE and gear == -1)
            or (control_mode == _SPEED and cruising_speed_kmh < 0.0))


_WIPER_DOWN, _WIPER_SLOW = WiperMode.DOWN, WiperMode.SLOW


class Wiper:
    """
    Both wipers of a car as one modelled angle (the two Webots wiper motors move together).

    The angle moves toward its target at the mode's speed; the step logic of driver.c picks the
    target: at the bottom go up, at the top (or in SLOW mode outside the first second of each
    4-second window) go down; DOWN parks the wipers.
    """

    __slots__ = ('mode', 'angle_rad', 'target_rad', 'speed_radps')

    def __init__(self):
        """Start parked (DOWN, angle 0)."""
        self.mode = WiperMode.DOWN
        self.angle_rad = WIPER_MIN_ANGLE_RAD
        self.target_rad = WIPER_MIN_ANGLE_RAD
        self.speed_radps = WIPER_SLOW_SPEED_RADPS

    def set_mode(self, mode):
        """
        Select a wiper mode (driver.c set_wiper_mode); the value must already be valid.

        :param mode: WiperMode value.
        """
        self.mode = WiperMode(mode)
        self.speed_radps = (WIPER_FAST_SPEED_RADPS if self.mode == WiperMode.FAST
                            else WIPER_SLOW_SPEED_RADPS)
        if self.mode == WiperMode.DOWN:
            self.target_rad = WIPER_MIN_ANGLE_RAD

    def step(self, time_s, dt_s):
        """
        Choose the target from the current angle, then move toward it for ``dt_s``.

        :param time_s: simulation time [s] before this step.
        :param dt_s: step length [s].
        :return: the new angle [rad].
        """
        mode = self.mode
        if mode != _WIPER_DOWN:
            if self.angle_rad <= WIPER_MIN_ANGLE_RAD + WIPER_LIMIT_TOLERANCE_RAD:
                self.target_rad = WIPER_MAX_ANGLE_RAD
            slow_pause = (mode == _WIPER_SLOW
                          and int(time_s) % WIPER_SLOW_WINDOW_S != 0)
            if self.angle_rad >= WIPER_MAX_ANGLE_RAD - WIPER_LIMIT_TOLERANCE_RAD or slow_pause:
                self.target_rad = WIPER_MIN_ANGLE_RAD
        max_move = self.speed_radps * dt_s
        error = self.target_rad - self.angle_rad
        if abs(error) <= max_move:
            self.angle_rad = self.target_rad
        else:
            self.angle_rad += max_move if error > 0.0 else -max_move
        return self.angle_rad


class Lights:
    """Lamp states of VehicleLights (front, rear, antifog, brake, backwards, indicators)."""

    __slots__ = ('dipped_beams', 'antifog', 'brake', 'backwards', 'right_indicator',
                 'left_indicator')

    def __init__(self):
        """Start with every lamp off."""
        self.dipped_beams = False
        self.antifog = False
        self.brake = False
        self.backwards = False
        self.right_indicator = False
        self.left_indicator = False

    @property
    def front(self):
        # Dipped beams drive both front_lights and rear_lights (driver.c set_dipped_beams).
        return self.dipped_beams

    @property
    def rear(self):
        return self.dipped_beams
