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
A camera's segmentation and recognition topics over the wire (docs/sensors.md, ros_interface.md).

The automobile node runs a world with a car whose camera has ``segmentation`` and
``recognition``, a crate 10 m ahead and a wall behind it, synchronous; the test steps it and
reads the semantic and instance images (mono16), the detections (vision_msgs/Detection2DArray)
and the latched label table (vision_msgs/LabelInfo).
"""

from automobile_helpers import automobile_fixtures, stamp_of, wait_for
import numpy as np
import pytest
import yaml

from vehicle_sim.core.sensors.labels import LABEL_IDS, LABELS
from vehicle_sim.ros.sensor_interfaces import QOS_SENSOR
from vehicle_sim.transport.qos import QOS_LATCHED

pytestmark = pytest.mark.transport

NAMESPACE = 'seen'
WIDTH, HEIGHT = 80, 60
WORLD = {
    'vehicles': [{'name': 'ego', 'sensors': [
        {'type': 'camera', 'name': 'camera', 'pose': {'x': 1.5, 'z': 1.3}, 'width': WIDTH,
         'height': HEIGHT, 'rate_hz': 10.0, 'segmentation': True, 'recognition': True}]}],
    'obstacles': [
        {'name': 'crate', 'shape': 'box', 'size': [1.0, 2.0, 2.0], 'position': [10.0, 0.0, 1.0]},
        {'name': 'wall', 'shape': 'box', 'size': [1.0, 30.0, 6.0], 'position': [30.0, 0.0, 3.0]},
    ],
}
TOPICS = {'camera/semantic/image_raw': 'sensor_msgs/msg/Image',
          'camera/instance/image_raw': 'sensor_msgs/msg/Image',
          'camera/detections': 'vision_msgs/msg/Detection2DArray'}


@pytest.fixture(scope='module')
def world_file(tmp_path_factory):
    path = tmp_path_factory.mktemp('perceived') / 'world.yaml'
    path.write_text(yaml.safe_dump(WORLD), encoding='utf-8')
    return path


node, tester, car = automobile_fixtures(
    'perception_tester', lambda request: ['--ros-args', '-r', f'__ns:=/{NAMESPACE}', '-p',
                                          f'world:={request.getfixturevalue("world_file")}',
                                          '-p', 'synchronous:=true'],
    ['/clock'], NAMESPACE, names=('node', 'tester', 'car'))


@pytest.fixture(scope='module')
def received(car):
    found = {topic: [] for topic in TOPICS}
    subs = [car.node.create_subscription(ros_type, f'/{NAMESPACE}/{topic}',
                                         found[topic].append, QOS_SENSOR)
            for topic, ros_type in TOPICS.items()]
    assert wait_for(lambda: all(s.get_publisher_count() for s in subs), spin=car.node)
    assert car.call('robot/time_step', 300).success
    assert wait_for(lambda: all(len(found[t]) >= 3 for t in TOPICS), spin=car.node), \
        {t: len(m) for t, m in found.items()}
    return found


def _pixels(image):
    assert (image.encoding, image.is_bigendian, image.step) == ('mono16', 0, 2 * WIDTH)
    assert (image.width, image.height) == (WIDTH, HEIGHT)
    return np.frombuffer(bytes(image.data), dtype='<u2').reshape(HEIGHT, WIDTH)


def test_semantic_and_instance_images_are_mono16_label_and_object_ids(received):
    semantic_msg = received['camera/semantic/image_raw'][-1]
    instance_msg = received['camera/instance/image_raw'][-1]
    assert stamp_of(semantic_msg) == stamp_of(instance_msg) == pytest.approx(0.3)
    assert semantic_msg.header.frame_id == instance_msg.header.frame_id == 'camera_optical'
    semantic, instance = _pixels(semantic_msg), _pixels(instance_msg)
    assert semantic[HEIGHT // 2, WIDTH // 2] == LABEL_IDS['obstacle']    # the crate
    assert semantic[0, WIDTH // 2] == LABEL_IDS['none']                  # the sky
    assert semantic[HEIGHT - 1, 2] == LABEL_IDS['ground']
    crate = instance[HEIGHT // 2, WIDTH // 2]
    assert crate > 0 and instance[0, WIDTH // 2] == 0
    assert set(np.unique(semantic[instance == crate]).tolist()) == {LABEL_IDS['obstacle']}


def test_detections_carry_the_visible_objects_ids_classes_and_image_boxes(received):
    message = received['camera/detections'][-1]
    instance = _pixels(received['camera/instance/image_raw'][-1])
    assert stamp_of(message) == pytest.approx(0.3)
    assert message.header.frame_id == 'camera_optical'
    by_id = {d.id: d for d in message.detections}
    crate = int(instance[HEIGHT // 2, WIDTH // 2])
    detection = by_id[str(crate)]
    assert detection.header.frame_id == 'camera_optical'
    (result,) = detection.results
    assert (result.hypothesis.class_id, result.hypothesis.score) == ('obstacle', 1.0)
    # the pose of the crate's centre in the optical frame: z forward, x right, y down
    position = result.pose.pose.position
    assert position.z == pytest.approx(10.0 - 1.5, abs=0.01)
    assert position.x == pytest.approx(0.0, abs=0.01)
    rows, cols = np.nonzero(instance == crate)
    box = detection.bbox
    assert (box.center.position.x, box.center.position.y) == pytest.approx(
        ((cols.min() + cols.max()) / 2, (rows.min() + rows.max()) / 2))
    assert (box.size_x, box.size_y, box.center.theta) == (
        cols.max() - cols.min() + 1, rows.max() - rows.min() + 1, 0.0)
    # every detection is an object of the instance image
    assert {int(d) for d in by_id} <= set(np.unique(instance).tolist()) - {0}


def test_the_label_table_is_latched(car, received):
    tables = []
    car.node.create_subscription('vision_msgs/msg/LabelInfo', f'/{NAMESPACE}/camera/labels',
                                 tables.append, QOS_LATCHED)
    assert wait_for(lambda: tables, spin=car.node), 'no label table'
    table = tables[0]
    assert [(c.class_id, c.class_name) for c in table.class_map] == [
        (label.id, label.name) for label in LABELS]
    assert table.header.frame_id == 'camera_optical'
