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
The Humble mode (issue 11): distribution choice, 24-byte Gid, warnings about peers.

The peers warned about speak the other distribution or run Fast DDS.

Bytes are compared to rosbags' Humble and Jazzy type stores (``Stores.ROS2_HUMBLE`` /
``ROS2_JAZZY``), which serialise like rosidl; a process speaks one distribution, so the Humble
layouts of the type store are checked in a subprocess.
"""

import json
import subprocess
import sys
import uuid

from automobile_helpers import wait_for, WAIT_S
from conftest import peer_env, PeerProcess, stop_processes
from cyclonedds.domain import DomainParticipant
from cyclonedds.qos import Policy, Qos
from cyclonedds.sub import DataReader
from cyclonedds.topic import Topic
import numpy as np
import pytest
from rosbags.typesys import get_typestore, Stores

from vehicle_msgs_py import distro
from vehicle_msgs_py import types as msg_types
from vehicle_sim.transport import dds
from vehicle_sim.transport.dds import cyclone_private, DdsNode, discovery_info, peers, services
from vehicle_sim.transport.dds.domain_config import domain_id
from vehicle_sim.transport.dds.graph import GraphView
from vehicle_sim.transport.first_call import call_until_answered
from vehicle_sim.transport.qos import QOS_DISCOVERY_INFO_READER

GUID = bytes(range(1, 17))
READER = bytes(range(0x20, 0x30))
WRITER = bytes(range(0x40, 0x50))
NODES = (discovery_info.NodeEntry('/', 'automobile', (READER,), (WRITER, READER)),
         discovery_info.NodeEntry('/ns', 'x'))


# --------------------------------------------------------------------------------------------
# Which distribution

@pytest.mark.parametrize('environ, expected', [
    ({}, 'jazzy'),
    ({'ROS_DISTRO': 'humble'}, 'humble'),
    ({'ROS_DISTRO': 'jazzy'}, 'jazzy'),
    ({'ROS_DISTRO': 'rolling'}, 'jazzy'),
    ({'VEHICLE_SIM_ROS_DISTRO': 'humble'}, 'humble'),
    ({'VEHICLE_SIM_ROS_DISTRO': 'Humble', 'ROS_DISTRO': 'jazzy'}, 'humble'),
    ({'VEHICLE_SIM_ROS_DISTRO': 'jazzy', 'ROS_DISTRO': 'humble'}, 'jazzy'),
    ({'VEHICLE_SIM_ROS_DISTRO': '', 'ROS_DISTRO': 'humble'}, 'humble'),
])
def test_distro_choice_explicit_wins_then_ros_distro_then_jazzy(environ, expected):
    chosen, why = distro.choose(environ)
    assert chosen == expected
    assert ('VEHICLE_SIM_ROS_DISTRO=' in why) == bool(environ.get('VEHICLE_SIM_ROS_DISTRO'))


def test_unknown_explicit_distro_is_refused_naming_the_variable():
    with pytest.raises(ValueError, match=r"VEHICLE_SIM_ROS_DISTRO='iron': expected one of "
                                         r'humble, jazzy'):
        distro.choose({'VEHICLE_SIM_ROS_DISTRO': 'iron', 'ROS_DISTRO': 'humble'})


# --------------------------------------------------------------------------------------------
# The ros_discovery_info codec

def _rosbags_info(store_name, gid_size):
    store = get_typestore(store_name)
    info = store.types['rmw_dds_common/msg/ParticipantEntitiesInfo']
    node = store.types['rmw_dds_common/msg/NodeEntitiesInfo']
    gid = store.types['rmw_dds_common/msg/Gid']

    def make_gid(guid):
        return gid(data=np.frombuffer(guid + bytes(gid_size - len(guid)), dtype=np.uint8))

    msg = info(gid=make_gid(GUID), node_entities_info_seq=[
        node(node_namespace=n.namespace, node_name=n.name,
             reader_gid_seq=[make_gid(g) for g in n.reader_gids],
             writer_gid_seq=[make_gid(g) for g in n.writer_gids]) for n in NODES])
    return store.serialize_cdr(msg, info.__msgtype__)


@pytest.mark.parametrize('store_name, gid_size', [(Stores.ROS2_HUMBLE, 24),
                                                  (Stores.ROS2_JAZZY, 16)])
def test_discovery_info_bytes_equal_rosbags_for_each_distro(store_name, gid_size):
    data = discovery_info.encode(GUID, NODES, gid_size)
    assert data == _rosbags_info(store_name, gid_size)
    if gid_size == 24:   # Humble: the 16-byte GUID, then 8 zero bytes
        assert data[4:4 + 24] == GUID + bytes(8)


@pytest.mark.parametrize('gid_size', [16, 24])
@pytest.mark.parametrize('prefer', [16, 24])
@pytest.mark.parametrize('nodes', [NODES, ()])
def test_discovery_info_decodes_in_the_layout_it_fits_whatever_is_preferred(
        gid_size, prefer, nodes):
    found = discovery_info.decode(discovery_info.encode(GUID, nodes, gid_size), prefer=prefer)
    assert found.gid_size == gid_size
    assert found.distro == ('humble' if gid_size == 24 else 'jazzy')
    assert found.gid == GUID
    assert found.nodes == tuple(nodes)


def test_discovery_info_decodes_rosbags_humble_bytes_with_16_byte_gids():
    found = discovery_info.decode(_rosbags_info(Stores.ROS2_HUMBLE, 24), prefer=16)
    assert (found.gid, found.nodes[0].writer_gids) == (GUID, (WRITER, READER))


# ros_discovery_info of an rclpy node '/h_talker' on a ROS 2 Humble built from source
# (rmw_cyclonedds_cpp, Cyclone DDS 0.10), captured off the wire.
HUMBLE_TALKER_INFO = bytes.fromhex(
    '0001000001102c651e378fb08d1271e0000001c1000000000000000001000000020000002f00000009000000'
    '685f74616c6b6572000000000600000001102c651e378fb08d1271e000000904000000000000000001102c65'
    '1e378fb08d1271e000000b04000000000000000001102c651e378fb08d1271e000000d040000000000000000'
    '01102c651e378fb08d1271e000000f04000000000000000001102c651e378fb08d1271e00000110400000000'
    '0000000001102c651e378fb08d1271e00000130400000000000000000900000001102c651e378fb08d1271e0'
    '00000603000000000000000001102c651e378fb08d1271e000000703000000000000000001102c651e378fb0'
    '8d1271e000000803000000000000000001102c651e378fb08d1271e000000a03000000000000000001102c65'
    '1e378fb08d1271e000000c03000000000000000001102c651e378fb08d1271e000000e030000000000000000'
    '01102c651e378fb08d1271e000001003000000000000000001102c651e378fb08d1271e00000120300000000'
    '0000000001102c651e378fb08d1271e0000014030000000000000000')

# The same from '/f_talker' on ROS 2 Jazzy with Fast DDS 2.14.5 (rmw_fastrtps_dynamic_cpp).
FAST_DDS_TALKER_INFO = bytes.fromhex(
    '00010000010f78fd965c8d5a00000000000001c101000000020000002f00000009000000665f74616c6b6572'
    '0000000007000000010f78fd965c8d5a0000000000000504010f78fd965c8d5a0000000000000704010f78fd'
    '965c8d5a0000000000000904010f78fd965c8d5a0000000000000b04010f78fd965c8d5a0000000000000d04'
    '010f78fd965c8d5a0000000000000f04010f78fd965c8d5a00000000000011040a000000010f78fd965c8d5a'
    '0000000000000303010f78fd965c8d5a0000000000000403010f78fd965c8d5a0000000000000603010f78fd'
    '965c8d5a0000000000000803010f78fd965c8d5a0000000000000a03010f78fd965c8d5a0000000000000c03'
    '010f78fd965c8d5a0000000000000e03010f78fd965c8d5a0000000000001003010f78fd965c8d5a00000000'
    '00001203010f78fd965c8d5a0000000000001303')


@pytest.mark.parametrize('data, gid_size, name, counts', [
    (HUMBLE_TALKER_INFO, 24, 'h_talker', (6, 9)),
    (FAST_DDS_TALKER_INFO, 16, 'f_talker', (7, 10)),
])
def test_discovery_info_of_real_builds_decodes_and_encodes_to_the_same_bytes(
        data, gid_size, name, counts):
    found = discovery_info.decode(data, prefer=40 - gid_size)   # the other layout first
    assert found.gid_size == gid_size
    assert [(n.namespace, n.name) for n in found.nodes] == [('/', name)]
    node = found.nodes[0]
    assert (len(node.reader_gids), len(node.writer_gids)) == counts
    # every endpoint gid belongs to the participant (same 12-byte GUID prefix)
    assert {g[:12] for g in node.reader_gids + node.writer_gids} == {found.gid[:12]}
    assert discovery_info.encode(found.gid, found.nodes, gid_size) == data


@pytest.mark.parametrize('damage', ['truncated', 'not utf-8', 'not cdr', 'extra bytes'])
def test_discovery_info_that_fits_no_layout_is_refused(damage):
    data = discovery_info.encode(GUID, NODES, 24)
    data = {'truncated': data[:-6],
            'not utf-8': data.replace(b'automobile', b'\xff\xfeutomobile'),
            'not cdr': b'\x07\x07\x00\x00' + data[4:],
            'extra bytes': data + b'\x01' * 8}[damage]
    with pytest.raises(discovery_info.UndecodableSample):
        discovery_info.decode(data)


# --------------------------------------------------------------------------------------------
# Layouts of a Humble process (a subprocess: one process speaks one distribution)

RANGE_CHECK = """
import json, sys
from vehicle_msgs_py import distro, types
from vehicle_sim.ros import messages
rng = types.message_type('sensor_msgs/msg/Range')
stamp = types.message_type('builtin_interfaces/msg/Time')(sec=3, nanosec=5)
class Reading:
    radiation_type, field_of_view_rad, min_range_m, max_range_m = 1, 0.5, 0.1, 4.0
    range_m, variance_m2 = 2.5, 0.01
