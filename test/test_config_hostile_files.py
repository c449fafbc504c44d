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
Hostile world and scenario files, run as a user types the commands.

Given to ``vehicle-sim run --world`` and ``vehicle-sim scenario``, each is refused with one
short line naming the file and exit status 2, within a memory bound, and leaves no process
behind.
"""

import os
import resource
import shutil
import signal
import subprocess
import sys

from conftest import peer_env
import pytest

from vehicle_sim.core.specs.value_text import brief
from vehicle_sim.scenarios.yaml_lines import load_with_lines
from vehicle_sim.yaml_files import MAX_ALIAS_NODES, MAX_DEPTH, parse, YamlFileError

# Generous bound for one refused run (interpreter start and imports, on a loaded machine).
RUN_TIMEOUT_S = 60.0
MEMORY_BOUND_BYTES = 2 * 1024 ** 3
SHORT_LINE = 400            # characters: the refusal of a 5 MB value is about this long

COMMANDS = {
    'run': ('run', '--no-status', '--duration', '0.1', '--world'),
    'scenario': ('scenario', '--no-progress'),
}

SCENARIO = """\
world: {vehicles: [{name: ego}]}
duration: DURATION
driver: {commands: [{t: 0.0, brake_intensity: 0.0}]}
criteria: [{kind: no_collision}]
"""


def _vehicle_sim():
    found = shutil.which('vehicle-sim', path=os.path.dirname(sys.executable))
    return [found] if found else [sys.executable, '-m', 'vehicle_sim']


def _limit_memory():
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_BOUND_BYTES, MEMORY_BOUND_BYTES))


def _session_processes(session_id):
    """Return the ids of the processes of a session (Linux /proc)."""
    found = []
    for entry in os.listdir('/proc'):
        if not entry.isdigit():
            continue
        try:
            with open(f'/proc/{entry}/stat', encoding='ascii', errors='replace') as stat:
                fields = stat.read().rsplit(')', 1)[1].split()
        except OSError:
            continue
        if int(fields[3]) == session_id:     # state, ppid, pgrp, session
            found.append(int(entry))
    return found


def refused(command, path, *options):
    """
    Run ``vehicle-sim <command> [options] ... path`` in a session of its own, memory bounded.

    :return: (exit status, the stderr lines that are not log lines).
    """
    arguments = [*COMMANDS[command][:1], *options, *COMMANDS[command][1:], str(path)]
    proc = subprocess.Popen([*_vehicle_sim(), *arguments], env=peer_env(),
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            errors='replace', start_new_session=True, preexec_fn=_limit_memory)
    try:
        _, stderr = proc.communicate(timeout=RUN_TIMEOUT_S)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.communicate()
        pytest.fail(f'vehicle-sim {command} {path} still ran after {RUN_TIMEOUT_S} s')
    finally:
        left = _session_processes(proc.pid)
        for pid in left:
            os.kill(pid, signal.SIGKILL)
    assert left == [], f'vehicle-sim {command} left processes behind: {left}'
    lines = [line for line in stderr.splitlines() if not line.startswith('[INFO]')]
    return proc.returncode, lines


def assert_refused(command, path, fragment):
    status, lines = refused(command, path)
    assert len(lines) == 1, lines[-5:]
    assert lines[0].startswith(f'vehicle-sim {command}: {path}'), lines[0][:SHORT_LINE]
    assert len(lines[0]) < SHORT_LINE, lines[0][:SHORT_LINE]
    assert fragment in lines[0], lines[0]
    assert status == 2


def _laughs(levels=9, width=9):
    lines = [f'l0: &l0 [{", ".join(["lol"] * width)}]']
    for level in range(1, levels):
        lines.append(f'l{level}: &l{level} [{", ".join([f"*l{level - 1}"] * width)}]')
    return '\n'.join(lines) + f'\nvehicles: [{{name: Car, pose: *l{levels - 1}}}]\n'


def _mapping_laughs(levels=9, width=9):
    lines = ['m0: &m0 {' + ', '.join(f'k{i}: lol' for i in range(width)) + '}']
    for level in range(1, levels):
        lines.append(f'm{level}: &m{level} {{'
                     + ', '.join(f'k{i}: *m{level - 1}' for i in range(width)) + '}')
    return '\n'.join(lines) + f'\nvehicles: [{{name: Car, sensors: *m{levels - 1}}}]\n'


HOSTILE = {
    'not_utf8': (b'vehicles:\n  - name: C\xe4r\n', ':2: not UTF-8: byte 0xe4 at offset 21 '
                                                  '(line 2, column 12)'),
    'list_alias_bomb': (_laughs().encode(), ':6: aliases stand for more than 100000 values'),
    'mapping_alias_bomb': (_mapping_laughs().encode(), 'aliases stand for more than'),
    'recursive_alias': (b'vehicles: &v [*v]\n', ':1: alias *v is inside the value it names'),
    'deep_nesting': (b'vehicles:\n  - name: Car\n    pose: ' + b'[' * 10000 + b'\n',
                     ':3: nested deeper than 50 levels'),
    'control_character': (b'vehicles: [{name: Car\x07}]\n',
                          ':1: not valid YAML: character #x0007'),
    'huge_integer': (b'vehicles: [{name: Car, pose: {x: 1' + b'0' * 5000 + b'}}]\n',
                     'a value YAML cannot read: Exceeds the limit (4300 digits)'),
}


@pytest.mark.parametrize('command', sorted(COMMANDS))
@pytest.mark.parametrize('case', sorted(HOSTILE))
def test_hostile_yaml_is_refused_in_one_line_naming_the_file_exit_2(tmp_path, command, case):
    content, fragment = HOSTILE[case]
    path = tmp_path / f'{case}.yaml'
    path.write_bytes(content)
    assert_refused(command, path, fragment)


@pytest.mark.parametrize('command', sorted(COMMANDS))
def test_a_5_mb_value_is_quoted_by_its_first_80_characters_type_and_length(tmp_path, command):
    path = tmp_path / 'big.yaml'
    path.write_text('vehicles: [{name: Car, foo: ' + 'x' * 5_000_000 + '}]\n', encoding='utf-8')
    # the world names the unknown key; the scenario the unknown top-level key 'vehicles'
    fragment = '(str of 5000000 characters)' if command == 'run' else '(list of 1 entry)'
    assert_refused(command, path, fragment)


def test_run_a_model_name_no_file_system_takes_is_an_unknown_car(tmp_path):
    path = tmp_path / 'model.yaml'
    path.write_text('vehicles: [{name: Car, model: ' + 'M' * 5000 + '}]\n', encoding='utf-8')
    assert_refused('run', path, "field 'model': unknown car 'MMMM")


@pytest.mark.parametrize('command', sorted(COMMANDS))
def test_two_vehicles_of_one_name_in_two_namespaces_are_refused(tmp_path, command):
    vehicles = '[{name: A, namespace: a}, {name: A, namespace: b}]'
    text = (f'vehicles: {vehicles}\n' if command == 'run' else SCENARIO.replace(
        'DURATION', '1.0').replace('[{name: ego}]', vehicles))
    path = tmp_path / 'twice.yaml'
    path.write_text(text, encoding='utf-8')
    assert_refused(command, path, "vehicle name(s) used twice: ['A']")


@pytest.mark.parametrize('duration, fragment', [
    ('1000000000000.0', "field 'duration' = 1000000000000.0: must be > 0 and <= 86400"),
    ('1.0e12', 'must be a number (YAML reads it as a string: a float needs a dot and a signed '
               'exponent, e.g. 1.0e+12)'),
])
def test_scenario_duration_beyond_a_day_is_refused(tmp_path, duration, fragment):
    path = tmp_path / 'long.yaml'
    path.write_text(SCENARIO.replace('DURATION', duration), encoding='utf-8')
    assert_refused('scenario', path, fragment)


def test_scenario_paced_slower_than_a_day_of_wall_clock_is_refused(tmp_path):
    path = tmp_path / 'slow.yaml'
    path.write_text(SCENARIO.replace('DURATION', '10.0').replace(
        '{commands: [{t: 0.0, brake_intensity: 0.0}]}',
        '{processes: [python -c pass], real_time_factor: 0.0001}'), encoding='utf-8')
    assert_refused('scenario', path, 'real_time_factor = 0.0001: the 10 s would take 100000 s '
                                     'of wall clock; at most 86400 s')


def test_scenario_repeat_beyond_1000_runs_is_refused(tmp_path):
    path = tmp_path / 'repeat.yaml'
    path.write_text(SCENARIO.replace('DURATION', '1.0'), encoding='utf-8')
    assert refused('scenario', path, '--repeat', '1001') == (
        2, ['vehicle-sim scenario: --repeat 1001: must be 1 .. 1000'])


def _nested(depth):
    return '[' * (depth - 1) + '[]' + ']' * (depth - 1)


def test_nesting_of_max_depth_is_read_one_more_is_refused():
    data, _ = parse(_nested(MAX_DEPTH), 'f')
    assert str(data).count('[') == MAX_DEPTH
    with pytest.raises(YamlFileError, match=f'^f:1: nested deeper than {MAX_DEPTH} levels$'):
        parse(_nested(MAX_DEPTH + 1), 'f')


def test_nesting_through_aliases_counts_as_written_out():
    half = MAX_DEPTH // 2 + 1
    text = f'a: &a {_nested(half)}\nb: {"[" * half}*a{"]" * half}\n'
    with pytest.raises(YamlFileError, match='nested deeper than .* levels \\(aliases'):
        parse(text, 'f')


@pytest.mark.parametrize('uses, accepted', [(MAX_ALIAS_NODES // 11, True),
                                            (MAX_ALIAS_NODES // 11 + 1, False)])
def test_aliases_may_stand_for_at_most_max_alias_nodes_values(uses, accepted):
    # *a stands for 11 values: the list and its 10 numbers.
    text = 'a: &a [0, 1, 2, 3, 4, 5, 6, 7, 8, 9]\nb: [' + ', '.join(['*a'] * uses) + ']\n'
    if accepted:
        data, _ = parse(text, 'f')
        assert len(data['b']) == uses and data['b'][-1] is data['a']
    else:
        with pytest.raises(YamlFileError, match='^f:2: aliases stand for more than 100000'):
            parse(text, 'f')


def test_line_walker_walks_an_aliased_value_once_and_keeps_the_alias_line():
    data, lines = load_with_lines('a: &a {x: 1, y: [2, 3]}\nb:\n  - *a\n  - *a\n', 'f')
    assert data['b'] == [data['a'], data['a']]
    assert lines[('a', 'y', 1)] == 1
    assert ('b', 0, 'y') not in lines           # not walked again under the alias
    assert lines[('b',)] == 2


@pytest.mark.parametrize('value, text', [
    ([1.0, 'a', None, True], "[1.0, 'a', None, True]"),
    ({'x': (1,)}, "{'x': (1,)}"),
    ('x' * 100, "'" + 'x' * 79 + '... (str of 100 characters)'),
    (list(range(1000)), repr(list(range(1000)))[:80] + '... (list of 1000 entries)'),
])
def test_brief_is_repr_up_to_80_characters_then_the_type_and_length(value, text):
    assert brief(value) == text


def test_brief_quotes_a_value_that_holds_itself_without_expanding_it():
    shared = ['lol'] * 9
    for _ in range(9):
        shared = [shared] * 9      # 9 ** 9 strings when written out
    cyclic = []
    cyclic.append(cyclic)
    assert brief(shared).endswith('... (list of 9 entries)')
    assert brief(cyclic) == '[' * 80 + '... (list of 1 entry)'
