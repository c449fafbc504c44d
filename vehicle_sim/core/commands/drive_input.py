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
Streamed drive commands (``cmd_vel``, ``drive``) -> a Webots car (CarLogic), ROS-free.

The car node's ``<ns>/cmd_vel`` (v, yaw rate) and ``<ns>/drive`` (v, steering angle) become the
car's cruising speed and steering angle (docs/drive.md, "cmd_vel and drive"):

- Units and signs change only through ``core/specs/units.py``: commands are SI and REP 103
(steering
  + = left), the car takes km/h and a steering angle with + = right.
- cmd_vel: δ = atan(ω·L/v), the exact inverse of the bicycle model ω = v·tan(δ)/L (L = the
  car's wheelbase), valid forwards and in reverse. Below :data:`STANDSTILL_SPEED_MPS` the
  steering angle is undefined: the car keeps the steering it has (a car cannot turn in place;
  a yaw rate asked for there is reported and ignored).
- A topic stream is not refused like a service call: a steering angle beyond the car's limits,
  or a speed beyond its top speed, saturates at the limit and is reported (the node warns,
  throttled). A non-finite value is refused (InvalidCommandError) and nothing changes.
- The speed is that of base_link (the rear-axle centre, REP 105's twist of the base frame):
  the cruising speed, which Webots applies to the driven axle, is scaled so that the rear axle
  runs at v on the commanded turn (:func:`rear_axle_speed_ratio`).
- Negative speed: the cruising speed becomes negative, the car backs (SPEED mode drives the
  wheels backwards, as Webots' setCruisingSpeed does).
- Watchdog (:class:`~vehicle_sim.core.commands.watchdog.CommandWatchdog`, receipt time): once the
  last command is older than the timeout, a safety stop (core/car/speed_braking.py's full_stop:
  cruising speed 0, the throttle released and full brake), once per staleness.
- A service call that changes the car after a command disarms the watchdog, so the service's
  setting holds until the next command arrives.
"""

from dataclasses import dataclass
import math
from typing import Optional, Tuple

from vehicle_sim.core.car.drivetrain import central_ratio
from vehicle_sim.core.car.speed_braking import full_stop
from vehicle_sim.core.commands.watchdog import CommandWatchdog, DEFAULT_TIMEOUT_S
from vehicle_sim.core.diffdrive.kinematics import wheel_speeds_from_twist
from vehicle_sim.core.diffdrive.speed_limiter import limit_wheel_speeds
from vehicle_sim.core.specs.errors import InvalidCommandError
from vehicle_sim.core.specs.units import (
    kmh_to_mps,
    mps_to_kmh,
    ros_steering_to_webots,
    webots_steering_to_ros,
)

# |v| below which a car is at a standstill for cmd_vel: δ = atan(ω·L/v) is undefined there.
STANDSTILL_SPEED_MPS = 1e-3


def steering_from_yaw_rate(speed_mps, yaw_rate_radps, wheelbase_m,
                           standstill_mps=STANDSTILL_SPEED_MPS):
    """
    Return the bicycle-model steering angle giving a yaw rate: δ = atan(ω·L/v).

    The exact inverse of ω = v·tan(δ)/L for any |v| >= ``standstill_mps`` (in reverse, v < 0,
    the same ω needs the opposite δ). At a standstill no steering angle gives a yaw rate.

    :param speed_mps: forward speed v [m/s], negative = reverse.
    :param yaw_rate_radps: yaw rate ω [rad/s], positive = left.
    :param wheelbase_m: wheelbase L [m], > 0.
    :param standstill_mps: |v| below which the angle is undefined [m/s].
    :return: steering angle δ [rad], positive = left, in (−pi/2, pi/2); None at a standstill.
    """
    if abs(speed_mps) < standstill_mps:
        return None
    return math.atan(yaw_rate_radps * wheelbase_m / speed_mps)


def rear_axle_speed_ratio(car_type, steering_rad, front_radius_m=1.0, rear_radius_m=1.0):
    """
    Return the speed of the rear-axle centre (base_link) per unit of Webots cruising speed.

    Webots' cruise control (driver.c) sets the mean tyre speed of the driven axle: the front
    axle of a 'traction' car, the rear axle of a 'propulsion' car, and for a '4x4' the front
    axle 2·ratio_c and the rear axle 2·(1 − ratio_c) of it (ratio_c = central_ratio). In the
    bicycle geometry the front axle runs 1/cos δ faster than the rear axle on the same turn, so
    the rear axle runs at cos δ (traction), 1 (propulsion) or 2·(1 − ratio_c) (4x4; = 2·cos δ /
    (1 + cos δ) for equal radii) times the cruising speed.

    :param car_type: 'traction', 'propulsion' or '4x4'.
    :param steering_rad: steering angle δ [rad] (either sign).
    :param front_radius_m: front tyre radius [m] (4x4 central ratio).
    :param rear_radius_m: rear tyre radius [m] (4x4 central ratio).
    :return: rear-axle speed / cruising speed, in (0, 1].
    """
    if car_type == 'propulsion':
        return 1.0
    if car_type == '4x4':
        return 2.0 * (1.0 - central_ratio(steering_rad, front_radius_m, rear_radius_m))
    return math.cos(steering_rad)


def _finite(name, value, unit):
    if isinstance(value, bool) or not isinstance(value, (int, float)) or \
            not math.isfinite(value):
        raise InvalidCommandError(f'{name} = {value!r} {unit}: must be a finite number; '
                                  'command dropped, nothing changed')
    return float(value)


@dataclass(frozen=True)
class DriveTarget:
    """
    What one command sets on the car (Webots units and signs), and what was saturated.

    :param cruising_speed_kmh: cruising speed [km/h], negative = reverse.
    :param steering_angle_rad: steering angle [rad], + = right; None = keep the car's.
    :param notes: one text per saturation or ignored part (the node warns with them).
    """

    cruising_speed_kmh: float
    steering_angle_rad: Optional[float]
    notes: Tuple[str, ...] = ()


class CarDriveInput:
    """
    The car's cmd_vel and drive inputs: conversion, saturation, watchdog and precedence.

    ``now_s`` is the receipt time on the node clock (simulated time), passed in.
    """

    def __init__(self, logic, timeout_s=DEFAULT_TIMEOUT_S):
        """
        Drive a car.

        :param logic: CarLogic.
        :param timeout_s: command timeout [s]; 0 disables the watchdog.
        :raises InvalidParameterError: for a negative or non-finite timeout.
        """
        self.logic = logic
        self.watchdog = CommandWatchdog(timeout_s, 'brake')
        self.armed = False          # a command is in force and the watchdog watches it
        self.timeouts = 0           # times the watchdog acted

    # ------------------------------------------------------------------ conversions
    def _speed_mps(self, speed_mps, notes):
        # |v| beyond the top speed saturates (reported).
        top_mps = kmh_to_mps(self.logic.max_cruising_speed_kmh)
        if abs(speed_mps) > top_mps:
            limited = math.copysign(top_mps, speed_mps)
            notes.append(f"speed {speed_mps:g} m/s is beyond the car's top speed "
                         f'{top_mps:g} m/s: saturated at {limited:g} m/s')
            return limited
        return speed_mps

    def _steering_webots(self, steering_rad, notes, source):
        # steering_rad: REP 103 (+ left) -> Webots sign, saturated at the car's limits.
        logic = self.logic
        low, high = logic.min_steering_angle_rad, logic.max_steering_angle_rad
        angle = ros_steering_to_webots(steering_rad)
        if low <= angle <= high:
            return angle
        limited = min(max(angle, low), high)
        ros_low, ros_high = sorted((webots_steering_to_ros(low), webots_steering_to_ros(high)))
        notes.append(f"{source} {steering_rad:g} rad (+ left) is beyond the car's steering "
                     f'limits [{ros_low:g}, {ros_high:g}] rad: saturated at '
                     f'{webots_steering_to_ros(limited):g} rad')
        return limited

    def _target(self, speed_mps, steering_webots_rad, notes):
        # The cruising speed that drives base_link (the rear-axle centre) at speed_mps on this
        # steering angle (rear_axle_speed_ratio); None keeps the car's steering.
        logic = self.logic
        params = logic.params
        angle = logic.commanded_steering_angle_rad if steering_webots_rad is None \
            else steering_webots_rad
        ratio = rear_axle_speed_ratio(params.car_type, angle, params.front_tire_radius_m,
                                      params.rear_tire_radius_m)
        return DriveTarget(mps_to_kmh(speed_mps / ratio), steering_webots_rad, tuple(notes))

    def twist_target(self, speed_mps, yaw_rate_radps):
        """
        Convert a cmd_vel command (v [m/s], ω [rad/s, + left]) to a DriveTarget.

        δ = atan(ω·L/v) on the speed the car will drive (after saturation); at a standstill the
        steering is kept (a yaw rate asked for there is reported).

        :raises InvalidCommandError: for a non-finite value (nothing changes).
        """
        speed_mps = _finite('linear.x', speed_mps, 'm/s')
        yaw_rate_radps = _finite('angular.z', yaw_rate_radps, 'rad/s')
        notes = []
        speed_mps = self._speed_mps(speed_mps, notes)
        steering = steering_from_yaw_rate(speed_mps, yaw_rate_radps, self.logic.wheelbase_m)
        if steering is None:
            if yaw_rate_radps != 0.0:
                notes.append(f'angular.z {yaw_rate_radps:g} rad/s at a standstill (|linear.x| < '
                             f'{STANDSTILL_SPEED_MPS:g} m/s): a car cannot turn in place; '
                             'the steering angle is kept')
            return self._target(speed_mps, None, notes)
        return self._target(speed_mps, self._steering_webots(
            steering, notes, 'steering angle atan(angular.z·L/linear.x) ='), notes)

    def ackermann_target(self, speed_mps, steering_rad):
        """
        Convert a drive command (speed [m/s], steering_angle [rad, + left]) to a DriveTarget.

        :raises InvalidCommandError: for a non-finite value (nothing changes).
        """
        speed_mps = _finite('speed', speed_mps, 'm/s')
        steering_rad = _finite('steering_angle', steering_rad, 'rad')
        notes = []
        speed_mps = self._speed_mps(speed_mps, notes)
        return self._target(speed_mps, self._steering_webots(steering_rad, notes,
                                                             'steering_angle'), notes)

    # ------------------------------------------------------------------ commands
    def twist(self, speed_mps, yaw_rate_radps, now_s):
        """
        Apply a cmd_vel command received at ``now_s``.

        :return: the DriveTarget applied (its ``notes`` to report).
        :raises InvalidCommandError: for a non-finite value (nothing changes).
        """
        return self.apply(self.twist_target(speed_mps, yaw_rate_radps), now_s)

    def ackermann(self, speed_mps, steering_rad, now_s):
        """
        Apply a drive command received at ``now_s``.

        :return: the DriveTarget applied (its ``notes`` to report).
        :raises InvalidCommandError: for a non-finite value (nothing changes).
        """
        return self.apply(self.ackermann_target(speed_mps, steering_rad), now_s)

    def apply(self, target, now_s):
        """Set a DriveTarget on the car (brake released) and feed the watchdog."""
        self.watchdog.feed(now_s)
        logic = self.logic
        if target.steering_angle_rad is not None:
            logic.set_steering_angle(target.steering_angle_rad)
        logic.set_cruising_speed_kmh(target.cruising_speed_kmh)
        logic.set_brake_intensity(0.0)
        self.armed = True
        return target

    def service_override(self):
        """Stand the watchdog down: a service set the speed, which holds until the next command."""
        self.armed = False

    def tick(self, now_s):
        """
        Run the watchdog at ``now_s``; return True when it acted on this call.

        Once the command in force is stale: a safety stop (full_stop: cruising speed 0, the
        throttle released and full brake; the steering is kept), once; the next command drives
        again.
        """
        if not self.armed or not self.watchdog.is_stale(now_s):
            return False
        self.armed = False
        self.timeouts += 1
        full_stop(self.logic)
        return True


class DiffDriveInput:
    """
    The differential-drive robot's cmd_vel input: (v, ω) -> wheel speeds, watchdog, precedence.

    v_l = v − ω·tread/2, v_r = v + ω·tread/2 (a robot turns in place at v = 0). Wheel speeds
    beyond the robot's limit are scaled down together (curvature kept) and reported. ``now_s`` is
    the receipt time on the node clock, passed in.
    """

    def __init__(self, tread_m, wheel_radius_m, max_wheel_speed_radps,
                 timeout_s=DEFAULT_TIMEOUT_S):
        """
        Drive a robot.

        :param tread_m: distance between the left and right wheels [m], > 0.
        :param wheel_radius_m: driven wheel radius [m], > 0.
        :param max_wheel_speed_radps: wheel speed limit [rad/s], > 0.
        :param timeout_s: command timeout [s]; 0 disables the watchdog.
        """
        self.tread_m = tread_m
        self.wheel_radius_m = wheel_radius_m
        self.max_wheel_speed_radps = max_wheel_speed_radps
        self.max_wheel_speed_mps = max_wheel_speed_radps * wheel_radius_m
        self.watchdog = CommandWatchdog(timeout_s, 'brake')
        self.armed = False
        self.timeouts = 0

    def twist(self, speed_mps, yaw_rate_radps, now_s):
        """
        Convert a cmd_vel command received at ``now_s`` and feed the watchdog.

        :return: (left [rad/s], right [rad/s], notes) to command; ``notes`` name saturations.
        :raises InvalidCommandError: for a non-finite value (nothing changes).
        """
        speed_mps = _finite('linear.x', speed_mps, 'm/s')
        yaw_rate_radps = _finite('angular.z', yaw_rate_radps, 'rad/s')
        wheels = wheel_speeds_from_twist(speed_mps, yaw_rate_radps, self.tread_m)
        limited = limit_wheel_speeds(wheels.left_mps, wheels.right_mps,
                                     self.max_wheel_speed_mps)
        notes = ()
        if limited != wheels:
            notes = (f'cmd_vel ({speed_mps:g} m/s, {yaw_rate_radps:g} rad/s) needs wheel speeds '
                     f'({wheels.left_mps:g}, {wheels.right_mps:g}) m/s beyond the limit '
                     f'{self.max_wheel_speed_mps:g} m/s: saturated at ({limited.left_mps:g}, '
                     f'{limited.right_mps:g}) m/s, curvature kept',)
        self.watchdog.feed(now_s)
        self.armed = True
        # Clipped to the limit so that the scaling's last-bit rounding is never refused.
        limit, radius = self.max_wheel_speed_radps, self.wheel_radius_m
        return (min(max(limited.left_mps / radius, -limit), limit),
                min(max(limited.right_mps / radius, -limit), limit), notes)

    def override(self):
        """Stand the watchdog down: another input commanded the wheels until the next cmd_vel."""
        self.armed = False

    def tick(self, now_s):
        """Return True once when the command in force went stale (the node stops the wheels)."""
        if not self.armed or not self.watchdog.is_stale(now_s):
            return False
        self.armed = False
        self.timeouts += 1
        return True
