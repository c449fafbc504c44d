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
The automobile node's live view in-process: its channels, transforms, parameters and bad input.

The app's side (Foxglove's own client library) is test_foxglove_live_view.py.
"""

import errno
import socket
import sys
import threading
from types import SimpleNamespace

import pytest

pytest.importorskip('foxglove', reason="foxglove-sdk is not installed (pip install "
                                       "'vehicle_sim[foxglove]')")

import vehicle_msgs_py  # noqa: E402
from vehicle_sim.foxglove import scene_messages  # noqa: E402
from vehicle_sim.foxglove import sdk as fox_sdk  # noqa: E402
from vehicle_sim.foxglove.sdk import LiveViewError  # noqa: E402
from vehicle_sim.foxglove.services import on_node_thread  # noqa: E402
from vehicle_sim.foxglove.topics import LatchedChannelSink  # noqa: E402
from vehicle_sim.ros.automobile_node import AutomobileNode  # noqa: E402
from vehicle_sim.transport.errors import TransportError


def free_port() -> int:
    with socket.socket() as probe:
        probe.bind(('127.0.0.1', 0))
        return probe.getsockname()[1]


@pytest.fixture
def app():
    made = AutomobileNode(transport='dds', parameter_overrides={
        'foxglove': free_port(), 'synchronous': True})
    try:
        yield made
    finally:
        made.close()


def on_helper_thread(app, call):
    """Run ``call()`` on another thread (as the SDK does) while this one spins the node."""
    outcome = []
    thread = threading.Thread(target=lambda: outcome.append(call()))
    thread.start()
    while thread.is_alive():
        app.node.spin_once(0.01)
    thread.join()
    return outcome[0]


def test_every_published_topic_is_a_cdr_channel_with_its_ros2msg_schema(app):
    view = app._live
    published = {publisher.topic_name: row.ros_type
                 for vehicle in app._vehicles for row, publisher in
                 vehicle.outputs.publishers.items()}
    published.update({publisher.topic_name: row.ros_type
                      for row, publisher in app._fleet_outputs.publishers.items()})
    # The node's rows, and its own log and parameter events.
    published.update({'/rosout': 'rcl_interfaces/msg/Log',
                      '/parameter_events': 'rcl_interfaces/msg/ParameterEvent'})
    assert set(view.topics.sinks) == set(published)
    for topic, ros_type in published.items():
        channel = view.topics.sinks[topic].channel
        assert channel.message_encoding == 'cdr'
        schema = channel.schema()
        assert (schema.name, schema.encoding) == (ros_type, 'ros2msg')
        assert schema.data == vehicle_msgs_py.message_definition(ros_type).encode('utf-8')


def test_latched_topics_keep_their_message_for_later_clients(app):
    tf_static = app._live.topics.sinks['/tf_static']
    assert isinstance(tf_static, LatchedChannelSink)
    (data,) = tf_static.kept
    message = app.node.deserialize('tf2_msgs/msg/TFMessage', data)
    assert [(t.header.frame_id, t.child_frame_id) for t in message.transforms] == \
        [('world', 'odom')]


def test_transforms_are_the_tf_tree_with_the_car_where_it_is(app):
    app.step(5)
    transforms = {(t.parent, t.child): t for t in app._transforms()}
    assert set(transforms) == {('world', 'odom'), ('odom', 'base_link')}
    assert transforms[('world', 'odom')].translation_m == (0.0, 0.0, 0.0)
    pose = app.scene.vehicles['Car'].body.pose()
    odom = transforms[('odom', 'base_link')]
    # odom sits at the spawn pose (the origin): base_link in odom is its world pose.
    assert odom.translation_m == pytest.approx(pose[:3], abs=1e-9)
    assert odom.rotation == pytest.approx(pose[3:], abs=1e-9)


def test_parameters_are_set_through_the_nodes_own_checks(app):
    sdk = fox_sdk.load_sdk()
    params = app._live.parameters

    def set_one(name, **value):
        found = on_helper_thread(app, lambda: params.set([sdk.Parameter(name, **value)]))
        return [(p.name, p.get_value()) for p in found]
    # use_sim_time is the node's one writable parameter (as over ROS).
    assert set_one('use_sim_time', value=True) == [('use_sim_time', True)]
    assert app.node.get_parameter('use_sim_time') is True
    # A wrong type: refused by the node's type check, the value in force returned.
    assert set_one('use_sim_time', value='yes') == [('use_sim_time', True)]
    assert app.node.get_parameter('use_sim_time') is True
    # A start-up parameter is read-only once the node runs, as for `ros2 param set`; a
    # whole-valued float sent as an integer is compared as the float it stands for.
    assert set_one('cmd_vel_timeout_s', value=2) == [('cmd_vel_timeout_s', 0.5)]
    assert app.node.get_parameter('cmd_vel_timeout_s') == 0.5
    # A name the node does not have: refused, nothing to return.
    assert set_one('nope', value=1) == []


def test_all_parameters_are_listed_when_none_is_named(app):
    found = on_helper_thread(app, lambda: app._live.parameters.get([]))
    values = {p.name: p.get_value() for p in found}
    assert values['foxglove'] == app._live.port
    assert values['foxglove_host'] == '127.0.0.1'
    assert values['synchronous'] is True
    assert 'use_sim_time' in values


def test_a_call_waits_for_the_node_and_says_so_when_it_does_not_spin(app):
    with pytest.raises(LiveViewError, match='did not answer within 0.05 s'):
        on_node_thread(app.node, lambda: 1, timeout_s=0.05)


def test_a_port_in_use_is_one_clear_error():
    with socket.socket() as taken:
        taken.bind(('127.0.0.1', 0))
        taken.listen()
        port = taken.getsockname()[1]
        with pytest.raises(LiveViewError) as caught:
            AutomobileNode(transport='dds', parameter_overrides={'foxglove': port})
    text = str(caught.value)
    assert f'127.0.0.1:{port}' in text and 'in use' in text.lower()
    assert '\n' not in text


def test_a_host_that_is_not_an_address_is_refused_naming_the_parameter():
    with pytest.raises(LiveViewError, match="foxglove_host = 'far.example': not an IP"):
        AutomobileNode(transport='dds', parameter_overrides={
            'foxglove': free_port(), 'foxglove_host': 'far.example'})


def test_a_port_out_of_range_is_refused_by_the_parameter_table():
    with pytest.raises(TransportError, match="'foxglove'.*70000"):
        AutomobileNode(transport='dds', parameter_overrides={'foxglove': 70000})


def test_missing_sdk_names_the_extra(monkeypatch):
    monkeypatch.setitem(sys.modules, 'foxglove', None)     # import foxglove -> ImportError
    with pytest.raises(LiveViewError, match=r"pip install 'vehicle_sim\[foxglove\]'"):
        fox_sdk.load_sdk()


@pytest.mark.parametrize('time_s, sec, nsec', [(1.25, 1, 250_000_000), (2.9999999999, 3, 0),
                                               (0.0, 0, 0)])
def test_stamps_are_whole_nanoseconds_of_simulated_time(time_s, sec, nsec):
    stamp = scene_messages.timestamp(fox_sdk.load_sdk().messages, time_s)
    assert (stamp.sec, stamp.nsec) == (sec, nsec)


def test_a_topic_is_built_only_while_a_client_subscribes(app):
    view = app._live
    sink = view.topics.sinks['/automobile/current_speed']
    (publisher,) = [p for vehicle in app._vehicles for row, p in vehicle.outputs.publishers.items()
                    if p.topic_name == '/automobile/current_speed']
    channel_id = sink.channel.id()
    assert (sink.open, publisher.reader_gate.open) == (False, False)   # no client, no reader
    view.subscribed(channel_id)
    view.subscribed(channel_id)             # a second client
    assert (sink.open, publisher.reader_gate.open) == (True, True)
    view.unsubscribed(channel_id)
    assert sink.open is True                # one client left
    view.unsubscribed(channel_id)
    assert (sink.open, publisher.reader_gate.open) == (False, False)


def call_service(app, name, payload, encoding='cdr'):
    """Call a live-view service's handler as the SDK does (from its thread)."""
    handler = app._live.services.services[name].handler
    request = SimpleNamespace(service_name=name, client_id=1, call_id=1, encoding=encoding,
                              payload=payload)
    return on_helper_thread(app, lambda: _outcome(lambda: handler(request)))


