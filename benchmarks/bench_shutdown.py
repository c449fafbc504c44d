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
How long the automobile node takes to end after SIGTERM, and to leave the graph.

Target (issue 7, item 4; docs/transport.md): within 1 s of SIGINT/SIGTERM in every case. Cases:

* ``idle``: a synchronous node that served nothing;
* ``dead clients``: three services whose only client died (SIGKILL) right after sending its
  requests, so their replies are never acknowledged (Cyclone's default writer linger kept each
  reply writer up to 1 s, one after the other, before the fix);
* ``long time_step``: a ``robot/time_step`` of 2147483640 ms in progress;
* ``start-up``: SIGTERM as soon as the node's participant appears, while the node is built.

"exit" is SIGTERM to process exit; "graph" is SIGTERM until a graph observer (like
``ros2 node list``) no longer lists the node. Start-up has no "graph" figure (the node is not
listed yet).

Usage: ``python benchmarks/bench_shutdown.py [--runs N] [--cases CASE ...]``.
"""

import argparse
import os
import signal
import statistics
import subprocess
import sys
import textwrap
import time

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, REPO_ROOT)
os.environ.setdefault('ROS_AUTOMATIC_DISCOVERY_RANGE', 'LOCALHOST')
os.environ.setdefault('ROS_DOMAIN_ID', str(102 + os.getpid() % 100))

NODE = '/bench_shutdown/automobile'
SERVICES = ['/bench_shutdown/robot/get_time', '/bench_shutdown/robot/get_basic_time_step',
            '/bench_shutdown/automobile/get_cruising_speed']
WAIT_S = 60.0
CASES = ('idle', 'dead clients', 'long time_step', 'start-up')
POLL_S = 0.002
DYING_CLIENT = textwrap.dedent("""
    import os, signal, sys
    from vehicle_sim.transport.dds import DdsNode
    node = DdsNode('dying_client')
    clients = [node.create_client('vehicle_msgs/srv/GetFloat', name) for name in sys.argv[1:]]
    for client in clients:
        assert client.wait_for_service(60), client.service_name
    for client in clients:
        client.call_async(node.srv('vehicle_msgs/srv/GetFloat').Request())
    os.kill(os.getpid(), signal.SIGKILL)
""")


def _env():
    env = dict(os.environ)
    env['PYTHONPATH'] = REPO_ROOT + os.pathsep + env.get('PYTHONPATH', '')
    return env


def _spawn():
    return subprocess.Popen(
        [sys.executable, '-m', 'vehicle_sim.ros.automobile_node', '--ros-args',
         '-r', '__ns:=/bench_shutdown', '-p', 'synchronous:=true'],
        env=_env(), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def _wait(predicate, refresh):
    deadline = time.monotonic() + WAIT_S
    while not predicate():
        if time.monotonic() > deadline:
            raise RuntimeError('timed out')
        refresh()
        time.sleep(POLL_S)


def _stop_and_time(proc, view):
    """Send SIGTERM; return (seconds to exit, seconds until the graph no longer lists it)."""
    start = time.monotonic()
    proc.send_signal(signal.SIGTERM)
    gone = None
    while proc.poll() is None or gone is None:
        view.refresh()
        if gone is None and view.find_node(NODE) is None:
            gone = time.monotonic() - start
        if proc.poll() is not None and not hasattr(proc, 'exit_s'):
            proc.exit_s = time.monotonic() - start
        time.sleep(POLL_S)
    exit_s = getattr(proc, 'exit_s', time.monotonic() - start)
    return exit_s, gone


def _prepare(case, view, client_node):
    proc = _spawn()
    _wait(lambda: view.find_node(NODE) is not None, view.refresh)
    ready = client_node.create_client('vehicle_msgs/srv/GetFloat', SERVICES[0])
    ready.wait_for_service(WAIT_S)
    ready.call(client_node.srv('vehicle_msgs/srv/GetFloat').Request(), WAIT_S)   # built
    if case == 'dead clients':
        subprocess.run([sys.executable, '-c', DYING_CLIENT, *SERVICES], env=_env(),
                       timeout=WAIT_S, check=False)
        for name in SERVICES:   # answered after the dead client's requests
            caller = client_node.create_client('vehicle_msgs/srv/GetFloat', name)
            caller.wait_for_service(WAIT_S)
            caller.call(client_node.srv('vehicle_msgs/srv/GetFloat').Request(), WAIT_S)
    elif case == 'long time_step':
        caller = client_node.create_client('vehicle_msgs/srv/SetInt',
                                           '/bench_shutdown/robot/time_step')
        caller.wait_for_service(WAIT_S)
        caller.call_async(client_node.srv('vehicle_msgs/srv/SetInt').Request(value=2147483640))
        client_node.spin_once(0.2)
    return proc


def _start_up_case(watch_participants):
    before = watch_participants()
    proc = _spawn()
    _wait(lambda: watch_participants() - before, lambda: None)
    start = time.monotonic()
    proc.send_signal(signal.SIGTERM)
    proc.wait(WAIT_S)
    return time.monotonic() - start, None


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--runs', type=int, default=5)
    parser.add_argument('--cases', nargs='*', default=CASES, choices=CASES)
    args = parser.parse_args()

    from cyclonedds.builtin import BuiltinDataReader, BuiltinTopicDcpsParticipant
    from cyclonedds.core import InstanceState

    from vehicle_sim.transport.dds import DdsNode
    from vehicle_sim.transport.dds.graph import GraphView

    view = GraphView()
    client_node = DdsNode('bench_shutdown_client')
    reader = BuiltinDataReader(view._participant, BuiltinTopicDcpsParticipant)
    alive = set()

    def participants():
        for sample in reader.take(N=256):
            if sample.sample_info.instance_state == InstanceState.Alive:
                alive.add(sample.key.bytes)
            else:
                alive.discard(sample.key.bytes)
        return set(alive)

    print(f'SIGTERM -> exit / -> off the graph, {args.runs} runs each (target: <= 1 s)')
    try:
        for case in args.cases:
            exits, gones = [], []
            for _ in range(args.runs):
                if case == 'start-up':
                    exit_s, gone_s = _start_up_case(participants)
                else:
                    proc = _prepare(case, view, client_node)
                    exit_s, gone_s = _stop_and_time(proc, view)
                exits.append(exit_s)
                if gone_s is not None:
                    gones.append(gone_s)
            line = (f'{case:15s} exit  median {statistics.median(exits):6.3f} s  '
                    f'max {max(exits):6.3f} s')
            if gones:
                line += (f' | graph median {statistics.median(gones):6.3f} s  '
                         f'max {max(gones):6.3f} s')
            print(line, flush=True)
    finally:
        client_node.shutdown()
        view.close()


if __name__ == '__main__':
    main()
