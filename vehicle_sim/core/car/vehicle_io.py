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
The contract between the vehicle logic (core) and a physics body.

Each basic step the body fills a Measurement, the logic turns it into an Actuation, the body
applies the Actuation, and the world steps. Wheel arrays use the Webots index order
FRONT_RIGHT, FRONT_LEFT, REAR_RIGHT, REAR_LEFT (car.h, WbuCarWheelIndex).
"""

from enum import IntEnum

import numpy as np


class Wheel(IntEnum):
    """Webots wheel indices (car.h)."""

    FRONT_RIGHT = 0
    FRONT_LEFT = 1
    REAR_RIGHT = 2
    REAR_LEFT = 3


WHEEL_COUNT = 4


def as_floats(values):
    """
    Return numbers (a numpy array or any sequence) as a list of floats.

    The per-step code works on 4-element lists: numpy calls and element reads on arrays that
    small cost more than the arithmetic.
    """
    return values.tolist() if type(values) is np.ndarray else [float(v) for v in values]
WHEEL_NAMES = ('front_right', 'front_left', 'rear_right', 'rear_left')


class WheelMode(IntEnum):
    """How the physics drives one wheel joint."""

    FREE = 0        # no motor: only wheel damping and brake
    VELOCITY = 1    # velocity motor to wheel_velocity_radps with a large torque (SPEED mode, hold)
    TORQUE = 2      # applied torque wheel_torque_nm (TORQUE mode)


class Measurement:
    """Sensor values read from the body after a world step (rad, per wheel index)."""

    __slots__ = ('wheel_position_rad', 'steer_right_rad', 'steer_left_rad')

    def __init__(self):
        self.wheel_position_rad = np.zeros(WHEEL_COUNT)
        self.steer_right_rad = 0.0
        self.steer_left_rad = 0.0


class Actuation:
    """
    Commands for the body, valid until the next Actuation.

    steer_*_rad are position targets already inside the steering limits; the body's steering
    motors follow them like Webots' default RotationalMotor (P = 10 1/s, at most 10 rad/s,
    force limit maxSteeringTorque). brake_torque_nm is a torque opposing the wheel's rotation
    that also holds the wheel at standstill.
    """

    __slots__ = ('steer_right_rad', 'steer_left_rad', 'wheel_mode', 'wheel_velocity_radps',
                 'wheel_torque_nm', 'brake_torque_nm')

    def __init__(self):
        self.steer_right_rad = 0.0
        self.steer_left_rad = 0.0
        self.wheel_mode = [WheelMode.FREE] * WHEEL_COUNT
        self.wheel_velocity_radps = np.zeros(WHEEL_COUNT)
        self.wheel_torque_nm = np.zeros(WHEEL_COUNT)
        self.brake_torque_nm = np.zeros(WHEEL_COUNT)
