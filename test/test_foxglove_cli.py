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


"""``--foxglove`` and ``--foxglove-host`` of ``vehicle-sim run`` and ``scenario``: bad input."""

import base64
import errno
import os
from pathlib import Path
import queue
import signal
import socket
import struct
import subprocess
import sys
import threading

from conftest import peer_env
import pytest

from vehicle_sim.tools import cli

pytest.importorskip('foxglove', reason="foxglove-sdk is not installed (pip install "
                                       "'vehicle_sim[foxglove]')")

SCENARIO = str(Path(__file__).resolve().parent.parent / 'scenarios' / 'stop_before_obstacle.yaml')
# The console script pip installed next to this interpreter: what a user types.
VEHICLE_SIM = os.path.join(os.path.dirname(sys.executable), 'vehicle-sim')
CLI_TIMEOUT_S = 120.0
# Generous bound for a line of a running command to come.
LINE_TIMEOUT_S = 60.0


def port_left_in_time_wait():
    """
    Return a port whose only socket is a closed connection (TIME_WAIT), no listener.

    As after a simulator stopped while the app was connected: the server's side closed first.
    The server's listener sets SO_REUSEADDR, as foxglove-sdk's (tokio's) does: the connection
    left in TIME_WAIT keeps the flag, which lets a new listener with it bind.
    """
    with socket.socket() as server:
        server.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        server.bind(('127.0.0.1', 0))
        server.listen()
        port = server.getsockname()[1]
        with socket.create_connection(('127.0.0.1', port)) as client:
            accepted, _ = server.accept()
            accepted.close()                    # the server's side closes first
            assert client.recv(1) == b''        # the client sees it and closes too
    with socket.socket() as plain, pytest.raises(OSError) as caught:
        plain.bind(('127.0.0.1', port))         # a bind without SO_REUSEADDR is refused
    assert caught.value.errno == errno.EADDRINUSE
    return port


@pytest.mark.parametrize('command', [['run', '--duration', '0'], ['scenario', SCENARIO]])
def test_a_port_in_use_exits_2_in_one_line_before_anything_starts(command, capsys):
    with socket.socket() as taken:
        taken.bind(('127.0.0.1', 0))
        taken.listen()
        port = taken.getsockname()[1]
        assert cli.main([*command, '--foxglove', str(port)]) == 2
    out, err = capsys.readouterr()
    assert err == (f'vehicle-sim {command[0]}: --foxglove: cannot listen on 127.0.0.1:{port}: '
                   'Address already in use\n')
    assert 'automobile ready' not in out + err and 'scenario ' not in out


def test_a_port_held_only_by_time_wait_is_accepted_by_the_installed_command():
    # Restarting the simulator at once while the app was connected: the pre-check accepts the
    # port (as the server's own listener does) and the live view starts on it.
    port = port_left_in_time_wait()
    done = subprocess.run([VEHICLE_SIM, 'run', '--no-status', '--duration', '0', '--foxglove',
                           str(port)], env=peer_env(), capture_output=True, text=True,
                          timeout=CLI_TIMEOUT_S)
    assert done.returncode == 0, done.stderr
    assert f'Foxglove live view on ws://127.0.0.1:{port} ' in done.stdout + done.stderr


def websocket_handshake(port, subprotocol='foxglove.sdk.v1'):
    """Open a WebSocket offering ``subprotocol``; return it and the first frame read."""
    client = socket.create_connection(('127.0.0.1', port), timeout=LINE_TIMEOUT_S)
    key = base64.b64encode(os.urandom(16)).decode()
    client.sendall((f'GET / HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nUpgrade: websocket\r\n'
                    f'Connection: Upgrade\r\nSec-WebSocket-Key: {key}\r\n'
                    f'Sec-WebSocket-Version: 13\r\nSec-WebSocket-Protocol: {subprotocol}\r\n'
                    '\r\n').encode())
    received = b''
    while b'\r\n\r\n' not in received or len(received.split(b'\r\n\r\n', 1)[1]) < 2:
        chunk = client.recv(65536)
        assert chunk, f'the server closed the connection: {received!r}'
        received += chunk
    head, frame = received.split(b'\r\n\r\n', 1)
    assert head.startswith(b'HTTP/1.1 101 '), head
    return client, frame


