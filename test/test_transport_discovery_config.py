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
The Cyclone configuration per discovery range, as rmw_cyclonedds (Jazzy) builds it (item 8).

The expected fragments are transcribed from rmw_cyclonedds' ``rmw_node.cpp``
(``check_create_domain``) and rcl's ``init.c`` (ROS_LOCALHOST_ONLY wins, static peers dropped).
Only LOCALHOST configurations are handed to Cyclone here (DDS traffic of the tests stays on
loopback); the others are checked as text and as well-formed XML.
"""

import os
from xml.etree import ElementTree

from automobile_helpers import make_client_node, NodeProcess, wait_node_matched, WAIT_S
from conftest import peer_env
import pytest

from vehicle_sim.ros import automobile_interfaces as itf
from vehicle_sim.transport.dds import domain_config
from vehicle_sim.transport.errors import TransportError

RMW_LOCALHOST = (
    '<CycloneDDS><Domain><General><AllowMulticast>false</AllowMulticast></General>'
    '<Discovery><ParticipantIndex>auto</ParticipantIndex>'
    '<MaxAutoParticipantIndex>32</MaxAutoParticipantIndex>'
    '<Peers><Peer address="localhost"/>{peers}</Peers></Discovery></Domain></CycloneDDS>')
RMW_OFF = (
    '<CycloneDDS><Domain><General><AllowMulticast>false</AllowMulticast></General>'
    '<Discovery><ParticipantIndex>none</ParticipantIndex><Tag>ros_discovery_off_4242</Tag>'
    '</Discovery></Domain></CycloneDDS>')
RMW_SUBNET = (
    '<CycloneDDS><Domain><Discovery><ParticipantIndex>auto</ParticipantIndex>'
    '<MaxAutoParticipantIndex>32</MaxAutoParticipantIndex>{peers}</Discovery></Domain>'
    '</CycloneDDS>')
PEERS = {'ROS_STATIC_PEERS': '192.168.1.7;robot.local'}
PEER_XML = '<Peer address="192.168.1.7"/><Peer address="robot.local"/>'
LOOPBACK_PIN = '<NetworkInterface address="127.0.0.1"/>'
LINGER = '<WriterLingerDuration>0 s</WriterLingerDuration>'
USER_LO_NAME = ('<CycloneDDS><Domain><General><Interfaces><NetworkInterface name="lo"/>'
                '</Interfaces></General></Domain></CycloneDDS>')
USER_LO_ADDRESS = ('<CycloneDDS><Domain><General><Interfaces>'
                   '<NetworkInterface address="127.0.0.1"/></Interfaces></General></Domain>'
                   '</CycloneDDS>')


def _env(scope, **more):
    env = {'ROS_AUTOMATIC_DISCOVERY_RANGE': scope} if scope else {}
    env.update(more)
    return env


@pytest.mark.parametrize('env, expected', [
    (_env('LOCALHOST'), RMW_LOCALHOST.format(peers='')),
    (_env('LOCALHOST', **PEERS), RMW_LOCALHOST.format(peers=PEER_XML)),
    (_env('OFF', **PEERS), RMW_OFF),                       # static peers ignored
    (_env('SUBNET'), RMW_SUBNET.format(peers='')),
    (_env(None), RMW_SUBNET.format(peers='')),             # the default range
    (_env('SUBNET', **PEERS), RMW_SUBNET.format(peers=f'<Peers>{PEER_XML}</Peers>')),
    (_env('SYSTEM_DEFAULT', **PEERS), ''),                 # nothing, static peers ignored
    # ROS_LOCALHOST_ONLY=1 wins over the range and drops the static peers (rcl init.c).
    (_env('SUBNET', ROS_LOCALHOST_ONLY='1', **PEERS), RMW_LOCALHOST.format(peers='')),
])
def test_rmw_fragment_per_range_is_the_one_rmw_cyclonedds_builds(env, expected):
    assert domain_config.rmw_fragment(env, pid=4242) == expected
    if expected:
        ElementTree.fromstring(expected)   # well-formed


@pytest.mark.parametrize('scope', domain_config.RANGES)
def test_config_is_ours_then_rmw_then_the_user_uri_in_every_range(scope):
    user = '<CycloneDDS><Domain><Tracing><Verbosity>warning</Verbosity></Tracing></Domain>' \
           '</CycloneDDS>'
    env = _env(scope, CYCLONEDDS_URI=user, ROS_DOMAIN_ID='3')
    parts = [domain_config.own_fragment(env), domain_config.rmw_fragment(env), user]
    assert domain_config.cyclone_config(env) == ','.join(p for p in parts if p)
    assert LINGER in parts[0]   # every range: no writer linger on shutdown
    assert (LOOPBACK_PIN in parts[0]) == (scope == 'LOCALHOST')
    # LOCALHOST announces every second: multicast-only peers (Humble's Fast DDS with
    # ROS_LOCALHOST_ONLY=1) learn of us from our unicast announcements alone.
    assert ('<SPDPInterval>1 s</SPDPInterval>' in parts[0]) == (scope == 'LOCALHOST')


@pytest.mark.parametrize('user_uri', [
    USER_LO_NAME,
    USER_LO_ADDRESS,
    # Cyclone accepts inline fragments without the CycloneDDS / Domain elements.
    '<General><Interfaces><NetworkInterface name="lo"/></Interfaces></General>',
    '<Domain id="any"><General><Interfaces><NetworkInterface name="lo"/></Interfaces>'
    '</General></Domain>',
    '<CycloneDDS><Domain Id="3"><General><NetworkInterfaceAddress>127.0.0.1'
    '</NetworkInterfaceAddress></General></Domain></CycloneDDS>',   # deprecated form
    '<CycloneDDS xmlns="https://cdds.io/config"><Domain><General><Interfaces>'
    '<NetworkInterface name="lo"/></Interfaces></General></Domain></CycloneDDS>',
    f'<Tracing><Verbosity>warning</Verbosity></Tracing>,{USER_LO_NAME}',
])
def test_localhost_pins_no_interface_when_the_user_uri_selects_one(user_uri):
    env = _env('LOCALHOST', CYCLONEDDS_URI=user_uri, ROS_DOMAIN_ID='3')
    assert LOOPBACK_PIN not in domain_config.own_fragment(env)
    assert domain_config.cyclone_config(env).endswith(user_uri)


def test_localhost_reads_interface_selections_from_configuration_files(tmp_path):
    path = tmp_path / 'cyclone.xml'
    path.write_text('<?xml version="1.0" encoding="utf-8"?>\n' + USER_LO_ADDRESS)
    for uri in (str(path), f'file://{path}'):
        env = _env('LOCALHOST', CYCLONEDDS_URI=uri, ROS_DOMAIN_ID='3')
        assert LOOPBACK_PIN not in domain_config.cyclone_config(env)
    # A file that cannot be read: leave the interfaces to the user's configuration, like rmw.
    env = _env('LOCALHOST', CYCLONEDDS_URI=str(tmp_path / 'missing.xml'))
    assert LOOPBACK_PIN not in domain_config.cyclone_config(env)


@pytest.mark.parametrize('user_uri', [
    '',
    '<CycloneDDS><Domain><Tracing><Verbosity>warning</Verbosity></Tracing></Domain>'
    '</CycloneDDS>',
    # An interface chosen for another domain does not apply to ours.
    '<CycloneDDS><Domain Id="9"><General><Interfaces><NetworkInterface name="eth0"/>'
    '</Interfaces></General></Domain></CycloneDDS>',
])
def test_localhost_pins_loopback_when_the_user_uri_selects_none(user_uri):
    env = _env('LOCALHOST', CYCLONEDDS_URI=user_uri, ROS_DOMAIN_ID='3')
    assert LOOPBACK_PIN in domain_config.cyclone_config(env)


def test_bad_range_is_refused_and_localhost_only_is_honoured():
    with pytest.raises(TransportError, match='ROS_AUTOMATIC_DISCOVERY_RANGE'):
        domain_config.discovery_range(_env('PLANET'))
    assert domain_config.discovery_range({'ROS_LOCALHOST_ONLY': '1'}) == 'LOCALHOST'
    assert domain_config.discovery_range({}) == 'SUBNET'


def test_domain_error_is_one_line_naming_cyclone_reason_and_the_environment():
    uri = '<CycloneDDS><Domain><NoSuchSetting>1</NoSuchSetting></Domain></CycloneDDS>'
    env = _env('LOCALHOST', CYCLONEDDS_URI=uri, ROS_DOMAIN_ID='7')
    with pytest.raises(TransportError) as raised:
        domain_config.create_domain(7, env)
    message = str(raised.value)
    assert '\n' not in message
    assert message.startswith('Cyclone DDS refused domain 7: ')
    assert 'NoSuchSetting' in message
    for name in ('ROS_DOMAIN_ID', 'ROS_AUTOMATIC_DISCOVERY_RANGE', 'CYCLONEDDS_URI'):
        assert name in message


@pytest.mark.parametrize('user_uri, namespace', [(USER_LO_ADDRESS, '/user_uri_address'),
                                                 (USER_LO_NAME, '/user_uri_name')],
                         ids=['address_127_0_0_1', 'name_lo'])
def test_node_starts_and_serves_with_a_user_uri_selecting_loopback(user_uri, namespace):
    # A namespace of its own per case: the test process's one DDS participant may still know
    # the previous case's server for a while after that process ended, and a request sent to it
    # alone would get no reply (the service race of ROS 2 itself, not what is tested here).
    env = peer_env()
    env['CYCLONEDDS_URI'] = user_uri
    process = NodeProcess('--ros-args', '-r', f'__ns:={namespace}', '-p', 'synchronous:=true',
                          env=env)
    node = make_client_node('user_uri_tester')
    try:
        client = node.create_client('vehicle_msgs/srv/SetInt',
                                    f'{namespace}/' + itf.service('robot/time_step').name)
        assert client.wait_for_service(WAIT_S), process.text()
        # the node just started: its match of the client first (docs/transport.md, "A service
        # just discovered")
        wait_node_matched(node, f'{namespace}/automobile/get_parameters',
                          'rcl_interfaces/srv/GetParameters')
        request = node.srv('vehicle_msgs/srv/SetInt').Request(value=30)
        assert client.call(request, WAIT_S).success is True
        assert process.proc.poll() is None
    finally:
        node.shutdown()
        process.stop()


@pytest.mark.parametrize('module, program', [
    ('vehicle_sim.ros.automobile_node', 'automobile'),
    ('vehicle_sim.ros.diff_robot_node', 'diff_robot'),
    ('vehicle_sim.ros.bridge_node', 'ackermann_to_differential'),
])
def test_node_refused_by_cyclone_exits_with_one_line_and_no_traceback(module, program):
    # The embedded transport's own line (on rclpy Cyclone prints its reason itself:
    # test_transport_rclpy.py)
    env = peer_env(transport='dds')
    env['CYCLONEDDS_URI'] = USER_LO_NAME + ',' + USER_LO_NAME   # the user selects lo twice
    process = NodeProcess('--ros-args', '-r', '__ns:=/refused', module=module, env=env)
    try:
        assert process.wait() == 2, process.text()
    finally:
        process.stop()
    lines = [line for line in process.output if line.strip()
             and not line.startswith('pybullet build time')]
    assert len(lines) == 1, lines
    assert lines[0].startswith(f'{program}: Cyclone DDS refused domain ')
    assert 'lo: the same interface may not be selected twice' in lines[0]
    assert f'CYCLONEDDS_URI={env["CYCLONEDDS_URI"]!r}' in lines[0]
    assert os.environ['ROS_DOMAIN_ID'] in lines[0]
