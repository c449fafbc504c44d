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