def _outcome(call):
    try:
        return call()
    except Exception as error:  # noqa: BLE001 - handed back to the test
        return error


def test_services_run_the_ros_handler_with_its_odd_input_policy(app):
    node = app.node
    srv = node.srv('vehicle_msgs/srv/SetFloat')
    logic = app.vehicles[''].logic
    name = '/automobile/set_cruising_speed'
    reply = call_service(app, name, node.serialize(srv.Request(value=30.0)))
    assert node.deserialize_as(srv.Response, reply).success is True
    assert logic.status().target_cruising_speed_kmh == 30.0
    # NaN: the ROS column of the odd-input policy, success false and nothing changed.
    reply = call_service(app, name, node.serialize(srv.Request(value=float('nan'))))
    assert node.deserialize_as(srv.Response, reply).success is False
    assert logic.status().target_cruising_speed_kmh == 30.0


@pytest.mark.parametrize('payload, encoding, message', [
    (b'\x00\x01\x00\x00\x00', 'cdr', 'the request is not a CDR SetFloat_Request'),
    (b'{"value": 50}', 'json', "request encoding 'json'; this server takes 'cdr'"),
])
def test_a_malformed_request_is_refused_and_changes_nothing(app, payload, encoding, message):
    logic = app.vehicles[''].logic
    before = logic.status().target_cruising_speed_kmh
    error = call_service(app, '/automobile/set_cruising_speed', payload, encoding)
    assert isinstance(error, LiveViewError) and message in str(error)
    assert str(error).startswith('/automobile/set_cruising_speed: ')
    assert logic.status().target_cruising_speed_kmh == before


