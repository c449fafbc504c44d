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
Round trip of an in-process recording, read back with rosbags.

10 s of the automobile node recorded in process (as ``vehicle-sim run --record``), read with
rosbags: an independent reader and CDR decoder, its types built from the file's own schemas.
"""

from collections import Counter
import os
import subprocess
import sys

from conftest import peer_env
import pytest

pytest.importorskip('mcap', reason="recording needs the mcap package (the 'record' extra)")

from rosbags.rosbag2 import Reader  # noqa: E402
from rosbags.typesys import get_types_from_msg, get_typestore, Stores  # noqa: E402

from vehicle_sim.recording.recorder import record_node  # noqa: E402
from vehicle_sim.ros.automobile_node import AutomobileNode, NODE_NAME  # noqa: E402
from vehicle_sim.transport import create_node  # noqa: E402

STEPS = 1000                    # 10 s at the default 10 ms step
STEP_S = 0.01
SPEED_KMH = 30.0
VEHICLE_SIM = os.path.join(os.path.dirname(sys.executable), 'vehicle-sim')
# Topics published once (latched) and those published at each step (the default rates).
LATCHED = {'/tf_static', '/robot_description'}
EACH_STEP = {'/clock', '/tf', '/odom', '/joint_states', '/automobile/current_speed',
             '/automobile/throttle', '/automobile/brake_intensity',
             '/automobile/steering_angle', '/automobile/front_left_wheel_speed'}


@pytest.fixture(scope='module')
def recording(tmp_path_factory):
    """Record 10 s of the automobile node; return (path, truth by step, the node's topics)."""
    path = str(tmp_path_factory.mktemp('record') / 'run.mcap')
    node = create_node(NODE_NAME, args=['rt', '--ros-args', '-r', '__ns:=/rt_round',
                                        '-p', 'synchronous:=true'], transport='dds')
    recorder = record_node(node, path)
    published = set()
    node.tap_publishers(lambda topic, ros_type, qos: published.add(topic))   # names only
    app = AutomobileNode(node=node)
    try:
        car = app.vehicles['']
        car.logic.set_cruising_speed_kmh(SPEED_KMH)
        body = app.scene.vehicles[next(iter(app.scene.vehicles))].body
        truth = []
        for _ in range(STEPS):
            time_s = app.step_once()
            truth.append((time_s, car.logic.status().current_speed_kmh, body.pose()[0]))
    finally:
        assert recorder.close() is None
        app.close()
    return path, truth, published


def _typestore(reader):
    # Types from the file's schemas only: each schema is a type followed by its dependencies.
    store = get_typestore(Stores.EMPTY)
    for connection in reader.connections:
        store.register(get_types_from_msg(connection.msgdef.data, connection.msgtype))
    return store


def _name(topic):
    return topic.replace('/rt_round', '', 1) if topic.startswith('/rt_round/') else topic


def test_every_published_topic_is_recorded_with_the_count_of_its_rate(recording):
    path, _, published = recording
    with Reader(path) as reader:
        counts = Counter(connection.topic for connection, _, _ in reader.messages())
        topics = {connection.topic for connection in reader.connections}
        # Log times are simulated time: 0 .. 10 s (rosbags' end time is one past the last).
        assert (reader.start_time, reader.end_time - 1) == (0, round(STEPS * STEP_S * 1e9))
    assert topics == published
    for topic in topics:
        name = _name(topic)
        if name in LATCHED:
            assert counts[topic] == 1, topic
        elif name in EACH_STEP:     # t = 0 (the node's first publication) and every step
            assert abs(counts[topic] - (STEPS + 1)) <= 1, (topic, counts[topic])


def test_messages_decode_with_rosbags_to_the_values_the_node_published(recording):
    path, truth, _ = recording
    with Reader(path) as reader:
        store = _typestore(reader)
        speeds, clocks, odom_x = [], [], []
        for connection, timestamp, raw in reader.messages():
            name = _name(connection.topic)
            if name not in ('/automobile/current_speed', '/clock', '/odom'):
                continue
            msg = store.deserialize_cdr(raw, connection.msgtype)
            if name == '/clock':
                clocks.append(msg.clock.sec * 10**9 + msg.clock.nanosec)
                assert timestamp == clocks[-1]
            elif name == '/odom':
                odom_x.append(msg.pose.pose.position.x)
            else:
                speeds.append((msg.header.stamp.sec + msg.header.stamp.nanosec * 1e-9,
                               msg.data))
    # The first message of each is the node's publication at t = 0, before the first step.
    assert clocks[1:] == [round(t * 1e9) for t, _, _ in truth]
    assert [s for _, s in speeds[1:]] == pytest.approx([s for _, s, _ in truth], abs=1e-9)
    assert [t for t, _ in speeds[1:]] == pytest.approx([t for t, _, _ in truth], abs=1e-9)
    assert odom_x[1:] == pytest.approx([x for _, _, x in truth], abs=1e-9)
    assert truth[-1][1] > 20.0      # the car did drive: the values are not all zero


def test_schemas_are_ros2msg_with_their_dependencies_and_qos_as_rosbag2_stores_it(recording):
    path, _, _ = recording
    with Reader(path) as reader:
        by_topic = {_name(c.topic): c for c in reader.connections}
        odom = by_topic['/odom']
        assert odom.msgdef.format.name == 'MSG'
        assert 'MSG: geometry_msgs/PoseWithCovariance' in odom.msgdef.data
        parsed = get_types_from_msg(odom.msgdef.data, 'nav_msgs/msg/Odometry')
        assert 'geometry_msgs/msg/Pose' in parsed
        qos = by_topic['/tf_static'].ext.offered_qos_profiles[0]
        assert qos.durability.name == 'TRANSIENT_LOCAL' and qos.depth == 1
        assert by_topic['/clock'].ext.serialization_format == 'cdr'


def test_rosbag2_metadata_record_is_version_9_with_qos_as_a_list(recording):
    # ros2 bag info parses it with yaml-cpp: version 9 wants each topic's profiles as a list.
    from mcap.reader import make_reader
    import yaml
    path, _, published = recording
    with open(path, 'rb') as stream:
        (record,) = [m for m in make_reader(stream).iter_metadata() if m.name == 'rosbag2']
    assert record.metadata['ROS_DISTRO'] == 'jazzy'
    info = yaml.safe_load(record.metadata['serialized_metadata'])
    assert info['version'] == 9 and info['storage_identifier'] == 'mcap'
    assert info['duration'] == {'nanoseconds': STEPS * 10_000_000}
    topics = {t['topic_metadata']['name']: t for t in info['topics_with_message_count']}
    assert set(topics) == published
    clock = topics['/clock']
    assert clock['message_count'] == STEPS + 1
    (profile,) = clock['topic_metadata']['offered_qos_profiles']
    assert profile['reliability'] == 'reliable' and profile['deadline']['sec'] == 9223372036
    assert clock['topic_metadata']['type_description_hash'].startswith('RIHS01_')


def test_run_record_then_bag_info_lists_topics_types_and_counts(tmp_path):
    path = str(tmp_path / 'cli.mcap')
    run = subprocess.run([VEHICLE_SIM, 'run', '--no-status', '--synchronous', '--duration', '0.5',
                          '--record', path, '--', '--ros-args', '-r', '__ns:=/rt_cli'],
                         env=peer_env(), capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    assert f'into {path}' in run.stderr
    info = subprocess.run([VEHICLE_SIM, 'bag', 'info', path], env=peer_env(),
                          capture_output=True, text=True, timeout=60)
    assert info.returncode == 0, info.stderr
    # Synchronous and never stepped: the node's first publication only.
    assert ('Topic: /clock | Type: rosgraph_msgs/msg/Clock | Count: 1 | '
            'Serialization Format: cdr') in info.stdout
    assert ('Topic: /rt_cli/automobile/current_speed | Type: vehicle_msgs/msg/Float64Stamped | '
            'Count: 1 | Serialization Format: cdr') in info.stdout
    assert 'Storage id:        mcap' in info.stdout
    assert 'Compression:       zstd' in info.stdout


@pytest.mark.parametrize('compression', ['lz4', 'none'])
def test_lz4_and_uncompressed_chunks_read_back(tmp_path, compression):
    from vehicle_msgs_py import types
    from vehicle_sim.recording.bag_reader import read_info
    from vehicle_sim.recording.bag_writer import BagWriter
    from vehicle_sim.recording.recorder import Recorder
    path = str(tmp_path / f'{compression}.mcap')
    recorder = Recorder(BagWriter(path, compression, chunk_size=4096))
    write = recorder.channel('/chatter', 'std_msgs/msg/String', '')
    string = types.message_type('std_msgs/msg/String')
    for index in range(500):
        write(string(data=f'hello {index}').serialize())
    assert recorder.close() is None
    info = read_info(path)
    assert info.compression == compression and info.chunk_count > 1
    with Reader(path) as reader:
        store = _typestore(reader)
        texts = [store.deserialize_cdr(raw, c.msgtype).data for c, _, raw in reader.messages()]
    assert texts == [f'hello {index}' for index in range(500)]
