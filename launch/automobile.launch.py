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
Launch the automobile node (Webots ros_automobile interface on PyBullet), and optionally RViz.

Example: ``ros2 launch vehicle_sim automobile.launch.py car_model:=ToyotaPrius synchronous:=true``

``rviz:=true`` also starts one robot_state_publisher per vehicle (in the vehicle's namespace, fed
the URDF the node publishes on ``<ns>/robot_description``, so RViz's RobotModel gets the TF of
every link from ``<ns>/joint_states``) and rviz2 with config/rviz/vehicle_sim.rviz. Both run on
simulated time: every stamp the node publishes is simulated time.
"""

import json
import os
import shlex
import subprocess
import sys

from ament_index_python.packages import get_package_prefix, get_package_share_directory
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, OpaqueFunction
from launch.conditions import IfCondition
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node
from launch_ros.parameter_descriptions import ParameterValue
import yaml


def _node_python():
    # The interpreter of the installed node (its shebang): the one with PyBullet, which the
    # Python running `ros2 launch` may lack.
    executable = os.path.join(get_package_prefix('vehicle_sim'), 'lib', 'vehicle_sim',
                              'automobile')
    with open(executable, encoding='utf-8') as stream:
        first = stream.readline()
    return shlex.split(first[2:]) if first.startswith('#!') else [sys.executable]


def _robot_state_publishers(context, config):
    # One per vehicle of the world the node runs, fed the URDF of the node's own function
    # (vehicle_sim/ros/descriptions.py) with the sensors parameter of the params file.
    with open(config, encoding='utf-8') as stream:
        sensors = yaml.safe_load(stream)['automobile']['ros__parameters'].get('sensors', [''])
    car_model = LaunchConfiguration('car_model').perform(context)
    world = LaunchConfiguration('world').perform(context)
    result = subprocess.run(
        _node_python() + ['-m', 'vehicle_sim.ros.descriptions', car_model, world,
                          *[name for name in sensors if name]],
        capture_output=True, text=True, check=False)
    if result.returncode != 0:
        raise RuntimeError(f'vehicle_sim: no URDF for car_model {car_model!r}, world '
                           f'{world!r}: {result.stderr.strip()}')
    return [Node(package='robot_state_publisher', executable='robot_state_publisher',
                 namespace=namespace, output='screen',
                 parameters=[{'robot_description': urdf, 'use_sim_time': True}],
                 # The node publishes <ns>/robot_description itself; this copy goes aside.
                 remappings=[('robot_description', 'robot_state_publisher/robot_description')])
            for namespace, urdf in json.loads(result.stdout)]


def generate_launch_description():
    share = get_package_share_directory('vehicle_sim')
    config = os.path.join(share, 'config', 'automobile.yaml')
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
        DeclareLaunchArgument('gui', default_value='false',
                              description="open PyBullet's window with a chase camera"),
        DeclareLaunchArgument('rviz', default_value='false',
                              description='also start robot_state_publisher and rviz2'),
        DeclareLaunchArgument('rviz_config',
                              default_value=os.path.join(share, 'config', 'rviz',
                                                         'vehicle_sim.rviz'),
                              description='RViz configuration file'),
    ]
    overrides = {
        'car_model': LaunchConfiguration('car_model'),
        'world': LaunchConfiguration('world'),
        'synchronous': ParameterValue(LaunchConfiguration('synchronous'), value_type=bool),
        'real_time_factor': ParameterValue(LaunchConfiguration('real_time_factor'),
                                           value_type=float),
        'use_sim_time': ParameterValue(LaunchConfiguration('use_sim_time'), value_type=bool),
        'gui': ParameterValue(LaunchConfiguration('gui'), value_type=bool),
    }
    node = Node(package='vehicle_sim', executable='automobile', name='automobile',
                output='screen', parameters=[config, overrides])
    rviz = IfCondition(LaunchConfiguration('rviz'))
    # The publishers come first: a refused car or world, or a missing robot_state_publisher,
    # stops the launch before the node starts.
    publishers = OpaqueFunction(function=_robot_state_publishers, args=[config], condition=rviz)
    viewer = Node(package='rviz2', executable='rviz2', name='rviz2', output='screen',
                  arguments=['-d', LaunchConfiguration('rviz_config')],
                  parameters=[{'use_sim_time': True}], condition=rviz)
    return LaunchDescription(arguments + [publishers, node, viewer])
