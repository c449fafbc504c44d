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
Limits on a differential drive's wheel command: one wheel-speed cap, a rate limiter per velocity.

ROS-free; ``dt_s`` is passed in, the limiters keep no state of their own.
"""

import math

from vehicle_sim.core.diffdrive.kinematics import is_number, WheelSpeeds
from vehicle_sim.core.specs.errors import InvalidParameterError


def _check_limit(name, value):
    if not is_number(value) or not math.isfinite(value) or value < 0.0:
        raise InvalidParameterError(
            f'{name} = {value!r}: must be a finite number >= 0 (0 disables the limit)')
    return float(value)


def limit_wheel_speeds(left_mps, right_mps, max_wheel_speed_mps):
    """
    Scale both wheel speeds by one factor so that neither exceeds the limit; curvature is kept.

    Scaling v_l and v_r by the same s scales v and ω by s, so ω/v (the path's curvature) and
    the turn direction are unchanged; only the speed along the path drops.

    :param left_mps: left wheel speed [m/s].
    :param right_mps: right wheel speed [m/s].
    :param max_wheel_speed_mps: limit [m/s], > 0; 0 disables.
    :return: WheelSpeeds [m/s].
    """
    max_wheel_speed_mps = _check_limit('max_wheel_speed_mps', max_wheel_speed_mps)
    largest = max(abs(left_mps), abs(right_mps))
    if max_wheel_speed_mps == 0.0 or largest <= max_wheel_speed_mps:
        return WheelSpeeds(left_mps, right_mps)
    scale = max_wheel_speed_mps / largest
    return WheelSpeeds(left_mps * scale, right_mps * scale)


class SpeedLimiter:
    """
    Rate limiter for one signed velocity, in the style of ros2_controllers' SpeedLimiter.

    Acceleration applies while |value| grows, deceleration while it shrinks; a sign change first
    decelerates to 0 and spends the rest of the step accelerating the other way. A limit of 0
    disables it. ``dt_s`` is passed in; the limiter keeps no state.
    """

    def __init__(self, max_accel=0.0, max_decel=0.0, name='speed'):
        """
        Create a limiter.

        :param max_accel: largest rate of increase of |value| [unit/s²]; 0 = unlimited.
        :param max_decel: largest rate of decrease of |value| [unit/s²]; 0 = unlimited.
        :param name: quoted in error messages.
        :raises InvalidParameterError: for a negative or non-finite limit.
        """
        self.max_accel = _check_limit(f'{name} max_accel', max_accel)
        self.max_decel = _check_limit(f'{name} max_decel', max_decel)

    def limit(self, target, previous, dt_s):
        """
        Return the value closest to ``target`` reachable from ``previous`` within ``dt_s``.

        :param target: wanted value.
        :param previous: value applied one step before.
        :param dt_s: time since ``previous`` was applied [s], >= 0.
        :return: the limited value.
        """
        accel = self.max_accel if self.max_accel > 0.0 else math.inf
        decel = self.max_decel if self.max_decel > 0.0 else math.inf
        if previous * target < 0.0:
            # Sign change: brake to zero first, then accelerate with the remaining time.
            time_to_zero_s = abs(previous) / decel      # 0 when deceleration is unlimited
            if time_to_zero_s > 0.0 and dt_s <= time_to_zero_s:
                return previous - math.copysign(_reach(decel, dt_s), previous)
            reach = _reach(accel, dt_s - time_to_zero_s)
            return math.copysign(min(abs(target), reach), target)
        bound = _reach(accel if abs(target) > abs(previous) else decel, dt_s)
        return previous + max(-bound, min(bound, target - previous))


def _reach(rate, dt_s):
    """Return how far a rate-limited value moves in dt_s; unlimited (inf) stays inf at dt 0."""
    return math.inf if math.isinf(rate) else rate * dt_s
