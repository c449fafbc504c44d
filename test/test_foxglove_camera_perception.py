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
The live view shows a camera's segmentation and recognition topics (Foxglove channels).

The automobile node in process, its car's camera with segmentation and recognition: the images
(an Image panel shows mono16), the detections and the latched label table are channels with
their ros2msg schemas, the label table kept for clients that come later.
"""

import socket

import pytest
import yaml

pytest.importorskip('foxglove', reason="foxglove-sdk is not installed (pip install "
                                       "'vehicle_sim[foxglove]')")

import vehicle_msgs_py  # noqa: E402
from vehicle_sim.core.sensors.labels import LABELS  # noqa: E402
from vehicle_sim.foxglove.topics import LatchedChannelSink  # noqa: E402
from vehicle_sim.ros.automobile_node import AutomobileNode  # noqa: E402

WORLD = {'vehicles': [{'name': 'ego', 'namespace': 'ego', 'sensors': [
    {'type': 'camera', 'name': 'camera', 'pose': {'x': 1.5, 'z': 1.3}, 'width': 32,
     'height': 24, 'segmentation': True, 'recognition': True}]}]}
CHANNELS = {'/ego/camera/semantic/image_raw': 'sensor_msgs/msg/Image',
            '/ego/camera/instance/image_raw': 'sensor_msgs/msg/Image',
            '/ego/camera/detections': 'vision_msgs/msg/Detection2DArray',
            '/ego/camera/labels': 'vision_msgs/msg/LabelInfo'}


def free_port() -> int:
    with socket.socket() as probe:
        probe.bind(('127.0.0.1', 0))
        return probe.getsockname()[1]


@pytest.fixture
def app(tmp_path):
    world = tmp_path / 'world.yaml'
    world.write_text(yaml.safe_dump(WORLD), encoding='utf-8')
    made = AutomobileNode(transport='dds', parameter_overrides={
        'foxglove': free_port(), 'synchronous': True, 'world': str(world)})
    try:
        yield made
    finally:
        made.close()


def test_the_segmentation_and_recognition_topics_are_channels_the_view_shows(app):
    sinks = app._live.topics.sinks
    for topic, ros_type in CHANNELS.items():
        schema = sinks[topic].channel.schema()
        assert (schema.name, schema.encoding) == (ros_type, 'ros2msg'), topic
        assert schema.data == vehicle_msgs_py.message_definition(ros_type).encode('utf-8')
    labels = sinks['/ego/camera/labels']
    assert isinstance(labels, LatchedChannelSink)
    (data,) = labels.kept
    table = app.node.deserialize('vision_msgs/msg/LabelInfo', data)
    assert [c.class_name for c in table.class_map] == [label.name for label in LABELS]
