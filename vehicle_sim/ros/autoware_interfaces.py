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
The Autoware side of a vehicle interface: command inputs, status reports, control-mode service.

Shared by the ``ackermann_to_differential`` bridge and ``autoware_automobile``: the command
read (``BRIDGE_INPUTS`` by the ``input_type`` parameter), the gear / turn-indicator /
hazard-light commands, the control-mode service and the six ``/vehicle/status`` reports.
Rows are :mod:`.endpoints` rows; docs/autoware.md embeds :func:`autoware_side_markdown`.

Converter contexts. Status rows: wiring ``w.frame_id``; call: a :class:`VehicleReport`. Input
rows convert a message to the node's command.
"""

from dataclasses import dataclass
from typing import Optional

from vehicle_sim.core.specs.param_spec import ParamSpec
from vehicle_sim.ros import messages as m
from vehicle_sim.ros.endpoints import (
    converter,
    DOC_COLUMNS,
    EACH_STATUS,
    frame_id_wiring,
    input_topic,
    Service,
    service_table_markdown,
    Topic,
    topic_table_markdown,
)
from vehicle_sim.transport.qos import QOS_DEFAULT

CONTROL = 'autoware_control_msgs/msg/Control'
AUTO_ACKERMANN = 'autoware_auto_control_msgs/msg/AckermannControlCommand'
ACKERMANN_DRIVE = 'ackermann_msgs/msg/AckermannDriveStamped'
TWIST_STAMPED = m.TWIST_STAMPED

# input_type parameter value -> the row it is read from (remap to change). The converter gives
# (speed [m/s], steering tire angle [rad, + left] or yaw rate [rad/s]); the bridge and
# autoware_automobile read their commands through it.
BRIDGE_INPUTS = {
    CONTROL: input_topic(
        '/control/command/control_cmd', CONTROL,
        lambda msg: (msg.longitudinal.velocity, msg.lateral.steering_tire_angle),
        'input_type (default): Autoware (autoware_msgs 1.x) control command: v [m/s], '
        'steering_tire_angle [rad, + left]'),
    AUTO_ACKERMANN: input_topic(
        '/control/command/control_cmd', AUTO_ACKERMANN,
        lambda msg: (msg.longitudinal.speed, msg.lateral.steering_tire_angle),
        'input_type: older Autoware.Auto command: longitudinal.speed [m/s], '
        'lateral.steering_tire_angle [rad, + left]'),
    ACKERMANN_DRIVE: input_topic(
        '/ackermann_cmd', ACKERMANN_DRIVE,
        lambda msg: (msg.drive.speed, msg.drive.steering_angle),
        'input_type: ackermann_msgs: drive.speed [m/s], drive.steering_angle [rad, + left]'),
    TWIST_STAMPED: input_topic(
        '/cmd_vel', TWIST_STAMPED,
        lambda msg: (msg.twist.linear.x, msg.twist.angular.z),
        'input_type: twist.linear.x [m/s], twist.angular.z [rad/s, + left]; passed through the '
        'limits without the bicycle model'),
}
DEFAULT_INPUT_TYPE = CONTROL

# The input_type parameter of the bridge and of autoware_automobile (one row for both).
INPUT_TYPE_PARAMETER = ParamSpec(
    'input_type', kind='enum', default=DEFAULT_INPUT_TYPE, choices=tuple(BRIDGE_INPUTS),
    doc='message type of the command read; it decides the topic (BRIDGE_INPUTS: '
        '/control/command/control_cmd for the Autoware types)')


def _command_field(msg):
    return msg.command


GEAR_COMMAND = input_topic('/control/command/gear_cmd', 'autoware_vehicle_msgs/msg/GearCommand',
                           _command_field,
                           'DRIVE/LOW: pass; REVERSE: v = -|v|; PARK/NEUTRAL: zero wheels',
                           switch='vehicle_status')
TURN_INDICATORS_COMMAND = input_topic(
    '/control/command/turn_indicators_cmd', 'autoware_vehicle_msgs/msg/TurnIndicatorsCommand',
    _command_field, 'reflected in turn_indicators_status', switch='vehicle_status')
HAZARD_LIGHTS_COMMAND = input_topic(
    '/control/command/hazard_lights_cmd', 'autoware_vehicle_msgs/msg/HazardLightsCommand',
    _command_field, 'reflected in hazard_lights_status', switch='vehicle_status')
COMMAND_INPUTS = (GEAR_COMMAND, TURN_INDICATORS_COMMAND, HAZARD_LIGHTS_COMMAND)
CONTROL_MODE_REQUEST = Service(
    '/control/control_mode_request', 'autoware_vehicle_msgs/srv/ControlModeCommand',
    kind='control_mode', value='int', switch='vehicle_status',
    doc='AUTONOMOUS or MANUAL (others: success=false)')


@dataclass
class VehicleReport:
    """
    The call context of the status rows: the vehicle state in Autoware's report values.

    ``speed_mps`` (with ``heading_rate_radps``) and ``steering_tire_rad`` are None while not
    measured (their reports are then not published).
    """

    stamp: object
    speed_mps: Optional[float]
    heading_rate_radps: Optional[float]
    steering_tire_rad: Optional[float]
    gear: int
    turn_indicators: int
    hazard_lights: int
    control_mode: int


def _status(name, ros_type, builder, values, doc='', constants=None):
    return Topic(name, ros_type, QOS_DEFAULT, EACH_STATUS, converter(builder, values, constants),
                 doc=doc, switch='vehicle_status')


VELOCITY_STATUS = _status(
    '/vehicle/status/velocity_status', m.VELOCITY_REPORT, m.velocity_report_builder,
    lambda r: None if r.speed_mps is None else (r.stamp, r.speed_mps, r.heading_rate_radps),
    'measured v [m/s] and yaw rate [rad/s]', frame_id_wiring)
STEERING_STATUS = _status(
    '/vehicle/status/steering_status', m.STEERING_REPORT, m.steering_report_builder,
    lambda r: None if r.steering_tire_rad is None else (r.stamp, r.steering_tire_rad),
    'steering tire angle [rad, + left]')
GEAR_STATUS = _status('/vehicle/status/gear_status', m.GEAR_REPORT, m.gear_report_builder,
                      lambda r: (r.stamp, r.gear), 'gear (DRIVE at start-up)')
TURN_INDICATORS_STATUS = _status(
    '/vehicle/status/turn_indicators_status', m.TURN_INDICATORS_REPORT,
    m.turn_indicators_report_builder, lambda r: (r.stamp, r.turn_indicators))
HAZARD_LIGHTS_STATUS = _status(
    '/vehicle/status/hazard_lights_status', m.HAZARD_LIGHTS_REPORT,
    m.hazard_lights_report_builder, lambda r: (r.stamp, r.hazard_lights))
CONTROL_MODE_STATUS = _status(
    '/vehicle/status/control_mode', m.CONTROL_MODE_REPORT, m.control_mode_report_builder,
    lambda r: (r.stamp, r.control_mode), 'AUTONOMOUS at start-up; follows control_mode_request')
STATUS_TOPICS = (VELOCITY_STATUS, STEERING_STATUS, GEAR_STATUS, TURN_INDICATORS_STATUS,
                 HAZARD_LIGHTS_STATUS, CONTROL_MODE_STATUS)


def autoware_side_markdown() -> str:
    """Return the tables of the Autoware side (the bridge and autoware_automobile)."""
    rows = tuple(BRIDGE_INPUTS.values()) + COMMAND_INPUTS + STATUS_TOPICS
    return (topic_table_markdown(rows, DOC_COLUMNS) + '\n' +
            service_table_markdown((CONTROL_MODE_REQUEST,)))