def test_a_client_dropping_its_connection_is_a_debug_line_of_the_node_logger():
    # A client that goes away without closing (a reset: the app killed, a network gone): the
    # SDK's "Error receiving from client ...: Connection reset by peer (os error 104)" is a
    # debug line of the node's logger (shown here at --log-level debug), never a raw line.
    port = cli_port()
    proc = subprocess.Popen([VEHICLE_SIM, 'run', '--no-status', '--foxglove', str(port), '--',
                             '--ros-args', '--log-level', 'debug'], env=peer_env(),
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    lines = queue.Queue()
    reader = threading.Thread(target=lambda: [lines.put(line) for line in proc.stderr],
                              daemon=True)
    reader.start()
    seen = []

    def wait_for(text):
        while True:
            line = lines.get(timeout=LINE_TIMEOUT_S)
            seen.append(line)
            if text in line:
                return line

    try:
        wait_for(f'Foxglove live view on ws://127.0.0.1:{port} ')
        client, frame = websocket_handshake(port)
        assert frame[0] == 0x81                 # a text frame: the serverInfo
        client.setsockopt(socket.SOL_SOCKET, socket.SO_LINGER, struct.pack('ii', 1, 0))
        client.close()                          # linger 0: a reset, not a close
        dropped = wait_for('Error receiving from client')
    finally:
        proc.send_signal(signal.SIGINT)
        try:
            proc.wait(timeout=CLI_TIMEOUT_S)
        finally:
            if proc.poll() is None:
                proc.kill()
            reader.join()
    while not lines.empty():
        seen.append(lines.get())
    assert dropped.startswith('[DEBUG] ') and '[automobile]: ' in dropped, dropped
    assert 'Connection reset' in dropped
    raw = [line for line in seen if 'client' in line and not line.startswith('[')]
    assert raw == []
    assert proc.returncode == 0, ''.join(seen[-20:])


WATCHED = """\
name: watched
world: obstacle_course
duration: 2.0
seed: 0
driver:
  commands: [{t: 0.0, cruising_speed: 10.0}]
criteria:
  - kind: no_collision
"""


def summary(stdout):
    """Return (simulated s, wall s, odometry sha256 start) of a scenario's verdict line."""
    (line,) = [line for line in stdout.splitlines() if ' simulated in ' in line]
    simulated = float(line.split(' s simulated in ')[0].rsplit(' ', 1)[1])
    wall = float(line.split(' s simulated in ')[1].split(' s;')[0])
    return simulated, wall, line.rsplit('odometry sha256 ', 1)[1]


def test_a_watched_scenario_waits_for_a_client_then_runs_at_real_time(tmp_path, capsys):
    # scenario --foxglove: the run waits for the app before its first step, then steps at the
    # pace of the wall clock (2 s simulated take at least 2 s), with the results of a run told
    # not to wait nor pace (stepping stays synchronous: the same odometry).
    scenario = tmp_path / 'watched.yaml'
    scenario.write_text(WATCHED, encoding='utf-8')
    assert cli.main(['scenario', str(scenario), '--no-progress', '--foxglove', str(cli_port()),
                     '--no-wait-client', '--real-time-factor', '0']) == 0
    out, err = capsys.readouterr()
    assert 'waiting for a Foxglove client' not in err
    at_once = summary(out)
    port = cli_port()
    proc = subprocess.Popen([VEHICLE_SIM, 'scenario', str(scenario), '--no-progress',
                             '--foxglove', str(port)], env=peer_env(), stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    try:
        waiting = proc.stderr.readline()
        while waiting and 'waiting for a Foxglove client' not in waiting:
            waiting = proc.stderr.readline()
        assert waiting.startswith(f'waiting for a Foxglove client on ws://127.0.0.1:{port} ')
        assert proc.poll() is None                      # it waits
        client, frame = websocket_handshake(port)
        with client:
            out, err = proc.communicate(timeout=CLI_TIMEOUT_S)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.communicate()
    assert proc.returncode == 0, err
    assert 'PASS: 1/1 criteria passed' in out
    simulated, wall, sha = summary(out)
    assert simulated == at_once[0] == 2.0 and wall >= simulated
    assert sha == at_once[2]


@pytest.mark.parametrize('args, message', [
    (['--no-wait-client'], '--no-wait-client needs --foxglove [PORT]'),
    (['--real-time-factor', '-1'], '--real-time-factor -1: must be a number >= 0'),
    (['--real-time-factor', 'nan'], '--real-time-factor nan: must be a number >= 0'),
    (['--real-time-factor', '1e-9'], '--real-time-factor 1e-09: the 10 s scenario would last'),
])
def test_bad_pace_options_of_scenario_are_refused_before_the_run(args, message, capsys):
    assert cli.main(['scenario', SCENARIO, '--no-progress', *args]) == 2
    out, err = capsys.readouterr()
    assert err.startswith(f'vehicle-sim scenario: {message}') and err.count('\n') == 1
    assert 'scenario ' not in out


def cli_port():
    with socket.socket() as probe:
        probe.bind(('127.0.0.1', 0))
        return probe.getsockname()[1]


@pytest.mark.parametrize('args, message', [
    (['--foxglove-host', '0.0.0.0'], '--foxglove-host needs --foxglove [PORT]'),
    (['--foxglove', '70000'], '--foxglove 70000: the port must be 1 .. 65535'),
    (['--foxglove', '--foxglove-host', 'far.example'],
     "--foxglove-host = 'far.example': not an IP address"),
])
def test_bad_options_are_refused_naming_them(args, message, capsys):
    assert cli.main(['run', '--duration', '0', *args]) == 2
    _, err = capsys.readouterr()
    assert err.startswith(f'vehicle-sim run: {message}') and err.count('\n') == 1


def test_foxglove_without_a_port_takes_foxglove_s_default():
    args = cli.build_parser().parse_args(['run', '--foxglove'])
    assert (args.foxglove, args.foxglove_host) == (8765, None)