def test_reset_pause_and_set_pose_are_offered(app):
    offered = app._live.services.services
    assert {'/automobile/set_cruising_speed', '/reset', '/set_pose', '/sim/pause',
            '/sim/reset'} <= set(offered)
    assert not [name for name in offered if 'parameter' in name]   # via the capability


def opening_handshake(port, offer):
    """Send a WebSocket opening handshake offering ``offer``; return the answer's head."""
    with socket.create_connection(('127.0.0.1', port), timeout=30.0) as client:
        client.sendall((f'GET / HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nUpgrade: websocket\r\n'
                        'Connection: Upgrade\r\nSec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n'
                        f'Sec-WebSocket-Version: 13\r\nSec-WebSocket-Protocol: {offer}\r\n'
                        '\r\n').encode())
        answer = b''
        while b'\r\n\r\n' not in answer:
            chunk = client.recv(65536)
            if not chunk:
                break
            answer += chunk
    return answer.split(b'\r\n\r\n', 1)[0].decode('latin-1')


@pytest.mark.parametrize('offer, chosen', [
    ('foxglove.websocket.v1', 'foxglove.websocket.v1'),     # Lichtblick, ws-protocol's example
    ('foxglove.sdk.v1', 'foxglove.sdk.v1'),                 # foxglove-sdk's name
    ('foxglove.websocket.v1, foxglove.sdk.v1', 'foxglove.websocket.v1'),   # the client's first
    ('chat, foxglove.sdk.v1', 'foxglove.sdk.v1'),
])
def test_both_names_of_the_protocol_are_accepted_and_answered_as_offered(app, offer, chosen):
    head = opening_handshake(app._live.port, offer)
    lines = head.split('\r\n')
    assert lines[0] == 'HTTP/1.1 101 Switching Protocols'
    headers = [line.split(':', 1) for line in lines[1:]]
    values = {name.strip().lower(): [] for name, _ in headers}
    for name, value in headers:
        values[name.strip().lower()].append(value.strip())
    assert values['sec-websocket-protocol'] == [chosen]
    # RFC 6455's example key and its accept value: the rest of the answer is the SDK's own
    assert values['sec-websocket-accept'] == ['s3pPLMBiTxaQ9kYGzzhZRbK+xOo=']


