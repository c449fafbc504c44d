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
Launch the automobile node (Webots ros_automobile interface on PyBullet).

Example: ``ros2 launch vehicle_sim automobile.launch.py car_model:=ToyotaPrius synchronous:=true``
"""

import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node
from launch_ros.parameter_descriptions import ParameterValue


def generate_launch_description():
    config = os.path.join(get_package_share_directory('vehicle_sim'), 'config',
                          'automobile.yaml')
    arguments = [
        DeclareLaunchArgument('car_model', default_value='Car',
                              description='car preset (config/cars) or path to a .yaml'),
        DeclareLaunchArgument('world', default_value='default',
                              description='world (config/worlds) or path to a world .yaml'),
        DeclareLaunchArgument('synchronous', default_value='false',
                              description='step only on robot/time_step calls'),
        DeclareLaunchArgument('real_time_factor', default_value='1.0',
                              description='1 = real time, 0 = as fast as possible'),
        DeclareLaunchArgument('use_sim_time', default_value='false',
                              description='use /clock as the node clock'),
    ]
    overrides = {
        'car_model': LaunchConfiguration('car_model'),
        'world': LaunchConfiguration('world'),
        'synchronous': ParameterValue(LaunchConfiguration('synchronous'), value_type=bool),
        'real_time_factor': ParameterValue(LaunchConfiguration('real_time_factor'),
                                           value_type=float),
        'use_sim_time': ParameterValue(LaunchConfiguration('use_sim_time'), value_type=bool),
    }
    node = Node(package='vehicle_sim', executable='automobile', name='automobile',
                output='screen', parameters=[config, overrides])
    return LaunchDescription(arguments + [node])
