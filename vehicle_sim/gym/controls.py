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
The action layouts of the Gym environment: what each entry of the action Box means.

Every layout is a continuous Box in physical units (bounds from the vehicle's parameters); an
action outside the Box, of the wrong shape or not finite is refused with a ValueError naming
the entry. Nothing is clipped here beyond float rounding at a bound: wrap the environment in
``gymnasium.wrappers.ClipAction`` to clip a policy's samples, or ``RescaleAction`` for [-1, 1].

- ``speed_steering`` (car): [steering angle [rad], + = left (REP 103); cruising speed [m/s],
  negative = reverse]. The car's speed controller (Webots' cruising speed) tracks the speed.
- ``braking_speed_steering`` (car): the entries of ``speed_steering``; a speed more than 1 m/s
  slower than the car's is reached with the brakes instead (throttle released, Webots' brake
  intensity growing to full at 5 m/s slower: core/car/speed_braking.py), as a driver brakes
  out of cruise control; else as ``speed_steering``.
- ``throttle_steering`` (car): [steering angle [rad], + = left; throttle [0, 1]; brake
  [0, 1]]. The car's engine model gives the torque (Webots' throttle and brake).
- ``twist`` (robot): [forward speed [m/s]; yaw rate [rad/s], + = left]. The wheel speeds are
  v -+ w t / 2; where one would exceed max_wheel_speed both are scaled by one factor (the
  turning radius is kept, core diff_drive.limit_wheel_speeds).