msg = messages.range_builder(types.message_type, 'sonar')(stamp, Reading)
print(json.dumps({'distro': distro.selected(), 'variance': hasattr(rng, 'variance'),
                  'bytes': msg.serialize().hex()}))
"""


def _range_in(env_distro):
    env = peer_env()
    env['VEHICLE_SIM_ROS_DISTRO'] = env_distro
    done = subprocess.run([sys.executable, '-c', RANGE_CHECK], env=env, capture_output=True,
                          text=True, timeout=WAIT_S, check=True)
    return json.loads(done.stdout)


@pytest.mark.parametrize('env_distro, store_name', [('humble', Stores.ROS2_HUMBLE),
                                                    ('jazzy', Stores.ROS2_JAZZY)])
def test_range_has_each_distros_layout(env_distro, store_name):
    found = _range_in(env_distro)
    store = get_typestore(store_name)
    types = store.types
    fields = dict(header=types['std_msgs/msg/Header'](
        stamp=types['builtin_interfaces/msg/Time'](sec=3, nanosec=5), frame_id='sonar'),
        radiation_type=1, field_of_view=0.5, min_range=0.1, max_range=4.0, range=2.5)
    if env_distro == 'jazzy':
        fields['variance'] = 0.01
    expected = store.serialize_cdr(types['sensor_msgs/msg/Range'](**fields),
                                   'sensor_msgs/msg/Range')
    assert found['distro'] == env_distro
    assert found['variance'] == (env_distro == 'jazzy')
    assert bytes.fromhex(found['bytes']) == expected


# --------------------------------------------------------------------------------------------
# Two processes, one in each mode, on this test's domain

def _peer(env_distro, namespace, monkeypatch):
    with monkeypatch.context() as patch:
        patch.setenv('VEHICLE_SIM_ROS_DISTRO', env_distro)
        return PeerProcess(['--ros-args', '-r', '__node:=peer', '-r', f'__ns:={namespace}'])


def _warnings(peer, about):
    return [line for line in peer.stderr_lines
            if '[WARN]' in line and f'a ROS 2 {about} participant' in line]


def _node_lists_of(reader, participant_hex):
    """Return the node lists the participant wrote to ros_discovery_info (raw reader)."""
    found = []
    for data, info in cyclone_private.take_serialized(reader, 256):
        if info.valid_data:
            sample = discovery_info.decode(data)
            if sample.gid.hex() == participant_hex:
                found.append(sample.nodes)
    return found


@pytest.mark.transport
def test_a_humble_and_a_jazzy_process_each_warn_once_and_keep_serving(monkeypatch):
    humble = _peer('humble', '/distro_h', monkeypatch)
    # Everything written to ros_discovery_info from now on (transient local, keep all).
    dds.ensure_domain()
    raw = DomainParticipant(domain_id())
    info_type = msg_types.message_type('rmw_dds_common/msg/ParticipantEntitiesInfo')
    reader = DataReader(raw, Topic(raw, 'ros_discovery_info', info_type),
                        qos=dds.dds_qos(QOS_DISCOVERY_INFO_READER, b'', writer=False))
    jazzy = _peer('jazzy', '/distro_j', monkeypatch)
    try:
        assert 'speaking ROS 2 Humble' in ''.join(humble.stderr_lines)
        assert 'speaking ROS 2 Jazzy' in ''.join(jazzy.stderr_lines)
        assert wait_for(lambda: _warnings(jazzy, 'Humble') and _warnings(humble, 'Jazzy'))
        (to_jazzy,) = _warnings(jazzy, 'Humble')
        assert 'set VEHICLE_SIM_ROS_DISTRO=humble' in to_jazzy
        (to_humble,) = _warnings(humble, 'Jazzy')
        assert 'set VEHICLE_SIM_ROS_DISTRO=jazzy' in to_humble
        assert 'no longer announces its nodes' in to_jazzy
        with GraphView() as view:
            # the Jazzy process, having met a Humble one, announces no nodes (Humble would
            # misread them); the Humble process's nodes are listed with their distribution
            def listed():
                by_guid = {p.guid.hex(): p for p in view.participants()}
                return (by_guid.get(humble.info['participant']),
                        by_guid.get(jazzy.info['participant']))

            assert view.wait_until(lambda: all(listed()) and listed()[0].nodes and
                                   listed()[1].distro and not listed()[1].nodes, WAIT_S)
            humble_entry, jazzy_entry = listed()
            assert (humble_entry.vendor, humble_entry.distro, humble_entry.nodes) == (
                peers.CYCLONE, 'humble', ('/distro_h/peer',))
            assert (jazzy_entry.vendor, jazzy_entry.distro) == (peers.CYCLONE, 'jazzy')
            assert view.find_node('/distro_h/peer').distro == 'humble'
            assert view.find_node('/distro_j/peer') is None
            other = 'humble' if view.distro == 'jazzy' else 'jazzy'
            assert len(view.warnings) == 1
            assert f'set VEHICLE_SIM_ROS_DISTRO={other}' in view.warnings[0]
            # each still serves: a call from this process to both works
            node = DdsNode('distro_caller', '/distro_test')
            try:
                for namespace in ('/distro_h', '/distro_j'):
                    client = node.create_client('vehicle_msgs/srv/SetInt',
                                                f'{namespace}/set_int')
                    assert client.wait_for_service(WAIT_S)
                    # (set_int only stores its value: sent again if lost, docs/transport.md)
                    assert call_until_answered(client, client._types.request(value=4),
                                               WAIT_S).success
            finally:
                node.shutdown()
        assert len(_warnings(jazzy, 'Humble')) == 1 and len(_warnings(humble, 'Jazzy')) == 1
        # The Jazzy process met the Humble one before announcing: it never wrote a node list
        # (Humble keeps a misread one for good), only empty ones.
        written = _node_lists_of(reader, jazzy.info['participant'])
        assert written and all(nodes == () for nodes in written)
    finally:
        stop_processes([humble.proc, jazzy.proc])
        cyclone_private.delete_participant(raw)


# --------------------------------------------------------------------------------------------
# Vendors and Fast DDS clients

@pytest.mark.parametrize('prefix, vendor', [
    ('010f', peers.FAST_DDS), ('0110', peers.CYCLONE), ('0101', 'RTI Connext DDS'),
    ('ab12', peers.UNKNOWN), ('', peers.UNKNOWN)])
def test_vendor_from_the_guid_prefix(prefix, vendor):
    assert peers.vendor_of(bytes.fromhex(prefix + '00' * (14 if prefix else 0))) == vendor


def test_this_process_participant_is_cyclone():
    node = DdsNode('vendor_self', '/distro_test')
    try:
        from vehicle_sim.transport import dds
        assert peers.vendor_of(dds.participant_guid()) == peers.CYCLONE
    finally:
        node.shutdown()


class _Endpoint:
    def __init__(self, prefix, user_data):
        self.participant_key = uuid.UUID(bytes=bytes.fromhex(prefix) + bytes(14))
        self.qos = Qos(Policy.Userdata(data=user_data)) if user_data is not None else Qos()


class _Status:
    def __init__(self, total):
        self.total_count = total


class _FakeRequestReader:
    """Stands in for a service's request reader: its matched request writers."""

    def __init__(self):
        self.writers = {}

    def get_subscription_matched_status(self):
        return _Status(len(self.writers))

    def get_matched_publications(self):
        return list(self.writers)

    def get_matched_publication_data(self, handle):
        return self.writers.get(handle)


