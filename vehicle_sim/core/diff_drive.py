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
Ackermann → differential-drive kinematics of the Autoware bridge, ROS-free.

Signs and units: Autoware / REP 103, SI. Steering tire angle δ [rad] positive = LEFT, speed v
[m/s] positive = forward, yaw rate ω [rad/s] positive = counter-clockwise (left). Wheel speeds
are tyre-surface speeds [m/s] unless the name ends in ``_radps``. Time steps ``dt_s`` are passed
in (time is an argument). Formulas and their reasons: docs/bridge_kinematics.md.
"""

from dataclasses import dataclass
import math
from typing import NamedTuple

from vehicle_sim.core.errors import InvalidCommandError, InvalidParameterError
from vehicle_sim.core.geometry import wrap_angle_rad
from vehicle_sim.core.param_spec import ParamSpec, validate_table
from vehicle_sim.core.watchdog import DEFAULT_TIMEOUT_ACTION, DEFAULT_TIMEOUT_S, TIMEOUT_ACTIONS

KINEMATIC_MODES = ('kinematic', 'literal')

# Below this |v| the reported steering is regularised (equivalent_steering_rad).
STEERING_REPORT_SPEED_EPS_MPS = 0.05

# wheel_base_plausibility: Autoware's diff-drive note suggests wheel_base ≈ wheel_tread; outside
# this band, warn.
WHEEL_BASE_MIN_TREAD_RATIO = 0.5
WHEEL_BASE_MAX_TREAD_RATIO = 3.0

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


# ---------------------------------------------------------------------------------------------
# Validation helpers


def _is_number(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def check_speed_mps(speed_mps, name='speed'):
    """
    Validate a commanded speed.

    :param speed_mps: speed [m/s].
    :param name: the field name quoted in the error.
    :return: the speed as float.
    :raises InvalidCommandError: naming the value when it is not a finite number.
    """
    if not _is_number(speed_mps) or not math.isfinite(speed_mps):
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
    if not _is_number(steering_rad) or not math.isfinite(steering_rad):
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
    if not _is_number(dt_s) or not math.isfinite(dt_s) or dt_s < 0.0:
        raise InvalidCommandError(f'dt_s = {dt_s!r} s: must be a finite number >= 0')
    return float(dt_s)


def _check_positive(name, value):
    if not _is_number(value) or not math.isfinite(value) or value <= 0.0:
        raise InvalidParameterError(f'{name} = {value!r}: must be a finite number > 0')
    return float(value)


def _check_limit(name, value):
    if not _is_number(value) or not math.isfinite(value) or value < 0.0:
        raise InvalidParameterError(
            f'{name} = {value!r}: must be a finite number >= 0 (0 disables the limit)')
    return float(value)


# ---------------------------------------------------------------------------------------------
# Forward and inverse kinematics


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
    wheel_base_m = _check_positive('wheel_base', wheel_base_m)
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
    tread_m = _check_positive('wheel_tread', tread_m)
    return Twist2D((left_mps + right_mps) / 2.0, (right_mps - left_mps) / tread_m)


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
    wheel_base_m = _check_positive('wheel_base', wheel_base_m)
    tread_m = _check_positive('wheel_tread', tread_m)
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
    wheel_base_m = _check_positive('wheel_base', wheel_base_m)
    speed_eps_mps = _check_positive('speed_eps_mps', speed_eps_mps)
    denominator = max(speed_mps * speed_mps, speed_eps_mps * speed_eps_mps)
    return math.atan(yaw_rate_radps * wheel_base_m * speed_mps / denominator)


def wheel_radps_from_mps(speed_mps, wheel_radius_m):
    """
    Return a wheel's angular speed from its tyre-surface speed: ω_wheel = v / r.

    :param speed_mps: tyre-surface speed [m/s].
    :param wheel_radius_m: wheel radius r [m], > 0.
    :return: angular speed [rad/s].
    """
    return speed_mps / _check_positive('wheel_radius', wheel_radius_m)


def wheel_mps_from_radps(speed_radps, wheel_radius_m):
    """
    Return a wheel's tyre-surface speed from its angular speed: v = ω_wheel · r.

    :param speed_radps: angular speed [rad/s].
    :param wheel_radius_m: wheel radius r [m], > 0.
    :return: tyre-surface speed [m/s].
    """
    return speed_radps * _check_positive('wheel_radius', wheel_radius_m)


# ---------------------------------------------------------------------------------------------
# Limits


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


# ---------------------------------------------------------------------------------------------
# Turn in place, plausibility, pose integration


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
    wheel_base_m = _check_positive('wheel_base', wheel_base_m)
    tread_m = _check_positive('wheel_tread', tread_m)
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


# ---------------------------------------------------------------------------------------------
# Parameters


BRIDGE_PARAM_SPECS = (
    ParamSpec('wheel_base', 'wheel_base_m', 'float', 0.5, 'm',
              '(pseudo) wheel base of the bicycle model Autoware assumes; near wheel_tread',
              gt=0.0),
    ParamSpec('wheel_tread', 'wheel_tread_m', 'float', 0.5, 'm',
              'distance between the left and right wheel contact points', gt=0.0),
    ParamSpec('wheel_radius', 'wheel_radius_m', 'float', 0.1, 'm',
              'drive wheel radius (m/s <-> rad/s)', gt=0.0),
    ParamSpec('max_wheel_speed_mps', 'max_wheel_speed_mps', 'float', 1.0, 'm/s',
              'largest tyre-surface speed; both wheels scale together (0 disables)', ge=0.0),
    ParamSpec('max_accel_mps2', 'max_accel_mps2', 'float', 1.0, 'm/s^2',
              'largest increase rate of |v| (0 disables)', ge=0.0),
    ParamSpec('max_decel_mps2', 'max_decel_mps2', 'float', 2.0, 'm/s^2',
              'largest decrease rate of |v| (0 disables)', ge=0.0),
    ParamSpec('max_angular_accel_radps2', 'max_angular_accel_radps2', 'float', 0.0, 'rad/s^2',
              'largest change rate of |yaw rate|; non-zero trades path fidelity for smoothness '
              '(0 disables)', ge=0.0),
    ParamSpec('mode', 'mode', 'enum', 'kinematic', choices=KINEMATIC_MODES,
              doc="kinematic: yaw rate v*tan(steer)/wheel_base; literal: the snippet of "
                  "Autoware's note (steering angle used as yaw rate), compatibility only"),
    ParamSpec('turn_in_place', 'turn_in_place', 'bool', False,
              doc='rotate in place when |v| < turn_in_place_speed_threshold_mps and steer != 0'),
    ParamSpec('turn_in_place_speed_threshold_mps', 'turn_in_place_speed_threshold_mps', 'float',
              0.05, 'm/s', 'commanded |v| below which turn-in-place applies', gt=0.0),
    ParamSpec('turn_in_place_gain_per_s', 'turn_in_place_gain_per_s', 'float', 1.0, '1/s',
              'in-place yaw rate per rad of steering', gt=0.0),
    ParamSpec('turn_in_place_max_yaw_rate_radps', 'turn_in_place_max_yaw_rate_radps', 'float',
              0.5, 'rad/s', 'largest in-place yaw rate', gt=0.0),
    ParamSpec('command_timeout_s', 'command_timeout_s', 'float', DEFAULT_TIMEOUT_S, 's',
              'age of the last accepted command (receipt, node clock) after which '
              'timeout_action applies (0 disables)', ge=0.0),
    ParamSpec('timeout_action', 'timeout_action', 'enum', DEFAULT_TIMEOUT_ACTION,
              choices=TIMEOUT_ACTIONS,
              doc='brake: publish zero wheel speeds; coast: publish nothing; hold: repeat the '
                  'last command'),
)



@dataclass(frozen=True)
class BridgeParams:
    """Validated bridge parameters (SI units; meaning in BRIDGE_PARAM_SPECS)."""

    wheel_base_m: float
    wheel_tread_m: float
    wheel_radius_m: float
    max_wheel_speed_mps: float
    max_accel_mps2: float
    max_decel_mps2: float
    max_angular_accel_radps2: float
    mode: str
    turn_in_place: bool
    turn_in_place_speed_threshold_mps: float
    turn_in_place_gain_per_s: float
    turn_in_place_max_yaw_rate_radps: float
    command_timeout_s: float
    timeout_action: str


def default_bridge_dict():
    """Return the bridge defaults keyed by parameter name."""
    return {spec.key: spec.default for spec in BRIDGE_PARAM_SPECS}


def bridge_params_from_dict(data=None, source='bridge parameters'):
    """
    Validate bridge parameters (ROS names, see BRIDGE_PARAM_SPECS) and build BridgeParams.

    :param data: mapping of parameter names to values; missing names take their default.
    :param source: origin quoted in error messages (file or node name).
    :return: BridgeParams.
    :raises InvalidParameterError: naming the parameter, its value and the allowed range, for an
        unknown name, a wrong type or an out-of-range value (nothing is clamped).
    """
    values = validate_table(BRIDGE_PARAM_SPECS, {} if data is None else data, source,
                            default_bridge_dict(), 'bridge parameters', 'parameter')
    return BridgeParams(**values)


DEFAULT_BRIDGE_PARAMS = bridge_params_from_dict(source='bridge defaults')


# ---------------------------------------------------------------------------------------------
# Composition


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


BridgeKinematics = AckermannToDifferential
