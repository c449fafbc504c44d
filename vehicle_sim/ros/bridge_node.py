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

Wiring only; the kinematics, limits and watchdog are core's (``core/bridge/``,
``core/commands/watchdog.py``), the vehicle-interface state (gear, control mode, lights) is core's
:class:`~vehicle_sim.core.bridge.controller.BridgeController` (ROS-free, time injected). Names,
types and QoS: ``ros/autoware_interfaces.py`` and ``ros/bridge_interfaces.py``; behaviour and
parameters: ``docs/autoware.md``.

Output is published on receipt of every accepted command (lowest latency) and on the control
tick (ramps, watchdog): a wall timer at ``control_rate_hz``, or, with ``use_sim_time``, on the
first /clock of every period of ``1/control_rate_hz`` of simulated time (at its multiples when no
/clock is missed, however late the node started), so the watchdog acts in sim time and a lockstep
runner knows which messages answer which /clock.
"""

import math
import sys
from types import SimpleNamespace

from vehicle_sim.core.autoware.codes import control_mode_refusal
from vehicle_sim.core.bridge.ackermann_mapping import equivalent_steering_rad
from vehicle_sim.core.bridge.controller import BridgeController
from vehicle_sim.core.bridge.params import BRIDGE_PARAM_SPECS, bridge_params_from_dict
from vehicle_sim.core.diffdrive.kinematics import twist_from_wheel_speeds
from vehicle_sim.core.specs.errors import InvalidCommandError, InvalidParameterError
from vehicle_sim.core.specs.param_spec import ParamSpec
from vehicle_sim.ros import autoware_interfaces as awi
from vehicle_sim.ros import bridge_interfaces as bi
from vehicle_sim.ros.endpoints import EACH_COMMAND, EACH_STATUS, Outputs, serve, subscribe
from vehicle_sim.ros.node_support import declare_parameters, run_main
from vehicle_sim.transport.logger import ThrottledWarning
from vehicle_sim.transport.ros_time import Time
from vehicle_sim.transport.selection import create_node


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
    _joint_sides(value)
    return None


# The node's own parameters; the kinematic ones are core's BRIDGE_PARAM_SPECS.
NODE_PARAMETERS = (
    awi.INPUT_TYPE_PARAMETER,
    # The output switches are the rows' ``switch`` (bridge_interfaces.BRIDGE_OUTPUTS).
    ParamSpec('publish_differential_command', kind='bool', default=True,
              doc=f'publish {bi.DIFFERENTIAL_COMMAND_OUT.ros_type} on '
                  f'{bi.DIFFERENTIAL_COMMAND_OUT.name}'),
    ParamSpec('publish_wheel_velocities', kind='bool', default=True,
              doc=f'publish {bi.WHEEL_VELOCITIES_OUT.ros_type} [rad/s] on '
                  f'{bi.WHEEL_VELOCITIES_OUT.name}'),
    ParamSpec('publish_twist', kind='bool', default=False,
              doc=f'publish {bi.TWIST_OUT.ros_type} on {bi.TWIST_OUT.name}'),
    ParamSpec('publish_twist_stamped', kind='bool', default=False,
              doc=f'publish {bi.TWIST_STAMPED_OUT.ros_type} on {bi.TWIST_STAMPED_OUT.name}'),
    ParamSpec('wheel_joints', kind='str_list', default=('left_wheel_joint', 'right_wheel_joint'),
              doc='driven joints, in Float64MultiArray order; "left"/"right" in a name gives '
                  'its side', check=_wheel_joints),
    ParamSpec('control_rate_hz', kind='float', default=50.0, unit='Hz', gt=0.0,
              doc='control tick rate (ramps, watchdog; node clock)'),
    ParamSpec('status_rate_hz', kind='float', default=30.0, unit='Hz', gt=0.0,
              doc='feedback report rate (wall time)'),
    ParamSpec('vehicle_status', kind='bool', default=True,
              doc='publish the /vehicle/status reports and serve /control/control_mode_request'),
    ParamSpec('frame_id', kind='str', default='base_link',
              doc='frame_id of stamped outputs and VelocityReport'),
)
BRIDGE_NODE_PARAMETERS = BRIDGE_PARAM_SPECS + NODE_PARAMETERS


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
        values = declare_parameters(node, BRIDGE_NODE_PARAMETERS)
        self.params = bridge_params_from_dict(
            {spec.key: values[spec.attr] for spec in BRIDGE_PARAM_SPECS},
            source=node.get_fully_qualified_name())
        self.input_type = values['input_type']
        twist_input = self.input_type == awi.TWIST_STAMPED
        self.controller = BridgeController(self.params, twist_input=twist_input)
        self.wheel_joints = tuple(values['wheel_joints'])
        self._sides = _joint_sides(self.wheel_joints)
        self._frame_id = values['frame_id']
        self._control_period_s = 1.0 / values['control_rate_hz']
        self._use_sim_time = bool(node.get_parameter('use_sim_time'))
        self._last_clock_s = None
        self._last_tick_s = None
        self._last_tick_period = None
        self._warn = ThrottledWarning(node.get_logger())
        self.rejected = 0
        self._measured = None        # (v [m/s], yaw rate [rad/s]) from joint_states
        self._wire(values)
        warning = self.controller.kinematics.plausibility_warning()
        if warning:
            node.get_logger().warn(warning)
        outputs = ', '.join(p.topic_name for p in self._outputs.publishers.values())
        node.announce_ready(
            f'bridge ready: {self.input_type} on {self._input.name} -> '
            f'{outputs or "no outputs"}; mode {self.params.mode}, wheel_base '
            f'{self.params.wheel_base_m:g} m, tread '
            f'{self.params.wheel_tread_m:g} m, timeout {self.params.command_timeout_s:g} s '
            f'({self.params.timeout_action}){", sim time" if self._use_sim_time else ""}')

    def _wire(self, values):
        # Rows of autoware_interfaces and bridge_interfaces, switched by the node's parameters;
        # the wiring context of the output and status rows is self._wiring.
        node = self.node
        switches = dict(values, use_sim_time=self._use_sim_time)
        self._wiring = SimpleNamespace(frame_id=self._frame_id, wheel_sides=self._sides)
        self._outputs = Outputs(node, bi.BRIDGE_OUTPUTS, self._wiring, switches=switches)
        self._status = Outputs(node, awi.STATUS_TOPICS, self._wiring, switches=switches)
        self._input = awi.BRIDGE_INPUTS[self.input_type]
        self._read_command = self._input.converter
        self._subs = subscribe(node, {
            self._input: self._on_command,
            awi.GEAR_COMMAND: self._on_gear_cmd,
            awi.TURN_INDICATORS_COMMAND: self._on_turn_indicators_cmd,
            awi.HAZARD_LIGHTS_COMMAND: self._on_hazard_lights_cmd,
            bi.JOINT_STATES_IN: self.handle_joint_states,
            bi.CLOCK_IN: self._on_clock}, switches=switches)
        self._services = serve(node, {
            awi.CONTROL_MODE_REQUEST: self._handle_control_mode_request}, switches=switches)
        self._status_timer = None
        if values['vehicle_status']:
            self._status_timer = node.create_timer(1.0 / values['status_rate_hz'],
                                                   self.publish_status)
        self._control_timer = None
        if not self._use_sim_time:
            self._control_timer = node.create_timer(self._control_period_s, self._on_timer)

    # ---------------------------------------------------------------- time
    def now_s(self):
        """
        Node clock [s]: sim time (latest /clock) under use_sim_time, else wall time.

        Under use_sim_time the time of the latest /clock message this node handled wins: the
        control ticks run on those messages, so command receipt times and ticks share one time
        source (the port's node clock, a second /clock subscription, may be served earlier and
        run a step ahead: a command would then look newer than the tick and trip the watchdog).
        """
        if self._use_sim_time and self._last_clock_s is not None:
            return self._last_clock_s
        now = self.node.now().nanoseconds * 1e-9
        if self._last_clock_s is not None and self._last_clock_s > now:
            return self._last_clock_s
        return now

    def _on_clock(self, msg):
        now_s = bi.CLOCK_IN.converter(msg)
        self._last_clock_s = now_s
        # the period's index, robust to the rounding of multiples (0.06 / 0.02 = 2.9999...)
        period = math.floor(now_s / self._control_period_s + 1e-6)
        if self._last_tick_s is None or now_s < self._last_tick_s or \
                period != self._last_tick_period:
            # the first /clock of a period, or sim time went back (a reset): tick
            self._last_tick_s = now_s
            self._last_tick_period = period
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
        if self._outputs.publishers:
            self._outputs.publish(EACH_COMMAND, SimpleNamespace(stamp=self._stamp(now_s),
                                                                command=command))

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
                f'control_mode_request {control_mode_refusal(request.mode)}')
        return response

    def handle_joint_states(self, msg):
        """Take the measured wheel speeds [rad/s] of ``wheel_joints`` from a JointState."""
        names, velocities = bi.JOINT_STATES_IN.converter(msg)
        if not velocities:
            return
        index = {name: i for i, name in enumerate(names)}
        sums = {'left': [0.0, 0], 'right': [0.0, 0]}
        for joint, side in zip(self.wheel_joints, self._sides):
            i = index.get(joint)
            if i is not None and i < len(velocities) and math.isfinite(velocities[i]):
                sums[side][0] += velocities[i]
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

    def status_report(self):
        """Return the VehicleReport of the status rows (velocity/steering once measured)."""
        controller = self.controller
        speed = yaw_rate = steering = None
        if self._measured is not None:
            speed, yaw_rate = self._measured
            steering = equivalent_steering_rad(speed, yaw_rate, self.params.wheel_base_m)
        return awi.VehicleReport(self._stamp(self.now_s()), speed, yaw_rate, steering,
                                controller.gear, controller.turn_indicators,
                                controller.hazard_lights, controller.control_mode)

    def publish_status(self):
        """Publish the six /vehicle/status reports (velocity/steering only once measured)."""
        if self._status.publishers:
            self._status.publish(EACH_STATUS, self.status_report())

    def destroy(self):
        """Leave the graph."""
        self.node.shutdown()


def main(args=None):
    """Run the bridge until SIGINT/SIGTERM (``ros2 run vehicle_sim ackermann_to_differential``)."""
    return run_main(bi.BRIDGE_NODE_NAME, lambda argv: AckermannToDifferentialNode(argv).node,
                    args)


if __name__ == '__main__':
    sys.exit(main())
