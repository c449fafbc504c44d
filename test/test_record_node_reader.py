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
A recording read by an independent implementation in another language, in Node.

MCAP's and Foxglove's own TypeScript libraries: ``@mcap/core``, ``@foxglove/rosmsg``,
``@foxglove/rosmsg2-serialization``, and ``fzstd`` for the zstd chunks.

The test installs them with npm into pytest's cache folder, runs ``record_node_reader.cjs`` on
a recording of the automobile node, and compares what it reads with rosbags' reading of the
same file. It skips, saying why, where node or npm is missing or the install fails.
"""

import json
import os
import shutil
import subprocess

import pytest

pytest.importorskip('mcap', reason="recording needs the mcap package (the 'record' extra)")

from record_helpers import record_automobile, typestore  # noqa: E402
from rosbags.rosbag2 import Reader  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPT = os.path.join(HERE, 'record_node_reader.cjs')
PACKAGES = ('@mcap/core@2', '@foxglove/rosmsg@5', '@foxglove/rosmsg2-serialization@3',
            'fzstd@0.1')
STEPS = 300


@pytest.fixture(scope='module')
def node_modules(request, tmp_path_factory):
    """Install the npm packages once into pytest's cache; skip when that cannot be done."""
    node, npm = shutil.which('node'), shutil.which('npm')
    if node is None or npm is None:
        reason = 'node and npm are needed for the independent reader (not found on PATH)'
        print(f'SKIPPED: {reason}')
        pytest.skip(reason)
    cache = getattr(request.config, 'cache', None)     # None with -p no:cacheprovider
    prefix = str(cache.mkdir('record_npm') if cache is not None
                 else tmp_path_factory.mktemp('record_npm'))
    modules = os.path.join(prefix, 'node_modules')
    if not all(os.path.isdir(os.path.join(modules, p.rsplit('@', 1)[0])) for p in PACKAGES):
        result = subprocess.run([npm, 'install', '--prefix', prefix, '--no-audit', '--no-fund',
                                 '--no-save', *PACKAGES], capture_output=True, text=True,
                                timeout=600)
        if result.returncode != 0:
            reason = f'npm install {" ".join(PACKAGES)} failed: {result.stderr.strip()[-300:]}'
            print(f'SKIPPED: {reason}')
            pytest.skip(reason)
    return modules


@pytest.fixture(scope='module')
def recording(tmp_path_factory):
    path = str(tmp_path_factory.mktemp('node_reader') / 'run.mcap')

    def drive(app):
        app.vehicles[''].logic.set_cruising_speed_kmh(30.0)
        app.vehicles[''].logic.set_steering_angle(0.1)
        app.step(STEPS)
    assert record_automobile(path, '/rt_node', drive)[2] is None
    return path


def _rosbags_last(path):
    """Return {topic: (count, last message decoded)} as rosbags reads the file."""
    with Reader(path) as reader:
        store = typestore(reader.connections)
        found = {}
        for connection, _, raw in reader.messages():
            count = found.get(connection.topic, (0, None))[0]
            found[connection.topic] = (count + 1, (connection.msgtype, raw))
        return {topic: (count, store.deserialize_cdr(raw, msgtype))
                for topic, (count, (msgtype, raw)) in found.items()}


def test_node_libraries_read_the_summary_and_decode_every_topic(node_modules, recording):
    result = subprocess.run(['node', SCRIPT, node_modules, recording], capture_output=True,
                            text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    read = json.loads(result.stdout)
    assert read['profile'] == 'ros2' and read['compression'] == ['zstd']
    topics = read['topics']
    expected = _rosbags_last(recording)
    assert {t for t, v in topics.items() if v['count']} == set(expected)
    assert read['message_count'] == sum(count for count, _ in expected.values())
    for name, topic in topics.items():
        assert topic['schema_encoding'] == 'ros2msg' and topic['message_encoding'] == 'cdr'
        assert topic['qos'].startswith('- history: keep_last')
        if not topic['count']:
            continue
        count, msg = expected[name]
        assert topic['count'] == count, name
        last = topic['last']
        if topic['type'] == 'vehicle_msgs/msg/Float64Stamped':
            assert last['data'] == msg.data, name
            assert last['header']['stamp'] == {'sec': msg.header.stamp.sec,
                                               'nanosec': msg.header.stamp.nanosec}
    speed = topics['/rt_node/automobile/current_speed']['last']['data']
    assert speed > 5.0                                      # a moving car, not zeros
    assert topics['/clock']['last']['clock'] == {'sec': 3, 'nanosec': 0}
    odom = topics['/rt_node/odom']['last']['pose']['pose']['position']
    odom_msg = expected['/rt_node/odom'][1].pose.pose.position
    assert (odom['x'], odom['y']) == (odom_msg.x, odom_msg.y) and odom['x'] > 1.0
    frames = [t['child_frame_id'] for t in topics['/tf_static']['last']['transforms']]
    assert frames == [t.child_frame_id for t in expected['/tf_static'][1].transforms]
    joints = topics['/rt_node/joint_states']['last']
    assert joints['name'] == list(expected['/rt_node/joint_states'][1].name)