class _Log:
    def __init__(self):
        self.lines = []

    def warning(self, text):
        self.lines.append(text)


def test_a_fast_dds_client_is_warned_about_once_per_client_and_service(monkeypatch):
    node = DdsNode('fast_dds_check', '/distro_test')
    try:
        first = node.create_service('vehicle_msgs/srv/SetInt', 'set_int', lambda q, r: r)
        second = node.create_service('vehicle_msgs/srv/SetInt', 'set_other', lambda q, r: r)
        log = _Log()
        monkeypatch.setattr(node, 'get_logger', lambda: log)
        fakes = [_FakeRequestReader(), _FakeRequestReader()]
        monkeypatch.setattr(first, '_reader', fakes[0])
        monkeypatch.setattr(second, '_reader', fakes[1])
        fakes[0].writers[1] = _Endpoint('010f', None)                   # Fast DDS client
        fakes[0].writers[2] = _Endpoint('0110', b'clientid=1.2.3;')     # rmw_cyclonedds client
        fakes[0].writers[3] = _Endpoint('0110', b'')                    # Cyclone, no id: served
        services.warn_unservable_clients([first, second])
        services.warn_unservable_clients([first, second])
        (line,) = log.lines
        assert line.startswith('service /distro_test/set_int: a client (participant 01.0f.')
        assert 'runs Fast DDS' in line and 'RMW_IMPLEMENTATION=rmw_cyclonedds_cpp' in line
        assert 'rclpy' in line
        # one client participant matching two services at once: one line naming both
        other = _Endpoint('010f', b'enclave=/;')
        other.participant_key = uuid.UUID(bytes=bytes.fromhex('010f') + b'\x07' * 14)
        fakes[0].writers[4] = other
        fakes[1].writers[9] = other
        services.warn_unservable_clients([first, second])
        assert len(log.lines) == 2
        assert log.lines[1].startswith(
            'services /distro_test/set_int, /distro_test/set_other: a client (participant '
            '01.0f.07.07.')
    finally:
        node.shutdown()


