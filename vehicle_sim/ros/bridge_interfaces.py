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
The vehicle side of the ``ackermann_to_differential`` bridge: what it sends to your drive.

The wheel command in four forms (remap to your drive; each behind its ``publish_*`` switch),
the measured joint states it reads back for the reports, and ``/clock``. Its Autoware side is
:mod:`.autoware_interfaces`. Rows are :mod:`.endpoints` rows; docs/autoware.md embeds
:func:`vehicle_side_markdown`.

Converter contexts. Outputs: wiring ``w.frame_id`` and ``w.wheel_sides`` ('left'/'right' per
``wheel_joints`` entry); call ``ctx.stamp`` and ``ctx.command`` (core DiffDriveCommand). The
bridge reads ``/clock`` best effort, as rclpy's TimeSource does.
"""

from vehicle_sim.core.specs.units import stamp_to_seconds
from vehicle_sim.ros import messages as m
from vehicle_sim.ros.endpoints import (
    CLOCK,
    converter,
    DOC_COLUMNS,
    EACH_COMMAND,
    frame_id_wiring,
    input_topic,
    Topic,
    topic_table_markdown,
)
from vehicle_sim.transport.qos import QOS_CLOCK, QOS_DEFAULT

BRIDGE_NODE_NAME = 'ackermann_to_differential'


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
    'publish_differential_command', 'left/right tyre-surface speeds [m/s]', frame_id_wiring)
WHEEL_VELOCITIES_OUT = Topic(
    '/vehicle/wheel_velocities', m.FLOAT64_MULTI_ARRAY, QOS_DEFAULT, EACH_COMMAND,
    _wheel_velocities, switch='publish_wheel_velocities',
    doc='ros2_control velocity controllers: rad/s, one entry per joint in wheel_joints order')
TWIST_OUT = _output('/vehicle/cmd_vel', m.TWIST, m.twist_builder,
                    lambda c: (c.command.speed_mps, c.command.yaw_rate_radps), 'publish_twist',
                    'applied v [m/s] and yaw rate [rad/s]')
TWIST_STAMPED_OUT = _output(
    '/vehicle/cmd_vel_stamped', m.TWIST_STAMPED, m.twist_stamped_builder,
    lambda c: (c.stamp, c.command.speed_mps, c.command.yaw_rate_radps), 'publish_twist_stamped',
    "the same, stamped (Jazzy's diff_drive_controller)", frame_id_wiring)
BRIDGE_OUTPUTS = (DIFFERENTIAL_COMMAND_OUT, WHEEL_VELOCITIES_OUT, TWIST_OUT, TWIST_STAMPED_OUT)

JOINT_STATES_IN = input_topic('/vehicle/joint_states', m.JOINT_STATE,
                              lambda msg: (msg.name, msg.velocity),
                              'measured wheel speeds [rad/s] for the feedback reports',
                              switch='vehicle_status')
# The one /clock row, read best effort (rclpy's TimeSource profile); the converter gives [s].
CLOCK_IN = input_topic(CLOCK.name, CLOCK.ros_type,
                       lambda msg: stamp_to_seconds(msg.clock.sec, msg.clock.nanosec),
                       'node clock for the watchdog and ramps (use_sim_time)', QOS_CLOCK, 's',
                       switch='use_sim_time')


def vehicle_side_markdown() -> str:
    """Return the table of the bridge's vehicle side (docs/autoware.md)."""
    return topic_table_markdown(BRIDGE_OUTPUTS + (JOINT_STATES_IN, CLOCK_IN), DOC_COLUMNS)
