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
Helpers of the automobile node tests: the node in a subprocess and a client node in the test.

The node runs as ``python -m vehicle_sim.ros.automobile_node`` with this test run's DDS settings
(test/conftest.py: localhost discovery, a ROS_DOMAIN_ID of its own). Waits are generous bounds
on outcomes, never durations.
"""

import contextlib
import subprocess
import sys
import threading
import time

from conftest import peer_env
import pytest

from vehicle_sim.core.specs.units import stamp_to_seconds
from vehicle_sim.ros import automobile_interfaces as itf
from vehicle_sim.transport.dds import DdsNode
from vehicle_sim.transport.first_call import call_until_answered
from vehicle_sim.transport.qos import QOS_TF_STATIC_LISTENER

WAIT_S = 60.0
# How long wait_node_matched waits for a reply before it sends its request again [s].
RESEND_S = 5.0
NODE_MODULE = 'vehicle_sim.ros.automobile_node'


def wait_for(predicate, timeout_s=WAIT_S, spin=None):
    """Poll ``predicate`` (spinning ``spin`` if given) until true; return its last value."""
    deadline = time.monotonic() + timeout_s
    while True:
        value = predicate()
        if value or time.monotonic() >= deadline:
            return value
        if spin is not None:
            spin.spin_once(0.02)
        else:
            time.sleep(0.01)


def wait_node_matched(node, service, srv_type):
    """
    Return once the node serving ``service`` has matched every subscription ``node`` has made.

    A subscription matches the node's publisher at once (``get_publisher_count``); the node
    matches the subscription later, the later the more loaded the machine, and publishes
    nothing to it before. A participant announces its readers in the order it creates them, and
    a node answers a client only once it has matched the client's reply reader: the reply to a
    client created after the subscriptions says that the node has matched them.

    Writers are announced in order too, so the reply also says that the node has matched the
    request writers of the clients created before this one, and their first requests reach it.

    The request is sent again every ``RESEND_S`` without a reply, until ``WAIT_S``: a request
    written before the node matched the client's request writer is lost (docs/transport.md, "A
    service just discovered"), and a node gives up on a reply whose client reply reader it has
    not matched within its ``reply_match_timeout_s`` (10 s by default), which a loaded machine
    (or a node just resumed from SIGSTOP, with its discovery backlog) can exceed. Any reply is
    the event waited for.
    """
    client = node.create_client(srv_type, service)
    assert client.wait_for_service(WAIT_S), f'{service} not available'
    call_until_answered(client, node.srv(srv_type).Request(), WAIT_S, RESEND_S)


class NodeProcess:
    """A node (default: the automobile node) in a subprocess; its output is collected."""

    def __init__(self, *args, module=NODE_MODULE, env=None):
        self.proc = subprocess.Popen(
            [sys.executable, '-m', module, *args], env=env or peer_env(),
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        self.output = []
        for stream in (self.proc.stdout, self.proc.stderr):
            threading.Thread(target=self._read, args=(stream,), daemon=True).start()

    def _read(self, stream):
        for line in stream:
            self.output.append(line)

    def text(self):
        return ''.join(self.output)

    def wait(self, timeout_s=WAIT_S):
        return self.proc.wait(timeout_s)

    def stop(self):
        stop_process(self.proc)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.stop()
        return False


def stop_process(proc):
    """SIGTERM a child process still running, then SIGKILL it if it has not ended in WAIT_S."""
    if proc.poll() is None:
        proc.terminate()
        try:
            proc.wait(WAIT_S)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()


class VehicleClient:
    """
    A test-side node talking to one vehicle namespace of the automobile node.

    :param node: the test's DdsNode.
    :param namespace: vehicle namespace ('' for the default car).
    """

    def __init__(self, node, namespace=''):
        self.node = node
        self.namespace = namespace
        self._clients = {}
        self.latest = {}
        self.history = {}
        self._subs = {}

    def name(self, table_name):
        name = itf.vehicle_name(table_name, self.namespace)
        return name if name.startswith('/') else '/' + name

    def client(self, table_name):
        """
        Return this test's client of a table service (created once, available, matched).

        A new client is returned once the node has matched it too (:meth:`wait_node_matched`):
        its first request would be lost otherwise (docs/transport.md, "A service just
        discovered").
        """
        client = self._clients.get(table_name)
        if client is None:
            spec = _service_row(table_name)
            client = self.node.create_client(spec.srv_type, self.name(table_name))
            assert client.wait_for_service(WAIT_S), f'{self.name(table_name)} not available'
            self.wait_node_matched()
            self._clients[table_name] = client
        return client

    def call(self, table_name, value=None, **fields):
        """
        Call a table service; ``value`` goes into ``value`` (setters) or is ignored.

        ``fields`` set other request fields (``data`` of a SetBool, ``pose`` of a SetPose).
        """
        spec = _service_row(table_name)
        client = self.client(table_name)
        request = self.node.srv(spec.srv_type).Request()
        if value is not None:
            request.value = value
        for key, field in fields.items():
            setattr(request, key, field)
        return client.call(request, WAIT_S)

    def subscribe(self, table_name):
        """Subscribe to a table topic, keeping the latest message; return the subscription."""
        if table_name not in self._subs:
            spec = itf.topic(table_name)
            # A tf_static listener keeps 100 (rmw's tf_static QoS): every broadcaster sends its
            # own.
            qos = QOS_TF_STATIC_LISTENER if table_name == '/tf_static' else spec.qos
            self.history[table_name] = []
            self._subs[table_name] = self.node.create_subscription(
                spec.ros_type, self.name(table_name),
                lambda msg, key=table_name: self._store(key, msg), qos)
        return self._subs[table_name]

    def _store(self, key, msg):
        self.latest[key] = msg
        if key.startswith('/tf_static') or key == 'robot_description':
            self.history[key].append(msg)   # latched: several nodes may publish one each

    def wait_matched(self, table_names):
        """Subscribe to topics; return once the node has matched the subscriptions too."""
        subs = [self.subscribe(name) for name in table_names]
        assert wait_for(lambda: all(s.get_publisher_count() for s in subs), spin=self.node)
        self.wait_node_matched()

    def wait_node_matched(self):
        """Return once the node has matched every subscription of this test node."""
        wait_node_matched(self.node, self.name('robot/get_time'), 'vehicle_msgs/srv/GetFloat')

    def time_s(self):
        return self.call('robot/get_time').value

    def step_and_read(self, table_name, duration_ms=0):
        """Step the world (synchronous node) and return the message stamped with the new time."""
        assert self.call('robot/time_step', duration_ms).success
        now = self.time_s()

        def fresh():
            msg = self.latest.get(table_name)
            return msg is not None and abs(stamp_of(msg) - now) < 1e-9 and msg

        msg = wait_for(fresh, spin=self.node)
        assert msg, f'no {table_name} message stamped {now}'
        return msg

    def observe(self, table_name, duration_ms=0):
        """Return what a getter service or a Float64Stamped topic reports now."""
        if any(s.name == table_name for s in itf.SERVICES):
            return self.call(table_name).value
        return self.step_and_read(table_name, duration_ms).data


def _service_row(name):
    # A row of the automobile table, or a node-wide one (/sim/reset, /sim/pause).
    for spec in itf.SERVICES + itf.WORLD_SERVICES:
        if spec.name == name:
            return spec
    raise KeyError(name)


def stamp_of(msg):
    """Return the stamp [s] of a message with a header, or of a Clock."""
    stamp = msg.clock if hasattr(msg, 'clock') else msg.header.stamp
    return stamp_to_seconds(stamp.sec, stamp.nanosec)


def make_client_node(name):
    return DdsNode(name, '/automobile_test')


@contextlib.contextmanager
def client_node(name):
    """Yield a client node (:func:`make_client_node`), shut down when the block ends."""
    node = make_client_node(name)
    try:
        yield node
    finally:
        node.shutdown()



def node_fixture(node_args, scope='module', name='sim'):
    """
    Return a fixture running a node in a subprocess (:class:`NodeProcess`) while it is in use.

    :param node_args: the node's command line, or ``node_args(request)`` giving it (for a file
        another fixture writes: ``request.getfixturevalue``).
    """
    @pytest.fixture(scope=scope, name=name)
    def node(request):
        with NodeProcess(*(node_args(request) if callable(node_args) else node_args)) as process:
            yield process
    return node


def tester_fixture(node_name, name='tester'):
    """Return a module fixture yielding a client node (:func:`client_node`) named ``node_name``."""
    @pytest.fixture(scope='module', name=name)
    def tester():
        with client_node(node_name) as node:
            yield node
    return tester


def car_fixture(topics, namespace='', scope='module', node='sim', tester='tester', name='car'):
    """
    Return a fixture giving an VehicleClient of the ``tester`` fixture on ``namespace``.

    It starts the ``node`` fixture first and returns once the node publishes ``topics``.
    """
    @pytest.fixture(scope=scope, name=name)
    def car(request):
        process = request.getfixturevalue(node)
        client = VehicleClient(request.getfixturevalue(tester), namespace)
        try:
            client.wait_matched(list(topics))
        except AssertionError:
            # (a node that refused to start says why: a ROS type not installed, say)
            raise AssertionError(f'the node did not serve {list(topics)}; it printed:\n'
                                 f'{process.text()}') from None
        return client
    return car


def automobile_fixtures(tester_name, node_args, topics, namespace='', scope='module',
                        names=('sim', 'tester', 'car')):
    """
    Return the three fixtures of a module testing the automobile node over the wire.

    ``sim``: the node in a subprocess run with ``node_args`` (:func:`node_fixture`); ``tester``:
    a client node (:func:`tester_fixture`); ``car``: an VehicleClient of the tester on
    ``namespace`` once the node publishes ``topics`` (:func:`car_fixture`). A module binds them
    to the same names: ``sim, tester, car = automobile_fixtures(...)``.

    :param scope: the scope of ``sim`` and ``car`` ('module' or 'class'; ``tester``: module).
    :param names: the fixtures' names, in that order.
    """
    sim, tester, car = names
    return (node_fixture(node_args, scope, sim), tester_fixture(tester_name, tester),
            car_fixture(topics, namespace, scope, sim, tester, car))
