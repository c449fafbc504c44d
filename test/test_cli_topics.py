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
The graph tools as a user types them: the installed ``vehicle-sim`` command in a subprocess.

``pub`` / ``hz`` / ``echo --field --rate``, ``call`` with a type that is not the graph's, the
node's log lines under a refused call, and what the CLI says when it sees nobody at all. Peers:
test/transport_peer.py (node /tp_topics/peer: echo_in -> echo_out, 'echo: ' + data) and the
automobile node of ``vehicle-sim run`` (real time, endpoints under /automobile).
"""

import os
import re
import subprocess
import sys

from automobile_helpers import wait_for
from conftest import peer_env, PEER_START_TIMEOUT_S, stop_processes
import pytest
import yaml

from vehicle_sim.tools.graph_commands import PrintRate
from vehicle_sim.tools.topic_commands import rate_report
from vehicle_sim.transport.dds import DdsNode
from vehicle_sim.transport.dds.domain_config import domain_id
from vehicle_sim.transport.qos import QOS_ROSOUT

NS = '/tp_topics'
# The console script pip installed next to this interpreter: what a user types.
VEHICLE_SIM = os.path.join(os.path.dirname(sys.executable), 'vehicle-sim')
# Generous bound for one CLI run (interpreter start, discovery, one exchange).
CLI_TIMEOUT_S = 60.0
REFUSAL = ('automobile/set_cruising_speed: refused 300.0: cruising speed = 300.0 km/h is '
           'outside the valid range [-180.0, 180.0] km/h; nothing changed')

pytestmark = pytest.mark.transport


def vehicle_sim(*args, env=None, timeout_s=CLI_TIMEOUT_S):
    """Run the installed ``vehicle-sim ARGS`` and return the CompletedProcess (text output)."""
    return subprocess.run([VEHICLE_SIM, *args], env=env or peer_env(), capture_output=True,
                          text=True, timeout=timeout_s)


@pytest.fixture(scope='module')
def peer(spawn_peer):
    return spawn_peer('--ros-args', '-r', '__ns:=' + NS)


@pytest.fixture(scope='module')
def automobile():
    """``vehicle-sim run`` in the background, answering calls."""
    proc = subprocess.Popen([VEHICLE_SIM, 'run', '--no-status', '--duration', '300'],
                            env=peer_env(), stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)
    try:
        result = vehicle_sim('call', '/automobile/get_gear', '--wait', str(PEER_START_TIMEOUT_S))
        assert result.returncode == 0, result.stderr
        yield proc
    finally:
        stop_processes([proc])


def test_the_installed_command_is_next_to_the_interpreter():
    assert os.access(VEHICLE_SIM, os.X_OK), f'{VEHICLE_SIM}: pip install -e . first'


# -------------------------------------------------------------------------------- call --type

def test_call_with_another_type_than_the_graph_fails_at_once_naming_both_types(automobile):
    # With --timeout 600 a client waiting for a server of the wrong type would outlive the
    # 60 s bound of vehicle_sim(): the answer comes from the graph, without waiting.
    result = vehicle_sim('call', '/automobile/set_cruising_speed', '30',
                         '--type', 'vehicle_msgs/srv/SetInt', '--timeout', '600')
    assert (result.returncode, result.stdout) == (1, '')
    assert result.stderr == (
        'vehicle-sim call: service /automobile/set_cruising_speed has type '
        'vehicle_msgs/srv/SetFloat on the graph, not vehicle_msgs/srv/SetInt (the type '
        'given)\n')


def test_echo_with_another_type_than_the_graph_names_both_types(peer):
    result = vehicle_sim('echo', f'{NS}/echo_out', '--type', 'std_msgs/msg/Float64',
                         '--once', '--timeout', '600')
    assert result.returncode == 1
    assert (f'topic {NS}/echo_out has type std_msgs/msg/String on the graph, not '
            'std_msgs/msg/Float64') in result.stderr


# -------------------------------------------------------------------------------- call + rosout

def test_refused_call_prints_the_node_reason_under_the_response(automobile):
    result = vehicle_sim('call', '/automobile/set_cruising_speed', '300')
    assert result.returncode == 0, result.stderr
    response, *logs = result.stdout.splitlines()
    assert response == 'success: false'
    assert [re.sub(r'\[\d+\.\d{9}\]', '[T]', line) for line in logs] == [
        f'[WARN] [T] [automobile]: {REFUSAL}']


def test_accepted_call_prints_the_response_only(automobile):
    result = vehicle_sim('call', '/automobile/set_cruising_speed', '20')
    assert (result.returncode, result.stdout) == (0, 'success: true\n'), result.stderr


def test_brake_while_cruising_is_taken_with_a_warning_saying_what_to_do(automobile):
    assert vehicle_sim('call', '/automobile/set_cruising_speed', '20').stdout == \
        'success: true\n'
    try:
        result = vehicle_sim('call', '/automobile/set_brake_intensity', '1')
        assert result.returncode == 0, result.stderr
        response, *logs = result.stdout.splitlines()
        assert response == 'success: true'      # taken, as Webots takes it
        assert [re.sub(r'\[\d+\.\d{9}\]', '[T]', line) for line in logs] == [
            '[WARN] [T] [automobile]: automobile/set_brake_intensity: brake intensity 1 has no '
            'effect while cruise control holds 20 km/h (the driven wheels follow the cruising '
            'speed): set the cruising speed to 0 to slow down, or set the throttle (TORQUE '
            'mode) so that the brake acts']
    finally:
        vehicle_sim('call', '/automobile/set_brake_intensity', '0')


def test_refusal_reaches_rosout_as_rcl_log_with_its_call_site(automobile):
    listener = DdsNode('rosout_listener', '/tp_topics_test',
                       args=['--ros-args', '--disable-rosout-logs'])
    try:
        records = []
        listener.create_subscription('rcl_interfaces/msg/Log', '/rosout', records.append,
                                     QOS_ROSOUT)
        assert vehicle_sim('call', '/automobile/set_cruising_speed', '-500').returncode == 0
        found = wait_for(lambda: [r for r in records if 'refused -500.0' in r.msg],
                         spin=listener)
        assert [(r.name, r.level, os.path.basename(r.file), r.function) for r in found] == [
            ('automobile', 30, 'automobile_node.py', '_handle_setter')]
        assert found[0].line > 0 and found[0].stamp.sec > 0
    finally:
        listener.shutdown()


# -------------------------------------------------------------------------------- nobody found

def test_nothing_found_names_the_domain_the_discovery_range_and_the_rule(peer):
    # The peer is on LOCALHOST; discovery OFF sees nobody (and keeps DDS off the network).
    env = dict(peer_env(), ROS_AUTOMATIC_DISCOVERY_RANGE='OFF')
    result = vehicle_sim('echo', '/clock', '--wait', '1', env=env)
    assert result.returncode == 1
    assert result.stderr == (
        f"vehicle-sim echo: topic '/clock' not found on the graph after 1 s "
        f'(ROS_DOMAIN_ID={domain_id()}); no other DDS participant seen at all on domain '
        f'{domain_id()} with ROS_AUTOMATIC_DISCOVERY_RANGE=OFF: both sides must use the same '
        'ROS_DOMAIN_ID and the same discovery range (README, "Try it")\n')


def test_not_found_beside_other_participants_does_not_blame_discovery(peer):
    result = vehicle_sim('echo', f'{NS}/nothing_here', '--wait', '1')
    assert result.returncode == 1
    assert 'not found on the graph' in result.stderr
    assert 'no other DDS participant' not in result.stderr


# -------------------------------------------------------------------------------- pub

def test_pub_takes_the_type_from_the_graph_and_reaches_the_subscriber(peer):
    publisher = subprocess.Popen([VEHICLE_SIM, 'pub', f'{NS}/echo_in', 'hello', '--rate', '5'],
                                 env=peer_env(), stdout=subprocess.PIPE,
                                 stderr=subprocess.PIPE, text=True)
    try:
        echoed = vehicle_sim('echo', f'{NS}/echo_out', '--once', '--timeout', '30')
        assert (echoed.returncode, echoed.stdout) == (0, "data: 'echo: hello'\n---\n")
    finally:
        stop_processes([publisher])
    out, err = publisher.communicate()
    assert publisher.returncode == 0, err
    assert out.startswith('publisher: beginning loop (every 0.2 s)\n'
                          'publishing #1: {data: hello}\n')


def test_pub_times_publishes_n_messages_and_exits(peer):
    result = vehicle_sim('pub', f'{NS}/echo_in', 'std_msgs/msg/String', '{data: hi}',
                         '--times', '3', '--rate', '20')
    assert result.returncode == 0, result.stderr
    assert re.findall(r'publishing #(\d+): \{data: hi\}', result.stdout) == ['1', '2', '3']


def test_pub_once_to_cmd_vel_is_taken_by_the_car(automobile):
    # --once waits for a matched subscriber: the car's /cmd_vel reader.
    result = vehicle_sim('pub', '/cmd_vel', 'geometry_msgs/msg/Twist',
                         '{linear: {x: 3.0}, angular: {z: 0.3}}', '--once')
    assert result.returncode == 0, result.stderr
    assert ('publishing #1: {linear: {x: 3.0, y: 0.0, z: 0.0}, '
            'angular: {x: 0.0, y: 0.0, z: 0.3}}\n') in result.stdout


def test_pub_with_a_wrong_field_exits_2_with_one_line(peer):
    result = vehicle_sim('pub', f'{NS}/echo_in', '{dat: x}', '--once')
    assert (result.returncode, result.stdout) == (2, '')
    assert result.stderr == ("vehicle-sim pub: message: std_msgs/msg/String has no field "
                             "'dat'; fields: data\n")


def test_pub_to_an_unknown_topic_without_type_exits_2_asking_for_it(peer):
    result = vehicle_sim('pub', f'{NS}/nothing_here', '{data: 1}', '--once', '--wait', '1')
    assert result.returncode == 2
    assert result.stderr.rstrip().endswith(
        f'give its TYPE: vehicle-sim pub {NS}/nothing_here TYPE VALUES')


# -------------------------------------------------------------------------------- echo, hz

def test_echo_field_prints_only_that_field(automobile):
    result = vehicle_sim('echo', '/automobile/current_speed', '--field', 'data',
                         '--rate', '2', '--count', '2', '--timeout', '30')
    assert result.returncode == 0, result.stderr
    values = result.stdout.split('---\n')
    assert values[-1] == '' and len(values) == 3
    assert values[:2] == [f'{float(v)!r}\n' for v in values[:2]]   # a bare number each


def test_echo_field_that_the_type_lacks_exits_2_listing_the_fields(automobile):
    result = vehicle_sim('echo', '/automobile/current_speed', '--field', 'header.nope',
                         '--once')
    assert result.returncode == 2
    assert result.stderr == ("vehicle-sim echo: --field header.nope: header has no field "
                             "'nope'; fields: stamp, frame_id\n")


# A JointState longer than ros2 topic echo's default truncate length (128) in every way: a
# 130-character frame_id, 130 joint names and positions.
LONG = 130
LONG_NAMES = [f'j{i}' for i in range(LONG)]
LONG_POSITIONS = [float(i) for i in range(LONG)]


@pytest.fixture(scope='module')
def long_joint_states():
    """``vehicle-sim pub`` of the long JointState on /tp_topics/long_joints, 5 times a second."""
    values = yaml.safe_dump({'header': {'frame_id': 'f' * LONG}, 'name': LONG_NAMES,
                             'position': LONG_POSITIONS}, default_flow_style=True,
                            width=float('inf')).strip()
    proc = subprocess.Popen([VEHICLE_SIM, 'pub', f'{NS}/long_joints',
                             'sensor_msgs/msg/JointState', values, '--rate', '5'],
                            env=peer_env(), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        yield f'{NS}/long_joints'
    finally:
        stop_processes([proc])


def echo_once(topic, *options):
    """Run ``vehicle-sim echo TOPIC --once OPTIONS``; return the message it printed, parsed."""
    result = vehicle_sim('echo', topic, '--once', '--timeout', '30', '--wait', '30', *options)
    assert result.returncode == 0, result.stderr
    text, rest = result.stdout.split('---\n')
    assert rest == ''
    return yaml.safe_load(text)


def test_echo_cuts_strings_and_arrays_after_128_items_as_ros2_topic_echo(long_joint_states):
    shown = echo_once(long_joint_states)
    assert shown['header']['frame_id'] == 'f' * 128 + '...'
    assert shown['name'] == LONG_NAMES[:128] + ['...']
    assert shown['position'] == LONG_POSITIONS[:128] + ['...']
    assert (shown['velocity'], shown['effort']) == ([], [])


def test_echo_truncate_length_sets_where_values_are_cut(long_joint_states):
    shown = echo_once(long_joint_states, '--truncate-length', '2')
    assert shown['header']['frame_id'] == 'ff...'
    assert (shown['name'], shown['position']) == (['j0', 'j1', '...'], [0.0, 1.0, '...'])


def test_echo_full_length_prints_every_item(long_joint_states):
    shown = echo_once(long_joint_states, '--full-length')
    assert shown['header']['frame_id'] == 'f' * LONG
    assert (shown['name'], shown['position']) == (LONG_NAMES, LONG_POSITIONS)


def test_echo_no_arr_and_no_str_print_types_and_lengths_only(long_joint_states):
    shown = echo_once(long_joint_states, '--no-arr', '--no-str')
    assert shown['header']['frame_id'] == f'<string length: <{LONG}>>'
    assert shown['name'] == f'<sequence type: string, length: {LONG}>'
    assert shown['position'] == f'<sequence type: double, length: {LONG}>'
    assert shown['effort'] == '<sequence type: double, length: 0>'


def test_echo_negative_truncate_length_exits_2_naming_it():
    result = vehicle_sim('echo', '/anything', '--truncate-length', '-3')
    assert result.returncode == 2
    assert "argument --truncate-length/-l: must be an integer >= 0, got '-3'" in result.stderr


def test_echo_timeout_without_count_ends_the_echo_with_exit_0(long_joint_states):
    # --timeout alone says how long to listen: the messages that came are the result.
    result = vehicle_sim('echo', long_joint_states, '--timeout', '10')
    assert (result.returncode, result.stderr) == (0, '')
    messages = result.stdout.split('---\n')
    assert messages[-1] == '' and len(messages) >= 2
    assert all(yaml.safe_load(m)['name'][:2] == ['j0', 'j1'] for m in messages[:-1])


def test_echo_timeout_with_count_fails_saying_how_many_came(long_joint_states):
    result = vehicle_sim('echo', long_joint_states, '--timeout', '1', '--count', '100000')
    assert result.returncode == 1
    assert re.fullmatch(r'vehicle-sim echo: (got \d+ of 100000 messages|no message) on '
                        f'{NS}/long_joints within 1 s\n', result.stderr)


def test_format_message_no_arr_names_a_fixed_array_by_its_type_and_size():
    from vehicle_msgs_py import message_type
    from vehicle_sim.tools.message_yaml import Abbreviation, format_message
    msg = message_type('geometry_msgs/msg/PoseWithCovariance')()
    shown = yaml.safe_load(format_message(msg, Abbreviation(no_arr=True)))
    assert shown['covariance'] == '<array type: double[36]>'
    assert shown['pose']['position'] == {'x': 0.0, 'y': 0.0, 'z': 0.0}


def test_print_rate_lets_through_at_most_one_message_per_period():
    rate = PrintRate(2.0)   # 0.5 s apart at least
    assert [rate.due(t) for t in (0.0, 0.2, 0.49, 0.5, 0.7, 1.1)] == [
        True, False, False, True, False, True]
    assert all(PrintRate(None).due(t) for t in (0.0, 0.0, 0.1))


def test_rate_report_is_ros2_topic_hz_of_the_periods():
    # periods 0.1 s and 0.2 s: mean 0.15 s -> 6.667 Hz; std dev = |0.2 - 0.1| / 2 = 0.05 s.
    assert rate_report([10.0, 10.1, 10.3]) == (
        'average rate: 6.667\n\tmin: 0.100s max: 0.200s std dev: 0.05000s window: 3')
    assert rate_report([10.0]) is None


def test_hz_reports_the_rate_of_current_speed(automobile):
    result = vehicle_sim('hz', '/automobile/current_speed', '--count', '30')
    assert result.returncode == 0, result.stderr
    last_report = '\n'.join(result.stdout.rstrip('\n').split('\n')[-2:])
    rate, low, high, std_dev, window = re.fullmatch(
        r'average rate: ([\d.]+)\n\tmin: ([\d.]+)s max: ([\d.]+)s std dev: ([\d.]+)s '
        r'window: (\d+)', last_report).groups()
    # The mean period lies between the shortest and the longest (printed to 1 ms).
    assert float(low) - 5e-4 <= 1.0 / float(rate) <= float(high) + 5e-4
    assert (float(std_dev) >= 0.0, int(window)) == (True, 30)
