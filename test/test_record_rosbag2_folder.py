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
``vehicle-sim bag info`` and ``play`` on a rosbag2 folder, as ``ros2 bag record`` writes it.

The folder is made by an independent producer, rosbags' rosbag2 writer (MCAP storage, metadata
version 9): two recordings of consecutive halves of one topic, put into one folder as rosbag2
splits a recording (``<name>_0.mcap``, ``<name>_1.mcap``, one ``metadata.yaml`` naming both in
order, with the per-file entries and the totals).
"""

import os
import shutil
import subprocess
import sys

from conftest import peer_env, PEER_START_TIMEOUT_S, stop_processes
import pytest

pytest.importorskip('mcap', reason="recording needs the mcap package (the 'record' extra)")

from rosbags.interfaces import (  # noqa: E402
    Qos,
    QosDurability,
    QosHistory,
    QosLiveliness,
    QosReliability,
    QosTime,
)
from rosbags.rosbag2 import StoragePlugin, Writer  # noqa: E402
from rosbags.typesys import get_typestore, Stores  # noqa: E402
import yaml  # noqa: E402

from vehicle_sim.transport.dds import DdsNode  # noqa: E402
from vehicle_sim.transport.qos import QosProfile  # noqa: E402

VEHICLE_SIM = os.path.join(os.path.dirname(sys.executable), 'vehicle-sim')
TOPIC = '/rt_rb2/chatter'
COUNT = 50
START_NS = 1_700_000_000 * 10**9
PERIOD_NS = 20_000_000          # 50 Hz
INFINITE = QosTime(sec=9223372036, nsec=854775807)
RELIABLE_DEPTH_10 = Qos(QosHistory.KEEP_LAST, 10, QosReliability.RELIABLE,
                        QosDurability.VOLATILE, INFINITE, INFINITE, QosLiveliness.AUTOMATIC,
                        INFINITE, False)

pytestmark = pytest.mark.transport


def _write_part(path, indexes):
    """Write messages ``m<i>`` for ``indexes`` with rosbags' writer; return its metadata."""
    store = get_typestore(Stores.ROS2_JAZZY)
    string = store.types['std_msgs/msg/String']
    with Writer(path, version=9, storage_plugin=StoragePlugin.MCAP) as writer:
        connection = writer.add_connection(TOPIC, 'std_msgs/msg/String', typestore=store,
                                           offered_qos_profiles=[RELIABLE_DEPTH_10])
        for i in indexes:
            writer.write(connection, START_NS + i * PERIOD_NS,
                         store.serialize_cdr(string(data=f'm{i}'), 'std_msgs/msg/String'))
    with open(path / 'metadata.yaml', encoding='utf-8') as stream:
        return yaml.safe_load(stream)['rosbag2_bagfile_information']


@pytest.fixture(scope='module')
def split_bag(tmp_path_factory):
    """Write a rosbag2 folder of two MCAP files, split in time order; return its path."""
    work = tmp_path_factory.mktemp('rosbag2')
    halves = [range(0, COUNT // 2), range(COUNT // 2, COUNT)]
    parts = [_write_part(work / f'part{n}', indexes) for n, indexes in enumerate(halves)]
    folder = work / 'rec'
    folder.mkdir()
    names = []
    for n, part in enumerate(parts):
        (source,) = part['relative_file_paths']
        names.append(f'rec_{n}.mcap')
        shutil.move(str(work / f'part{n}' / source), str(folder / names[-1]))
        part['files'][0]['path'] = names[-1]
    first, second = parts
    metadata = dict(first)
    metadata['relative_file_paths'] = names
    metadata['files'] = first['files'] + second['files']
    metadata['message_count'] = COUNT
    end_ns = START_NS + (COUNT - 1) * PERIOD_NS
    metadata['duration'] = {'nanoseconds': end_ns - START_NS}
    (topic,) = metadata['topics_with_message_count']
    topic['message_count'] = COUNT
    # rosbag2 (C++) stores the QoS profiles as a YAML text inside the YAML, and its distro.
    profiles = topic['topic_metadata']['offered_qos_profiles']
    topic['topic_metadata']['offered_qos_profiles'] = yaml.safe_dump(profiles, sort_keys=False)
    metadata['ros_distro'] = 'jazzy'
    with open(folder / 'metadata.yaml', 'w', encoding='utf-8') as stream:
        yaml.safe_dump({'rosbag2_bagfile_information': metadata}, stream)
    return str(folder)


def vehicle_sim(*args):
    return subprocess.run([VEHICLE_SIM, *args], env=peer_env(), capture_output=True, text=True,
                          timeout=PEER_START_TIMEOUT_S)


def test_bag_info_of_a_rosbag2_folder_lists_its_files_in_order_and_its_topics(split_bag):
    result = vehicle_sim('bag', 'info', split_bag)
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert lines[:2] == ['Files:             rec_0.mcap', '                   rec_1.mcap']
    assert 'Storage id:        mcap' in lines
    assert f'Duration:          0.{(COUNT - 1) * PERIOD_NS:09d}s' in lines
    assert f'Messages:          {COUNT}' in lines
    assert (f'Topic information: Topic: {TOPIC} | Type: std_msgs/msg/String | Count: {COUNT} | '
            'Serialization Format: cdr') in lines
    assert not any(line.startswith('note:') for line in lines)    # both files are whole


def test_play_of_a_rosbag2_folder_publishes_both_files_in_order(split_bag):
    node = DdsNode('rt_rb2_listener')
    got = []
    try:
        node.create_subscription('std_msgs/msg/String', TOPIC, lambda m: got.append(m.data),
                                 QosProfile(depth=100))
        play = subprocess.Popen([VEHICLE_SIM, 'play', split_bag, '--rate', '5', '--delay', '2'],
                                env=peer_env(), stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                text=True)
        try:
            assert node.spin_until(lambda: play.poll() is not None, PEER_START_TIMEOUT_S)
            node.spin_until(lambda: len(got) >= COUNT, 5.0)
        finally:
            stop_processes([play])
        out, err = play.communicate()
        assert play.returncode == 0, err
    finally:
        node.shutdown()
    assert got == [f'm{i}' for i in range(COUNT)]
    assert out.splitlines() == [f'Playing {split_bag}: 1 topics, 0.98 s at rate 5',
                                f'published {COUNT} messages']


def test_a_folder_without_rosbag2_metadata_is_a_one_line_error(tmp_path):
    for command in (('bag', 'info'), ('play',)):
        result = vehicle_sim(*command, str(tmp_path))
        assert (result.returncode, result.stdout) == (1, ''), command
        assert result.stderr.endswith(f'{tmp_path}: a folder without metadata.yaml: not a '
                                      'rosbag2 recording\n')
        assert result.stderr.count('\n') == 1
