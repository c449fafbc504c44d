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
The bridge's mapping of an Ackermann command (v, δ) onto a differential drive, ROS-free.

Which yaw rate a steering angle asks of a robot without steered wheels (the bicycle model
Autoware assumes, or the literal snippet of Autoware's differential-drive note), the steering
angle reported back for a measured twist, turning in place, and the plausibility of the pseudo
wheel base. Signs and units as in :mod:`vehicle_sim.core.diffdrive.kinematics`.
"""

import math

from vehicle_sim.core.diffdrive.kinematics import (
    check_positive,
    check_speed_mps,
    check_steering_rad,
    wheel_speeds_from_twist,
)
from vehicle_sim.core.specs.errors import InvalidParameterError

KINEMATIC_MODES = ('kinematic', 'literal')

# Below this |v| the reported steering is regularised (equivalent_steering_rad).
STEERING_REPORT_SPEED_EPS_MPS = 0.05

# wheel_base_plausibility: Autoware's diff-drive note suggests wheel_base ≈ wheel_tread; outside
# this band, warn.
WHEEL_BASE_MIN_TREAD_RATIO = 0.5
WHEEL_BASE_MAX_TREAD_RATIO = 3.0


def ackermann_to_wheel_speeds(speed_mps, steering_rad, wheel_base_m, tread_m, mode='kinematic'):
    """
    Convert an Ackermann command (v, δ) to differential wheel speeds, without limits.

    ``mode='kinematic'`` (default): ω = v·tan(δ)/L, the yaw rate of the bicycle model that
    Autoware's planner and controllers assume, so the robot follows the commanded curvature
    tan(δ)/L at any speed.

    ``mode='literal'``: the snippet of Autoware's note (Autoware "Customizing for differential
    drive
    vehicle"), v_l = v − δ·t/2, v_r = v + δ·t/2, i.e. the steering *angle* is used as if it were a
    yaw *rate* (rad taken as rad/s). Kept only for compatibility with vehicle interfaces built
    from that snippet. It is not the default because its curvature δ/v depends on speed and not
    on the wheel base: the robot turns too sharply at low speed (it even spins at v = 0) and too
    widely at high speed, so it leaves the path Autoware planned unless the controller's feedback
    keeps correcting it.

    :param speed_mps: forward speed v [m/s].
    :param steering_rad: steering tire angle δ [rad], positive = left, |δ| < pi/2.
    :param wheel_base_m: (pseudo) wheel base L [m], > 0 (unused in 'literal' mode).
    :param tread_m: wheel tread t [m], > 0.
    :param mode: 'kinematic' or 'literal'.
    :return: WheelSpeeds [m/s].
    :raises InvalidCommandError: for a non-finite speed or an invalid steering angle.
    :raises InvalidParameterError: for an unknown mode or a non-positive length.
    """
    if mode not in KINEMATIC_MODES:
        raise InvalidParameterError(
            f'mode = {mode!r}: must be one of {", ".join(KINEMATIC_MODES)}')
    speed_mps = check_speed_mps(speed_mps)
    steering_rad = check_steering_rad(steering_rad)
    wheel_base_m = check_positive('wheel_base', wheel_base_m)
    tread_m = check_positive('wheel_tread', tread_m)
    if mode == 'literal':
        yaw_rate_radps = steering_rad
    else:
        yaw_rate_radps = speed_mps * math.tan(steering_rad) / wheel_base_m
    return wheel_speeds_from_twist(speed_mps, yaw_rate_radps, tread_m)


def equivalent_steering_rad(speed_mps, yaw_rate_radps, wheel_base_m,
                            speed_eps_mps=STEERING_REPORT_SPEED_EPS_MPS):
    """
    Return the bicycle-model steering angle that matches a measured (v, ω), for SteeringReport.

    Exact inverse δ = atan(ω·L/v) for |v| >= v_eps. Below, the denominator is regularised:
    δ = atan(ω·L·v / max(v², v_eps²)), which equals the exact inverse at |v| = v_eps, is
    continuous in v and ω everywhere (also through v = 0, where the sign of δ for a given ω must
    flip between forward and reverse), and reports 0 at standstill, where a pure rotation has no
    Ackermann equivalent. The result always lies in (−pi/2, pi/2).

    :param speed_mps: forward speed v [m/s].
    :param yaw_rate_radps: yaw rate ω [rad/s], positive = left.
    :param wheel_base_m: (pseudo) wheel base L [m], > 0.
    :param speed_eps_mps: regularisation speed v_eps [m/s], > 0.
    :return: steering angle [rad], positive = left.
    """
    wheel_base_m = check_positive('wheel_base', wheel_base_m)
    speed_eps_mps = check_positive('speed_eps_mps', speed_eps_mps)
    denominator = max(speed_mps * speed_mps, speed_eps_mps * speed_eps_mps)
    return math.atan(yaw_rate_radps * wheel_base_m * speed_mps / denominator)


def turn_in_place_yaw_rate(steering_rad, gain_per_s, max_yaw_rate_radps):
    """
    Return the in-place rotation rate for a steering command: sign(δ)·min(|δ|·k, ω_max).

    :param steering_rad: steering tire angle δ [rad], positive = left (counter-clockwise).
    :param gain_per_s: k [1/s], > 0.
    :param max_yaw_rate_radps: ω_max [rad/s], > 0.
    :return: yaw rate [rad/s]; 0 for δ = 0.
    """
    if steering_rad == 0.0:
        return 0.0
    return math.copysign(min(abs(steering_rad) * gain_per_s, max_yaw_rate_radps), steering_rad)


def wheel_base_plausibility(wheel_base_m, tread_m):
    """
    Return a warning when the pseudo wheel base is implausible for the robot, else None.

    Autoware's note on differential-drive vehicles: a differential robot has no wheel base, so
    set a pseudo value, e.g. equal to the tread. Too small and the vehicle may leave the planned
    path; too large and planning becomes over-conservative. Warn outside
    [0.5, 3] × tread (WHEEL_BASE_MIN_TREAD_RATIO, WHEEL_BASE_MAX_TREAD_RATIO).

    :param wheel_base_m: pseudo wheel base [m], > 0.
    :param tread_m: wheel tread [m], > 0.
    :return: warning text, or None when plausible.
    """
    wheel_base_m = check_positive('wheel_base', wheel_base_m)
    tread_m = check_positive('wheel_tread', tread_m)
    ratio = wheel_base_m / tread_m
    if ratio < WHEEL_BASE_MIN_TREAD_RATIO:
        return (f'wheel_base {wheel_base_m:g} m is {ratio:.2f} x wheel_tread {tread_m:g} m '
                f'(< {WHEEL_BASE_MIN_TREAD_RATIO:g} x): Autoware may steer too sharply and drive '
                'beyond the planned path; a value near the tread is suggested')
    if ratio > WHEEL_BASE_MAX_TREAD_RATIO:
        return (f'wheel_base {wheel_base_m:g} m is {ratio:.2f} x wheel_tread {tread_m:g} m '
                f'(> {WHEEL_BASE_MAX_TREAD_RATIO:g} x): Autoware will plan over-conservative '
                'trajectories for a vehicle this long; a value near the tread is suggested')
    return None
