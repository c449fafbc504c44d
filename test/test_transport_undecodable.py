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
A sample that cannot be decoded is dropped and counted; the node serves on (issue 7, item 2).

Over the wire, in separate processes: a GetParameters request whose name is not UTF-8 sent to
the automobile node, and a JointState whose frame_id is not UTF-8 sent to the bridge node. In
this process: every other kind of reader (subscription, client reply, graph reader).
"""

from automobile_helpers import NodeProcess, wait_for, WAIT_S
from conftest import peer_env
from cyclonedds.domain import DomainParticipant
from cyclonedds.pub import DataWriter
from cyclonedds.sub import DataReader
from cyclonedds.topic import Topic
import pytest

from vehicle_msgs_py import types as msg_types
from vehicle_sim.ros import bridge_interfaces as bi
from vehicle_sim.transport import dds
from vehicle_sim.transport.dds import cyclone_private, DdsNode
from vehicle_sim.transport.dds.domain_config import domain_id
from vehicle_sim.transport.dds.graph import GraphView
from vehicle_sim.transport.parameter_types import PARAMETER_BOOL, PARAMETER_STRING
from vehicle_sim.transport.qos import (
    QOS_DEFAULT,
    QOS_DISCOVERY_INFO_WRITER,
    QOS_PARAMETERS,
    QOS_SERVICES,
)

pytestmark = pytest.mark.transport

NOT_UTF8 = b'\xff\xfe\xc3'
GET_PARAMETERS = 'rcl_interfaces/srv/GetParameters'
CLIENT_TOKEN = 'undecodable-test-client'


def _with_bad_string(sample, placeholder='abc'):
    """Serialize ``sample`` and put NOT_UTF8 in place of its ``placeholder`` string."""
    data = sample.serialize()
    assert data.count(placeholder.encode()) == 1
    return data.replace(placeholder.encode(), NOT_UTF8)


@pytest.fixture(scope='module')
def raw():
    dds.ensure_domain()
    participant = DomainParticipant(domain_id())
    yield participant
    cyclone_private.delete_participant(participant)


@pytest.fixture(scope='module')
def tester():
    node = DdsNode('undecodable_tester', '/undecodable_test')
    yield node
    node.shutdown()


def _raw_client(raw, service):
    """Return a raw request writer and reply reader of ``service`` sharing one clientid."""
    types = msg_types.service_types(GET_PARAMETERS)
    user_data = f'clientid={CLIENT_TOKEN};'.encode()
    reader = DataReader(raw, Topic(raw, f'rr{service}Reply', types.response_wire),
                        qos=dds.dds_qos(QOS_PARAMETERS, user_data, writer=False))
    writer = DataWriter(raw, Topic(raw, f'rq{service}Request', types.request_wire),
                        qos=dds.dds_qos(QOS_PARAMETERS, user_data, writer=True))
    return types, writer, reader


def test_automobile_node_drops_a_request_that_is_not_utf8_and_answers_the_next(raw, tester):
    # (the nodes on the embedded transport, whose decoding this is: on rclpy, rosidl's
    # conversion decodes such a string with replacement characters and answers the request)
    process = NodeProcess('--ros-args', '-r', '__ns:=/undecodable', '-p', 'synchronous:=true',
                          env=peer_env(transport='dds'))
    try:
        service = '/undecodable/automobile/get_parameters'
        types, writer, reader = _raw_client(raw, service)
        assert wait_for(lambda: writer.get_matched_subscriptions()
                        and reader.get_matched_publications()), process.text()
        bad = _with_bad_string(types.request_to_wire(types.request(names=['abc']), 7, 1))
        assert len(bad) == 32   # header 4 + client id 8 + sequence 8 + one 4-byte name in a list
        cyclone_private.write_serialized(writer, bad)
        # Right behind it (same take batch, most likely): a valid request of the same client.
        writer.write(types.request_to_wire(types.request(names=['use_sim_time']), 7, 2))
        replies = []
        assert wait_for(lambda: replies.extend(
            s for s in cyclone_private.take(reader, 16)[0] if s.client_id == 7) or replies)
        assert [(r.sequence, [v.bool_value for v in r.values]) for r in replies] == [
            (2, [False])]
        # A later request from an ordinary client is answered too, and the node still runs.
        client = tester.create_client(GET_PARAMETERS, service)
        assert client.wait_for_service(WAIT_S)
        answer = client.call(tester.srv(GET_PARAMETERS).Request(names=['car_model']), WAIT_S)
        assert [v.string_value for v in answer.values] == ['Car']
        assert process.proc.poll() is None
        assert wait_for(lambda: 'cannot be decoded' in process.text())
        warning = next(line for line in process.text().splitlines()
                       if 'cannot be decoded' in line)
        assert f'service {service} ({GET_PARAMETERS}) request' in warning
        assert 'UnicodeDecodeError' in warning and '1 dropped so far' in warning
    finally:
        process.stop()


def test_bridge_node_drops_a_joint_state_that_is_not_utf8_and_serves_on(raw, tester):
    process = NodeProcess('--ros-args', '-r', '__node:=undecodable_bridge',
                          '-r', f'{bi.JOINT_STATES_IN.name}:=/undecodable/joint_states',
                          module='vehicle_sim.ros.bridge_node', env=peer_env(transport='dds'))
    try:
        joint_state = msg_types.message_type(bi.JOINT_STATES_IN.ros_type)
        writer = DataWriter(raw, Topic(raw, 'rt/undecodable/joint_states', joint_state),
                            qos=dds.dds_qos(bi.JOINT_STATES_IN.qos, b'', writer=True))
        assert wait_for(lambda: writer.get_matched_subscriptions()), process.text()
        sample = joint_state()
        sample.header.frame_id = 'abc'
        cyclone_private.write_serialized(writer, _with_bad_string(sample))
        assert wait_for(lambda: 'cannot be decoded' in process.text()), process.text()
        # The node still answers requests (its parameter services).
        client = tester.create_client(GET_PARAMETERS, '/undecodable_bridge/get_parameters')
        assert client.wait_for_service(WAIT_S)
        answer = client.call(tester.srv(GET_PARAMETERS).Request(names=['use_sim_time']),
                             WAIT_S)
        assert [v.type for v in answer.values] == [PARAMETER_BOOL]
        assert process.proc.poll() is None
        assert 'subscription /undecodable/joint_states (sensor_msgs/msg/JointState)' in (
            process.text())
    finally:
        process.stop()


def test_subscription_drops_the_undecodable_sample_and_keeps_the_rest_of_the_batch(raw):
    node = DdsNode('undecodable_subscriber', '/undecodable_test')
    try:
        string = msg_types.message_type('std_msgs/msg/String')
        received = []
        sub = node.create_subscription('std_msgs/msg/String', '/undecodable/strings',
                                       lambda m: received.append(m.data))
        writer = DataWriter(raw, Topic(raw, 'rt/undecodable/strings', string),
                            qos=dds.dds_qos(QOS_DEFAULT, b'', writer=True))
        assert wait_for(lambda: writer.get_matched_subscriptions())
        writer.write(string(data='before'))
        cyclone_private.write_serialized(writer, _with_bad_string(string(data='abc')))
        writer.write(string(data='after'))
        assert wait_for(lambda: len(received) == 2, spin=node)
        assert received == ['before', 'after']
        assert sub.dropped_samples == 1
    finally:
        node.shutdown()


def test_client_drops_an_undecodable_reply_and_takes_the_next(raw):
    node = DdsNode('undecodable_client', '/undecodable_test')
    try:
        service = '/undecodable/fake_get_parameters'
        types = msg_types.service_types(GET_PARAMETERS)
        server_requests = DataReader(raw, Topic(raw, f'rq{service}Request', types.request_wire),
                                     qos=dds.dds_qos(QOS_SERVICES, b'', writer=False))
        server_replies = DataWriter(raw, Topic(raw, f'rr{service}Reply', types.response_wire),
                                    qos=dds.dds_qos(QOS_SERVICES, b'', writer=True))
        client = node.create_client(GET_PARAMETERS, service)
        assert client.wait_for_service(WAIT_S)
        future = client.call_async(types.request(names=['x']))
        requests = []
        assert wait_for(lambda: requests.extend(cyclone_private.take(server_requests, 4)[0])
                        or requests)
        value = msg_types.message_type('rcl_interfaces/msg/ParameterValue')
        reply = types.response(values=[value(type=PARAMETER_STRING, string_value='abc')])
        cyclone_private.write_serialized(server_replies, _with_bad_string(
            types.response_to_wire(reply, client.client_id, future.sequence)))
        reply.values[0].string_value = 'fine'
        server_replies.write(types.response_to_wire(reply, client.client_id, future.sequence))
        assert node.spin_until(future.done, WAIT_S)
        assert [v.string_value for v in future.result().values] == ['fine']
        assert client.dropped_samples == 1
    finally:
        node.shutdown()


def test_graph_view_drops_an_undecodable_discovery_sample_and_still_lists_nodes(raw):
    info_type = msg_types.message_type('rmw_dds_common/msg/ParticipantEntitiesInfo')
    node_info = msg_types.message_type('rmw_dds_common/msg/NodeEntitiesInfo')
    gid = msg_types.message_type('rmw_dds_common/msg/Gid')
    writer = DataWriter(raw, Topic(raw, 'ros_discovery_info', info_type),
                        qos=dds.dds_qos(QOS_DISCOVERY_INFO_WRITER, b'', writer=True))
    bad = info_type(gid=gid(data=b'\x01' * 16), node_entities_info_seq=[
        node_info(node_namespace='/', node_name='abc')])
    with GraphView() as view:
        assert wait_for(lambda: writer.get_matched_subscriptions())
        cyclone_private.write_serialized(writer, _with_bad_string(bad))
        node = DdsNode('undecodable_listed', '/undecodable_test')
        try:
            assert view.wait_until(
                lambda: view.find_node('/undecodable_test/undecodable_listed'), WAIT_S)
            assert view.dropped_samples == 1
        finally:
            node.shutdown()
