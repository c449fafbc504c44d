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
Autoware Ackermann command → differential drive: the ``ackermann_to_differential`` node.

Wiring only; the kinematics, limits and watchdog are core's (``core/diff_drive.py``,
``core/watchdog.py``), the vehicle-interface state (gear, control mode, lights) is
:class:`BridgeController` below (ROS-free, time injected). Names, types and QoS:
``ros/bridge_interfaces.py``; behaviour and parameters: ``docs/autoware.md``.

Output is published on receipt of every accepted command (lowest latency) and on the control
tick (ramps, watchdog): a wall timer at ``control_rate_hz``, or, with ``use_sim_time``, every
``1/control_rate_hz`` of simulated time as /clock advances, so the watchdog acts in sim time.
"""

import math
import sys

from vehicle_sim.core.diff_drive import (
    AckermannToDifferential,
    BRIDGE_PARAM_SPECS,
    bridge_params_from_dict,
    check_speed_mps,
    check_steering_rad,
    DiffDriveCommand,
    equivalent_steering_rad,
    limit_wheel_speeds,
    SpeedLimiter,
    STOP_COMMAND,
    twist_from_wheel_speeds,
    wheel_speeds_from_twist,
)
from vehicle_sim.core.errors import (
    InvalidCommandError,
    InvalidParameterError,
    VehicleSimError,
)
from vehicle_sim.core.units import stamp_to_seconds
from vehicle_sim.core.watchdog import CommandWatchdog
from vehicle_sim.ros import bridge_interfaces as bi
from vehicle_sim.transport.port import ThrottledWarning, Time  # noqa: F401 - re-exported
from vehicle_sim.transport.selection import create_node, run_node

# autoware_vehicle_msgs constants (GearCommand/GearReport share their values; likewise the
# turn-indicator, hazard-light and control-mode commands and reports).
GEAR_NONE, GEAR_NEUTRAL, GEAR_DRIVE = 0, 1, 2
GEAR_REVERSE, GEAR_REVERSE_2, GEAR_PARK, GEAR_LOW, GEAR_LOW_2 = 20, 21, 22, 23, 24
REVERSE_GEARS = (GEAR_REVERSE, GEAR_REVERSE_2)
STOP_GEARS = (GEAR_NEUTRAL, GEAR_PARK)
VALID_GEARS = frozenset(range(0, 25))
NO_COMMAND, DISABLE, ENABLE_LEFT, ENABLE_RIGHT = 0, 1, 2, 3
HAZARD_ENABLE = 2
MODE_AUTONOMOUS, MODE_MANUAL = 1, 4
MIN_DT_S = 1e-9

# name, default, description, validator — the bridge's own parameters (the kinematic ones come
# from BRIDGE_PARAM_SPECS).


def _positive(value):
    return None if math.isfinite(value) and value > 0.0 else 'must be a finite number > 0'


def _input_type(value):
    if value not in bi.BRIDGE_INPUTS:
        return f'must be one of {", ".join(bi.BRIDGE_INPUTS)}'
    return None


def _joint_sides(joints):
    """Return 'left'/'right' per joint name; raise InvalidParameterError when ambiguous."""
    sides = []
    for joint in joints:
        lower = joint.lower()
        if ('left' in lower) == ('right' in lower):
            raise InvalidParameterError(
                f'wheel_joints: {joint!r} must contain exactly one of "left" or "right" (that '
                'decides which side it drives)')
        sides.append('left' if 'left' in lower else 'right')
    if 'left' not in sides or 'right' not in sides:
        raise InvalidParameterError(f'wheel_joints {list(joints)}: need a left and a right joint')
    return tuple(sides)


def _wheel_joints(value):
    if not isinstance(value, list) or not all(isinstance(v, str) and v for v in value):
        return 'must be a list of joint names'
    _joint_sides(value)
    return None


NODE_PARAMETERS = (
    ('input_type', bi.DEFAULT_INPUT_TYPE, 'command type read: ' + ', '.join(bi.BRIDGE_INPUTS),
     _input_type),
    ('publish_differential_command', True,
     f'publish {bi.DIFFERENTIAL_COMMAND_OUT.ros_type} on {bi.DIFFERENTIAL_COMMAND_OUT.name}',
     None),
    ('publish_wheel_velocities', True,
     f'publish {bi.WHEEL_VELOCITIES_OUT.ros_type} [rad/s] on {bi.WHEEL_VELOCITIES_OUT.name}',
     None),
    ('publish_twist', False, f'publish geometry_msgs/Twist on {bi.TWIST_OUT.name}', None),
    ('publish_twist_stamped', False,
     f'publish geometry_msgs/TwistStamped on {bi.TWIST_STAMPED_OUT.name}', None),
    ('wheel_joints', ['left_wheel_joint', 'right_wheel_joint'],
     'driven joints, in Float64MultiArray order; "left"/"right" in a name gives its side',
     _wheel_joints),
    ('control_rate_hz', 50.0, 'control tick rate [Hz] (ramps, watchdog; node clock)',
     _positive),
    ('status_rate_hz', 30.0, 'feedback report rate [Hz] (wall time)', _positive),
    ('vehicle_status', True,
     'publish the /vehicle/status reports and serve /control/control_mode_request', None),
    ('frame_id', 'base_link', 'frame_id of stamped outputs and VelocityReport', None),
)


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
        if gear not in VALID_GEARS:
            raise InvalidCommandError(f'gear command {gear!r}: not a GearCommand constant')
        if gear != GEAR_NONE:
            self.gear = gear

    def set_turn_indicators(self, command):
        """Set the turn indicators (TurnIndicatorsCommand); NO_COMMAND keeps the state."""
        if command not in (NO_COMMAND, DISABLE, ENABLE_LEFT, ENABLE_RIGHT):
            raise InvalidCommandError(f'turn indicators command {command!r}: undefined')
        if command != NO_COMMAND:
            self.turn_indicators = command

    def set_hazard_lights(self, command):
        """Set the hazard lights (HazardLightsCommand); NO_COMMAND keeps the state."""
        if command not in (NO_COMMAND, DISABLE, HAZARD_ENABLE):
            raise InvalidCommandError(f'hazard lights command {command!r}: undefined')
        if command != NO_COMMAND:
            self.hazard_lights = command

    def request_control_mode(self, mode):
        """
        Handle a ControlModeCommand request.

        :return: True for AUTONOMOUS or MANUAL (applied); False otherwise (nothing changes).
        """
        if mode not in (MODE_AUTONOMOUS, MODE_MANUAL):
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
        # SpeedLimiter computes inf * 0 = NaN for a disabled limit at dt = 0 (core issue,
        # reported); 1 ns moves an enabled ramp by a negligible amount.
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


def _bridge_validator(key):
    def validate(value):
        bridge_params_from_dict({key: value}, source='parameter')
        return None
    return validate


class AckermannToDifferentialNode:
    """
    The bridge node: parameters, publishers and subscriptions wired to a BridgeController.

    In-process API (tests, benchmarks): :meth:`handle_command` (a message of the input type,
    optional ``now_s``), :meth:`tick`, :meth:`handle_joint_states`, :meth:`publish_status`; the
    controller is ``self.controller``.

    :param args: command line (``--ros-args`` part applied).
    :param parameter_overrides: parameter values that win over the command line.
    :param transport: 'auto', 'rclpy' or 'dds'.
    """

    def __init__(self, args=None, parameter_overrides=None, transport=None,
                 node_name=bi.BRIDGE_NODE_NAME, namespace=''):
        node = self.node = create_node(node_name, namespace, args=args,
                                       parameter_overrides=parameter_overrides,
                                       transport=transport)
        try:
            self._setup()
        except BaseException:
            node.shutdown()
            raise

    def _setup(self):
        node = self.node
        kinematic = {spec.key: node.declare_parameter(
            spec.key, spec.default, read_only=True, validator=_bridge_validator(spec.key),
            description=f'{spec.doc} [{spec.unit}]' if spec.unit else spec.doc)
            for spec in BRIDGE_PARAM_SPECS}
        values = {name: node.declare_parameter(name, default, description=doc,
                                               validator=validator, read_only=True)
                  for name, default, doc, validator in NODE_PARAMETERS}
        self.params = bridge_params_from_dict(kinematic, source=node.get_fully_qualified_name())
        self.input_type = values['input_type']
        twist_input = self.input_type == bi.TWIST_STAMPED
        self.controller = BridgeController(self.params, twist_input=twist_input)
        self.wheel_joints = tuple(values['wheel_joints'])
        self._sides = _joint_sides(self.wheel_joints)
        self._frame_id = values['frame_id']
        self._control_period_s = 1.0 / values['control_rate_hz']
        self._use_sim_time = bool(node.get_parameter('use_sim_time'))
        self._last_clock_s = None
        self._last_tick_s = None
        self._warn = ThrottledWarning(node.get_logger())
        self.rejected = 0
        self._measured = None        # (v [m/s], yaw rate [rad/s]) from joint_states
        msg = node.msg
        self._types = {name: msg(name) for name in (
            'vehicle_msgs/msg/DifferentialCommand', 'std_msgs/msg/Float64MultiArray',
            'geometry_msgs/msg/Twist', 'geometry_msgs/msg/TwistStamped',
            'autoware_vehicle_msgs/msg/VelocityReport', 'autoware_vehicle_msgs/msg/SteeringReport',
            'autoware_vehicle_msgs/msg/GearReport',
            'autoware_vehicle_msgs/msg/TurnIndicatorsReport',
            'autoware_vehicle_msgs/msg/HazardLightsReport',
            'autoware_vehicle_msgs/msg/ControlModeReport')}
        self._outputs = {}
        for switch, spec in bi.BRIDGE_OUTPUTS.items():
            if values[switch]:
                self._outputs[spec] = node.create_publisher(spec.ros_type, spec.name, spec.qos)
        self._input = bi.BRIDGE_INPUTS[self.input_type]
        self._read_command = COMMAND_READERS[self.input_type]
        self._subs = [node.create_subscription(self._input.ros_type, self._input.name,
                                               self._on_command, self._input.qos)]
        self._status = {}
        if values['vehicle_status']:
            for spec in bi.STATUS_TOPICS:
                self._status[spec] = node.create_publisher(spec.ros_type, spec.name, spec.qos)
            for spec, callback in ((bi.GEAR_COMMAND, self._on_gear_cmd),
                                   (bi.TURN_INDICATORS_COMMAND, self._on_turn_indicators_cmd),
                                   (bi.HAZARD_LIGHTS_COMMAND, self._on_hazard_lights_cmd),
                                   (bi.JOINT_STATES_IN, self.handle_joint_states)):
                self._subs.append(node.create_subscription(spec.ros_type, spec.name, callback,
                                                           spec.qos))
            self._control_mode_srv = node.create_service(
                bi.CONTROL_MODE_REQUEST.ros_type, bi.CONTROL_MODE_REQUEST.name,
                self._handle_control_mode_request)
            self._status_timer = node.create_timer(1.0 / values['status_rate_hz'],
                                                   self.publish_status)
        if self._use_sim_time:
            self._subs.append(node.create_subscription(bi.CLOCK.ros_type, bi.CLOCK.name,
                                                       self._on_clock, bi.CLOCK.qos))
            self._control_timer = None
        else:
            self._control_timer = node.create_timer(self._control_period_s, self._on_timer)
        warning = self.controller.kinematics.plausibility_warning()
        if warning:
            node.get_logger().warn(warning)
        node.get_logger().info(
            f'bridge ready: {self.input_type} on {self._input.name} -> '
            f'{", ".join(p.topic_name for p in self._outputs.values()) or "no outputs"}; mode '
            f'{self.params.mode}, wheel_base {self.params.wheel_base_m:g} m, tread '
            f'{self.params.wheel_tread_m:g} m, timeout {self.params.command_timeout_s:g} s '
            f'({self.params.timeout_action}){", sim time" if self._use_sim_time else ""}')

    # ---------------------------------------------------------------- time
    def now_s(self):
        """Node clock [s]: sim time (latest /clock) under use_sim_time, else wall time."""
        now = self.node.now().nanoseconds * 1e-9
        if self._last_clock_s is not None and self._last_clock_s > now:
            return self._last_clock_s
        return now

    def _on_clock(self, msg):
        now_s = stamp_to_seconds(msg.clock.sec, msg.clock.nanosec)
        self._last_clock_s = now_s
        if self._last_tick_s is not None and now_s < self._last_tick_s:
            self._last_tick_s = None            # sim time went back (reset): restart ticks
        if self._last_tick_s is None or \
                now_s - self._last_tick_s >= self._control_period_s - 1e-9:
            self._last_tick_s = now_s
            self.tick(now_s)

    def _on_timer(self):
        self.tick()

    # ---------------------------------------------------------------- commands
    def _on_command(self, msg):
        self.handle_command(msg)

    def handle_command(self, msg, now_s=None):
        """
        Convert and apply one input message, publishing the result at once.

        :param msg: a message of ``input_type``.
        :param now_s: receipt time [s]; the node clock when None.
        :return: the published DiffDriveCommand, or None (rejected, or nothing to publish).
        """
        now_s = self.now_s() if now_s is None else now_s
        speed, second = self._read_command(msg)
        try:
            output = self.controller.command(speed, second, now_s)
        except InvalidCommandError as error:
            self.rejected += 1
            self._warn.warn(f'{self.input_type} rejected, not sent to the wheels: {error}')
            return None
        if output is not None:
            self._publish(output, now_s)
        return output

    def tick(self, now_s=None):
        """Run one control tick at ``now_s`` (node clock when None); return what was published."""
        now_s = self.now_s() if now_s is None else now_s
        output = self.controller.tick(now_s)
        if output is not None:
            self._publish(output, now_s)
        return output

    def _stamp(self, now_s):
        ns = int(round(now_s * 1e9))
        return self.node.time_msg(Time(ns))

    def _publish(self, command, now_s):
        stamp = None
        for spec, publisher in self._outputs.items():
            if spec is bi.DIFFERENTIAL_COMMAND_OUT:
                msg = self._types['vehicle_msgs/msg/DifferentialCommand']()
                msg.header.stamp = stamp = stamp or self._stamp(now_s)
                msg.header.frame_id = self._frame_id
                msg.left_wheel.velocity = command.left_mps
                msg.right_wheel.velocity = command.right_mps
            elif spec is bi.WHEEL_VELOCITIES_OUT:
                msg = self._types['std_msgs/msg/Float64MultiArray'](data=[
                    command.left_radps if side == 'left' else command.right_radps
                    for side in self._sides])
            elif spec is bi.TWIST_OUT:
                msg = self._types['geometry_msgs/msg/Twist']()
                msg.linear.x = command.speed_mps
                msg.angular.z = command.yaw_rate_radps
            else:
                msg = self._types['geometry_msgs/msg/TwistStamped']()
                msg.header.stamp = stamp = stamp or self._stamp(now_s)
                msg.header.frame_id = self._frame_id
                msg.twist.linear.x = command.speed_mps
                msg.twist.angular.z = command.yaw_rate_radps
            publisher.publish(msg)

    # ---------------------------------------------------------------- vehicle interface
    def _on_gear_cmd(self, msg):
        self._apply_enum(self.controller.set_gear, msg.command, 'gear_cmd')

    def _on_turn_indicators_cmd(self, msg):
        self._apply_enum(self.controller.set_turn_indicators, msg.command, 'turn_indicators_cmd')

    def _on_hazard_lights_cmd(self, msg):
        self._apply_enum(self.controller.set_hazard_lights, msg.command, 'hazard_lights_cmd')

    def _apply_enum(self, setter, value, name):
        try:
            setter(value)
        except InvalidCommandError as error:
            self._warn.warn(f'{name} rejected: {error}')

    def _handle_control_mode_request(self, request, response):
        response.success = self.controller.request_control_mode(request.mode)
        if not response.success:
            self.node.get_logger().warn(
                f'control_mode_request mode={request.mode} refused: only AUTONOMOUS (1) and '
                'MANUAL (4) are supported')
        return response

    def handle_joint_states(self, msg):
        """Take the measured wheel speeds [rad/s] of ``wheel_joints`` from a JointState."""
        if not msg.velocity:
            return
        index = {name: i for i, name in enumerate(msg.name)}
        sums = {'left': [0.0, 0], 'right': [0.0, 0]}
        for joint, side in zip(self.wheel_joints, self._sides):
            i = index.get(joint)
            if i is not None and i < len(msg.velocity) and math.isfinite(msg.velocity[i]):
                sums[side][0] += msg.velocity[i]
                sums[side][1] += 1
        if not sums['left'][1] or not sums['right'][1]:
            return
        radius = self.params.wheel_radius_m
        twist = twist_from_wheel_speeds(sums['left'][0] / sums['left'][1] * radius,
                                        sums['right'][0] / sums['right'][1] * radius,
                                        self.params.wheel_tread_m)
        self._measured = (twist.speed_mps, twist.yaw_rate_radps)

    @property
    def measured_twist(self):
        """(v [m/s], yaw rate [rad/s]) from the last usable joint_states, or None."""
        return self._measured

    def publish_status(self):
        """Publish the six /vehicle/status reports (velocity/steering only once measured)."""
        if not self._status:
            return
        stamp = self._stamp(self.now_s())
        t = self._types
        controller = self.controller
        if self._measured is not None:
            speed, yaw_rate = self._measured
            velocity = t['autoware_vehicle_msgs/msg/VelocityReport']()
            velocity.header.stamp = stamp
            velocity.header.frame_id = self._frame_id
            velocity.longitudinal_velocity = speed
            velocity.lateral_velocity = 0.0
            velocity.heading_rate = yaw_rate
            self._status[bi.VELOCITY_STATUS].publish(velocity)
            self._status[bi.STEERING_STATUS].publish(
                t['autoware_vehicle_msgs/msg/SteeringReport'](
                    stamp=stamp, steering_tire_angle=equivalent_steering_rad(
                        speed, yaw_rate, self.params.wheel_base_m)))
        self._status[bi.GEAR_STATUS].publish(t['autoware_vehicle_msgs/msg/GearReport'](
            stamp=stamp, report=controller.gear))
        self._status[bi.TURN_INDICATORS_STATUS].publish(
            t['autoware_vehicle_msgs/msg/TurnIndicatorsReport'](
                stamp=stamp, report=controller.turn_indicators))
        self._status[bi.HAZARD_LIGHTS_STATUS].publish(
            t['autoware_vehicle_msgs/msg/HazardLightsReport'](
                stamp=stamp, report=controller.hazard_lights))
        self._status[bi.CONTROL_MODE_STATUS].publish(
            t['autoware_vehicle_msgs/msg/ControlModeReport'](
                stamp=stamp, mode=controller.control_mode))

    def destroy(self):
        """Leave the graph."""
        self.node.shutdown()


# input_type -> message -> (speed [m/s], steering [rad] or yaw rate [rad/s])
COMMAND_READERS = {
    bi.CONTROL: lambda m: (m.longitudinal.velocity, m.lateral.steering_tire_angle),
    bi.AUTO_ACKERMANN: lambda m: (m.longitudinal.speed, m.lateral.steering_tire_angle),
    bi.ACKERMANN_DRIVE: lambda m: (m.drive.speed, m.drive.steering_angle),
    bi.TWIST_STAMPED: lambda m: (m.twist.linear.x, m.twist.angular.z),
}


def main(args=None):
    """Run the bridge until SIGINT/SIGTERM (``ros2 run vehicle_sim ackermann_to_differential``)."""
    try:
        return run_node(lambda argv: AckermannToDifferentialNode(argv).node,
                        sys.argv if args is None else args)
    except VehicleSimError as error:   # a refused parameter, or DDS refused by Cyclone
        print(f'ackermann_to_differential: {error}', file=sys.stderr)
        return 2


if __name__ == '__main__':
    sys.exit(main())
