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
The ``ackermann_to_differential`` bridge's state machine, ROS-free (time injected).

Gear, control mode, lights, watchdog and kinematics of the bridge node
(``ros/bridge_node.py`` wires it to topics). Kinematics and limits: the rest of ``core/bridge/``;
watchdog: ``core/commands/watchdog.py``; the Autoware codes and their validation:
``core/autoware/codes.py``.
"""

from vehicle_sim.core.autoware.codes import (
    check_gear,
    check_hazard_lights,
    check_turn_indicators,
    DISABLE,
    GEAR_DRIVE,
    GEAR_NONE,
    is_supported_control_mode,
    MODE_AUTONOMOUS,
    MODE_MANUAL,
    NO_COMMAND,
    REVERSE_GEARS,
    STOP_GEARS,
)
from vehicle_sim.core.bridge.converter import (
    AckermannToDifferential,
    DiffDriveCommand,
    STOP_COMMAND,
)
from vehicle_sim.core.commands.watchdog import CommandWatchdog
from vehicle_sim.core.diffdrive.kinematics import (
    check_speed_mps,
    check_steering_rad,
    twist_from_wheel_speeds,
    wheel_speeds_from_twist,
)
from vehicle_sim.core.diffdrive.speed_limiter import limit_wheel_speeds, SpeedLimiter

# SpeedLimiter computes inf * 0 = NaN for a disabled limit at dt = 0; 1 ns moves an enabled ramp
# by a negligible amount.
MIN_DT_S = 1e-9


class BridgeController:
    """
    The bridge's state machine, ROS-free: gear, control mode, lights, watchdog, kinematics.

    Every method takes ``now_s`` (node clock [s], sim time included). Outputs are
    DiffDriveCommand (publish it) or None (publish nothing).

    - gear DRIVE/LOW/NONE: the command's sign is kept; REVERSE: v = −|v| (Autoware sends a
      negative velocity in reverse; an unsigned magnitude works too), the steering angle is kept,
      so the robot backs along the commanded curvature like a car; PARK/NEUTRAL: zero wheels.
    - control mode AUTONOMOUS (start): commands drive the wheels; MANUAL: one zero command,
      then nothing (another source owns the wheels).
    - watchdog (CommandWatchdog, receipt time): brake = zero wheels and the ramps restart from
      standstill; coast = nothing; hold = the last command. Rejected commands do not feed it.
    """

    def __init__(self, params, twist_input=False):
        """
        Create the controller.

        :param params: BridgeParams.
        :param twist_input: True when commands are (v, yaw rate) instead of (v, steering).
        """
        self.params = params
        self.kinematics = AckermannToDifferential(params)
        self.watchdog = CommandWatchdog(params.command_timeout_s, params.timeout_action)
        self.twist_input = twist_input
        self._linear = SpeedLimiter(params.max_accel_mps2, params.max_decel_mps2, 'linear')
        self._angular = SpeedLimiter(params.max_angular_accel_radps2,
                                     params.max_angular_accel_radps2, 'angular')
        self._twist = (0.0, 0.0)
        self.gear = GEAR_DRIVE
        self.control_mode = MODE_AUTONOMOUS
        self.turn_indicators = DISABLE
        self.hazard_lights = DISABLE
        self._target = None          # (v, steering or yaw rate) as commanded
        self._last_step_s = None
        self._stop_pending = False
        self.last_output = None

    # ---------------------------------------------------------------- commands
    def command(self, speed_mps, second, now_s):
        """
        Accept one command and return what to publish now.

        :param speed_mps: v [m/s].
        :param second: steering tire angle [rad, + left], or the yaw rate [rad/s] for twist
            input.
        :param now_s: receipt time on the node clock [s].
        :return: DiffDriveCommand or None.
        :raises InvalidCommandError: NaN/±inf, or |steering| >= pi/2; nothing changes then.
        """
        speed_mps = check_speed_mps(speed_mps)
        if self.twist_input:
            second = check_speed_mps(second, 'yaw_rate')
        else:
            second = check_steering_rad(second)
        self.watchdog.feed(now_s)
        self._target = (speed_mps, second)
        return self._output(now_s)

    def tick(self, now_s):
        """Return what to publish on a control tick at ``now_s`` (ramps, watchdog)."""
        return self._output(now_s)

    def set_gear(self, gear):
        """Set the gear (GearCommand value); raise InvalidCommandError for an undefined one."""
        if check_gear(gear) != GEAR_NONE:
            self.gear = gear

    def set_turn_indicators(self, command):
        """Set the turn indicators (TurnIndicatorsCommand); NO_COMMAND keeps the state."""
        if check_turn_indicators(command) != NO_COMMAND:
            self.turn_indicators = command

    def set_hazard_lights(self, command):
        """Set the hazard lights (HazardLightsCommand); NO_COMMAND keeps the state."""
        if check_hazard_lights(command) != NO_COMMAND:
            self.hazard_lights = command

    def request_control_mode(self, mode):
        """
        Handle a ControlModeCommand request.

        :return: True for AUTONOMOUS or MANUAL (applied); False otherwise (nothing changes).
        """
        if not is_supported_control_mode(mode):
            return False
        if mode == MODE_MANUAL and self.control_mode != MODE_MANUAL:
            self._stop_pending = True
        self.control_mode = mode
        return True

    # ---------------------------------------------------------------- output
    def _stop(self):
        self.kinematics.reset()
        self._twist = (0.0, 0.0)
        return STOP_COMMAND

    def _output(self, now_s):
        dt_s = 0.0 if self._last_step_s is None else max(0.0, now_s - self._last_step_s)
        dt_s = max(dt_s, MIN_DT_S)
        self._last_step_s = now_s
        output = self._decide(now_s, dt_s)
        self.last_output = output
        return output

    def _decide(self, now_s, dt_s):
        if self.control_mode == MODE_MANUAL:
            if self._stop_pending:
                self._stop_pending = False
                return self._stop()
            return None
        if self.watchdog.is_stale(now_s):
            action = self.watchdog.action
            if action == 'brake':
                return self._stop()
            if action == 'coast' or self._target is None:
                return None
        if self._target is None:
            return None
        if self.gear in STOP_GEARS:
            return self._stop()
        speed_mps, second = self._target
        reverse = self.gear in REVERSE_GEARS
        if self.twist_input:
            return self._twist_step(speed_mps, second, reverse, dt_s)
        if reverse:
            speed_mps = -abs(speed_mps)
        return self.kinematics.step(speed_mps, second, dt_s)

    def _twist_step(self, speed_mps, yaw_rate_radps, reverse, dt_s):
        if reverse and speed_mps > 0.0:
            # keep the curvature: drive the same circle backwards
            speed_mps, yaw_rate_radps = -speed_mps, -yaw_rate_radps
        params = self.params
        v = self._linear.limit(speed_mps, self._twist[0], dt_s)
        w = self._angular.limit(yaw_rate_radps, self._twist[1], dt_s)
        wheels = wheel_speeds_from_twist(v, w, params.wheel_tread_m)
        wheels = limit_wheel_speeds(wheels.left_mps, wheels.right_mps,
                                    params.max_wheel_speed_mps)
        twist = twist_from_wheel_speeds(wheels.left_mps, wheels.right_mps, params.wheel_tread_m)
        self._twist = (twist.speed_mps, twist.yaw_rate_radps)
        return DiffDriveCommand(twist.speed_mps, twist.yaw_rate_radps, wheels.left_mps,
                                wheels.right_mps, wheels.left_mps / params.wheel_radius_m,
                                wheels.right_mps / params.wheel_radius_m)