"""

import numpy as np

from vehicle_sim.core.car.speed_braking import brake_for_speed
from vehicle_sim.core.diffdrive.kinematics import wheel_speeds_from_twist
from vehicle_sim.core.diffdrive.speed_limiter import limit_wheel_speeds
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.units import mps_to_kmh, ros_steering_to_webots

# Relative float rounding taken as the bound (float32 epsilon is 1.2e-7; a rescaled bound is a
# few of them off).
ROUNDING_TOLERANCE = 1.0e-6
# The car's default largest speed action [m/s] (72 km/h) when the top speed is higher.
DEFAULT_MAX_SPEED_MPS = 20.0


class Control:
    """One action layout: ``names``, ``units``, ``low``, ``high`` and ``apply(action)``."""

    names = ()
    units = ()

    def __init__(self, low, high):
        self.low = np.asarray(low, dtype=np.float32)
        self.high = np.asarray(high, dtype=np.float32)

    def check(self, action):
        """
        Return the action as float64, or raise ValueError naming the first bad entry.

        Bounds are those of the Box (float32), compared in float64. A value past a bound by
        float rounding only (ROUNDING_TOLERANCE of the bound: what RescaleAction's arithmetic
        gives for -1 and 1) is taken as the bound.
        """
        values = np.array(action, dtype=np.float64)
        if values.shape != self.low.shape:
            raise ValueError(f'action of shape {values.shape}: expected {self.low.shape} '
                             f'({", ".join(self.names)})')
        for i, value in enumerate(values):
            low, high = float(self.low[i]), float(self.high[i])
            if not low <= value <= high:      # NaN fails too
                slack_low = ROUNDING_TOLERANCE * max(1.0, abs(low))
                slack_high = ROUNDING_TOLERANCE * max(1.0, abs(high))
                if low - slack_low <= value < low:
                    values[i] = low
                elif high < value <= high + slack_high:
                    values[i] = high
                else:
                    raise ValueError(f'action[{i}] ({self.names[i]}) = {float(value)!r} '
                                     f'{self.units[i]}: outside [{low:g}, {high:g}] (the '
                                     'action space; gymnasium.wrappers.ClipAction clips)')
        return values

    def apply(self, action):
        """Command the vehicle (a checked action)."""
        raise NotImplementedError

    def stop(self):
        """Command the vehicle to stand still (the state after a reset)."""

    def halt(self):
        """Brake the vehicle to a stand (an agent that left a multi-agent episode)."""
        self.stop()


class SpeedSteering(Control):
    """Car: [steering angle [rad] (+ left), cruising speed [m/s]]."""

    names = ('steering_angle', 'speed')
    units = ('rad', 'm/s')

    def __init__(self, car, max_speed_mps, max_reverse_mps, max_steering_rad=None):
        logic = car.logic
        self.logic = logic
        top = logic.max_cruising_speed_kmh / 3.6 if logic.max_cruising_speed_kmh > 0 else \
            DEFAULT_MAX_SPEED_MPS
        if max_speed_mps is None:
            max_speed_mps = min(top, DEFAULT_MAX_SPEED_MPS)
        right, left = steering_bounds(logic, max_steering_rad)
        super().__init__((right, -max_reverse_mps), (left, max_speed_mps))

    def apply(self, action):
        self.logic.set_steering_angle(ros_steering_to_webots(float(action[0])))
        self.logic.set_cruising_speed_kmh(mps_to_kmh(float(action[1])))

    def halt(self):
        self.apply((0.0, 0.0))


class BrakingSpeedSteering(SpeedSteering):
    """
    Car: [steering angle [rad] (+ left), speed [m/s]], braking for a speed well below the car's.

    The brake intensity comes from the car's forward speed when the action is applied
    (core/car/speed_braking.py): above 0, the throttle is released (TORQUE mode) and the brakes
    applied; else the brake is released and the cruise control takes the speed (its ramp starts
    at the wheels' speeds, driver.c).
    """

    def __init__(self, car, max_speed_mps, max_reverse_mps, max_steering_rad=None):
        super().__init__(car, max_speed_mps, max_reverse_mps, max_steering_rad)
        self.body = car.body

    def apply(self, action):
        logic = self.logic
        logic.set_steering_angle(ros_steering_to_webots(float(action[0])))
        speed = float(action[1])
        brake = brake_for_speed(self.body.body_twist()[0][0], speed)
        if brake > 0.0:
            logic.set_throttle(0.0)
            logic.set_brake_intensity(brake)
        else:
            logic.set_brake_intensity(0.0)
            logic.set_cruising_speed_kmh(mps_to_kmh(speed))


class ThrottleSteering(Control):
    """Car: [steering angle [rad] (+ left), throttle [0, 1], brake [0, 1]]."""

    names = ('steering_angle', 'throttle', 'brake')
    units = ('rad', '', '')

    def __init__(self, car, max_steering_rad=None):
        logic = car.logic
        self.logic = logic
        right, left = steering_bounds(logic, max_steering_rad)
        super().__init__((right, 0.0, 0.0), (left, 1.0, 1.0))

    def apply(self, action):
        logic = self.logic
        logic.set_steering_angle(ros_steering_to_webots(float(action[0])))
        logic.set_throttle(float(action[1]))
        logic.set_brake_intensity(float(action[2]))

    def halt(self):
        self.apply((0.0, 0.0, 1.0))


class Twist(Control):
    """Robot: [forward speed [m/s], yaw rate [rad/s] (+ left)]."""

    names = ('speed', 'yaw_rate')
    units = ('m/s', 'rad/s')

    def __init__(self, robot):
        params = robot.params
        self.robot = robot
        self._tread = params.wheel_tread_m
        self._radius = params.wheel_radius_m
        self._max_mps = params.max_wheel_speed_mps
        top = self._max_mps
        super().__init__((-top, -2.0 * top / self._tread), (top, 2.0 * top / self._tread))

    def apply(self, action):
        left, right = wheel_speeds_from_twist(float(action[0]), float(action[1]), self._tread)
        left, right = limit_wheel_speeds(left, right, self._max_mps)
        # rounding may put a scaled wheel a hair above the limit: the body refuses that
        limit = self.robot.params.max_wheel_speed_radps
        self.robot.set_wheel_velocities(min(max(left / self._radius, -limit), limit),
                                        min(max(right / self._radius, -limit), limit))

    def stop(self):
        self.robot.set_wheel_velocities(0.0, 0.0)


def steering_bounds(logic, max_steering_rad=None):
    """
    Return the steering action's (low, high) [rad], + = left (REP 103).

    :param logic: the car's driver logic (its Webots steering limits, + = right).
    :param max_steering_rad: None: the car's limits; else (-it, it), which must lie within them.
    :raises InvalidParameterError: for a bound beyond the car's steering limit.
    """
    # REP 103 (+ left) = -(Webots, + right): the bounds swap.
    low, high = -logic.max_steering_angle_rad, -logic.min_steering_angle_rad
    if max_steering_rad is None:
        return low, high
    limit = min(-low, high)
    if max_steering_rad > limit:
        raise InvalidParameterError(
            f"option max_steering = {max_steering_rad!r} rad: more than the car's steering "
            f'limit ({limit:g} rad); give at most that, or null for the limits')
    return -max_steering_rad, max_steering_rad


def make_control(name, vehicle, max_speed_mps=None, max_reverse_mps=5.0,
                 max_steering_rad=None):
    """
    Return the Control of a layout for the ego.

    :param name: 'auto', 'speed_steering', 'braking_speed_steering', 'throttle_steering' or
        'twist'.
    :param vehicle: the ego's SceneVehicle (``car`` is None for a robot).
    :param max_steering_rad: a car's largest steering action either way (None: its limits).
    :raises ValueError: for a car layout on a robot or the robot layout on a car.
    """
    is_car = vehicle.car is not None
    if name == 'auto':
        name = 'speed_steering' if is_car else 'twist'
    if is_car and name == 'speed_steering':
        return SpeedSteering(vehicle.car, max_speed_mps, max_reverse_mps, max_steering_rad)
    if is_car and name == 'braking_speed_steering':
        return BrakingSpeedSteering(vehicle.car, max_speed_mps, max_reverse_mps,
                                    max_steering_rad)
    if is_car and name == 'throttle_steering':
        return ThrottleSteering(vehicle.car, max_steering_rad)
    if not is_car and name == 'twist':
        if max_steering_rad is not None:
            raise InvalidParameterError(
                f'option max_steering = {max_steering_rad!r} rad: the ego {vehicle.name!r} is a '
                'robot (twist actions have no steering angle); give null')
        return Twist(vehicle.body)
    kind = 'car' if is_car else 'robot'
    valid = 'speed_steering, braking_speed_steering, throttle_steering' if is_car else 'twist'
    raise ValueError(f'control {name!r} does not fit the ego {vehicle.name!r}, a {kind}; '
                     f'valid: {valid}')
