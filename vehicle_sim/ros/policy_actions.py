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
A policy's action written as the automobile node's drive commands.

The policy's action is in its card's ``action_range`` (RescaleAction's [-1, 1]); it is mapped
back to the environment's physical action Box with RescaleAction's own affine map (float32, as
gymnasium computes it), checked against that Box as the environment checks it (a value past a
bound by float rounding only is the bound; anything else is refused, naming the entry), and
turned into the Webots-level setters of the car, the services of the automobile node's table
(docs/ros_interface.md), in their units:

- ``speed_steering`` [steering angle [rad], + left; speed [m/s]] ->
  ``automobile/set_steering_angle`` (rad, + RIGHT: the sign flips) and
  ``automobile/set_cruising_speed`` (km/h: m/s x 3.6);
- ``braking_speed_steering`` [the same entries]: for a speed more than 1 m/s below the car's
  forward speed (its odometry's at the tick; core/car/speed_braking.py)
  ``automobile/set_steering_angle``, ``automobile/set_throttle`` 0 and
  ``automobile/set_brake_intensity``; else ``set_steering_angle``, ``set_brake_intensity`` 0 and
  ``set_cruising_speed``;
- ``throttle_steering`` [steering angle; throttle; brake] -> ``automobile/set_steering_angle``,
  ``automobile/set_throttle``, ``automobile/set_brake_intensity``.

The environment applies the same values through the same car logic setters (gym/controls.py).
"""

import numpy as np

from vehicle_sim.core.car.speed_braking import brake_for_speed
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.units import mps_to_kmh, ros_steering_to_webots

SET_STEERING = 'automobile/set_steering_angle'
SET_CRUISING_SPEED = 'automobile/set_cruising_speed'
SET_THROTTLE = 'automobile/set_throttle'
SET_BRAKE = 'automobile/set_brake_intensity'

# Relative float rounding taken as the bound (the environment's, gym/controls.py).
ROUNDING_TOLERANCE = 1.0e-6


def _speed_steering(a, _forward_mps):
    return [(SET_STEERING, ros_steering_to_webots(a[0])), (SET_CRUISING_SPEED, mps_to_kmh(a[1]))]


def _braking_speed_steering(a, forward_mps):
    # as gym/controls.py's BrakingSpeedSteering: brake out of cruise control for a speed well
    # below the car's (core/car/speed_braking.py), else cruise
    brake = brake_for_speed(forward_mps, a[1])
    if brake > 0.0:
        return [(SET_STEERING, ros_steering_to_webots(a[0])), (SET_THROTTLE, 0.0),
                (SET_BRAKE, brake)]
    return [(SET_STEERING, ros_steering_to_webots(a[0])), (SET_BRAKE, 0.0),
            (SET_CRUISING_SPEED, mps_to_kmh(a[1]))]


def _throttle_steering(a, _forward_mps):
    return [(SET_STEERING, ros_steering_to_webots(a[0])), (SET_THROTTLE, a[1]), (SET_BRAKE, a[2])]


# layout -> (entry names, units, the services it may call, (physical action, forward speed
# [m/s]) -> [(service, value)])
LAYOUTS = {
    'speed_steering': (('steering_angle', 'speed'), ('rad', 'm/s'),
                       (SET_STEERING, SET_CRUISING_SPEED), _speed_steering),
    'braking_speed_steering': (('steering_angle', 'speed'), ('rad', 'm/s'),
                               (SET_STEERING, SET_CRUISING_SPEED, SET_THROTTLE, SET_BRAKE),
                               _braking_speed_steering),
    'throttle_steering': (('steering_angle', 'throttle', 'brake'), ('rad', '', ''),
                          (SET_STEERING, SET_THROTTLE, SET_BRAKE), _throttle_steering),
}


class ActionWriter:
    """
    A policy's action -> the drive commands of the car.

    :param control: the action layout (a key of :data:`LAYOUTS`).
    :param low: the environment's physical action Box low bounds (its ``unwrapped`` space).
    :param high: its high bounds.
    :param action_range: (low, high) the policy's actions were rescaled to (its card's).
    :raises InvalidParameterError: an unknown layout, or bounds of the wrong length.
    """

    def __init__(self, control, low, high, action_range=(-1.0, 1.0)):
        if control not in LAYOUTS:
            raise InvalidParameterError(
                f'control {control!r}: the automobile node is driven by '
                f'{", ".join(LAYOUTS)} (a robot policy, twist, drives no car)')
        self.control = control
        self.names, self.units, self._services, self._setters = LAYOUTS[control]
        self.low = np.asarray(low, dtype=np.float32)
        self.high = np.asarray(high, dtype=np.float32)
        if self.low.shape != (len(self.names),) or self.high.shape != self.low.shape:
            raise InvalidParameterError(
                f'control {control!r}: bounds of shape {self.low.shape} and '
                f'{self.high.shape}; expected ({len(self.names)},) ({", ".join(self.names)})')
        new_min = np.full(self.low.shape, action_range[0], dtype=np.float32)
        new_max = np.full(self.low.shape, action_range[1], dtype=np.float32)
        # gymnasium.wrappers.utils.rescale_box: y = gradient x + intercept (x physical)
        diff = self.high.astype(np.float64) - self.low.astype(np.float64)
        self._gradient = ((new_max - new_min) / diff).astype(np.float32)
        self._intercept = (self._gradient * -self.low + new_min).astype(np.float32)

    @property
    def services(self):
        """The services this layout may call."""
        return self._services

    def physical(self, action):
        """
        Return the physical action (float64) of a policy's action, checked against the Box.

        :raises ValueError: naming the entry: a wrong shape, NaN, or a value outside the Box.
        """
        action = np.asarray(action, dtype=np.float32)
        if action.shape != self.low.shape:
            raise ValueError(f'action of shape {action.shape}: expected {self.low.shape} '
                             f'({", ".join(self.names)})')
        values = ((action - self._intercept) / self._gradient).astype(np.float64)
        for i, value in enumerate(values):
            low, high = float(self.low[i]), float(self.high[i])
            if low <= value <= high:
                continue
            if low - ROUNDING_TOLERANCE * max(1.0, abs(low)) <= value < low:
                values[i] = low
            elif high < value <= high + ROUNDING_TOLERANCE * max(1.0, abs(high)):
                values[i] = high
            else:
                raise ValueError(f'action[{i}] ({self.names[i]}) = {float(value)!r} '
                                 f'{self.units[i]}: outside [{low:g}, {high:g}]')
        return values

    def setters(self, values, forward_mps=0.0):
        """
        Return [(service, value in its unit)] of a physical action, in call order.

        :param forward_mps: the car's forward speed (its odometry's) when the action is taken:
            braking_speed_steering brakes or cruises by it.
        """
        return [(name, float(value)) for name, value in self._setters(values, forward_mps)]

    def commands(self, action, forward_mps=0.0):
        """Return [(service, value in its unit)] for a policy's action, in call order."""
        return self.setters(self.physical(action), forward_mps)
