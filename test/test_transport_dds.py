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
Cross-process tests of the embedded Cyclone DDS transport (docs/transport.md).

The peer node runs in a subprocess (test/transport_peer.py); the test process talks to it with
its own DdsNode and, where the wire itself is checked, with raw cyclonedds readers and writers.
Waits have generous bounds and the assertions are on outcomes, never on durations.
"""


from automobile_helpers import wait_for
from cyclonedds.builtin import BuiltinDataReader, BuiltinTopicDcpsParticipant
from cyclonedds.core import InstanceState
from cyclonedds.domain import DomainParticipant
from cyclonedds.pub import DataWriter
from cyclonedds.sub import DataReader
from cyclonedds.topic import Topic
import pytest

from vehicle_msgs_py import distro
from vehicle_msgs_py import types as msg_types
from vehicle_sim.transport import dds
from vehicle_sim.transport.dds import DdsNode
from vehicle_sim.transport.dds.domain_config import domain_id
from vehicle_sim.transport.parameter_types import (
    Parameter,
    PARAMETER_DOUBLE,
    PARAMETER_NOT_SET,
    PARAMETER_STRING,
)
from vehicle_sim.transport.qos import (
    QOS_CLOCK,
    QOS_DISCOVERY_INFO_READER,
    QOS_PARAMETER_EVENTS,
    QOS_ROSOUT,
    QOS_SERVICES,
)

pytestmark = pytest.mark.transport

WAIT_S = 30.0
NS = '/tp'


@pytest.fixture(scope='module')
def peer(spawn_peer):
    # A long reply-match window makes the late-reader test independent of machine load.
    return spawn_peer('--reply-timeout', '120', '--ros-args', '-r', '__ns:=' + NS,
                      '-p', 'gain:=2.5')


@pytest.fixture(scope='module')
def node(peer):
    test_node = DdsNode('tester', '/tp_test')
    try:
        yield test_node
    finally:
        test_node.shutdown()


@pytest.fixture(scope='module')
def raw():
    """Return a second, plain cyclonedds participant for wire-level checks."""
    dds.ensure_domain()
    return DomainParticipant(domain_id())


def discovery_reader(raw_participant):
    info_type = msg_types.message_type('rmw_dds_common/msg/ParticipantEntitiesInfo')
    topic = Topic(raw_participant, 'ros_discovery_info', info_type)
    return DataReader(raw_participant, topic, qos=dds.dds_qos(
        QOS_DISCOVERY_INFO_READER, b'', writer=False))


def test_topic_string_round_trips_both_directions(node, peer):
    string = node.msg('std_msgs/msg/String')
    received = []
    sub = node.create_subscription('std_msgs/msg/String', NS + '/echo_out',
                                   lambda m: received.append(m.data))
    pub = node.create_publisher('std_msgs/msg/String', NS + '/echo_in')
    assert wait_for(lambda: pub.get_subscription_count() and sub.get_publisher_count())

    def echoed():
        pub.publish(string(data='ping'))
        node.spin_once(0.1)
        return 'echo: ping' in received

    assert wait_for(echoed, spin=node)


def test_service_set_int_round_trip_echoes_request_header(node, peer, raw):
    types = msg_types.service_types('vehicle_msgs/srv/SetInt')
    tap = DataReader(raw, Topic(raw, 'rr' + NS + '/set_intReply', types.response_wire),
                     qos=dds.dds_qos(QOS_SERVICES, b'', writer=False))
    client = node.create_client('vehicle_msgs/srv/SetInt', NS + '/set_int')
    assert client.wait_for_service(WAIT_S)
    request = node.srv('vehicle_msgs/srv/SetInt').Request
    assert client.call(request(value=4), WAIT_S).success is True
    future = client.call_async(request(value=7))
    assert node.spin_until(future.done, WAIT_S)
    assert future.result().success is False
    # The reply on the wire carries the client id and sequence number of the request.
    headers = []
    wait_for(lambda: headers.extend(
        (s.client_id, s.sequence) for s in tap.take(N=64) if s.sample_info.valid_data)
        or (client.client_id, future.sequence) in headers)
    assert (client.client_id, future.sequence) in headers


def test_client_ignores_replies_for_other_clients_and_sequences(node, peer, raw):
    types = msg_types.service_types('vehicle_msgs/srv/SetInt')
    client = node.create_client('vehicle_msgs/srv/SetInt', NS + '/set_int')
    assert client.wait_for_service(WAIT_S)
    forger = DataWriter(raw, Topic(raw, 'rr' + NS + '/set_intReply', types.response_wire),
                        qos=dds.dds_qos(QOS_SERVICES, b'', writer=True))
    assert wait_for(lambda: client._reader.get_matched_publications()
                    and len(client._reader.get_matched_publications()) >= 2)
    request = node.srv('vehicle_msgs/srv/SetInt').Request
    future = client.call_async(request(value=7))  # the peer answers success=False
    # Same-process delivery: these forged replies arrive before the peer's real one.
    forged = types.response(success=True)
    forger.write(types.response_to_wire(forged, client.client_id ^ 1, future.sequence))
    forger.write(types.response_to_wire(forged, client.client_id, future.sequence + 1000))
    assert node.spin_until(future.done, WAIT_S)
    assert future.result().success is False


def test_late_client_reply_reader_does_not_block_the_server(node, peer, raw):
    types = msg_types.service_types('vehicle_msgs/srv/SetInt')
    token = 'late-client-token'
    late_writer = DataWriter(
        raw, Topic(raw, 'rq' + NS + '/set_intRequest', types.request_wire),
        qos=dds.dds_qos(QOS_SERVICES, f'clientid={token};'.encode(), writer=True))
    assert wait_for(lambda: late_writer.get_matched_subscriptions())
    late_writer.write(types.request_to_wire(types.request(value=8), 424242, 1))
    # While that reply waits (up to 120 s) for a reply reader that does not exist yet, the
    # peer keeps serving: a normal call is answered.
    client = node.create_client('vehicle_msgs/srv/SetInt', NS + '/set_int')
    assert client.wait_for_service(WAIT_S)
    request = node.srv('vehicle_msgs/srv/SetInt').Request
    assert client.call(request(value=2), WAIT_S).success is True
    # The reply reader appears late and still gets its queued reply.
    late_reader = DataReader(
        raw, Topic(raw, 'rr' + NS + '/set_intReply', types.response_wire),
        qos=dds.dds_qos(QOS_SERVICES, f'clientid={token};'.encode(), writer=False))
    replies = []
    wait_for(lambda: replies.extend(
        s for s in late_reader.take(N=64) if s.sample_info.valid_data and s.client_id == 424242)
        or replies)
    assert [(r.sequence, r.success) for r in replies] == [(1, True)]


def _node_entries(samples, participant_hex):
    return [s.node_entities_info_seq for s in samples
            if s.sample_info.valid_data and bytes(s.gid.data).hex() == participant_hex]


def test_discovery_info_lists_peer_node_with_its_endpoint_gids(peer, raw):
    reader = discovery_reader(raw)
    seen = []

    def peer_listed():
        seen.extend(_node_entries(reader.take(N=256), peer.info['participant']))
        return seen and seen[-1]

    nodes = wait_for(peer_listed)
    assert [(n.node_namespace, n.node_name) for n in nodes] == [(NS, 'peer')]
    readers = {bytes(g.data).hex() for g in nodes[0].reader_gid_seq}
    writers = {bytes(g.data).hex() for g in nodes[0].writer_gid_seq}
    # A5.3: subscription and service request reader -> readers; publisher and reply writer ->
    # writers; the hidden parameter services, /rosout and /parameter_events add more.
    assert {peer.info['echo_in_reader'], peer.info['set_int_reader']} <= readers
    assert {peer.info['echo_out_writer'], peer.info['set_int_writer']} <= writers
    assert len(readers) == 2 + 6 and len(writers) == 2 + 6 + 2


def test_node_leaving_publishes_empty_entity_list_before_its_participant_goes(
        spawn_peer, raw):
    leaver = spawn_peer('--ros-args', '-r', '__node:=leaver', '-r', '__ns:=/tp_leave')
    guid_hex = leaver.info['participant']
    info_reader = discovery_reader(raw)
    participants = BuiltinDataReader(raw, BuiltinTopicDcpsParticipant)
    history = []
    handle = []

    def listed():
        history.extend(_node_entries(info_reader.take(N=256), guid_hex))
        for s in participants.take(N=256):
            if s.sample_info.valid_data and s.key.hex == guid_hex:
                handle.append(s.sample_info.instance_handle)
        return history and history[-1] and handle

    assert wait_for(listed)
    assert leaver.terminate() == 0
    gone = []

    def participant_gone():
        for s in participants.take(N=256):
            if (s.sample_info.instance_handle in handle
                    and s.sample_info.instance_state != InstanceState.Alive):
                # Read the discovery topic now: the empty list must already be there.
                history.extend(_node_entries(info_reader.take(N=256), guid_hex))
                gone.append(True)
        return gone

    assert wait_for(participant_gone)
    assert list(history[-1]) == []


def _parameter_client(node, service, srv_type):
    client = node.create_client('rcl_interfaces/srv/' + srv_type, f'{NS}/peer/{service}')
    assert client.wait_for_service(WAIT_S)
    return client, node.srv('rcl_interfaces/srv/' + srv_type).Request


def _double(node, value):
    return node.msg('rcl_interfaces/msg/ParameterValue')(
        type=PARAMETER_DOUBLE, double_value=value)


def _get_gain(node):
    client, request = _parameter_client(node, 'get_parameters', 'GetParameters')
    (value,) = client.call(request(names=['gain']), WAIT_S).values
    assert value.type == PARAMETER_DOUBLE
    return value.double_value


def test_parameter_services_list_get_set_and_reject(node, peer):
    events = []
    node.create_subscription('rcl_interfaces/msg/ParameterEvent', '/parameter_events',
                             events.append, QOS_PARAMETER_EVENTS)
    lister, list_request = _parameter_client(node, 'list_parameters', 'ListParameters')
    names = lister.call(list_request(), WAIT_S).result.names
    assert {'gain', 'use_sim_time'} <= set(names)
    assert _get_gain(node) == 2.5  # the -p gain:=2.5 override

    setter, set_request = _parameter_client(node, 'set_parameters', 'SetParameters')
    parameter = node.msg('rcl_interfaces/msg/Parameter')
    assert wait_for(lambda: setter._writer.get_matched_subscriptions())
    (ok,) = setter.call(set_request(parameters=[parameter(name='gain',
                                                          value=_double(node, 3.0))]),
                        WAIT_S).results
    assert ok.successful and _get_gain(node) == 3.0
    (rejected,) = setter.call(set_request(parameters=[parameter(
        name='gain', value=_double(node, 99.0))]), WAIT_S).results
    assert not rejected.successful and 'outside [0, 10]' in rejected.reason
    (wrong_type,) = setter.call(set_request(parameters=[parameter(
        name='gain', value=node.msg('rcl_interfaces/msg/ParameterValue')(
            type=PARAMETER_STRING, string_value='high'))]), WAIT_S).results
    assert not wrong_type.successful
    assert _get_gain(node) == 3.0  # unchanged by both rejected sets

    def gain_event():
        return [p.value.double_value for e in events if e.node == NS + '/peer'
                for p in e.changed_parameters if p.name == 'gain']

    assert wait_for(gain_event, spin=node) == [3.0]

    typer, types_request = _parameter_client(node, 'get_parameter_types', 'GetParameterTypes')
    assert list(typer.call(types_request(names=['gain', 'nope']), WAIT_S).types) == [
        PARAMETER_DOUBLE, PARAMETER_NOT_SET]
    describer, describe_request = _parameter_client(
        node, 'describe_parameters', 'DescribeParameters')
    (descriptor,) = describer.call(describe_request(names=['gain']), WAIT_S).descriptors
    assert descriptor.description == 'test gain [1]'


def test_rosout_receives_the_peer_log(node, peer):
    logs = []
    node.create_subscription('rcl_interfaces/msg/Log', '/rosout', logs.append, QOS_ROSOUT)
    found = wait_for(lambda: [m for m in logs if m.name == 'tp.peer' and
                              m.msg == 'peer ready'], spin=node)
    assert [(m.level, m.msg) for m in found] == [(20, 'peer ready')]
    # the process's first node also says which distribution it speaks (issue 11)
    (announced,) = [m for m in logs if m.name == 'tp.peer' and m.msg != 'peer ready']
    spoken = distro.title(distro.choose()[0])   # the peer runs in this test's environment
    assert (announced.level, announced.msg.split(' on domain')[0]) == (
        20, f'speaking ROS 2 {spoken}')


def test_use_sim_time_node_clock_follows_clock_topic(node):
    sim = DdsNode('sim_clock_user', '/tp_test', parameter_overrides={'use_sim_time': True})
    try:
        clock = node.create_publisher('rosgraph_msgs/msg/Clock', '/clock', QOS_CLOCK)
        clock_msg = node.msg('rosgraph_msgs/msg/Clock')
        time_msg = node.msg('builtin_interfaces/msg/Time')
        assert sim.now().nanoseconds == 0

        def ticked():
            clock.publish(clock_msg(clock=time_msg(sec=42, nanosec=5)))
            sim.spin_once(0.05)
            return sim.now().nanoseconds == 42_000_000_005

        assert wait_for(ticked)
    finally:
        sim.shutdown()


# -------------------------------------------------------------------- parameters in-process

def test_read_only_parameter_set_is_refused_with_rclpy_wording_and_keeps_its_value():
    node = DdsNode('read_only_user', '/tp_test')
    try:
        node.declare_parameter('model', 'Car', read_only=True)
        (result,) = node.set_parameters([Parameter('model', 'BmwX5')])
        assert (result.successful, result.reason) == (
            False, 'Trying to set a read-only parameter: model.')
        assert node.get_parameter('model') == 'Car'
    finally:
        node.shutdown()


def _warnings(text):
    return [line for line in text.splitlines() if line.startswith('[WARN]')]


def test_misspelt_override_is_warned_once_at_the_first_spin_naming_the_parameters(capsys):
    node = DdsNode('misspelt', '/tp_test',
                   args=['x', '--ros-args', '-p', 'publish_period:=0.02', '-p', 'period_ms:=20'])
    try:
        node.declare_parameter('period_ms', 0)
        assert _warnings(capsys.readouterr().err) == []     # declarations are not over yet
        node.spin_once(0.0)
        node.spin_once(0.0)
        (warning,) = _warnings(capsys.readouterr().err)
        assert warning.endswith(
            '[tp_test.misspelt]: ignored parameter override publish_period: not declared by '
            'this node; its parameters: period_ms, use_sim_time')
        assert node.get_parameter('period_ms') == 20
    finally:
        node.shutdown()


def test_params_file_entry_for_an_undeclared_parameter_is_warned(tmp_path, capsys):
    path = tmp_path / 'params.yaml'
    path.write_text('/tp_test/from_file:\n  ros__parameters:\n    gain: 2.0\n    gian: 3.0\n')
    node = DdsNode('from_file', '/tp_test', args=['--ros-args', '--params-file', str(path)])
    try:
        node.declare_parameter('gain', 1.0)
        node.spin_once(0.0)
        (warning,) = _warnings(capsys.readouterr().err)
        assert 'ignored parameter override gian (did you mean gain?)' in warning
        assert node.get_parameter('gain') == 2.0
    finally:
        node.shutdown()


def test_declared_overrides_give_no_warning(capsys):
    node = DdsNode('all_known', '/tp_test', args=['--ros-args', '-p', 'gain:=2.0'],
                   parameter_overrides={'use_sim_time': False})
    try:
        node.declare_parameter('gain', 1.0)
        node.spin_once(0.0)
        assert _warnings(capsys.readouterr().err) == []
    finally:
        node.shutdown()


def test_endpoint_user_data_puts_tokens_before_the_type_hash_like_rmw_cyclonedds():
    # rmw_cyclonedds (rmw_node.cpp): 'serviceid=<id>;typehash=RIHS01_<hex>;' on a service.
    assert dds.endpoint_user_data('std_srvs/srv/SetBool_Request', serviceid=7) == (
        b'serviceid=7;typehash=RIHS01_'
        b'c62fbb99d94e1b25e8ef9e109f9581956bb1b3361a45a4e5810c36a90d29932e;')
    assert dds.endpoint_user_data('std_msgs/msg/String') == (
        b'typehash=RIHS01_df668c740482bbd48fb39d76a70dfd4bd59db1288021743503259e948f6b1a18;')
