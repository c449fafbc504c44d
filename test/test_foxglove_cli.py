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

from pathlib import Path
import socket

import pytest

from vehicle_sim.tools import cli

pytest.importorskip('foxglove', reason="foxglove-sdk is not installed (pip install "
                                       "'vehicle_sim[foxglove]')")

SCENARIO = str(Path(__file__).resolve().parent.parent / 'scenarios' / 'stop_before_obstacle.yaml')


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
