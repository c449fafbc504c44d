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
``vehicle-sim record`` against a running node, and ``vehicle-sim play`` into a fresh graph.

The commands run as a user types them (the installed console script in a subprocess); this
process's DDS node is the other side (the subscriber of what is played).
"""

import os
import signal
import subprocess
import sys
import threading

from automobile_helpers import wait_for
from conftest import peer_env, PEER_START_TIMEOUT_S, scaled_s, stop_processes
import pytest

pytest.importorskip('mcap', reason="recording needs the mcap package (the 'record' extra)")

from record_helpers import record_automobile, typestore  # noqa: E402
from rosbags.rosbag2 import Reader  # noqa: E402

from vehicle_sim.transport.dds import DdsNode  # noqa: E402
from vehicle_sim.transport.qos import QOS_TF_STATIC_LISTENER, QosProfile

VEHICLE_SIM = os.path.join(os.path.dirname(sys.executable), 'vehicle-sim')
STEPS = 1000
SPEED = '/rt_play/automobile/current_speed'

pytestmark = pytest.mark.transport


def _stamps_and_values(path, topic):
    with Reader(path) as reader:
        store = typestore(reader.connections)
        found = []
        for connection, _, raw in reader.messages():
            if connection.topic == topic:
                msg = store.deserialize_cdr(raw, connection.msgtype)
                found.append((msg.header.stamp.sec * 10**9 + msg.header.stamp.nanosec,
                              msg.data))
        return found


@pytest.fixture(scope='module')
def recording(tmp_path_factory):
    """10 s of the automobile node (namespace /rt_play), recorded in process."""
    path = str(tmp_path_factory.mktemp('play') / 'run.mcap')

    def drive(app):
        app.vehicles[''].logic.set_cruising_speed_kmh(30.0)
        app.step(STEPS)
    assert record_automobile(path, '/rt_play', drive)[2] is None
    return path


def test_play_into_a_fresh_graph_reproduces_counts_stamps_and_clock(recording):
    recorded = _stamps_and_values(recording, SPEED)
    assert len(recorded) == STEPS + 1
    node = DdsNode('rt_play_listener')
    got, clocks, static = [], [], []
    try:
        speed_type = node.msg('vehicle_msgs/msg/Float64Stamped')
        node.create_subscription(
            speed_type.__ros_type__, SPEED,
            lambda m: got.append((m.header.stamp.sec * 10**9 + m.header.stamp.nanosec, m.data)),
            QosProfile(depth=2000))
        node.create_subscription('rosgraph_msgs/msg/Clock', '/clock',
                                 lambda m: clocks.append(m.clock.sec * 10**9 + m.clock.nanosec),
                                 QosProfile(depth=100))
        node.create_subscription('tf2_msgs/msg/TFMessage', '/tf_static', static.append,
                                 QOS_TF_STATIC_LISTENER)
        play = subprocess.Popen([VEHICLE_SIM, 'play', recording, '--rate', '4', '--clock', '50',
                                 '--delay', str(scaled_s(2))], env=peer_env(),
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        try:
            assert node.spin_until(lambda: play.poll() is not None, PEER_START_TIMEOUT_S)
            node.spin_until(lambda: len(got) >= len(recorded), PEER_START_TIMEOUT_S)
        finally:
            stop_processes([play])
        _, err = play.communicate()
        assert play.returncode == 0, err
    finally:
        node.shutdown()
    assert got == recorded                      # every message, its stamp and value
    assert len(static) == 1 and static[0].transforms
    # /clock from the recorded time (50 Hz of wall time at rate 4: ~12.5 Hz of recorded
    # time), never going back, from the start to the end of the recording.
    assert len(clocks) >= 20
    assert clocks == sorted(clocks)
    assert clocks[0] <= 200_000_000 and clocks[-1] == STEPS * 10_000_000


def test_play_with_topics_and_start_plays_only_those_from_there(recording):
    node = DdsNode('rt_play_listener_2')
    got = []
    try:
        node.create_subscription('vehicle_msgs/msg/Float64Stamped', SPEED,
                                 lambda m: got.append(m.header.stamp.sec * 10**9
                                                      + m.header.stamp.nanosec),
                                 QosProfile(depth=2000))
        play = subprocess.run([VEHICLE_SIM, 'play', recording, '--rate', '10', '--start', '8',
                               '--topics', SPEED, '--delay', str(scaled_s(2))], env=peer_env(),
                              capture_output=True, text=True, timeout=PEER_START_TIMEOUT_S)
        assert play.returncode == 0, play.stderr
        node.spin_until(lambda: len(got) >= 201, PEER_START_TIMEOUT_S)
    finally:
        node.shutdown()
    assert 'Playing' in play.stdout and '1 topics' in play.stdout
    assert got == [t for t in range(8 * 10**9, 10 * 10**9 + 1, 10_000_000)]


def test_record_command_writes_what_a_running_node_publishes(tmp_path):
    path = str(tmp_path / 'graph.mcap')
    run = subprocess.Popen([VEHICLE_SIM, 'run', '--no-status', '--duration', '120', '--',
                            '--ros-args', '-r', '__ns:=/rt_rec'], env=peer_env(),
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        record = subprocess.run(
            [VEHICLE_SIM, 'record', '/rt_rec/automobile/current_speed', '/rt_rec/odom',
             '-o', path, '--duration', '4', '--use-sim-time'], env=peer_env(),
            capture_output=True, text=True, timeout=PEER_START_TIMEOUT_S * 2)
    finally:
        stop_processes([run])
    assert record.returncode == 0, record.stderr
    assert "Subscribed to topic '/rt_rec/odom'" in record.stdout
    found = _stamps_and_values(path, '/rt_rec/automobile/current_speed')
    assert len(found) > 50
    stamps = [s for s, _ in found]
    # Every message as it came: consecutive steps of 10 ms, none lost or repeated.
    assert all(b - a == 10_000_000 for a, b in zip(stamps, stamps[1:]))
    with Reader(path) as reader:
        topics = {c.topic: c for c in reader.connections}
        assert set(topics) == {'/rt_rec/automobile/current_speed', '/rt_rec/odom'}
        qos = topics['/rt_rec/odom'].ext.offered_qos_profiles[0]
        # A publisher seen on the graph: rosbag2's unknown history and depth 0.
        assert qos.history.name == 'UNKNOWN' and qos.depth == 0
        assert qos.reliability.name == 'RELIABLE'
        # --use-sim-time: log times from /clock (subscribed to, not recorded), so each
        # message's log time is the simulated time it was published at, within a step or two
        # (/clock and the topic come through different readers).
        speed = topics['/rt_rec/automobile/current_speed']
        store = typestore([speed])
        for _, log_ns, raw in reader.messages([speed]):
            stamp = store.deserialize_cdr(raw, speed.msgtype).header.stamp
            assert abs(log_ns - (stamp.sec * 10**9 + stamp.nanosec)) <= 50_000_000


def test_record_command_on_sighup_closes_a_complete_file_up_to_the_signal(tmp_path):
    # A closed terminal sends SIGHUP: the file is finished as on Ctrl-C, not cut at its last
    # complete chunk (a second of current_speed alone is ~1,000 messages: most of a 1 MiB chunk).
    path = str(tmp_path / 'hup.mcap')
    topic = '/rt_hup/automobile/current_speed'
    run = subprocess.Popen([VEHICLE_SIM, 'run', '--no-status', '--duration', '120', '--',
                            '--ros-args', '-r', '__ns:=/rt_hup'], env=peer_env(),
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    node = DdsNode('rt_hup_watch')
    seen = []
    node.create_subscription('vehicle_msgs/msg/Float64Stamped', topic,
                             lambda msg: seen.append(msg.header.stamp.sec * 10**9
                                                     + msg.header.stamp.nanosec),
                             QosProfile(depth=100))
    record = subprocess.Popen([VEHICLE_SIM, 'record', topic, '-o', path], env=peer_env(),
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    lines = []
    reader = threading.Thread(target=lambda: lines.extend(record.stdout), daemon=True)
    reader.start()
    try:
        assert wait_for(lambda: f"Subscribed to topic '{topic}'\n" in lines,
                        PEER_START_TIMEOUT_S, spin=node), lines
        # Let it record a few simulated seconds, then hang up at a known simulated time.
        assert wait_for(lambda: seen and seen[-1] - seen[0] >= 3 * 10**9,
                        PEER_START_TIMEOUT_S, spin=node)
        signal_ns = seen[-1]
        record.send_signal(signal.SIGHUP)
        record.wait(PEER_START_TIMEOUT_S)
        reader.join(PEER_START_TIMEOUT_S)
    finally:
        node.shutdown()
        stop_processes([run, record])
    assert record.returncode == 0, record.stderr.read()
    recorded = [stamp for stamp, _ in _stamps_and_values(path, topic)]   # rosbags reads it
    assert lines[-1] == f'recorded {len(recorded)} messages on 1 topics into {path}\n'
    # Consecutive 10 ms steps up to within half a simulated second of the signal.
    assert all(b - a == 10_000_000 for a, b in zip(recorded, recorded[1:]))
    assert recorded[-1] >= signal_ns - 500_000_000


def test_player_loops_until_stopped(recording):
    from vehicle_sim.recording.player import Player
    node = DdsNode('rt_play_loop')
    try:
        player = Player(node, recording, rate=1000.0, topics=['/tf_static', SPEED])
        rounds = []

        def stop():
            if player.counts[SPEED] >= 3 * (STEPS + 1):
                rounds.append(player.counts[SPEED])
                return True
            return False
        published = player.play(stop, loop=True)
    finally:
        node.shutdown()
    assert player.counts[SPEED] == 3 * (STEPS + 1)      # three times the recording
    assert player.counts['/tf_static'] == 3
    assert published == sum(player.counts.values()) and rounds


def test_failing_scenario_records_its_run_and_its_junit_names_the_recording(tmp_path):
    from xml.etree import ElementTree
    path = str(tmp_path / 'crash.mcap')
    junit = str(tmp_path / 'results.xml')
    repo = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    result = subprocess.run([VEHICLE_SIM, 'scenario', 'scenarios/drive_into_obstacle.yaml',
                             '--no-progress', '--record', path, '--junit', junit],
                            env=peer_env(), capture_output=True, text=True, cwd=repo,
                            timeout=PEER_START_TIMEOUT_S * 3)
    assert result.returncode == 1, result.stderr           # the car hits the wall
    assert f'(replay it: vehicle-sim play {path})' in result.stdout
    suite = ElementTree.parse(junit).getroot().find('testsuite')
    properties = {p.get('name'): p.get('value') for p in suite.iter('property')}
    assert properties['recording'] == path
    failures = [f.text for f in suite.iter('failure')]
    assert failures and all(f'recording: {path}' in text for text in failures)
    from vehicle_sim.recording.bag_reader import read_info
    info = read_info(path)
    # The scenario's 10 s, every step (10 ms) and the first publication at t = 0.
    assert info.duration_ns == 10 * 10**9
    assert abs(info.topic('/automobile/current_speed').count - 1001) <= 1
    assert info.topic('/collision').count >= 1             # the crash is in the file
