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
config/foxglove/vehicle_sim.json (the shipped Foxglove layout) against the node's interface.

Every topic a panel reads is one the automobile node publishes for its default car (every preset
sensor mounted) or one of the live view's own (the scene); a plotted field is a field of its
topic's message; the layout tree holds exactly the configured panels.
"""

import json
from pathlib import Path

import pytest

import vehicle_msgs_py
from vehicle_sim.config import load_car
from vehicle_sim.core.sensors.sets import enable_sensors
from vehicle_sim.foxglove.live_view import SCENE_TOPIC, TRANSFORMS_TOPIC
from vehicle_sim.ros import automobile_interfaces as itf
from vehicle_sim.ros.automobile_node import NODE_NAME
from vehicle_sim.ros.sensor_interfaces import sensor_rows
from vehicle_sim.transport.names import resolve_name

LAYOUT = Path(__file__).resolve().parent.parent / 'config' / 'foxglove' / 'vehicle_sim.json'
LIVE_VIEW_TOPICS = {SCENE_TOPIC: 'foxglove.SceneUpdate',
                    TRANSFORMS_TOPIC: 'foxglove.FrameTransforms'}


@pytest.fixture(scope='module')
def layout():
    return json.loads(LAYOUT.read_text(encoding='utf-8'))


def node_topics():
    """{fully-qualified name: ROS type} of the default car with every preset sensor."""
    sensors = enable_sensors(load_car('Car').sensor_set, 'all', 'test')
    rows = itf.VEHICLE_TOPICS + itf.WORLD_TOPICS + sensor_rows(sensors)
    return {resolve_name(itf.vehicle_name(row.name, ''), '/', NODE_NAME): row.ros_type
            for row in rows}


def panels_in(tree):
    if isinstance(tree, str):
        return [tree]
    return panels_in(tree['first']) + panels_in(tree['second'])


def field_names(ros_type):
    """Return the top-level field names of a message (its definition's first block)."""
    own = vehicle_msgs_py.message_definition(ros_type).split('=' * 80)[0]
    return {line.split()[1] for line in own.splitlines() if line.strip()
            and not line.startswith('#')}


def test_the_layout_tree_holds_exactly_the_configured_panels(layout):
    placed = panels_in(layout['layout'])
    assert sorted(placed) == sorted(layout['configById'])
    assert {panel.split('!')[0] for panel in placed} == {'3D', 'Plot', 'Image'}


def test_plots_show_speed_rpm_and_steering_fields_the_node_publishes(layout):
    topics = node_topics()
    plotted = {}
    for panel, config in layout['configById'].items():
        if panel.startswith('Plot!'):
            for path in config['paths']:
                topic, field = path['value'].rsplit('.', 1)
                assert topic in topics, f'{panel}: {topic} is not a topic of the node'
                assert field in field_names(topics[topic]), f'{panel}: {path["value"]}'
                plotted[topic] = field
    assert {'/automobile/current_speed', '/automobile/rpm', '/automobile/steering_angle'} <= \
        set(plotted)


def test_image_and_3d_panels_read_the_camera_lidar_and_scene(layout):
    topics = node_topics()
    configs = layout['configById']
    image_topic = configs['Image!camera']['imageMode']['imageTopic']
    assert topics[image_topic] == 'sensor_msgs/msg/Image'
    three_d = configs['3D!vehicle_sim']
    shown = {t for t, settings in three_d['topics'].items() if settings.get('visible')}
    assert SCENE_TOPIC in shown
    assert any(topics.get(t) in ('sensor_msgs/msg/LaserScan', 'sensor_msgs/msg/PointCloud2')
               for t in shown)
    for topic in three_d['topics']:
        assert topic in topics or topic in LIVE_VIEW_TOPICS, topic
    assert three_d['followTf'] == 'base_link'
    assert three_d['layers']['grid']['frameId'] == 'world'
