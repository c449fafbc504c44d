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
The ``autoware_automobile`` node: Autoware's vehicle interface on a simulated Webots car.

The same Autoware inputs as the bridge (``ros/autoware_interfaces.py``: the command of
``input_type`` on /control/command/control_cmd by default, gear, turn indicators, hazard lights,
/control/control_mode_request) drive a car, and the same /vehicle/status/* reports come back from
the car's own data. The node composes an :class:`AutomobileNode` on the same ROS node, so the
car's /automobile/*, /robot/time_step (synchronous stepping), /clock, odometry and TF stay
available; the mapping is ``core/autoware/car.py`` (units and signs through
``core/specs/units.py``). Behaviour, parameters and the gear table: docs/end_to_end.md.

Run: ``ros2 run vehicle_sim autoware_automobile --ros-args -p car_model:=ToyotaPrius`` or
``python -m vehicle_sim.ros.autoware_automobile_node --ros-args -p synchronous:=true``.
"""

import math
import sys
from types import SimpleNamespace

from vehicle_sim.core.autoware.car import (
    AutowareCar,
    car_report,
    gear_action_of_command,
    GEAR_REPORT,
    INDICATOR_OF_COMMAND,
    INDICATOR_REPORT,
    set_car_indicator,
)
from vehicle_sim.core.autoware.codes import (
    check_gear,
    check_hazard_lights,
    check_turn_indicators,
    control_mode_refusal,
    DISABLE,
    GEAR_NONE,
    HAZARD_ENABLE,
    is_supported_control_mode,
    MODE_AUTONOMOUS,
    NO_COMMAND,
)
from vehicle_sim.core.bridge.ackermann_mapping import equivalent_steering_rad
from vehicle_sim.core.commands.watchdog import (
    DEFAULT_TIMEOUT_ACTION,
    DEFAULT_TIMEOUT_S,
    TIMEOUT_ACTIONS,
)
from vehicle_sim.core.specs.errors import InvalidCommandError, InvalidParameterError
from vehicle_sim.core.specs.param_spec import ParamSpec
from vehicle_sim.ros import autoware_interfaces as awi
from vehicle_sim.ros.automobile_node import AutomobileNode  # composed on this node
from vehicle_sim.ros.endpoints import EACH_STATUS, Outputs, serve, subscribe
from vehicle_sim.ros.messages import stamp_builder
from vehicle_sim.ros.node_support import declare_parameters, run_main
from vehicle_sim.transport import create_node
from vehicle_sim.transport.logger import ThrottledWarning

NODE_NAME = 'autoware_automobile'

# The node's own parameters (the car and world ones are the automobile node's).
AUTOWARE_PARAMETERS = (
    awi.INPUT_TYPE_PARAMETER,
    ParamSpec('vehicle_namespace', kind='str', default='', empty=True,
              doc="namespace of the world's vehicle to drive ('' = the default car)"),
    ParamSpec('command_timeout_s', kind='float', default=DEFAULT_TIMEOUT_S, unit='s', ge=0.0,
              doc='age of the last accepted command (receipt, sim time) after which '
                  'timeout_action applies (0 disables)'),
    ParamSpec('timeout_action', kind='enum', default=DEFAULT_TIMEOUT_ACTION,
              choices=TIMEOUT_ACTIONS,
              doc='brake: a safety stop (throttle released, full brake); coast: neutral; hold: '
                  'keep the last command'),
    ParamSpec('status_rate_hz', kind='float', default=30.0, unit='Hz', gt=0.0,
              doc='rate of the /vehicle/status reports (simulated time)'),
    ParamSpec('frame_id', kind='str', default='base_link', doc='frame_id of VelocityReport'),
)


class _StepHook:
    """World hook: runs after the car's own pre_step (registered later), once per basic step."""

    def __init__(self, callback):
        self.pre_step = callback


class AutowareAutomobileNode:
    """
    Autoware's vehicle interface on a simulated car.

    In-process API (tests, runners): :meth:`handle_command` (a message of ``input_type``),
    :meth:`handle_gear`, :meth:`handle_turn_indicators`, :meth:`handle_hazard_lights`,
    :meth:`request_control_mode`, :meth:`status_messages`, :attr:`automobile` (the composed
    AutomobileNode: ``step_once()``, ``step(n)``, ``world``), :attr:`car` (SimulatedCar),
    :attr:`state` (core AutowareCar), :meth:`close`.

    :param args: command line (``--ros-args`` part applied).
    :param transport: 'auto', 'rclpy' or 'dds'.
    :param parameter_overrides: parameter values that win over the command line.
    """

    def __init__(self, args=None, *, transport=None, parameter_overrides=None):
        self.node = create_node(NODE_NAME, args=args, transport=transport,
                                parameter_overrides=parameter_overrides)
        self.automobile = None
        try:
            # Autoware's command drives the car: the car's own cmd_vel and drive are not wired.
            self.automobile = AutomobileNode(node=self.node, drive_inputs=False)
            self._setup()
        except BaseException:
            self.close()
            raise

    def _setup(self):
        node = self.node
        values = declare_parameters(node, AUTOWARE_PARAMETERS)
        vehicles = self.automobile.vehicles
        namespace = values['vehicle_namespace'].strip('/')
        if namespace not in vehicles:
            raise InvalidParameterError(
                f'vehicle_namespace = {namespace!r}: no such vehicle; known: '
                f'{sorted(vehicles)}')
        self.car = vehicles[namespace]
        self.world = self.automobile.world
        self.state = AutowareCar(self.car.logic, values['command_timeout_s'],
                                 values['timeout_action'])
        self.automobile.add_reset_listener(namespace, self.state.reset)
        self.input_type = values['input_type']
        self._frame_id = values['frame_id']
        step_s = self.world.time_step_s
        self._status_every = max(1, int(round(1.0 / (values['status_rate_hz'] * step_s))))
        self._warn = ThrottledWarning(node.get_logger())
        self.rejected = 0
        self.control_mode = MODE_AUTONOMOUS
        self._wire()
        self.world.add_body(_StepHook(self._on_step))
        limits = self.state.limits
        low, high = limits.autoware_steering_range_rad
        node.announce_ready(
            f'autoware_automobile ready: {self.input_type} on {self._input.name} drives '
            f'{self.car.params.model} (wheel_base {limits.wheelbase_m:g} m, steering tire angle '
            f'[{low:g}, {high:g}] rad, top speed {limits.max_speed_kmh / 3.6:g} m/s); timeout '
            f'{values["command_timeout_s"]:g} s ({values["timeout_action"]})')

    def _wire(self):
        # The Autoware-side rows of autoware_interfaces (the same as the bridge's).
        node = self.node
        self._stamp = stamp_builder(node.msg)
        self._status = Outputs(node, awi.STATUS_TOPICS, SimpleNamespace(frame_id=self._frame_id))
        self._input = awi.BRIDGE_INPUTS[self.input_type]
        self._read_command = self._input.converter
        self._subs = subscribe(node, {
            self._input: self.handle_command,
            awi.GEAR_COMMAND: self.handle_gear,
            awi.TURN_INDICATORS_COMMAND: self.handle_turn_indicators,
            awi.HAZARD_LIGHTS_COMMAND: self.handle_hazard_lights})
        self._services = serve(node, {
            awi.CONTROL_MODE_REQUEST: self._handle_control_mode_request})

    # ---------------------------------------------------------------- time
    def now_s(self):
        """Return the simulated time [s] (the world's)."""
        return self.world.time_s

    def _on_step(self):
        # Runs inside World.step() after the car's logic step: the car's measured state is the
        # one at now_s; watchdog actions take effect from the next step (one basic step later).
        now_s = self.world.time_s
        self.state.tick(now_s)
        if self.world.step_count % self._status_every == 0:
            self.publish_status()

    # ---------------------------------------------------------------- commands
    def handle_command(self, msg, now_s=None):
        """
        Apply one command message of ``input_type`` (receipt time: sim time when None).

        :return: the CarCommand applied; None when rejected or in MANUAL.
        """
        now_s = self.now_s() if now_s is None else now_s
        speed, second = self._read_command(msg)
        try:
            if self.input_type == awi.TWIST_STAMPED:
                # (v, yaw rate) -> the bicycle steering that gives that yaw rate on this car
                if not (math.isfinite(speed) and math.isfinite(second)):
                    raise InvalidCommandError(f'twist ({speed!r} m/s, {second!r} rad/s): '
                                              'must be finite numbers')
                second = equivalent_steering_rad(speed, second, self.state.limits.wheelbase_m)
            return self.state.command(speed, second, now_s)
        except InvalidCommandError as error:
            self.rejected += 1
            self._warn.warn(f'{self.input_type} rejected, the car is unchanged: {error}')
            return None

    def handle_gear(self, msg):
        """Apply a GearCommand (NONE keeps the gear; undefined values are rejected)."""
        gear = self._checked(check_gear, awi.GEAR_COMMAND.converter(msg), 'gear_cmd')
        if gear is not None and gear != GEAR_NONE:
            self.state.set_gear_action(gear_action_of_command(gear))

    def handle_turn_indicators(self, msg):
        """Apply a TurnIndicatorsCommand to the car's indicator (NO_COMMAND keeps it)."""
        command = self._checked(check_turn_indicators,
                                awi.TURN_INDICATORS_COMMAND.converter(msg), 'turn_indicators_cmd')
        if command is not None and command != NO_COMMAND:
            set_car_indicator(self.car.logic, INDICATOR_OF_COMMAND[command])

    def handle_hazard_lights(self, msg):
        """Apply a HazardLightsCommand to the car's hazard flashers (NO_COMMAND keeps them)."""
        command = self._checked(check_hazard_lights, awi.HAZARD_LIGHTS_COMMAND.converter(msg),
                                'hazard_lights_cmd')
        if command is not None and command != NO_COMMAND:
            self.car.logic.set_hazard_flashers(command == HAZARD_ENABLE)

    def _checked(self, check, value, name):
        # The bridge's validation (core/autoware/codes.py); a refused value changes nothing.
        try:
            return check(value)
        except InvalidCommandError as error:
            self.rejected += 1
            self._warn.warn(f'{name} rejected: {error}')
            return None

    def request_control_mode(self, mode):
        """AUTONOMOUS or MANUAL: True (applied); other modes: False, nothing changes."""
        if not is_supported_control_mode(mode):
            return False
        self.state.set_autonomous(mode == MODE_AUTONOMOUS)
        self.control_mode = mode
        return True

    def _handle_control_mode_request(self, request, response):
        response.success = self.request_control_mode(request.mode)
        if not response.success:
            self.node.get_logger().warn(
                f'control_mode_request {control_mode_refusal(request.mode)}')
        return response

    # ---------------------------------------------------------------- reports
    def status_report(self):
        """Return the VehicleReport of the status rows, from the car's own data."""
        report = car_report(self.car.logic)
        return awi.VehicleReport(
            self._stamp(self.now_s()), report.speed_mps, report.heading_rate_radps,
            report.steering_tire_rad, GEAR_REPORT[report.gear_action],
            INDICATOR_REPORT[report.indicator], HAZARD_ENABLE if report.hazard else DISABLE,
            self.control_mode)

    def status_messages(self):
        """Return {status row: message} built from the car's current state."""
        return self._status.messages(EACH_STATUS, self.status_report())

    def publish_status(self):
        """Publish the six /vehicle/status reports."""
        self._status.publish(EACH_STATUS, self.status_report())

    def close(self):
        """Leave the graph and free the physics (idempotent)."""
        if self.automobile is not None:
            self.automobile.close()
        elif self.node is not None:
            self.node.shutdown()


def main(args=None):
    """Entry point ``autoware_automobile``: build the node and spin it (Jazzy main shape)."""
    return run_main(NODE_NAME, AutowareAutomobileNode, args)


if __name__ == '__main__':
    sys.exit(main())
