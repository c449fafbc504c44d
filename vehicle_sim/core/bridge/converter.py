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
The bridge's command path, ROS-free: an Ackermann command -> the wheel command applied.

:class:`AckermannToDifferential` composes the mapping (ackermann_mapping), the limits
(speed_limiter) and the kinematics (core/diffdrive/kinematics) in the order its docstring gives.
"""

from dataclasses import dataclass
import math

from vehicle_sim.core.bridge.ackermann_mapping import (
    turn_in_place_yaw_rate,
    wheel_base_plausibility,
)
from vehicle_sim.core.bridge.params import BridgeParams, DEFAULT_BRIDGE_PARAMS
from vehicle_sim.core.diffdrive.kinematics import (
    check_dt_s,
    check_speed_mps,
    check_steering_rad,
    Twist2D,
    twist_from_wheel_speeds,
    wheel_speeds_from_twist,
)
from vehicle_sim.core.diffdrive.speed_limiter import limit_wheel_speeds, SpeedLimiter
from vehicle_sim.core.specs.errors import InvalidParameterError


@dataclass(frozen=True)
class DiffDriveCommand:
    """A differential-drive command as applied (after all limits)."""

    speed_mps: float
    yaw_rate_radps: float
    left_mps: float
    right_mps: float
    left_radps: float
    right_radps: float


STOP_COMMAND = DiffDriveCommand(0.0, 0.0, 0.0, 0.0, 0.0, 0.0)


class AckermannToDifferential:
    """
    The bridge's command path: (v, δ, dt) -> applied (v, ω, v_l, v_r) after every limit.

    Order per step: turn-in-place decision on the commanded v; linear acceleration limit on v;
    yaw rate from the mode (kinematic: v_applied·tan δ / L, so the commanded curvature holds
    even while ramping; literal: δ; turn-in-place: its law); optional angular acceleration limit;
    wheel speeds; wheel-speed limit (both wheels scaled, curvature kept). The applied (v, ω) are
    remembered as the start of the next ramp. The watchdog is the node's (see watchdog.py); call
    :meth:`reset` when it brakes so the next ramp starts from standstill.
    """

    def __init__(self, params=DEFAULT_BRIDGE_PARAMS):
        """
        Create the converter.

        :param params: BridgeParams (see bridge_params_from_dict).
        """
        if not isinstance(params, BridgeParams):
            raise InvalidParameterError(f'params must be BridgeParams, got {params!r}')
        self._params = params
        self._linear = SpeedLimiter(params.max_accel_mps2, params.max_decel_mps2, 'linear')
        self._angular = SpeedLimiter(params.max_angular_accel_radps2,
                                     params.max_angular_accel_radps2, 'angular')
        self._speed_mps = 0.0
        self._yaw_rate_radps = 0.0

    @property
    def params(self):
        return self._params

    @property
    def applied_twist(self):
        """The (v, ω) applied at the last step (start of the next ramp)."""
        return Twist2D(self._speed_mps, self._yaw_rate_radps)

    def reset(self, speed_mps=0.0, yaw_rate_radps=0.0):
        """
        Set the ramp start, e.g. to 0 after a watchdog brake or to a measured twist.

        :param speed_mps: forward speed [m/s].
        :param yaw_rate_radps: yaw rate [rad/s].
        """
        self._speed_mps = check_speed_mps(speed_mps)
        self._yaw_rate_radps = check_speed_mps(yaw_rate_radps, 'yaw_rate_radps')

    def is_turning_in_place(self, speed_mps, steering_rad):
        """Tell whether turn-in-place applies to this command (enabled, |v| small, δ != 0)."""
        params = self._params
        return (params.turn_in_place and steering_rad != 0.0
                and abs(speed_mps) < params.turn_in_place_speed_threshold_mps)

    def step(self, speed_mps, steering_rad, dt_s):
        """
        Convert one Ackermann command into the wheel command applied for the next ``dt_s``.

        :param speed_mps: commanded speed v [m/s], positive = forward.
        :param steering_rad: commanded steering tire angle δ [rad], positive = left.
        :param dt_s: time since the previous step [s], >= 0 (0: the ramps do not move).
        :return: DiffDriveCommand as applied.
        :raises InvalidCommandError: naming the value for a non-finite speed, a steering angle
            that is non-finite or has |δ| >= pi/2, or a bad dt; the state is then unchanged.
        """
        speed_mps = check_speed_mps(speed_mps)
        steering_rad = check_steering_rad(steering_rad)
        dt_s = check_dt_s(dt_s)
        params = self._params
        in_place = self.is_turning_in_place(speed_mps, steering_rad)
        target_mps = 0.0 if in_place else speed_mps
        applied_mps = self._linear.limit(target_mps, self._speed_mps, dt_s)
        if in_place:
            yaw_rate_radps = turn_in_place_yaw_rate(
                steering_rad, params.turn_in_place_gain_per_s,
                params.turn_in_place_max_yaw_rate_radps)
        elif params.mode == 'literal':
            yaw_rate_radps = steering_rad
        else:
            yaw_rate_radps = applied_mps * math.tan(steering_rad) / params.wheel_base_m
        yaw_rate_radps = self._angular.limit(yaw_rate_radps, self._yaw_rate_radps, dt_s)
        wheels = wheel_speeds_from_twist(applied_mps, yaw_rate_radps, params.wheel_tread_m)
        wheels = limit_wheel_speeds(wheels.left_mps, wheels.right_mps,
                                    params.max_wheel_speed_mps)
        twist = twist_from_wheel_speeds(wheels.left_mps, wheels.right_mps, params.wheel_tread_m)
        self._speed_mps, self._yaw_rate_radps = twist
        return DiffDriveCommand(
            twist.speed_mps, twist.yaw_rate_radps, wheels.left_mps, wheels.right_mps,
            wheels.left_mps / params.wheel_radius_m, wheels.right_mps / params.wheel_radius_m)

    def plausibility_warning(self):
        """Return wheel_base_plausibility for these parameters (text or None)."""
        return wheel_base_plausibility(self._params.wheel_base_m, self._params.wheel_tread_m)
