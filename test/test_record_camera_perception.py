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
A camera's segmentation and recognition topics in a recording, read back by rosbags.

The automobile node runs a world whose car's camera has segmentation and recognition, recorded
in process (as ``vehicle-sim run --record``) for 0.5 s; rosbags reads the file with types built
from the file's own schemas (vision_msgs included), so an independent decoder sees the images
and the detections.
"""

import numpy as np
import pytest
import yaml

pytest.importorskip('mcap', reason="recording needs the mcap package (the 'record' extra)")

from record_helpers import record_automobile, typestore  # noqa: E402
from rosbags.rosbag2 import Reader  # noqa: E402

from vehicle_sim.core.sensors.labels import LABEL_IDS, LABELS  # noqa: E402

WIDTH, HEIGHT = 48, 36
WORLD = {
    'vehicles': [{'name': 'ego', 'sensors': [
        {'type': 'camera', 'name': 'camera', 'pose': {'x': 1.5, 'z': 1.3}, 'width': WIDTH,
         'height': HEIGHT, 'rate_hz': 10.0, 'segmentation': True, 'recognition': True}]}],
    'obstacles': [
        {'name': 'crate', 'shape': 'box', 'size': [1.0, 2.0, 2.0], 'position': [10.0, 0.0, 1.0]}],
}


@pytest.fixture(scope='module')
def recording(tmp_path_factory):
    folder = tmp_path_factory.mktemp('record_perception')
    world = folder / 'world.yaml'
    world.write_text(yaml.safe_dump(WORLD), encoding='utf-8')
    path = str(folder / 'run.mcap')

    def drive(app):
        for _ in range(50):
            app.step_once()
    _, _, error = record_automobile(path, '/rec_seen', drive, parameters=(f'world:={world}',))
    assert error is None
    found = {}
    with Reader(path) as reader:
        store = typestore(reader.connections)
        for connection, _, raw in reader.messages():
            if '/camera/' in connection.topic:
                found.setdefault(connection.topic.split('/camera/')[1], []).append(
                    (connection.msgtype, store.deserialize_cdr(raw, connection.msgtype)))
    return found


def test_the_label_and_object_images_are_recorded_as_mono16(recording):
    assert len(recording['semantic/image_raw']) == len(recording['image_raw']) == 5
    ros_type, semantic = recording['semantic/image_raw'][-1]
    assert ros_type == 'sensor_msgs/msg/Image'
    assert (semantic.encoding, semantic.step) == ('mono16', 2 * WIDTH)
    pixels = np.frombuffer(bytes(semantic.data), dtype='<u2').reshape(HEIGHT, WIDTH)
    assert pixels[HEIGHT // 2, WIDTH // 2] == LABEL_IDS['obstacle']
    assert pixels[0, WIDTH // 2] == LABEL_IDS['none']
    _, instance = recording['instance/image_raw'][-1]
    assert instance.encoding == 'mono16' and len(instance.data) == 2 * WIDTH * HEIGHT


def test_the_detections_and_the_label_table_decode_from_the_files_own_schemas(recording):
    assert len(recording['detections']) == 5
    ros_type, detections = recording['detections'][-1]
    assert ros_type == 'vision_msgs/msg/Detection2DArray'
    assert detections.header.frame_id == 'camera_optical'
    (detection,) = detections.detections          # the crate
    (result,) = detection.results
    assert (result.hypothesis.class_id, result.hypothesis.score) == ('obstacle', 1.0)
    _, instance = recording['instance/image_raw'][-1]
    pixels = np.frombuffer(bytes(instance.data), dtype='<u2').reshape(HEIGHT, WIDTH)
    assert detection.id == str(pixels[HEIGHT // 2, WIDTH // 2]) != '0'
    assert detection.bbox.size_x == np.count_nonzero(pixels[HEIGHT // 2] == int(detection.id))
    ((ros_type, table),) = recording['labels']
    assert ros_type == 'vision_msgs/msg/LabelInfo'
    assert [(c.class_id, c.class_name) for c in table.class_map] == [
        (label.id, label.name) for label in LABELS]
