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
The interface tables of the bridge, the simulated differential robot and the Autoware side.

Rows are :mod:`.endpoints` rows. The bridge (``ackermann_to_differential``) and
``autoware_automobile`` share the Autoware side (command inputs, gear/lights commands,
control-mode service, the six ``/vehicle/status`` reports); the bridge adds the vehicle side;
the robot (``diff_robot``) has its own rows. Nodes, tests, the launch file and docs/autoware.md
(:func:`autoware_side_markdown`, :func:`vehicle_side_markdown`, :func:`robot_markdown`) read
these tables. Names are absolute except the robot's, which are private names of
the robot node (default ``/diff_robot``). ``/clock``, ``/tf`` and ``/tf_static`` are the shared
rows of :mod:`.endpoints`; the bridge reads ``/clock`` best effort, as rclpy's TimeSource does.

Converter contexts. Status rows: wiring ``w.frame_id``; call: a :class:`VehicleReport`. Bridge
outputs: wiring ``w.frame_id`` and ``w.wheel_sides`` ('left'/'right' per ``wheel_joints``
entry); call ``ctx.stamp`` and ``ctx.command`` (core DiffDriveCommand). Robot rows: wiring
``w.joint_names``, ``w.odom_frame``, ``w.base_frame``, ``w.urdf``, ``w.frame_prefix``; call
``ctx.stamp``, ``ctx.joints`` (positions, velocities), ``ctx.odom`` and ``ctx.ground_truth``
(xyz, q, linear, angular), and for the collision and sensor rows the attributes listed in
``ros/sensor_interfaces.py``. Input rows convert a message to the node's command.
"""

from dataclasses import dataclass
from typing import Optional

from vehicle_sim.core.specs.param_spec import ParamSpec
from vehicle_sim.core.specs.units import stamp_to_seconds
from vehicle_sim.ros import messages as m
from vehicle_sim.ros.endpoints import (
    CLOCK,
    CMD_VEL,
    CMD_VEL_STAMPED,
    converter,
    EACH_COMMAND,
    EACH_PUBLISH,
    EACH_STATUS,
    IN,
    ONCE_LATCHED,
    RECEIVED,
    Service,
    service_table_markdown,
    TF,
    TF_STATIC,
    Topic,
    topic_table_markdown,
)
from vehicle_sim.ros.sensor_interfaces import COLLISION
from vehicle_sim.ros.sim_control import vehicle_services, WORLD_INPUTS, WORLD_SERVICES
from vehicle_sim.transport.qos import QOS_CLOCK, QOS_DEFAULT, QOS_LATCHED


def _input(name, ros_type, read, doc, qos=QOS_DEFAULT, unit='', switch=None):
    return Topic(name, ros_type, qos, RECEIVED, read, IN, unit=unit, doc=doc, switch=switch)


# --------------------------------------------------------------------------------------------
# Bridge: Autoware side

CONTROL = 'autoware_control_msgs/msg/Control'
AUTO_ACKERMANN = 'autoware_auto_control_msgs/msg/AckermannControlCommand'
ACKERMANN_DRIVE = 'ackermann_msgs/msg/AckermannDriveStamped'
TWIST_STAMPED = m.TWIST_STAMPED

# input_type parameter value -> the row it is read from (remap to change). The converter gives
# (speed [m/s], steering tire angle [rad, + left] or yaw rate [rad/s]); the bridge and
# autoware_automobile read their commands through it.
BRIDGE_INPUTS = {
    CONTROL: _input('/control/command/control_cmd', CONTROL,
                    lambda msg: (msg.longitudinal.velocity, msg.lateral.steering_tire_angle),
                    'input_type (default): Autoware (autoware_msgs 1.x) control command: v '
                    '[m/s], steering_tire_angle [rad, + left]'),
    AUTO_ACKERMANN: _input('/control/command/control_cmd', AUTO_ACKERMANN,
                           lambda msg: (msg.longitudinal.speed, msg.lateral.steering_tire_angle),
                           'input_type: older Autoware.Auto command: longitudinal.speed [m/s], '
                           'lateral.steering_tire_angle [rad, + left]'),
    ACKERMANN_DRIVE: _input('/ackermann_cmd', ACKERMANN_DRIVE,
                            lambda msg: (msg.drive.speed, msg.drive.steering_angle),
                            'input_type: ackermann_msgs: drive.speed [m/s], drive.steering_angle '
                            '[rad, + left]'),
    TWIST_STAMPED: _input('/cmd_vel', TWIST_STAMPED,
                          lambda msg: (msg.twist.linear.x, msg.twist.angular.z),
                          'input_type: twist.linear.x [m/s], twist.angular.z [rad/s, + left]; '
                          'passed through the limits without the bicycle model'),
}
DEFAULT_INPUT_TYPE = CONTROL

# The input_type parameter of the bridge and of autoware_automobile (one row for both).
INPUT_TYPE_PARAMETER = ParamSpec(
    'input_type', kind='enum', default=DEFAULT_INPUT_TYPE, choices=tuple(BRIDGE_INPUTS),
    doc='message type of the command read; it decides the topic (BRIDGE_INPUTS: '
        '/control/command/control_cmd for the Autoware types)')


def _command_field(msg):
    return msg.command


GEAR_COMMAND = _input('/control/command/gear_cmd', 'autoware_vehicle_msgs/msg/GearCommand',
                      _command_field,
                      'DRIVE/LOW: pass; REVERSE: v = -|v|; PARK/NEUTRAL: zero wheels',
                      switch='vehicle_status')
TURN_INDICATORS_COMMAND = _input(
    '/control/command/turn_indicators_cmd', 'autoware_vehicle_msgs/msg/TurnIndicatorsCommand',
    _command_field, 'reflected in turn_indicators_status', switch='vehicle_status')
HAZARD_LIGHTS_COMMAND = _input(
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


def _frame_id(w):
    return (w.frame_id,)


def _status(name, ros_type, builder, values, doc='', constants=None):
    return Topic(name, ros_type, QOS_DEFAULT, EACH_STATUS, converter(builder, values, constants),
                 doc=doc, switch='vehicle_status')


VELOCITY_STATUS = _status(
    '/vehicle/status/velocity_status', m.VELOCITY_REPORT, m.velocity_report_builder,
    lambda r: None if r.speed_mps is None else (r.stamp, r.speed_mps, r.heading_rate_radps),
    'measured v [m/s] and yaw rate [rad/s]', _frame_id)
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

# --------------------------------------------------------------------------------------------
# Bridge: vehicle side (remap to your drive)


def _output(name, ros_type, builder, values, switch, doc, constants=None):
    return Topic(name, ros_type, QOS_DEFAULT, EACH_COMMAND, converter(builder, values, constants),
                 doc=doc, switch=switch)


def _wheel_velocities(kit, w):
    # One entry per wheel_joints entry, in that order: the speed of its side [rad/s].
    build = kit.builder(m.float64_multi_array_builder)
    left = tuple(side == 'left' for side in w.wheel_sides)

    def convert(ctx):
        command = ctx.command
        return build([command.left_radps if is_left else command.right_radps
                      for is_left in left])
    return convert


DIFFERENTIAL_COMMAND_OUT = _output(
    '/vehicle/differential_command', m.DIFFERENTIAL_COMMAND, m.differential_command_builder,
    lambda c: (c.stamp, c.command.left_mps, c.command.right_mps),
    'publish_differential_command', 'left/right tyre-surface speeds [m/s]', _frame_id)
WHEEL_VELOCITIES_OUT = Topic(
    '/vehicle/wheel_velocities', m.FLOAT64_MULTI_ARRAY, QOS_DEFAULT, EACH_COMMAND,
    _wheel_velocities, switch='publish_wheel_velocities',
    doc='ros2_control velocity controllers: rad/s, one entry per joint in wheel_joints order')
TWIST_OUT = _output('/vehicle/cmd_vel', m.TWIST, m.twist_builder,
                    lambda c: (c.command.speed_mps, c.command.yaw_rate_radps), 'publish_twist',
                    'applied v [m/s] and yaw rate [rad/s]')
TWIST_STAMPED_OUT = _output(
    '/vehicle/cmd_vel_stamped', TWIST_STAMPED, m.twist_stamped_builder,
    lambda c: (c.stamp, c.command.speed_mps, c.command.yaw_rate_radps), 'publish_twist_stamped',
    "the same, stamped (Jazzy's diff_drive_controller)", _frame_id)
BRIDGE_OUTPUTS = (DIFFERENTIAL_COMMAND_OUT, WHEEL_VELOCITIES_OUT, TWIST_OUT, TWIST_STAMPED_OUT)

JOINT_STATES_IN = _input('/vehicle/joint_states', m.JOINT_STATE,
                         lambda msg: (msg.name, msg.velocity),
                         'measured wheel speeds [rad/s] for the feedback reports',
                         switch='vehicle_status')
# The one /clock row, read best effort (rclpy's TimeSource profile); the converter gives [s].
CLOCK_IN = _input(CLOCK.name, CLOCK.ros_type,
                  lambda msg: stamp_to_seconds(msg.clock.sec, msg.clock.nanosec),
                  'node clock for the watchdog and ramps (use_sim_time)', QOS_CLOCK, 's',
                  switch='use_sim_time')

# --------------------------------------------------------------------------------------------
# The simulated differential robot (private names of its node, default /diff_robot)

ROBOT_NODE_NAME = 'diff_robot'
BRIDGE_NODE_NAME = 'ackermann_to_differential'

ROBOT_DIFFERENTIAL_COMMAND = _input(
    'differential_command', m.DIFFERENTIAL_COMMAND,
    lambda msg: (msg.left_wheel.velocity, msg.right_wheel.velocity),
    'left/right tyre-surface speeds [m/s]')
ROBOT_WHEEL_VELOCITIES = _input('wheel_velocities', m.FLOAT64_MULTI_ARRAY,
                                lambda msg: list(msg.data),
                                'rad/s, one entry per joint in wheel_joints order')
ROBOT_JOINT_STATES = Topic(
    'joint_states', m.JOINT_STATE, QOS_DEFAULT, EACH_PUBLISH,
    converter(m.joint_state_builder, lambda r: (r.stamp,) + r.joints,
              lambda w: (w.joint_names,)),
    unit='rad, rad/s', doc='driven wheels: position [rad], velocity [rad/s]')
ROBOT_ODOM = Topic(
    'odom', m.ODOMETRY, QOS_DEFAULT, EACH_PUBLISH,
    converter(m.odometry_builder, lambda r: (r.stamp,) + r.odom,
              lambda w: (w.odom_frame, w.base_frame)),
    unit='m, rad, m/s, rad/s',
    doc='wheel odometry (ideal differential law, integrate_pose), <p>odom -> <p>base_link')
ROBOT_GROUND_TRUTH_ODOM = Topic(
    'ground_truth/odom', m.ODOMETRY, QOS_DEFAULT, EACH_PUBLISH,
    converter(m.odometry_builder, lambda r: (r.stamp,) + r.ground_truth,
              lambda w: ('world', w.base_frame)),
    unit='m, rad, m/s, rad/s', doc='ground truth from the physics, frame world')
ROBOT_ROBOT_DESCRIPTION = Topic('robot_description', m.STRING, QOS_LATCHED, ONCE_LATCHED,
                                converter(m.string_builder, lambda r: (r.urdf,)), doc='URDF')
ROBOT_TIME_STEP = Service('robot/time_step', 'vehicle_msgs/srv/SetInt', kind='time_step',
                          value='int', unit='ms',
                          doc='synchronous mode: advance value ms (a multiple of the step, '
                              '0 = one step)')
# The robot's rows: inputs, then outputs in publishing order. Its publish period is the basic
# step; /clock is published only while the node owns its world, /tf while publish_tf. Its
# mounted sensors add their rows (ros/sensor_interfaces.py).
# cmd_vel is wired as CMD_VEL, or as CMD_VEL_STAMPED with the cmd_vel_stamped parameter.
ROBOT_INPUTS = (ROBOT_DIFFERENTIAL_COMMAND, ROBOT_WHEEL_VELOCITIES, CMD_VEL)
ROBOT_OUTPUTS = (CLOCK, ROBOT_JOINT_STATES, ROBOT_ODOM, ROBOT_GROUND_TRUTH_ODOM, TF, TF_STATIC,
                 ROBOT_ROBOT_DESCRIPTION, COLLISION)
# <ns>/reset and <ns>/set_pose (ros/sim_control.py); the node that owns its world also serves
# /sim/reset, /sim/pause and reads /initialpose (sim_control.WORLD_SERVICES, WORLD_INPUTS).
ROBOT_POSE_SERVICES = vehicle_services(
    '', 'back to the spawn pose at rest, wheel angles and commands 0, wheel odometry 0')
ROBOT_SERVICES = (ROBOT_TIME_STEP,) + ROBOT_POSE_SERVICES

# --------------------------------------------------------------------------------------------
# Docs (docs/autoware.md embeds these; a test checks it)

_COLUMNS = ('type', 'direction', 'QoS', 'published', 'switch', 'notes')


def autoware_side_markdown() -> str:
    """Return the tables of the Autoware side (bridge and autoware_automobile)."""
    rows = tuple(BRIDGE_INPUTS.values()) + COMMAND_INPUTS + STATUS_TOPICS
    return (topic_table_markdown(rows, _COLUMNS) + '\n' +
            service_table_markdown((CONTROL_MODE_REQUEST,)))


def vehicle_side_markdown() -> str:
    """Return the table of the bridge's vehicle side."""
    return topic_table_markdown(BRIDGE_OUTPUTS + (JOINT_STATES_IN, CLOCK_IN), _COLUMNS)


def robot_markdown() -> str:
    """Return the tables of the simulated robot (names under its default node name)."""
    def name(row):
        return row.name if row.name.startswith('/') else f'/{ROBOT_NODE_NAME}/{row.name}'
    rows = ROBOT_INPUTS + (CMD_VEL_STAMPED,) + ROBOT_OUTPUTS
    return (topic_table_markdown(rows + WORLD_INPUTS, _COLUMNS[:-2] + ('unit', 'notes'), name)
            + '\n' + service_table_markdown(ROBOT_SERVICES + WORLD_SERVICES, name))