def test_a_client_offering_another_protocol_is_refused_by_the_sdk(app):
    head = opening_handshake(app._live.port, 'chat')
    assert head.startswith('HTTP/1.1 400 ')


def test_a_restart_right_after_a_client_was_connected_gets_the_port():
    # The simulator stopped with the app connected, started again at once on the same port:
    # the connection the server closed first is left in TIME_WAIT, which keeps a plain bind
    # off the port but neither the pre-check nor the live view's listener.
    from vehicle_sim.foxglove.server import check_port_free
    port = free_port()
    first = AutomobileNode(transport='dds', parameter_overrides={
        'foxglove': port, 'synchronous': True})
    try:
        client = socket.create_connection(('127.0.0.1', port), timeout=30.0)
        client.sendall((f'GET / HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nUpgrade: websocket\r\n'
                        'Connection: Upgrade\r\nSec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n'
                        'Sec-WebSocket-Version: 13\r\nSec-WebSocket-Protocol: foxglove.sdk.v1\r\n'
                        '\r\n').encode())
        assert client.recv(12) == b'HTTP/1.1 101'
    finally:
        first.close()
    with client:
        while client.recv(65536):               # until the server's close
            pass
    with socket.socket() as plain, pytest.raises(OSError) as caught:
        plain.bind(('127.0.0.1', port))
    assert caught.value.errno == errno.EADDRINUSE           # TIME_WAIT holds the port
    check_port_free('127.0.0.1', port, '--foxglove')        # no error
    second = AutomobileNode(transport='dds', parameter_overrides={
        'foxglove': port, 'synchronous': True})
    try:
        assert second.live_view.port == port
    finally:
        second.close()


def test_sdk_log_records_reach_the_node_logger_at_debug_for_a_client_connection():
    import logging

    from vehicle_sim.foxglove.sdk_log import SdkLogRoute

    class Node:
        def call_soon(self, callback):
            callback()                          # the node's thread, at once here

    class Logger:
        def __init__(self):
            self.lines = []

        def log(self, level, message):
            self.lines.append((level, message))

    logger = Logger()
    route = SdkLogRoute(Node(), logger)
    try:
        assert logging.getLogger('foxglove').propagate is False
        logging.getLogger('foxglove.websocket.connected_client.poller').error(
            'Error receiving from client 127.0.0.1:1: IO error: Connection reset by peer')
        logging.getLogger('foxglove.websocket.server').error(
            'Dropping client 127.0.0.1:2: handshake failed')
        logging.getLogger('foxglove.websocket_server').warning('Redefining service /reset')
        logging.getLogger('foxglove.websocket.server').error('Failed to send required server '
                                                             'info: closed')
    finally:
        route.close()
    assert logger.lines == [
        (10, 'Foxglove: Error receiving from client 127.0.0.1:1: IO error: Connection reset '
             'by peer'),
        (10, 'Foxglove: Dropping client 127.0.0.1:2: handshake failed'),
        (30, 'Foxglove: Redefining service /reset'),
        (40, 'Foxglove: Failed to send required server info: closed')]
    assert logging.getLogger('foxglove').propagate is True     # as before, once closed
