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
A range finder's 32FC1 depth image and its organized cloud recorded to MCAP and read back.

The automobile node runs test/data/depth_course.yaml in process under the recorder; rosbags
reads the file with the schemas the file itself carries, and the depth bytes come back as they
were published (the wall's face 18 m ahead, the sky +inf); MCAP's and Foxglove's TypeScript
libraries decode the same bytes (skipped, saying why, without node and npm).
"""

import json
from pathlib import Path
import subprocess

import numpy as np
import pytest

pytest.importorskip('mcap', reason="recording needs the mcap package (the 'record' extra)")

from record_helpers import record_automobile, typestore  # noqa: E402
from rosbags.rosbag2 import Reader  # noqa: E402
import test_record_node_reader as node_reader  # noqa: E402

WORLD = str(Path(__file__).resolve().parent / 'data' / 'depth_course.yaml')
node_modules = node_reader.node_modules        # the fixture: the npm packages, or a skip
IMAGE, CLOUD = '/rec_depth/depth_cam/depth/image_raw', '/rec_depth/depth_cam/depth/points'


@pytest.fixture(scope='module')
def depth_recording(tmp_path_factory):
    """Record 0.4 s of the depth course (two samples at 5 Hz); return the .mcap path."""
    path = str(tmp_path_factory.mktemp('depth') / 'depth.mcap')
    error = record_automobile(path, '/rec_depth', lambda app: app.step(40),
                              parameters=(f'world:={WORLD}',))[2]
    assert error is None
    return path


def _read_back(path):
    found = {}
    with Reader(path) as reader:
        store = typestore(reader.connections)
        for connection, _, raw in reader.messages():
            if connection.topic in (IMAGE, CLOUD):
                found.setdefault(connection.topic, []).append(
                    store.deserialize_cdr(raw, connection.msgtype))
    return found


def test_depth_image_and_cloud_record_and_read_back_bit_for_bit(depth_recording):
    found = _read_back(depth_recording)
    assert len(found[IMAGE]) == len(found[CLOUD]) == 2
    image, cloud = found[IMAGE][-1], found[CLOUD][-1]
    assert (image.encoding, image.width, image.height, image.step) == ('32FC1', 64, 48, 256)
    depth = np.frombuffer(image.data.tobytes(), '<f4').reshape(48, 64)
    assert depth[24, 32] == pytest.approx(18.0, abs=0.02) and np.isposinf(depth[0]).all()
    points = np.frombuffer(cloud.data.tobytes(), '<f4').reshape(48, 64, 3)
    assert np.array_equal(points[..., 2], np.where(np.isfinite(depth), depth, np.nan),
                          equal_nan=True)


def test_node_libraries_decode_the_depth_image_as_rosbags_does(node_modules, depth_recording):
    # MCAP's and Foxglove's own TypeScript readers (test_record_node_reader.py)
    result = subprocess.run(['node', node_reader.SCRIPT, node_modules, depth_recording],
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    topics = json.loads(result.stdout)['topics']
    image, expected = topics[IMAGE], _read_back(depth_recording)[IMAGE][-1]
    assert image['type'] == 'sensor_msgs/msg/Image' and image['count'] == 2
    last = image['last']
    assert (last['encoding'], last['width'], last['height'], last['step']) == \
        ('32FC1', 64, 48, 256)
    assert bytes(last['data']) == expected.data.tobytes()
    cloud = topics[CLOUD]
    assert cloud['type'] == 'sensor_msgs/msg/PointCloud2' and cloud['count'] == 2
    assert [f['name'] for f in cloud['last']['fields']] == ['x', 'y', 'z']
