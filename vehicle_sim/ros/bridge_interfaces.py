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
The bridge's and the differential robot's ROS interfaces: names, types and QoS, in one place.

Nodes, tests, the launch file and docs/autoware.md read these tables (STYLE rule 9). Names are
absolute except the robot's, which are relative to the robot node's namespace (default
``/diff_robot``). QoS: ros2_wire A6 (default = reliable, volatile, depth 10; /clock
best effort depth 1; /tf reliable depth 100; /tf_static transient local depth 1).
"""

from dataclasses import dataclass

from vehicle_sim.core.params import ParamSpec
from vehicle_sim.transport.port import (
    QOS_CLOCK,
    QOS_DEFAULT,
    QOS_SERVICES,
    QOS_TF,
    QOS_TF_STATIC,
    QosProfile,
)


@dataclass(frozen=True)
class Endpoint:
    """One topic or service: ROS name, ROS type, QoS and a one-line description."""

    name: str
    ros_type: str
    qos: QosProfile = QOS_DEFAULT
    doc: str = ''


# --------------------------------------------------------------------------------------------
# Bridge: Autoware side

CONTROL = 'autoware_control_msgs/msg/Control'
AUTO_ACKERMANN = 'autoware_auto_control_msgs/msg/AckermannControlCommand'
ACKERMANN_DRIVE = 'ackermann_msgs/msg/AckermannDriveStamped'
TWIST_STAMPED = 'geometry_msgs/msg/TwistStamped'

# input_type parameter value -> the topic it is read from (remap to change).
BRIDGE_INPUTS = {
    CONTROL: Endpoint('/control/command/control_cmd', CONTROL,
                      doc='Autoware (autoware_msgs 1.x) control command: v [m/s], '
                          'steering_tire_angle [rad, + left]'),
    AUTO_ACKERMANN: Endpoint('/control/command/control_cmd', AUTO_ACKERMANN,
                             doc='older Autoware.Auto command: longitudinal.speed [m/s], '
                                 'lateral.steering_tire_angle [rad, + left]'),
    ACKERMANN_DRIVE: Endpoint('/ackermann_cmd', ACKERMANN_DRIVE,
                              doc='ackermann_msgs: drive.speed [m/s], drive.steering_angle '
                                  '[rad, + left]'),
    TWIST_STAMPED: Endpoint('/cmd_vel', TWIST_STAMPED,
                            doc='twist.linear.x [m/s], twist.angular.z [rad/s, + left]; '
                                'passed through the limits without the bicycle model'),
}
DEFAULT_INPUT_TYPE = CONTROL

# input_type -> message -> (speed [m/s], steering tire angle [rad, + left] or yaw rate [rad/s]);
# the bridge and autoware_automobile read their commands through it.
COMMAND_READERS = {
    CONTROL: lambda m: (m.longitudinal.velocity, m.lateral.steering_tire_angle),
    AUTO_ACKERMANN: lambda m: (m.longitudinal.speed, m.lateral.steering_tire_angle),
    ACKERMANN_DRIVE: lambda m: (m.drive.speed, m.drive.steering_angle),
    TWIST_STAMPED: lambda m: (m.twist.linear.x, m.twist.angular.z),
}

# The input_type parameter of the bridge and of autoware_automobile (one row for both).
INPUT_TYPE_PARAMETER = ParamSpec(
    'input_type', kind='enum', default=DEFAULT_INPUT_TYPE, choices=tuple(BRIDGE_INPUTS),
    doc='message type of the command read; it decides the topic (BRIDGE_INPUTS: '
        '/control/command/control_cmd for the Autoware types)')

GEAR_COMMAND = Endpoint('/control/command/gear_cmd', 'autoware_vehicle_msgs/msg/GearCommand',
                        doc='DRIVE/LOW: pass; REVERSE: v = -|v|; PARK/NEUTRAL: zero wheels')
TURN_INDICATORS_COMMAND = Endpoint(
    '/control/command/turn_indicators_cmd', 'autoware_vehicle_msgs/msg/TurnIndicatorsCommand',
    doc='reflected in turn_indicators_status')
HAZARD_LIGHTS_COMMAND = Endpoint(
    '/control/command/hazard_lights_cmd', 'autoware_vehicle_msgs/msg/HazardLightsCommand',
    doc='reflected in hazard_lights_status')
CONTROL_MODE_REQUEST = Endpoint(
    '/control/control_mode_request', 'autoware_vehicle_msgs/srv/ControlModeCommand',
    QOS_SERVICES, doc='AUTONOMOUS or MANUAL (others: success=false)')

VELOCITY_STATUS = Endpoint('/vehicle/status/velocity_status',
                           'autoware_vehicle_msgs/msg/VelocityReport',
                           doc='measured v [m/s] and yaw rate [rad/s] from the wheel speeds')
STEERING_STATUS = Endpoint('/vehicle/status/steering_status',
                           'autoware_vehicle_msgs/msg/SteeringReport',
                           doc='bicycle-model steering equivalent to the measured (v, yaw rate)')
GEAR_STATUS = Endpoint('/vehicle/status/gear_status', 'autoware_vehicle_msgs/msg/GearReport',
                       doc='last gear command (DRIVE at start-up)')
TURN_INDICATORS_STATUS = Endpoint('/vehicle/status/turn_indicators_status',
                                  'autoware_vehicle_msgs/msg/TurnIndicatorsReport')
HAZARD_LIGHTS_STATUS = Endpoint('/vehicle/status/hazard_lights_status',
                                'autoware_vehicle_msgs/msg/HazardLightsReport')
CONTROL_MODE_STATUS = Endpoint('/vehicle/status/control_mode',
                               'autoware_vehicle_msgs/msg/ControlModeReport',
                               doc='AUTONOMOUS at start-up; follows control_mode_request')
STATUS_TOPICS = (VELOCITY_STATUS, STEERING_STATUS, GEAR_STATUS, TURN_INDICATORS_STATUS,
                 HAZARD_LIGHTS_STATUS, CONTROL_MODE_STATUS)

# --------------------------------------------------------------------------------------------
# Bridge: vehicle side (remap to your drive)

DIFFERENTIAL_COMMAND_OUT = Endpoint('/vehicle/differential_command',
                                    'vehicle_msgs/msg/DifferentialCommand',
                                    doc='left/right tyre-surface speeds [m/s]')
WHEEL_VELOCITIES_OUT = Endpoint('/vehicle/wheel_velocities', 'std_msgs/msg/Float64MultiArray',
                                doc='ros2_control velocity controllers: rad/s, one entry per '
                                    'joint in wheel_joints order')
TWIST_OUT = Endpoint('/vehicle/cmd_vel', 'geometry_msgs/msg/Twist',
                     doc='applied v [m/s] and yaw rate [rad/s]')
TWIST_STAMPED_OUT = Endpoint('/vehicle/cmd_vel_stamped', 'geometry_msgs/msg/TwistStamped',
                             doc="the same, stamped (Jazzy's diff_drive_controller)")
JOINT_STATES_IN = Endpoint('/vehicle/joint_states', 'sensor_msgs/msg/JointState',
                           doc='measured wheel speeds [rad/s] for the feedback reports')
CLOCK = Endpoint('/clock', 'rosgraph_msgs/msg/Clock', QOS_CLOCK,
                 doc='simulated time (use_sim_time)')

# output switch parameter -> endpoint
BRIDGE_OUTPUTS = {
    'publish_differential_command': DIFFERENTIAL_COMMAND_OUT,
    'publish_wheel_velocities': WHEEL_VELOCITIES_OUT,
    'publish_twist': TWIST_OUT,
    'publish_twist_stamped': TWIST_STAMPED_OUT,
}

# --------------------------------------------------------------------------------------------
# The simulated differential robot (private names of its node, default /diff_robot)

ROBOT_NODE_NAME = 'diff_robot'
BRIDGE_NODE_NAME = 'ackermann_to_differential'

ROBOT_DIFFERENTIAL_COMMAND = Endpoint('differential_command',
                                      'vehicle_msgs/msg/DifferentialCommand',
                                      doc='left/right tyre-surface speeds [m/s]')
ROBOT_WHEEL_VELOCITIES = Endpoint('wheel_velocities', 'std_msgs/msg/Float64MultiArray',
                                  doc='rad/s, one entry per joint in wheel_joints order')
ROBOT_JOINT_STATES = Endpoint('joint_states', 'sensor_msgs/msg/JointState',
                              doc='driven wheels: position [rad], velocity [rad/s]')
ROBOT_ODOM = Endpoint('odom', 'nav_msgs/msg/Odometry',
                      doc='wheel odometry (ideal differential law, integrate_pose)')
ROBOT_GROUND_TRUTH_ODOM = Endpoint('ground_truth/odom', 'nav_msgs/msg/Odometry',
                                   doc='ground truth from the physics, frame world')
ROBOT_ROBOT_DESCRIPTION = Endpoint('robot_description', 'std_msgs/msg/String',
                                   QosProfile(depth=1, durability='transient_local'),
                                   doc='URDF')
ROBOT_TIME_STEP = Endpoint('robot/time_step', 'vehicle_msgs/srv/SetInt', QOS_SERVICES,
                           doc='synchronous mode: advance value ms (a multiple of the step, '
                               '0 = one step)')
TF = Endpoint('/tf', 'tf2_msgs/msg/TFMessage', QOS_TF, doc='<p>odom -> <p>base_link')
TF_STATIC = Endpoint('/tf_static', 'tf2_msgs/msg/TFMessage', QOS_TF_STATIC,
                     doc='world -> <p>odom at the spawn pose')
