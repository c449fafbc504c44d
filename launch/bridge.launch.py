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
Autoware → differential robot: the simulated robot and the ackermann_to_differential bridge.

``ros2 launch vehicle_sim bridge.launch.py [robot:=skid_steer_robot]``. With
``sim_robot:=false use_sim_time:=false`` only the bridge starts, for a real robot: remap its
outputs to your drive (see docs/autoware.md). The bridge's vehicle-side topics
(/vehicle/differential_command, /vehicle/joint_states) are remapped to the simulated robot's
/diff_robot/* topics, and the bridge runs on the robot's /clock.
"""

import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.conditions import IfCondition
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node


def generate_launch_description():
    config = os.path.join(get_package_share_directory('vehicle_sim'), 'config')
    robot = LaunchConfiguration('robot')
    sim_robot = LaunchConfiguration('sim_robot')
    bridge_params = LaunchConfiguration('bridge_params')
    return LaunchDescription([
        DeclareLaunchArgument('robot', default_value='caster_robot',
                              description='robot preset in config/robots'),
        DeclareLaunchArgument('sim_robot', default_value='true',
                              description='start the simulated robot (false: bridge only)'),
        DeclareLaunchArgument('use_sim_time', default_value='true',
                              description='bridge on /clock (false with a real robot)'),
        DeclareLaunchArgument('bridge_params',
                              default_value=os.path.join(config, 'bridge.yaml'),
                              description='bridge parameters file'),
        Node(
            package='vehicle_sim', executable='diff_robot', name='diff_robot',
            output='screen', condition=IfCondition(sim_robot),
            parameters=[os.path.join(config, 'diff_robot.yaml'), {'robot': robot}]),
        Node(
            package='vehicle_sim', executable='ackermann_to_differential',
            name='ackermann_to_differential', output='screen',
            parameters=[bridge_params, {'use_sim_time': LaunchConfiguration('use_sim_time')}],
            remappings=[
                ('/vehicle/differential_command', '/diff_robot/differential_command'),
                ('/vehicle/joint_states', '/diff_robot/joint_states'),
            ]),
    ])
