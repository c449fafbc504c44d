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
Differential-drive kinematics, ROS-free: wheel speeds <-> body twist, pose integration.

Signs and units: REP 103, SI. Speed v [m/s] positive = forward, yaw rate ω [rad/s] positive =
counter-clockwise (left), steering tire angle δ [rad] positive = left. Wheel speeds are
tyre-surface speeds [m/s] unless the name ends in ``_radps``. Time steps ``dt_s`` are passed in.
Formulas and their reasons: docs/bridge_kinematics.md.
"""

import math
from typing import NamedTuple

from vehicle_sim.core.geometry.angles import wrap_angle_rad
from vehicle_sim.core.specs.errors import InvalidCommandError, InvalidParameterError

# integrate_pose: below this |half turn angle| [rad] sinc(h) uses its Taylor series.
_SMALL_ANGLE_RAD = 1e-6


class WheelSpeeds(NamedTuple):
    """Left and right tyre-surface speeds [m/s]."""

    left_mps: float
    right_mps: float


class Twist2D(NamedTuple):
    """Planar body velocity: forward speed [m/s] and yaw rate [rad/s] (positive = left)."""

    speed_mps: float
    yaw_rate_radps: float


class Pose2D(NamedTuple):
    """Planar pose: position [m] and heading [rad] in (-pi, pi]."""

    x_m: float
    y_m: float
    yaw_rad: float


def is_number(value):
    """Tell whether ``value`` is an int or float (a bool is not a number here)."""
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def check_speed_mps(speed_mps, name='speed'):
    """
    Validate a commanded speed.

    :param speed_mps: speed [m/s].
    :param name: the field name quoted in the error.
    :return: the speed as float.
    :raises InvalidCommandError: naming the value when it is not a finite number.
    """
    if not is_number(speed_mps) or not math.isfinite(speed_mps):
        raise InvalidCommandError(f'{name} = {speed_mps!r} m/s: must be a finite number')
    return float(speed_mps)


def check_steering_rad(steering_rad):
    """
    Validate a steering tire angle.

    :param steering_rad: steering angle [rad], positive = left.
    :return: the angle as float.
    :raises InvalidCommandError: naming the value when it is NaN, infinite or |δ| >= pi/2
        (tan δ is unbounded there: no finite turning radius).
    """
    if not is_number(steering_rad) or not math.isfinite(steering_rad):
        raise InvalidCommandError(
            f'steering_tire_angle = {steering_rad!r} rad: must be a finite number')
    if abs(steering_rad) >= math.pi / 2:
        raise InvalidCommandError(
            f'steering_tire_angle = {steering_rad!r} rad: |angle| must be < pi/2')
    return float(steering_rad)


def check_dt_s(dt_s):
    """
    Validate a time step.

    :param dt_s: time step [s], finite and >= 0.
    :return: the step as float.
    :raises InvalidCommandError: naming the value otherwise.
    """
    if not is_number(dt_s) or not math.isfinite(dt_s) or dt_s < 0.0:
        raise InvalidCommandError(f'dt_s = {dt_s!r} s: must be a finite number >= 0')
    return float(dt_s)


def check_positive(name, value):
    if not is_number(value) or not math.isfinite(value) or value <= 0.0:
        raise InvalidParameterError(f'{name} = {value!r}: must be a finite number > 0')
    return float(value)


def yaw_rate_from_steering(speed_mps, steering_rad, wheel_base_m):
    """
    Return the bicycle-model yaw rate ω = v·tan(δ)/L.

    :param speed_mps: forward speed v [m/s].
    :param steering_rad: steering tire angle δ [rad], positive = left, |δ| < pi/2.
    :param wheel_base_m: (pseudo) wheel base L [m], > 0.
    :return: yaw rate [rad/s], positive = left.
    :raises InvalidCommandError: for a non-finite speed or an invalid steering angle.
    :raises InvalidParameterError: for a wheel base that is not > 0.
    """
    speed_mps = check_speed_mps(speed_mps)
    steering_rad = check_steering_rad(steering_rad)
    wheel_base_m = check_positive('wheel_base', wheel_base_m)
    return speed_mps * math.tan(steering_rad) / wheel_base_m


def wheel_speeds_from_twist(speed_mps, yaw_rate_radps, tread_m):
    """
    Return the wheel speeds of a differential drive: v_l = v − ω·t/2, v_r = v + ω·t/2.

    :param speed_mps: forward speed v [m/s].
    :param yaw_rate_radps: yaw rate ω [rad/s], positive = left.
    :param tread_m: distance t between the wheel contact points [m], > 0.
    :return: WheelSpeeds [m/s].
    """
    half = yaw_rate_radps * tread_m / 2.0
    return WheelSpeeds(speed_mps - half, speed_mps + half)


def twist_from_wheel_speeds(left_mps, right_mps, tread_m):
    """
    Return the body twist of a differential drive: v = (v_l + v_r)/2, ω = (v_r − v_l)/t.

    :param left_mps: left tyre-surface speed [m/s].
    :param right_mps: right tyre-surface speed [m/s].
    :param tread_m: wheel tread t [m], > 0.
    :return: Twist2D.
    :raises InvalidParameterError: for a tread that is not > 0.
    """
    tread_m = check_positive('wheel_tread', tread_m)
    return Twist2D((left_mps + right_mps) / 2.0, (right_mps - left_mps) / tread_m)


def wheel_radps_from_mps(speed_mps, wheel_radius_m):
    """
    Return a wheel's angular speed from its tyre-surface speed: ω_wheel = v / r.

    :param speed_mps: tyre-surface speed [m/s].
    :param wheel_radius_m: wheel radius r [m], > 0.
    :return: angular speed [rad/s].
    """
    return speed_mps / check_positive('wheel_radius', wheel_radius_m)


def wheel_mps_from_radps(speed_radps, wheel_radius_m):
    """
    Return a wheel's tyre-surface speed from its angular speed: v = ω_wheel · r.

    :param speed_radps: angular speed [rad/s].
    :param wheel_radius_m: wheel radius r [m], > 0.
    :return: tyre-surface speed [m/s].
    """
    return speed_radps * check_positive('wheel_radius', wheel_radius_m)


def integrate_pose(x_m, y_m, yaw_rad, speed_mps, yaw_rate_radps, dt_s):
    """
    Advance a planar pose by a constant twist over ``dt_s``, exactly (circular arc).

    The chord of the arc has length v·dt·sinc(ω·dt/2) and heading yaw + ω·dt/2; for
    |ω·dt/2| < 1e-6 sinc uses its Taylor series, so ω -> 0 gives the straight line without
    dividing by ω.

    :param x_m: x [m].
    :param y_m: y [m].
    :param yaw_rad: heading [rad].
    :param speed_mps: forward speed [m/s].
    :param yaw_rate_radps: yaw rate [rad/s], positive = left.
    :param dt_s: time step [s].
    :return: Pose2D with the heading wrapped to (−pi, pi].
    """
    half_turn_rad = yaw_rate_radps * dt_s / 2.0
    if abs(half_turn_rad) < _SMALL_ANGLE_RAD:
        sinc = 1.0 - half_turn_rad * half_turn_rad / 6.0
    else:
        sinc = math.sin(half_turn_rad) / half_turn_rad
    chord_m = speed_mps * dt_s * sinc
    heading_rad = yaw_rad + half_turn_rad
    return Pose2D(x_m + chord_m * math.cos(heading_rad), y_m + chord_m * math.sin(heading_rad),
                  wrap_angle_rad(yaw_rad + 2.0 * half_turn_rad))
