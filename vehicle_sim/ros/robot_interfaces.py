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
The interface table of the simulated differential-drive robot (``diff_robot``).

Names are private names of the robot node (default ``/diff_robot``) except the shared rows of
:mod:`.endpoints` (``/clock``, ``/tf``, ``/tf_static``, ``cmd_vel``). Rows are :mod:`.endpoints`
rows; docs/autoware.md embeds :func:`robot_markdown`.

Converter contexts: wiring ``w.joint_names``, ``w.odom_frame``, ``w.base_frame``, ``w.urdf``,
``w.frame_prefix``; call ``ctx.stamp``, ``ctx.joints`` (positions, velocities), ``ctx.odom`` and
``ctx.ground_truth`` (xyz, q, linear, angular), and for the collision and sensor rows the
attributes listed in ``ros/sensor_interfaces.py``. Input rows convert a message to a command.
"""

from vehicle_sim.ros import messages as m
from vehicle_sim.ros.endpoints import (
    CLOCK,
    CMD_VEL,
    CMD_VEL_STAMPED,
    converter,
    DOC_COLUMNS,
    EACH_PUBLISH,
    input_topic,
    ONCE_LATCHED,
    Service,
    service_table_markdown,
    TF,
    TF_STATIC,
    Topic,
    topic_table_markdown,
)
from vehicle_sim.ros.sensor_interfaces import COLLISION
from vehicle_sim.ros.sim_control import vehicle_services, WORLD_INPUTS, WORLD_SERVICES
from vehicle_sim.transport.qos import QOS_DEFAULT, QOS_LATCHED

ROBOT_NODE_NAME = 'diff_robot'

ROBOT_DIFFERENTIAL_COMMAND = input_topic(
    'differential_command', m.DIFFERENTIAL_COMMAND,
    lambda msg: (msg.left_wheel.velocity, msg.right_wheel.velocity),
    'left/right tyre-surface speeds [m/s]')
ROBOT_WHEEL_VELOCITIES = input_topic('wheel_velocities', m.FLOAT64_MULTI_ARRAY,
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


def robot_markdown() -> str:
    """Return the tables of the simulated robot (names under its default node name)."""
    def name(row):
        return row.name if row.name.startswith('/') else f'/{ROBOT_NODE_NAME}/{row.name}'
    rows = ROBOT_INPUTS + (CMD_VEL_STAMPED,) + ROBOT_OUTPUTS
    return (topic_table_markdown(rows + WORLD_INPUTS, DOC_COLUMNS[:-2] + ('unit', 'notes'), name)
            + '\n' + service_table_markdown(ROBOT_SERVICES + WORLD_SERVICES, name))
