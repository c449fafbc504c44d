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
Start-up and shutdown of node processes on the embedded transport (issue 7, items 4 and 5).

* A SIGTERM while the node is being built ends the process cleanly (exit 128 + the signal, no
  ready line) and leaves no node on the graph, for the node mains and for ``vehicle-sim run``.
* With services whose last clients died (their replies never acknowledged), SIGTERM still ends
  the process and the node leaves the graph; Cyclone's own configuration trace shows why it
  cannot take a second per writer any more (no writer linger). The time it takes is measured
  by benchmarks/bench_shutdown.py, not asserted here.
"""

import signal
import subprocess
import sys
import textwrap

from automobile_helpers import make_client_node, NodeProcess, wait_for, WAIT_S
from conftest import peer_env
from cyclonedds.builtin import BuiltinDataReader, BuiltinTopicDcpsParticipant
from cyclonedds.core import InstanceState
from cyclonedds.domain import DomainParticipant
import pytest

from vehicle_sim.transport import dds
from vehicle_sim.transport.dds import cyclone_private
from vehicle_sim.transport.dds.domain_config import domain_id
from vehicle_sim.transport.dds.graph import GraphView
from vehicle_sim.transport.first_call import call_until_answered

pytestmark = pytest.mark.transport


class ParticipantWatch:
    """Sees other processes' participants come and go (DCPSParticipant)."""

    def __init__(self):
        dds.ensure_domain()
        self.participant = DomainParticipant(domain_id())
        self._reader = BuiltinDataReader(self.participant, BuiltinTopicDcpsParticipant)
        self.alive = set()
        self.seen = set()
        self.refresh()
        self._known = set(self.alive)   # participants that existed before

    def refresh(self):
        for sample in self._reader.take(N=256):
            key = sample.key.bytes
            if sample.sample_info.instance_state == InstanceState.Alive:
                self.alive.add(key)
                self.seen.add(key)
            else:
                self.alive.discard(key)
        return self

    def new(self):
        return self.refresh().seen - self._known - {self.participant.guid.bytes}

    def close(self):
        cyclone_private.delete_participant(self.participant)


@pytest.mark.parametrize('stop_signal', [signal.SIGTERM, signal.SIGINT], ids=['TERM', 'INT'])
@pytest.mark.parametrize('module, leading_args, node_fqn', [
    ('vehicle_sim.ros.automobile_node', (), '/startup_a/automobile'),
    ('vehicle_sim.ros.diff_robot_node', (), '/startup_d/diff_robot'),
    ('vehicle_sim.ros.bridge_node', (), '/startup_b/ackermann_to_differential'),
    ('vehicle_sim.ros.autoware_automobile_node', (), '/startup_w/autoware_automobile'),
    # `vehicle-sim run`: the same node, built and spun by the command line tool
    ('vehicle_sim', ('run', '--no-status', '--'), '/startup_c/automobile'),
])
def test_signal_during_start_up_exits_cleanly_and_leaves_no_node(module, leading_args,
                                                                 node_fqn, stop_signal):
    watch = ParticipantWatch()
    namespace = node_fqn.rsplit('/', 1)[0]
    process = NodeProcess(*leading_args, '--ros-args', '-r', f'__ns:={namespace}',
                          module=module)
    try:
        # The node's participant exists: its node is being built (parameter services, the
        # world, the endpoints). Stop it right there.
        assert wait_for(watch.new, timeout_s=WAIT_S), process.text()
        process.proc.send_signal(stop_signal)
        status = process.wait()
        # One rule (transport/stop_signals.py): a node stopped before it was ready never says
        # it is, and exits 128 + the signal; one that made it to ready first exits 0.
        assert status == (0 if ' ready: ' in process.text() else 128 + stop_signal), \
            process.text()
        (guid,) = watch.new()
        assert wait_for(lambda: guid not in watch.refresh().alive)
        with GraphView() as view:
            view.wait(0.5)
            assert view.find_node(node_fqn) is None
        assert 'Traceback' not in process.text()
    finally:
        process.stop()
        watch.close()


DYING_CLIENT = textwrap.dedent("""
    import os, signal, sys
    from vehicle_sim.transport.dds import DdsNode
    node = DdsNode('dying_client')
    clients = [node.create_client('vehicle_msgs/srv/GetFloat', name) for name in sys.argv[1:]]
    for client in clients:
        assert client.wait_for_service(60), client.service_name
    for client in clients:
        client.call_async(node.srv('vehicle_msgs/srv/GetFloat').Request())
    print('sent', flush=True)
    os.kill(os.getpid(), signal.SIGKILL)   # dies before it can acknowledge the replies
""")


def test_sigterm_after_clients_died_ends_the_process_and_leaves_the_graph(tmp_path):
    trace = tmp_path / 'cyclone.log'
    env = peer_env()
    env['CYCLONEDDS_URI'] = (f'<Tracing><Category>config,discovery</Category>'
                             f'<OutputFile>{trace}</OutputFile></Tracing>')
    # The embedded transport's own discovery configuration (its writer linger) is under test;
    # on a ROS machine the node would otherwise run on rclpy with rmw_cyclonedds' configuration.
    env['VEHICLE_SIM_TRANSPORT'] = 'dds'
    process = NodeProcess('--ros-args', '-r', '__ns:=/dying', '-p', 'synchronous:=true',
                          env=env)
    services = ['/dying/robot/get_time', '/dying/robot/get_basic_time_step',
                '/dying/automobile/get_cruising_speed']
    node = make_client_node('dying_tester')
    try:
        client = subprocess.run([sys.executable, '-c', DYING_CLIENT, *services], env=peer_env(),
                                capture_output=True, text=True, timeout=WAIT_S)
        assert client.returncode == -signal.SIGKILL and client.stdout == 'sent\n', client
        # Our own calls are answered after the dead client's requests, which came first: its
        # replies are written, to readers that will never acknowledge them.
        for name in services:
            caller = node.create_client('vehicle_msgs/srv/GetFloat', name)
            assert caller.wait_for_service(WAIT_S)
            # a getter, sent again if lost (docs/transport.md, "A service just discovered")
            call_until_answered(caller, node.srv('vehicle_msgs/srv/GetFloat').Request(), WAIT_S)
        with GraphView() as view:
            assert view.wait_until(lambda: view.find_node('/dying/automobile'), WAIT_S)
            process.proc.send_signal(signal.SIGTERM)
            assert process.wait() == 0, process.text()
            assert view.wait_until(lambda: view.find_node('/dying/automobile') is None, WAIT_S)
        log = trace.read_text(errors='replace')
        # The reply writers were deleted with unacknowledged samples ...
        assert log.count("- unack'ed samples, will delete when ack'd") >= len(services)
        # ... and Cyclone did not keep them (its default: 1 s each, one after the other).
        assert 'Domain/Internal/WriterLingerDuration/#text: 0 s' in log
    finally:
        node.shutdown()
        process.stop()
