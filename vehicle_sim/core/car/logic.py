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
CarLogic: the complete state of the Webots driver and car libraries, with a strict API.

Built from CarParams; no ROS, no physics. Each basic step the physics body fills a Measurement,
``CarLogic.step`` turns it into an Actuation (Webots' wbu_driver_step order), the body applies it
and
the world steps. Setters validate first and raise InvalidCommandError, naming the value and the
valid range, without changing any state (docs/deviations.md, core column). Getters are read-only
properties (plus ``wheel_encoder_rad(i)`` / ``wheel_speed_radps(i)``); ``status()`` bundles all
of them for publishers and tests.

Accepted argument types: numbers are int or float (numpy scalars too) but not bool; enums and
gears are ints (not bool, not float); flags are bool (numpy bool too) or the ints 0 and 1.
"""

from dataclasses import dataclass
import math
import numbers
from typing import Tuple

import numpy as np

from vehicle_sim.core.car.ackermann import ackermann_angles
from vehicle_sim.core.car.drivetrain import (
    CAR_TYPE_BY_NAME,
    central_ratio,
    ControlMode,
    cruise_wheel_targets,
    current_speed_mps,
    distribute_torque,
    engine_rpm,
    front_ratio,
    max_signed_acceleration,
    output_torque_nm,
    rear_ratio,
    update_slip_ratios,
    wheel_acceleration_radps2,
    wheel_speeds,
)
from vehicle_sim.core.car.engines import make_engine
from vehicle_sim.core.car.signals import (
    auto_disable_indicator,
    backwards_light_on,
    DEFAULT_INDICATOR_PERIOD_S,
    Indicator,
    indicator_lamps,
    Lights,
    MIN_INDICATOR_PERIOD_S,
    Wiper,
    WiperMode,
)
from vehicle_sim.core.car.vehicle_io import Actuation, as_floats, WHEEL_COUNT, WheelMode
from vehicle_sim.core.specs.errors import InvalidCommandError
from vehicle_sim.core.specs.units import kmh_to_mps, mps_to_kmh

# ---------------------------------------------------------------------------------------------
# Validation helpers: each returns the normalised value or raises without side effects.

def _number(name, value):
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
        raise InvalidCommandError(f'{name} must be a number, got {value!r}')
    result = float(value)
    if not math.isfinite(result):
        raise InvalidCommandError(f'{name} = {value!r} is not a finite number')
    return result


def _number_in(name, value, low, high, unit=''):
    result = _number(name, value)
    if not low <= result <= high:
        raise InvalidCommandError(
            f'{name} = {result!r}{unit} is outside the valid range [{low!r}, {high!r}]{unit}')
    return result


def _integer_in(name, value, low, high, meaning=''):
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Integral):
        raise InvalidCommandError(f'{name} must be an int in {low}..{high}{meaning}, '
                                  f'got {value!r}')
    result = int(value)
    if not low <= result <= high:
        raise InvalidCommandError(f'{name} = {result} is outside the valid range '
                                  f'{low}..{high}{meaning}')
    return result


def _flag(name, value):
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, numbers.Integral) and int(value) in (0, 1):
        return bool(value)
    raise InvalidCommandError(f'{name} must be a bool (or 0/1), got {value!r}')


def _enum_meaning(enum_cls):
    return ' (' + ', '.join(f'{member.value} {member.name}' for member in enum_cls) + ')'


@dataclass(frozen=True)
class Dimensions:
    """Car dimensions as Webots' car library reports them [m]."""

    track_front_m: float
    track_rear_m: float
    wheelbase_m: float
    front_wheel_radius_m: float
    rear_wheel_radius_m: float


_NEW = object.__new__

# Enum members as plain names for the per-step code: each ``ControlMode.X`` lookup costs about
# 0.1 us on CPython 3.11, a dozen of them per step (benchmarks/bench_step.py).
_SPEED, _TORQUE = ControlMode.SPEED, ControlMode.TORQUE
_INDICATOR_OFF, _WIPER_DOWN = Indicator.OFF, WiperMode.DOWN
_WHEEL_TORQUE, _WHEEL_VELOCITY = WheelMode.TORQUE, WheelMode.VELOCITY


@dataclass(frozen=True)
class CarStatus:
    """Every value the driver and car library getters expose, at one instant."""

    time_s: float
    steering_angle_rad: float
    commanded_steering_angle_rad: float
    right_steering_angle_rad: float
    left_steering_angle_rad: float
    target_cruising_speed_kmh: float
    effective_cruising_speed_kmh: float
    current_speed_kmh: float
    throttle: float
    brake_intensity: float
    gear: int
    selected_gear: int
    control_mode: int
    rpm: float
    indicator: int
    hazard_flashers: bool
    dipped_beams: bool
    antifog_lights: bool
    front_lights: bool
    rear_lights: bool
    brake_lights: bool
    backwards_lights: bool
    right_indicator_light: bool
    left_indicator_light: bool
    wiper_mode: int
    wiper_angle_rad: float
    indicator_period_s: float
    limited_slip_differential: bool
    indicator_auto_disabling: bool
    wheel_encoders_rad: Tuple[float, float, float, float]
    wheel_speeds_radps: Tuple[float, float, float, float]


class CarLogic:
    """
    State and per-step logic of one Webots car (driver library + car library).

    Start state (wbu_driver_init, wbu_car_init): control mode UNDEFINED with the driven wheels
    held at 0 rad/s, gear 0, everything off, wipers DOWN, limited-slip differential and indicator
    auto-disabling on, indicator period 0.34 s.
    """

    def __init__(self, params):
        """
        Build the logic of a car.

        :param params: CarParams (validated presets, see core/car/params.py).
        :raises InvalidParameterError: for an unknown engine type.
        """
        self._params = params
        self._engine = make_engine(params)
        self._car_type = params.car_type
        self._driven = tuple(params.driven_wheels)
        radius = np.array([params.front_tire_radius_m, params.front_tire_radius_m,
                           params.rear_tire_radius_m, params.rear_tire_radius_m])
        # Car.proto driven-wheel motors: acceleration (100/3.6)/time0To100/r, maxVelocity v/r.
        self._wheel_acceleration_radps2 = wheel_acceleration_radps2(params.time_0_to_100_s,
                                                                    radius)
        self._wheel_acceleration_list = self._wheel_acceleration_radps2.tolist()
        self._max_wheel_radps = params.max_velocity_mps / radius
        self._max_cruising_kmh = mps_to_kmh(params.max_velocity_mps)
        self._min_steer = params.min_steering_angle_rad
        self._max_steer = params.max_steering_angle_rad
        self._max_gear = params.gear_number - 1
        self._time_s = 0.0
        self._reset_state()

    def _reset_state(self):
        # Every command, setting and estimate, as wbu_driver_init / wbu_car_init leave them.
        # Driver library commands (wbu_driver_init).
        self._steering_rad = 0.0
        self._cruising_kmh = 0.0
        self._throttle = 0.0
        self._brake = 0.0
        self._gear = 0
        self._mode = ControlMode.UNDEFINED
        self._indicator = Indicator.OFF
        self._indicator_angle_rad = 0.0
        self._hazard = False
        # Car library settings (wbu_car_init).
        self._indicator_period_s = DEFAULT_INDICATOR_PERIOD_S
        self._lsd = True
        self._auto_disable = True
        self._right_angle_rad = 0.0
        self._left_angle_rad = 0.0

        self._lights = Lights()
        self._wiper = Wiper()

        # Estimates from the measurements.
        # As lists of floats, as the step makes them (never changed in place).
        self._encoder = [0.0] * WHEEL_COUNT
        self._measured_right_rad = 0.0
        self._measured_left_rad = 0.0
        self._cruise_target = np.zeros(WHEEL_COUNT)
        self._cruise_target_list = [0.0] * WHEEL_COUNT   # its values, for the step
        self._actuation = Actuation()
        self._driven_mode = None       # wheel modes last written into the Actuation
        self._brake_written = 0.0      # the brake torque in it (Actuation() starts with 0)
        self._forget_motion()

    def _forget_motion(self):
        # The estimates and motor set-points of a car at rest with no previous sample: wheel
        # speeds, accelerations, rpm, limited-slip state, ramped set-points (the motors'
        # internal velocity) and distributed torques.
        self._rpm = 0.0
        self._slip = np.zeros(3)
        self._have_sample = False
        self._previous_position = [0.0] * WHEEL_COUNT
        self._speed = self._previous_speed = [0.0] * WHEEL_COUNT
        self._max_acceleration = 0.0
        self._ramp = [0.0] * WHEEL_COUNT     # a list: the step reads and writes it per wheel
        self._torque = np.zeros(WHEEL_COUNT)
        self._write_actuation(0.0)

    def reset(self):
        """
        Return to the start state (see the class docstring), as a freshly built CarLogic.

        Every command and setting (steering, cruising speed, throttle, brake, gear, control
        mode, indicators, lights, wipers, indicator period, differential) and every estimate
        (wheel speeds, encoders, rpm) goes back to its initial value. Only the time of the last
        step is kept: simulated time is not reset. The body must be put back at rest too (the
        next measurement starts a new sample, so no wheel speed spans the reset).
        """
        self._reset_state()

    def come_to_rest(self):
        """
        Forget the car's motion after its body was put at rest elsewhere (a teleport).

        The commands and settings stay in force (a car cruising at 30 km/h accelerates again
        from rest); the wheel speed estimates, rpm, limited-slip state and the wheel motors'
        ramped set-points restart from 0, and the next measurement starts a new sample (no
        wheel speed spans the jump).
        """
        self._forget_motion()

    # -----------------------------------------------------------------------------------------
    # Driver library setters.

    def set_steering_angle(self, angle_rad):
        """
        Steer the front wheels through the Ackermann geometry (wbu_driver_set_steering_angle).

        In SPEED mode the cruise targets are recomputed (new differential ratios); the indicator
        auto-disabling rule runs afterwards.

        :param angle_rad: steering angle [rad], positive = right, within
            [minSteeringAngle, maxSteeringAngle].
        :raises InvalidCommandError: non-finite or out-of-range angle.
        """
        angle_rad = _number_in('steering angle', angle_rad, self._min_steer, self._max_steer,
                               ' rad')
        self._steering_rad = angle_rad
        self._right_angle_rad, self._left_angle_rad = ackermann_angles(
            angle_rad, self._params.track_front_m, self._params.wheelbase_m)
        if self._mode == ControlMode.SPEED:
            self._update_cruise_target()
        if self._auto_disable:
            self._indicator, self._indicator_angle_rad = auto_disable_indicator(
                self._indicator, self._indicator_angle_rad, angle_rad)

    def set_cruising_speed_kmh(self, speed_kmh):
        """
        Switch to SPEED mode and drive the wheels toward a speed (wbu_driver_set_cruising_speed).

        The wheels' velocity set-points ramp at the acceleration implied by time0To100. Coming
        from TORQUE mode the ramp starts at the wheels' estimated speeds. The speed is stored as
        given (``target_cruising_speed_kmh`` returns it, as driver.c does); above the top speed
        the wheel motors saturate at maxVelocity / r, so the car drives at
        ``effective_cruising_speed_kmh``.

        :param speed_kmh: target speed [km/h], negative = reverse; any finite value.
        :raises InvalidCommandError: non-finite.
        """
        speed_kmh = _number('cruising speed', speed_kmh)
        if self._mode == ControlMode.TORQUE:
            self._ramp[:] = self._speed
        self._cruising_kmh = speed_kmh
        self._mode = ControlMode.SPEED
        self._update_cruise_target()

    def set_cruising_speed_within_top_kmh(self, speed_kmh):
        """
        Set the cruising speed, refusing speeds beyond the top speed (the ROS services' policy).

        Odd input, ROS column (docs/deviations.md): a service answers success=false rather than
        store a speed the
        car cannot reach; otherwise the same as ``set_cruising_speed_kmh``.

        :param speed_kmh: target speed [km/h], |v| <= maxVelocity·3.6.
        :raises InvalidCommandError: non-finite or beyond the top speed.
        """
        self.set_cruising_speed_kmh(_number_in('cruising speed', speed_kmh,
                                               -self._max_cruising_kmh, self._max_cruising_kmh,
                                               ' km/h'))

    def set_throttle(self, throttle):
        """
        Switch to TORQUE mode with a throttle position (wbu_driver_set_throttle).

        :param throttle: throttle in [0, 1].
        :raises InvalidCommandError: non-finite or outside [0, 1].
        """
        self._throttle = _number_in('throttle', throttle, 0.0, 1.0)
        self._mode = ControlMode.TORQUE

    def set_brake_intensity(self, intensity):
        """
        Brake all four wheels; the brake light follows (wbu_driver_set_brake_intensity).

        While cruise control holds a speed other than 0 (SPEED mode) the brake is taken but
        barely acts: the driven wheels' motors hold the cruising speed (1e8 N·m, as in Webots'
        driver.c, which neither changes the mode nor warns). The call returns a note saying so,
        which the Webots facade, the nodes and the scenario runner show as a warning.

        :param intensity: brake in [0, 1]; braking torque per wheel = intensity·brakeCoefficient.
        :return: None, or why this brake has no effect now and what to do instead.
        :raises InvalidCommandError: non-finite or outside [0, 1].
        """
        self._brake = _number_in('brake intensity', intensity, 0.0, 1.0)
        self._lights.brake = self._brake > 0.0
        if self._brake > 0.0 and self._mode == ControlMode.SPEED and self._cruising_kmh != 0.0:
            return (f'brake intensity {self._brake:g} has no effect while cruise control holds '
                    f'{self._cruising_kmh:g} km/h (the driven wheels follow the cruising speed): '
                    'set the cruising speed to 0 to slow down, or set the throttle (TORQUE '
                    'mode) so that the brake acts')
        return None

    def set_gear(self, gear):
        """
        Engage a gear (wbu_driver_set_gear); used in TORQUE mode.

        :param gear: −1 reverse, 0 neutral, 1..gear_number−1 forward.
        :raises InvalidCommandError: not an int or out of range.
        """
        self._gear = _integer_in('gear', gear, -1, self._max_gear,
                                 ' (-1 reverse, 0 neutral, then forward gears)')

    def set_indicator(self, indicator):
        """
        Set the indicator (wbu_driver_set_indicator); remembers the steering angle for the rule.

        :param indicator: 0 OFF, 1 RIGHT, 2 LEFT.
        :raises InvalidCommandError: not one of those ints.
        """
        self._indicator = Indicator(_integer_in('indicator', indicator, 0, 2,
                                                _enum_meaning(Indicator)))
        self._indicator_angle_rad = self._steering_rad

    def set_hazard_flashers(self, enabled):
        """Turn the hazard flashers (both indicators blink) on or off; bool or 0/1."""
        self._hazard = _flag('hazard flashers', enabled)

    def set_dipped_beams(self, enabled):
        """Turn the dipped beams (front and rear lights) on or off; bool or 0/1."""
        self._lights.dipped_beams = _flag('dipped beams', enabled)

    def set_antifog_lights(self, enabled):
        """Turn the antifog lights on or off; bool or 0/1."""
        self._lights.antifog = _flag('antifog lights', enabled)

    def set_wiper_mode(self, mode):
        """
        Set the wiper mode (wbu_driver_set_wiper_mode).

        :param mode: 0 DOWN, 1 SLOW, 2 NORMAL, 3 FAST.
        :raises InvalidCommandError: not one of those ints.
        """
        self._wiper.set_mode(_integer_in('wiper mode', mode, 0, 3, _enum_meaning(WiperMode)))

    # -----------------------------------------------------------------------------------------
    # Car library setters.

    def set_indicator_period_s(self, period_s):
        """
        Set the length of one ON (or OFF) phase of the indicators (wbu_car_set_indicator_period).

        :param period_s: period [s] >= MIN_INDICATOR_PERIOD_S (1 ms); Webots accepts any value,
            we reject what no basic step could show (see signals.MIN_INDICATOR_PERIOD_S).
        :raises InvalidCommandError: non-finite or below 1 ms.
        """
        period_s = _number('indicator period', period_s)
        if not period_s >= MIN_INDICATOR_PERIOD_S:
            raise InvalidCommandError(
                f'indicator period = {period_s!r} s is outside the valid range '
                f'[{MIN_INDICATOR_PERIOD_S!r}, inf) s (one phase must last at least the '
                'shortest basic time step, 1 ms)')
        self._indicator_period_s = period_s

    def set_right_steering_angle(self, angle_rad):
        """
        Command the right front wheel alone (wbu_car_set_right_steering_angle).

        The angle feeds the front differential ratio; the driver's steering angle, cruise
        targets and indicators are left alone, as in Webots.

        :param angle_rad: wheel angle [rad], positive = right, within the steering limits.
        :raises InvalidCommandError: non-finite or out of range.
        """
        self._right_angle_rad = _number_in('right steering angle', angle_rad, self._min_steer,
                                           self._max_steer, ' rad')

    def set_left_steering_angle(self, angle_rad):
        """
        Command the left front wheel alone (wbu_car_set_left_steering_angle).

        :param angle_rad: wheel angle [rad], positive = right, within the steering limits.
        :raises InvalidCommandError: non-finite or out of range.
        """
        self._left_angle_rad = _number_in('left steering angle', angle_rad, self._min_steer,
                                          self._max_steer, ' rad')

    def enable_limited_slip_differential(self, enabled):
        """Enable the limited-slip differential used in TORQUE mode; bool or 0/1."""
        self._lsd = _flag('limited slip differential', enabled)

    def enable_indicator_auto_disabling(self, enabled):
        """Enable switching the indicator off after the turn; bool or 0/1."""
        self._auto_disable = _flag('indicator auto disabling', enabled)

    # -----------------------------------------------------------------------------------------
    # The step.

    def step(self, measurement, now_s, dt_s):
        """
        Run one driver step (wbu_driver_step of Webots' driver.c) and return the commands.

        :param measurement: vehicle_io.Measurement read after the previous world step.
        :param now_s: simulation time [s] before this step (indicator phase, wiper window).
        :param dt_s: basic time step [s] > 0: the time since the previous measurement and the
            length of the coming world step.
        :return: the CarLogic's one Actuation object, refilled on every call.
        :raises InvalidCommandError: non-finite time or non-positive dt.
        """
        if type(now_s) is not float or type(dt_s) is not float:
            now_s = _number('time', now_s)
            dt_s = _number('time step', dt_s)
        elif not (math.isfinite(now_s) and math.isfinite(dt_s)):
            _number('time', now_s)
            _number('time step', dt_s)
        if dt_s <= 0.0:
            raise InvalidCommandError(f'time step = {dt_s!r} s must be > 0 s')
        self._time_s = now_s
        lights = self._lights
        # 1. Indicator lamps, with the time before the step (without the indicator or the
        # hazard flashers both are dark: no call).
        if self._hazard or self._indicator != _INDICATOR_OFF:
            lights.right_indicator, lights.left_indicator = indicator_lamps(
                self._indicator, self._hazard, now_s, self._indicator_period_s)
        else:
            lights.right_indicator = lights.left_indicator = False
        # 2. Wipers (parked ones stay where they are: no call). 3. Backwards light.
        wiper = self._wiper
        if wiper.mode != _WIPER_DOWN or wiper.angle_rad != wiper.target_rad:
            wiper.step(now_s, dt_s)
        lights.backwards = backwards_light_on(self._mode, self._gear, self._cruising_kmh)
        # 4. Wheel speeds; without a previous sample they are 0 (Webots: NaN twice).
        # As lists of floats: numpy calls on 4 elements cost more than the arithmetic.
        position = measurement.wheel_position_rad
        now = as_floats(position)
        previous = self._previous_position if self._have_sample else now
        self._have_sample = True
        speed = wheel_speeds(now, previous, dt_s)
        self._max_acceleration = max_signed_acceleration(speed, self._previous_speed, dt_s)
        self._previous_position = self._encoder = now
        self._previous_speed = self._speed = speed
        self._measured_right_rad = float(measurement.steer_right_rad)
        self._measured_left_rad = float(measurement.steer_left_rad)
        # 5. Engine rpm (every mode).
        params = self._params
        self._rpm = engine_rpm(speed, self._gear, params.gear_ratio, params.engine_max_rpm)
        # 6. TORQUE mode: limited-slip integrator, then output torque and its distribution.
        if self._mode == _TORQUE:
            if self._lsd:
                update_slip_ratios(self._slip, self._speed, self._car_type)
            torque = output_torque_nm(self._engine, self._rpm, self._gear, params.gear_ratio,
                                      self._throttle, self._max_acceleration)
            distribute_torque(torque, self._car_type, *self._ratios(),
                              slip=self._slip if self._lsd else None, out=self._torque)
        # 7. Brakes, and the commands for the coming world step.
        return self._write_actuation(dt_s)

    def _ratios(self):
        steering = self._steering_rad
        params = self._params
        return (front_ratio(steering, self._right_angle_rad, self._left_angle_rad),
                rear_ratio(steering, params.track_rear_m, params.wheelbase_m),
                central_ratio(steering, params.front_tire_radius_m, params.rear_tire_radius_m))

    def _update_cruise_target(self):
        params = self._params
        cruise_wheel_targets(kmh_to_mps(self._cruising_kmh), self._car_type, *self._ratios(),
                             params.front_tire_radius_m, params.rear_tire_radius_m,
                             out=self._cruise_target)
        # The wheel motors saturate at maxVelocity / r (WbMotor; Webots warns). A stored speed
        # near the float limit overflows to ±inf (saturated too), and inf·0 = NaN on a wheel
        # the differential gives no share: that wheel's target is 0.
        target = self._cruise_target
        target[np.isnan(target)] = 0.0      # (np.nan_to_num costs 5x more on 4 wheels)
        np.clip(self._cruise_target, -self._max_wheel_radps, self._max_wheel_radps,
                out=self._cruise_target)
        self._cruise_target_list = self._cruise_target.tolist()

    def _write_actuation(self, dt_s):
        actuation = self._actuation
        # min(max(angle, low), high), without the two calls
        low, high = self._min_steer, self._max_steer
        right, left = self._right_angle_rad, self._left_angle_rad
        actuation.steer_right_rad = low if right < low else (high if right > high else right)
        actuation.steer_left_rad = low if left < low else (high if left > high else left)
        # Per-wheel writes in plain Python: numpy calls on 4-element arrays cost more than the
        # arithmetic (benchmarks/bench_step.py).
        modes = actuation.wheel_mode
        velocity = actuation.wheel_velocity_radps
        torque = actuation.wheel_torque_nm
        driven_mode = _WHEEL_TORQUE if self._mode == _TORQUE else _WHEEL_VELOCITY
        if self._driven_mode != driven_mode:
            self._driven_mode = driven_mode
            velocity.fill(0.0)
            torque.fill(0.0)
            for wheel in range(WHEEL_COUNT):
                modes[wheel] = driven_mode if wheel in self._driven else WheelMode.FREE
        if driven_mode == _WHEEL_TORQUE:
            source = self._torque
            for wheel in self._driven:
                torque[wheel] = source[wheel]
        else:
            ramp = self._ramp
            if self._mode == _SPEED:
                target = self._cruise_target_list
                limits = self._wheel_acceleration_list
                for wheel in self._driven:
                    # ramp_toward(current, target, limit * dt), inline and without the min()
                    # and max() calls (the hot loop)
                    current = ramp[wheel]
                    step = limits[wheel] * dt_s
                    delta = target[wheel] - current
                    if delta > step:
                        delta = step
                    elif delta < -step:
                        delta = -step
                    ramp[wheel] = velocity[wheel] = current + delta
            else:
                for wheel in self._driven:
                    velocity[wheel] = ramp[wheel]
        brake = self._brake * self._params.brake_coefficient_nm
        if brake != self._brake_written:        # (a fill costs more than the comparison)
            actuation.brake_torque_nm.fill(brake)
            self._brake_written = brake
        return actuation

    # -----------------------------------------------------------------------------------------
    # Getters.

    @property
    def params(self):
        return self._params

    @property
    def actuation(self):
        """The last Actuation (the same object every step returns)."""
        return self._actuation

    @property
    def time_s(self):
        return self._time_s

    @property
    def steering_angle_rad(self):
        """Mean of the MEASURED right and left steering angles [rad] (driver.c)."""
        return 0.5 * (self._measured_right_rad + self._measured_left_rad)

    @property
    def commanded_steering_angle_rad(self):
        return self._steering_rad

    @property
    def right_steering_angle_rad(self):
        return self._measured_right_rad

    @property
    def left_steering_angle_rad(self):
        return self._measured_left_rad

    @property
    def target_cruising_speed_kmh(self):
        """The cruising speed as last set [km/h], even beyond the top speed (driver.c)."""
        return self._cruising_kmh

    @property
    def effective_cruising_speed_kmh(self):
        """
        The cruising speed the wheel motors drive at [km/h]: the target within ±top speed.

        Straight ahead this is the car's steady speed in SPEED mode; in a turn each wheel's
        target follows the differential and saturates at maxVelocity / r on its own.
        """
        top = self._max_cruising_kmh
        return min(max(self._cruising_kmh, -top), top)

    @property
    def current_speed_kmh(self):
        """Signed speed [km/h] estimated from the driven wheels' speeds."""
        return mps_to_kmh(current_speed_mps(self._speed, self._car_type,
                                            self._params.front_tire_radius_m,
                                            self._params.rear_tire_radius_m))

    @property
    def throttle(self):
        return self._throttle

    @property
    def brake_intensity(self):
        return self._brake

    @property
    def gear(self):
        """Engaged gear; 0 in SPEED mode, where Webots has no gear model."""
        return 0 if self._mode == ControlMode.SPEED else self._gear

    @property
    def selected_gear(self):
        """The last gear set, whatever the mode."""
        return self._gear

    @property
    def gear_number(self):
        """Number of gear ratios including reverse (Webots getGearNumber)."""
        return self._params.gear_number

    @property
    def control_mode(self):
        return self._mode

    @property
    def rpm(self):
        """Engine speed estimate [rpm]; 0 in SPEED mode, where Webots has no engine model."""
        return 0.0 if self._mode == ControlMode.SPEED else self._rpm

    @property
    def indicator(self):
        return self._indicator

    @property
    def hazard_flashers(self):
        return self._hazard

    @property
    def dipped_beams(self):
        return self._lights.dipped_beams

    @property
    def antifog_lights(self):
        return self._lights.antifog

    @property
    def front_lights(self):
        return self._lights.front

    @property
    def rear_lights(self):
        return self._lights.rear

    @property
    def brake_lights(self):
        return self._lights.brake

    @property
    def backwards_lights(self):
        return self._lights.backwards

    @property
    def right_indicator_light(self):
        return self._lights.right_indicator

    @property
    def left_indicator_light(self):
        return self._lights.left_indicator

    @property
    def wiper_mode(self):
        return self._wiper.mode

    @property
    def wiper_angle_rad(self):
        """Angle of both modelled wipers [rad], 0 = parked."""
        return self._wiper.angle_rad

    @property
    def indicator_period_s(self):
        return self._indicator_period_s

    @property
    def limited_slip_differential(self):
        return self._lsd

    @property
    def indicator_auto_disabling(self):
        return self._auto_disable

    def _wheel_index(self, index):
        return _integer_in('wheel index', index, 0, WHEEL_COUNT - 1,
                           ' (0 FRONT_RIGHT, 1 FRONT_LEFT, 2 REAR_RIGHT, 3 REAR_LEFT)')

    def wheel_encoder_rad(self, index):
        """
        Return a wheel's encoder value from the last measurement (wbu_car_get_wheel_encoder).

        :param index: wheel index 0..3 (FR, FL, RR, RL).
        :return: wheel angle [rad]; 0 before the first step.
        :raises InvalidCommandError: index not an int in 0..3.
        """
        return float(self._encoder[self._wheel_index(index)])

    def wheel_speed_radps(self, index):
        """
        Return a wheel's finite-difference speed from the last step (wbu_car_get_wheel_speed).

        :param index: wheel index 0..3 (FR, FL, RR, RL).
        :return: wheel speed [rad/s]; 0 before the second step.
        :raises InvalidCommandError: index not an int in 0..3.
        """
        return float(self._speed[self._wheel_index(index)])

    @property
    def car_type(self):
        """Webots WbuCarType value (drivetrain.CarType)."""
        return CAR_TYPE_BY_NAME[self._car_type]

    @property
    def engine_type(self):
        """Webots WbuCarEngineType value (engines.EngineType)."""
        return self._engine.engine_type

    @property
    def engine(self):
        return self._engine

    @property
    def track_front_m(self):
        return self._params.track_front_m

    @property
    def track_rear_m(self):
        return self._params.track_rear_m

    @property
    def wheelbase_m(self):
        return self._params.wheelbase_m

    @property
    def front_wheel_radius_m(self):
        return self._params.front_tire_radius_m

    @property
    def rear_wheel_radius_m(self):
        return self._params.rear_tire_radius_m

    @property
    def min_steering_angle_rad(self):
        return self._min_steer

    @property
    def max_steering_angle_rad(self):
        return self._max_steer

    @property
    def max_cruising_speed_kmh(self):
        return self._max_cruising_kmh

    def dimensions(self):
        """Return the car's Dimensions (Webots get_dimensions service)."""
        params = self._params
        return Dimensions(params.track_front_m, params.track_rear_m, params.wheelbase_m,
                          params.front_tire_radius_m, params.rear_tire_radius_m)

    def status(self):
        """Return every getter's value at once, as a frozen CarStatus."""
        # Filled without the frozen dataclass' __init__, whose per-field object.__setattr__ is
        # most of this call's cost (published each step); every field is given here, which
        # test_core_car_logic checks, and CarStatus has no __post_init__.
        status = _NEW(CarStatus)
        status.__dict__.update(
            time_s=self._time_s,
            steering_angle_rad=self.steering_angle_rad,
            commanded_steering_angle_rad=self._steering_rad,
            right_steering_angle_rad=self._measured_right_rad,
            left_steering_angle_rad=self._measured_left_rad,
            target_cruising_speed_kmh=self._cruising_kmh,
            effective_cruising_speed_kmh=self.effective_cruising_speed_kmh,
            current_speed_kmh=self.current_speed_kmh,
            throttle=self._throttle,
            brake_intensity=self._brake,
            gear=self.gear,
            selected_gear=self._gear,
            control_mode=int(self._mode),
            rpm=self.rpm,
            indicator=int(self._indicator),
            hazard_flashers=self._hazard,
            dipped_beams=self._lights.dipped_beams,
            antifog_lights=self._lights.antifog,
            front_lights=self._lights.front,
            rear_lights=self._lights.rear,
            brake_lights=self._lights.brake,
            backwards_lights=self._lights.backwards,
            right_indicator_light=self._lights.right_indicator,
            left_indicator_light=self._lights.left_indicator,
            wiper_mode=int(self._wiper.mode),
            wiper_angle_rad=self._wiper.angle_rad,
            indicator_period_s=self._indicator_period_s,
            limited_slip_differential=self._lsd,
            indicator_auto_disabling=self._auto_disable,
            wheel_encoders_rad=tuple(map(float, self._encoder)),
            wheel_speeds_radps=tuple(map(float, self._speed)),
        )
        return status
