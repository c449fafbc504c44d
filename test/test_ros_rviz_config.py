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
config/rviz/vehicle_sim.rviz against the automobile node's interface table.

Every topic a display subscribes to is a topic the node publishes for its default car (no
namespace, the node at /automobile), resolved as the node resolves its rows, with the message
type the display reads and the QoS the node offers; the fixed frame is ``world``.
"""

from pathlib import Path

import pytest
import yaml

from vehicle_sim.config import load_car
from vehicle_sim.core.sensors.sets import enable_sensors
from vehicle_sim.ros import automobile_interfaces as itf
from vehicle_sim.ros.automobile_node import NODE_NAME
from vehicle_sim.ros.sensor_interfaces import sensor_rows
from vehicle_sim.ros.sim_params import load_world
from vehicle_sim.transport.names import resolve_name

CONFIG = Path(__file__).resolve().parent.parent / 'config' / 'rviz' / 'vehicle_sim.rviz'
# RViz display class -> the message type it subscribes to (rviz_default_plugins).
DISPLAY_TYPES = {
    'rviz_default_plugins/RobotModel': 'std_msgs/msg/String',
    'rviz_default_plugins/Odometry': 'nav_msgs/msg/Odometry',
    'rviz_default_plugins/LaserScan': 'sensor_msgs/msg/LaserScan',
    'rviz_default_plugins/PointCloud2': 'sensor_msgs/msg/PointCloud2',
    'rviz_default_plugins/Image': 'sensor_msgs/msg/Image',
    'rviz_default_plugins/Range': 'sensor_msgs/msg/Range',
}
RELIABILITY = {'Reliable': 'reliable', 'Best Effort': 'best_effort'}
DURABILITY = {'Volatile': 'volatile', 'Transient Local': 'transient_local'}


@pytest.fixture(scope='module')
def config():
    return yaml.safe_load(CONFIG.read_text(encoding='utf-8'))


def node_topics():
    """{fully-qualified name: row} of the default car, every preset sensor mounted."""
    sensors = enable_sensors(load_car('Car').sensor_set, 'all', 'test')
    course = load_world('obstacle_course', 'Car').vehicles[0]
    rows = (itf.VEHICLE_TOPICS + itf.WORLD_TOPICS + sensor_rows(sensors)
            + sensor_rows(course.sensors))
    return {resolve_name(itf.vehicle_name(row.name, ''), '/', NODE_NAME): row for row in rows}


def displays(config):
    """Every display, groups flattened."""
    found, todo = [], list(config['Visualization Manager']['Displays'])
    while todo:
        display = todo.pop(0)
        found.append(display)
        todo.extend(display.get('Displays', []))
    return found


def subscriptions(config):
    """(display, its topic property) of every display that reads a topic."""
    return [(display, display[key]) for display in displays(config)
            for key in ('Topic', 'Description Topic') if isinstance(display.get(key), dict)]


def test_fixed_frame_is_world_and_the_view_follows_base_link(config):
    manager = config['Visualization Manager']
    assert manager['Global Options']['Fixed Frame'] == 'world'
    # The default car's frames: <p>odom -> <p>base_link with p = '' (docs/ros_interface.md).
    assert manager['Views']['Current']['Target Frame'] == itf.frame_prefix('') + 'base_link'


def test_every_display_topic_is_published_by_the_node_with_its_type_and_qos(config):
    topics = node_topics()
    subscribed = subscriptions(config)
    assert {display['Class'] for display, _ in subscribed} == {
        'rviz_default_plugins/RobotModel', 'rviz_default_plugins/Odometry',
        'rviz_default_plugins/LaserScan', 'rviz_default_plugins/Image'}
    for display, topic in subscribed:
        name = topic['Value']
        assert name in topics, f'{display["Name"]}: {name} is not a topic of the node'
        row = topics[name]
        assert DISPLAY_TYPES[display['Class']] == row.ros_type, name
        assert RELIABILITY[topic['Reliability Policy']] == row.qos.reliability, name
        assert DURABILITY[topic['Durability Policy']] == row.qos.durability, name
        assert topic['History Policy'] == 'Keep Last'


def test_robot_model_reads_the_latched_robot_description_topic(config):
    (model,) = [d for d in displays(config) if d['Class'] == 'rviz_default_plugins/RobotModel']
    assert model['Description Source'] == 'Topic'
    assert model['Description Topic']['Value'] == '/robot_description'
    assert model['Description Topic']['Durability Policy'] == 'Transient Local'
    assert model['TF Prefix'] == ''   # the URDF's names carry the prefix already


def test_tf_display_is_on_and_the_only_tool_topic_is_initialpose(config):
    assert any(d['Class'] == 'rviz_default_plugins/TF' and d['Enabled']
               for d in displays(config))
    tool_topics = [tool['Topic']['Value'] for tool in config['Visualization Manager']['Tools']
                   if 'Topic' in tool]
    assert tool_topics == ['/initialpose']


def test_launch_feeds_robot_state_publisher_the_urdf_the_node_publishes():
    # launch/automobile.launch.py rviz:=true calls robot_descriptions with the launch arguments
    # and the params file's sensors; the node publishes description() of each vehicle.
    from vehicle_sim.ros.automobile_node import AutomobileNode
    from vehicle_sim.ros.descriptions import robot_descriptions
    app = AutomobileNode(['x', '--ros-args', '-r', '__ns:=/rviz_urdf', '-p', 'world:=two_cars',
                          '-p', 'synchronous:=true', '-p', 'sensors:=[lidar]'], transport='dds')
    try:
        published = {v.spec.namespace: v.description() for v in app._vehicles}
    finally:
        app.close()
    launched = dict(robot_descriptions('Car', 'two_cars', ['lidar']))
    assert sorted(launched) == ['car1', 'car2']
    assert launched == published
    assert '<child link="car1/lidar"/>' in launched['car1']


def test_descriptions_command_prints_json_and_refuses_an_unknown_car_in_one_line():
    # What the launch file runs with the node's interpreter.
    import json
    import subprocess
    import sys

    from vehicle_sim.ros.descriptions import robot_descriptions
    command = [sys.executable, '-m', 'vehicle_sim.ros.descriptions']
    ok = subprocess.run(command + ['Car', 'default', 'lidar'], capture_output=True, text=True,
                        timeout=120)
    assert ok.returncode == 0, ok.stderr
    assert json.loads(ok.stdout) == [list(d) for d in robot_descriptions('Car', 'default',
                                                                         ['lidar'])]
    bad = subprocess.run(command + ['Nope', 'default'], capture_output=True, text=True,
                         timeout=120)
    assert bad.returncode == 2 and bad.stdout == ''
    assert len(bad.stderr.splitlines()) == 1 and "unknown car 'Nope'" in bad.stderr
