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
The ``vehicle-sim`` command, run as a subprocess against real peers over the embedded transport.

Peers: test/transport_peer.py (node /tp_cli/peer: service set_int, parameter gain in [0, 10]) and
the automobile node started by ``vehicle-sim run`` (real time, endpoints under /automobile).
"""

import dataclasses
import io
import re
import subprocess
import sys

from conftest import peer_env, PEER_START_TIMEOUT_S, scaled_s, stop_processes
import pytest

from vehicle_msgs_py import distro

NS = '/tp_cli'
# Generous bound for one CLI run (interpreter start, discovery, one exchange).
CLI_TIMEOUT_S = 60.0

pytestmark = pytest.mark.transport


def vehicle_sim(*args, timeout_s=CLI_TIMEOUT_S):
    """Run ``vehicle-sim ARGS`` and return the CompletedProcess (text output)."""
    return subprocess.run([sys.executable, '-m', 'vehicle_sim', *args], env=peer_env(),
                          capture_output=True, text=True, timeout=timeout_s)


@pytest.fixture(scope='module')
def peer(spawn_peer):
    return spawn_peer('--ros-args', '-r', '__ns:=' + NS)


@pytest.fixture(scope='module')
def automobile():
    """``vehicle-sim run`` in the background; stopped with SIGTERM, which must exit 0."""
    proc = subprocess.Popen(
        [sys.executable, '-m', 'vehicle_sim', 'run', '--no-status', '--duration', '300'],
        env=peer_env(), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        result = vehicle_sim('call', '/automobile/get_gear', '--wait',
                             str(PEER_START_TIMEOUT_S))
        assert result.returncode == 0, result.stderr
        yield proc
        proc.terminate()
        assert proc.wait(PEER_START_TIMEOUT_S) == 0
    finally:
        stop_processes([proc])


def test_list_shows_the_peer_node_topics_and_services_with_types(peer):
    result = vehicle_sim('list', '--wait', str(scaled_s(3)))
    assert result.returncode == 0, result.stderr
    assert f'  {NS}/peer\n' in result.stdout
    assert f'  {NS}/echo_out [std_msgs/msg/String]' in result.stdout
    assert f'  {NS}/set_int [vehicle_msgs/srv/SetInt]' in result.stdout
    assert '_vehicle_sim_cli' not in result.stdout


def test_list_ends_with_the_participants_their_vendor_and_distribution(peer):
    result = vehicle_sim('list', '--wait', str(scaled_s(3)))
    assert result.returncode == 0, result.stderr
    participants = result.stdout.split('participants:\n', 1)[1]
    spoken = distro.title(distro.choose(peer_env())[0])
    assert (f'  {peer.info["participant"]} [Eclipse Cyclone DDS; ROS 2 {spoken}]: {NS}/peer\n'
            in participants)


def test_call_single_value_and_yaml_request_print_the_response(peer):
    even = vehicle_sim('call', f'{NS}/set_int', '4')
    odd = vehicle_sim('call', f'{NS}/set_int', '{value: 3}')
    assert (even.returncode, even.stdout) == (0, 'success: true\n'), even.stderr
    assert (odd.returncode, odd.stdout) == (0, 'success: false\n'), odd.stderr


def test_call_with_a_value_of_the_wrong_type_fails_without_calling(peer):
    result = vehicle_sim('call', f'{NS}/set_int', '2.5')
    assert result.returncode == 1
    assert 'expected an integer (int32), got 2.5' in result.stderr


def test_call_unknown_service_exits_1_and_names_the_close_match(peer):
    result = vehicle_sim('call', f'{NS}/set_in', '2', '--wait', str(scaled_s(2)))
    assert result.returncode == 1
    assert 'not found' in result.stderr and f'{NS}/set_int' in result.stderr


def test_param_list_get_set_round_trip(peer):
    listed = vehicle_sim('param', 'list', f'{NS}/peer')
    assert listed.returncode == 0, listed.stderr
    assert '  gain\n' in listed.stdout and '  use_sim_time\n' in listed.stdout
    changed = vehicle_sim('param', 'set', f'{NS}/peer', 'gain', '2')
    assert (changed.returncode, changed.stdout) == (0, 'Set parameter successful\n')
    got = vehicle_sim('param', 'get', f'{NS}/peer', 'gain')
    assert (got.returncode, got.stdout) == (0, 'Double value is: 2.0\n'), got.stderr


def test_param_set_rejected_by_the_node_reports_failure(peer):
    result = vehicle_sim('param', 'set', f'{NS}/peer', 'gain', '20')
    assert result.returncode == 1
    assert 'Setting parameter failed: gain 20.0 outside [0, 10]' in result.stderr


def test_param_unknown_node_exits_1_and_names_the_close_match(peer):
    result = vehicle_sim('param', 'get', f'{NS}/pear', 'gain', '--wait', str(scaled_s(2)))
    assert result.returncode == 1
    assert "node '/tp_cli/pear' not found" in result.stderr and f'{NS}/peer' in result.stderr


def test_echo_unknown_topic_exits_1(peer):
    result = vehicle_sim('echo', f'{NS}/nothing_here', '--wait', '1')
    assert result.returncode == 1
    assert 'not found on the graph' in result.stderr


def test_echo_once_prints_one_stamped_value(automobile):
    result = vehicle_sim('echo', '/automobile/current_speed', '--once', '--timeout', '30')
    assert result.returncode == 0, result.stderr
    assert result.stdout.count('---\n') == 1
    assert 'frame_id: base_link\n' in result.stdout and '\ndata: ' in result.stdout


def test_call_set_cruising_speed_is_visible_through_the_getter(automobile):
    assert vehicle_sim('call', '/automobile/set_cruising_speed', '30').stdout == 'success: true\n'
    result = vehicle_sim('call', '/automobile/get_cruising_speed')
    assert (result.returncode, result.stdout) == (0, 'value: 30.0\n'), result.stderr


def test_export_interfaces_writes_the_vehicle_msgs_package(tmp_path):
    result = vehicle_sim('export-interfaces', str(tmp_path))
    assert result.returncode == 0, result.stderr
    package = tmp_path / 'vehicle_msgs'
    assert (package / 'package.xml').is_file()
    assert (package / 'srv' / 'SetFloat.srv').is_file()
    assert (package / 'msg' / 'Float64Stamped.msg').is_file()


def test_run_for_one_second_without_status_exits_0():
    result = vehicle_sim('run', '--duration', '1', '--no-status')
    assert result.returncode == 0, result.stderr
    assert result.stdout == ''


@pytest.mark.skipif(not sys.platform.startswith('linux'), reason='X display check: Linux only')
def test_run_gui_without_a_display_fails_with_a_clear_error():
    # PyBullet alone would print 'cannot connect to X server' and end the process with status 1.
    env = peer_env()
    env.pop('DISPLAY', None)
    result = subprocess.run([sys.executable, '-m', 'vehicle_sim', 'run', '--gui', '--duration',
                             '1', '--no-status'], env=env, capture_output=True, text=True,
                            timeout=CLI_TIMEOUT_S)
    assert result.returncode == 2, result.stderr
    assert result.stderr.startswith('vehicle-sim run: --gui: DISPLAY is not set'), result.stderr
    assert 'xvfb-run' in result.stderr


def test_run_prints_plain_status_lines_with_advancing_time_when_not_on_a_terminal():
    result = vehicle_sim('run', '--duration', '2.5')
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert lines, result.stderr
    assert all(re.match(r't +[0-9.]+ s \| +[-0-9.]+ km/h \| rpm', line) for line in lines), lines
    times = [float(line.split()[1]) for line in lines]
    assert times == sorted(times)


def test_run_behind_real_time_warns_and_shows_the_achieved_factor_in_the_status():
    # real_time_factor 10000: a 10 ms step in 1 us of wall time, which no step reaches
    result = vehicle_sim('run', '--real-time-factor', '10000', '--duration', '3.5')
    assert result.returncode == 0, result.stderr
    factors = [float(found.group(1)) for found in
               (re.search(r'\| real time +([0-9.]+)x$', line)
                for line in result.stdout.splitlines()) if found]
    assert factors, result.stdout
    assert all(0.0 < factor < 9000.0 for factor in factors), factors
    warnings = [line for line in result.stderr.splitlines() if 'behind real time' in line]
    assert warnings, result.stderr
    assert re.search(r'\[WARN\].*behind real time: [0-9.]+x achieved over the last [0-9.]+ s of '
                     r'wall time, real_time_factor 10000 asked', warnings[0]), warnings[0]


def test_demo_writes_a_png_where_asked(tmp_path):
    out = tmp_path / 'demo.png'
    result = vehicle_sim('demo', '--short', '--out', str(out))
    assert result.returncode == 0, result.stderr
    assert 'wrote' in result.stdout
    assert out.read_bytes()[:8] == b'\x89PNG\r\n\x1a\n'


def test_run_help_example_sets_a_parameter_the_node_declares(capsys):
    from vehicle_sim.ros import sim_params
    from vehicle_sim.tools.cli import build_parser
    with pytest.raises(SystemExit):
        build_parser().parse_args(['run', '--help'])
    examples = re.findall(r'-p (\w+):=', capsys.readouterr().out)
    assert examples and set(examples) <= set(sim_params.defaults())


def test_status_line_shows_time_speed_rpm_gear_mode_and_indicator():
    from vehicle_sim.config import load_car
    from vehicle_sim.core.car.logic import CarLogic
    from vehicle_sim.tools.run_command import status_line
    status = CarLogic(load_car('Car')).status()
    line = status_line(1.5, status)
    assert line.startswith('t      1.50 s |    0.00 km/h | rpm      - | gear  0 | UNDEFINED')
    assert line.endswith('indicator off | real time       -')       # before the first second
    assert status_line(1.5, status, 0.333).endswith('indicator off | real time   0.33x')
    # a car at rest jitters around 0: never shown as -0.00
    resting = status_line(1.5, dataclasses.replace(status, current_speed_kmh=-0.004))
    assert '|    0.00 km/h |' in resting


class _Terminal(io.StringIO):
    """Both output streams of a terminal, recorded."""

    def isatty(self):
        return True


def _screen(text):
    """Return the lines a terminal shows for ``text`` (CR: back to column 0, LF: next line)."""
    lines, line, column = [], [], 0
    for char in text:
        if char == '\n':
            lines.append(''.join(line).rstrip())
            line, column = [], 0
        elif char == '\r':
            column = 0
        else:
            line[column:column + 1] = [char]
            column += 1
    lines.append(''.join(line).rstrip())
    return lines


def test_run_log_lines_start_at_column_0_and_the_status_is_redrawn_below_them():
    from vehicle_sim.tools.run_command import _StatusOutput
    from vehicle_sim.transport.dds import DdsNode
    terminal = _Terminal()
    output = _StatusOutput(True, stdout=terminal, stderr=terminal)
    node = DdsNode('status_logger', '/status_test', args=['--ros-args', '--disable-rosout-logs'])
    output.install()
    try:
        output.maybe_show(0.0, lambda: 't      1.00 s | indicator off')
        node.get_logger().warning('set_indicator_period refused')   # the node's log line
        print('plain', 'output')                                     # written in two parts
        output.maybe_show(10.0, lambda: 't      2.00 s | indicator left')
    finally:
        output.finish()
        node.shutdown()
    screen = _screen(terminal.getvalue())
    assert re.fullmatch(r'\[WARN\] \[[0-9.]+\] \[status_test\.status_logger\]: '
                        r'set_indicator_period refused', screen[0])
    assert screen[1:] == ['plain output', 't      2.00 s | indicator left', '']


def test_run_status_without_a_terminal_is_plain_lines_and_streams_are_left_alone():
    from vehicle_sim.tools.run_command import _StatusOutput
    stream = io.StringIO()
    before = (sys.stdout, sys.stderr)
    output = _StatusOutput(True, stdout=stream, stderr=stream)
    output.install()
    try:
        assert (sys.stdout, sys.stderr) == before
        output.maybe_show(0.0, lambda: 'status 1')
        output.maybe_show(10.0, lambda: 'status 2')
    finally:
        output.finish()
    assert stream.getvalue() == 'status 1\nstatus 2\n'


def test_format_message_prints_nested_fields_in_definition_order():
    from vehicle_msgs_py import message_type
    from vehicle_sim.tools.message_yaml import format_message
    msg = message_type('vehicle_msgs/msg/Float64Stamped')(data=27.5)
    msg.header.frame_id = 'base_link'
    assert format_message(msg) == ('header:\n  stamp:\n    sec: 0\n    nanosec: 0\n'
                                   '  frame_id: base_link\ndata: 27.5\n')
