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
What a newcomer types, through the installed ``vehicle-sim`` command in a subprocess.

Output files in folders that do not exist yet, ``run``'s world and car given as paths, and the
arguments after ``--``.
"""

import os
import subprocess
import sys

from conftest import peer_env
import pytest

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
STOP = os.path.join(REPO, 'scenarios', 'stop_before_obstacle.yaml')
# The console script pip installed next to this interpreter: what a user types.
VEHICLE_SIM = os.path.join(os.path.dirname(sys.executable), 'vehicle-sim')
# Generous bound for one CLI run (interpreter start, a 10 s scenario simulated in < 1 s).
CLI_TIMEOUT_S = 120.0


def vehicle_sim(*args):
    """Run the installed ``vehicle-sim ARGS`` and return the CompletedProcess (text output)."""
    return subprocess.run([VEHICLE_SIM, *args], env=peer_env(), capture_output=True,
                          text=True, timeout=CLI_TIMEOUT_S)


def test_scenario_outputs_in_missing_folders_are_written_there(tmp_path):
    # As pytest's --junitxml does: the folders are made, the run goes on and writes both.
    junit = tmp_path / 'a' / 'b' / 'results.xml'
    plot = tmp_path / 'c' / 'plot.png'
    result = vehicle_sim('scenario', STOP, '--junit', str(junit), '--plot', str(plot),
                         '--no-progress')
    assert result.returncode == 0, result.stderr
    assert 'Traceback' not in result.stderr
    assert junit.read_text(encoding='utf-8').startswith('<?xml')
    assert plot.read_bytes()[:8] == b'\x89PNG\r\n\x1a\n'


@pytest.mark.parametrize('option', ['--junit', '--plot'])
def test_scenario_output_that_cannot_be_written_is_refused_before_the_run(tmp_path, option):
    blocker = tmp_path / 'file'
    blocker.write_text('a file, not a folder', encoding='utf-8')
    result = vehicle_sim('scenario', STOP, option, str(blocker / 'out'), '--no-progress')
    assert result.returncode == 2
    assert result.stdout == ''          # refused before the scenario ran
    assert result.stderr.count('\n') == 1
    assert result.stderr.startswith(f'vehicle-sim scenario: {option} {blocker / "out"}: '
                                    'cannot create its folder')


@pytest.mark.parametrize('option, value, what', [
    ('--world', 'no/such/world.yaml', 'world'),
    ('--world', 'missing.yaml', 'world'),
    ('--car', 'my_car.yaml', 'car'),
    ('--car', 'cars/MyCar', 'car'),
])
def test_run_with_a_path_that_does_not_exist_says_so(option, value, what):
    # A path (a slash, or a .yaml name) is not a preset name: no list of presets.
    result = vehicle_sim('run', option, value, '--duration', '5', '--no-status')
    assert result.returncode == 2
    assert result.stderr == (f"vehicle-sim run: {option} {value}: {what} file '{value}' does not "
                             f'exist (relative to {os.getcwd()})\n')


def test_run_with_an_unknown_preset_name_lists_the_known_ones():
    result = vehicle_sim('run', '--car', 'Tesla', '--duration', '5', '--no-status')
    assert result.returncode == 2
    assert result.stderr.startswith("vehicle-sim run: --car Tesla: unknown car 'Tesla'; known: "
                                    'BmwX5, Car, ')


def test_run_refuses_arguments_after_the_separator_that_are_not_ros_arguments():
    # '-p' means something only inside --ros-args: the node would have ignored it silently.
    result = vehicle_sim('run', '--duration', '5', '--no-status', '--', '-p', 'friction:=2')
    assert result.returncode == 2
    assert result.stdout == ''
    assert result.stderr == ("vehicle-sim run: arguments after '--' must be ROS arguments after "
                             "--ros-args, e.g. '-- --ros-args -p friction:=2'; not understood: "
                             '-p friction:=2\n')


def test_run_with_a_parameter_of_the_wrong_type_names_both_types_and_the_value():
    result = vehicle_sim('run', '--duration', '5', '--no-status', '--', '--ros-args', '-p',
                         'time_step_ms:=abc')
    assert result.returncode == 2
    assert ("vehicle-sim run: parameter 'time_step_ms' override 'abc' rejected: Wrong parameter "
            "type, parameter {time_step_ms} is of type {integer}, setting it to {string} 'abc' "
            'is not allowed.\n') in result.stderr