class _FakeRequestWriter:
    """Stands in for a client's request writer: its matched request readers (servers)."""

    def __init__(self, write):
        self.readers = {}
        self.write = write

    def get_matched_subscriptions(self):
        return list(self.readers)

    def get_matched_subscription_data(self, handle):
        return self.readers.get(handle)


def test_a_call_to_a_fast_dds_server_says_why_it_gets_no_answer(monkeypatch):
    # Measured on Jazzy with Fast DDS 2.14.5: the server's request reader matches, drops the
    # 24-byte request ("payload size larger than the history payload size") and never answers.
    from vehicle_sim.transport.errors import ServiceTimeoutError
    node = DdsNode('fast_dds_server_check', '/distro_test')
    try:
        client = node.create_client('std_srvs/srv/SetBool', '/distro_test/fast_srv')
        log = _Log()
        monkeypatch.setattr(node, 'get_logger', lambda: log)
        fake = _FakeRequestWriter(client._writer.write)
        fake.readers[7] = _Endpoint('010f', None)               # a Fast DDS server
        fake.readers[8] = _Endpoint('0110', b'serviceid=1.2;')  # an rmw_cyclonedds one
        monkeypatch.setattr(client, '_writer', fake)
        assert [vendor for _, vendor in client.foreign_servers()] == ['eProsima Fast DDS']
        monkeypatch.setattr(client, 'service_is_ready', lambda: True)
        assert client.wait_for_service(1.0) and client.wait_for_service(1.0)
        (line,) = log.lines                                     # once per server and client
        assert line.startswith('the server of /distro_test/fast_srv (participant 01.0f.')
        assert 'runs Fast DDS' in line and 'RMW_IMPLEMENTATION=rmw_cyclonedds_cpp' in line
        with pytest.raises(ServiceTimeoutError) as error:
            client.call(node.srv('std_srvs/srv/SetBool').Request(data=True), 0.2)
        assert str(error.value).startswith('no reply from /distro_test/fast_srv within 0.2 s; '
                                           'the server of /distro_test/fast_srv (participant '
                                           '01.0f.')
        fake.readers.pop(7)                                     # only Cyclone servers: no why
        with pytest.raises(ServiceTimeoutError) as error:
            client.call(node.srv('std_srvs/srv/SetBool').Request(data=True), 0.2)
        assert str(error.value) == 'no reply from /distro_test/fast_srv within 0.2 s'
    finally:
        node.shutdown()
