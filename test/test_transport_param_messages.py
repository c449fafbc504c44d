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
Parameter values <-> rcl_interfaces messages: one conversion, shared by the nodes and the CLI.

Unit round trips of vehicle_sim.transport.dds.param_messages (through CDR too), a source check
that no other module converts ParameterValue messages itself, and ``vehicle-sim param get/set``
on parameters of every array type of a node of this process (spun on a thread while the CLI runs
as a subprocess).
"""

import ast
import pathlib
import subprocess
import sys
import threading

from conftest import peer_env
import pytest

from vehicle_msgs_py import types as msg_types
import vehicle_sim
from vehicle_sim.transport.dds import param_messages
from vehicle_sim.transport.errors import TransportError
from vehicle_sim.transport.parameter_types import (
    Parameter,
    PARAMETER_BOOL,
    PARAMETER_BOOL_ARRAY,
    PARAMETER_BYTE_ARRAY,
    PARAMETER_DOUBLE,
    PARAMETER_DOUBLE_ARRAY,
    PARAMETER_INTEGER,
    PARAMETER_INTEGER_ARRAY,
    PARAMETER_NOT_SET,
    PARAMETER_STRING,
    PARAMETER_STRING_ARRAY,
)

PACKAGE = pathlib.Path(vehicle_sim.__file__).parent
SHARED = PACKAGE / 'transport' / 'dds' / 'param_messages.py'
CLI_MODULE = 'vehicle_sim'
NS = '/tp_param_msgs'
# Generous bound for one CLI run (interpreter start, discovery, one exchange).
CLI_TIMEOUT_S = 60.0

pytestmark = pytest.mark.transport

VALUES = [
    (True, PARAMETER_BOOL),
    (-7, PARAMETER_INTEGER),
    (2.5, PARAMETER_DOUBLE),
    ('héllo', PARAMETER_STRING),
    (b'\x00\xff', PARAMETER_BYTE_ARRAY),
    ([True, False], PARAMETER_BOOL_ARRAY),
    ([1, -2, 3], PARAMETER_INTEGER_ARRAY),
    ([1.0, -2.5], PARAMETER_DOUBLE_ARRAY),
    (['a', 'b'], PARAMETER_STRING_ARRAY),
]


@pytest.mark.parametrize('value, kind', VALUES)
def test_each_value_type_survives_message_and_cdr_round_trip(value, kind):
    msg = param_messages.to_parameter_msg('p', value)
    assert msg.value.type == kind
    wire = type(msg).deserialize(msg.serialize())
    back = param_messages.from_parameter_msg(wire)
    assert back == Parameter('p', value)
    assert type(back.value) is type(value)


def test_not_set_is_none_both_ways_and_an_unknown_type_code_reads_as_none():
    assert param_messages.to_value_msg(None).type == PARAMETER_NOT_SET
    assert param_messages.from_value_msg(param_messages.to_value_msg(None)) is None
    value_type = msg_types.message_type('rcl_interfaces/msg/ParameterValue')
    assert param_messages.from_value_msg(value_type(type=42)) is None


def test_a_double_array_given_integers_is_sent_as_doubles():
    msg = param_messages.to_value_msg([3, 4.5])
    assert msg.type == PARAMETER_DOUBLE_ARRAY
    assert list(msg.double_array_value) == [3.0, 4.5]
    assert all(type(v) is float for v in msg.double_array_value)


@pytest.mark.parametrize('value', [[], [1, 'a'], {'a': 1}, 1j])
def test_a_value_ros_parameters_cannot_hold_is_refused(value):
    with pytest.raises(TransportError):
        param_messages.to_value_msg(value)


# ------------------------------------------------------------------------- one source of truth

FIELD_NAMES = set(param_messages.VALUE_FIELDS.values()) | {'rcl_interfaces/msg/ParameterValue'}


def _names_used(source: str):
    """Return the ParameterValue field names a module spells, as strings or attributes."""
    found = set()
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Constant) and node.value in FIELD_NAMES:
            found.add(node.value)
        elif isinstance(node, ast.Attribute) and node.attr in FIELD_NAMES:
            found.add(node.attr)
    return found


def test_only_param_messages_converts_parameter_value_messages():
    spelled = {str(path.relative_to(PACKAGE)): _names_used(path.read_text(encoding='utf-8'))
               for path in sorted(PACKAGE.rglob('*.py')) if path != SHARED}
    assert {path: names for path, names in spelled.items() if names} == {}
    assert _names_used(SHARED.read_text(encoding='utf-8')) == FIELD_NAMES


def _imports_param_messages(tree) -> bool:
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.module == 'vehicle_sim.transport.dds' and \
                any(alias.name == 'param_messages' for alias in node.names):
            return True
        if isinstance(node, ast.ImportFrom) and \
                node.module == 'vehicle_sim.transport.dds.param_messages':
            return True
    return False


def test_the_cli_param_command_uses_the_shared_conversion():
    modules = {path: ast.parse(path.read_text(encoding='utf-8'))
               for path in PACKAGE.rglob('*.py')}
    cli = [path for path, tree in modules.items()
           if any(isinstance(n, ast.FunctionDef) and n.name == 'cmd_param'
                  for n in ast.walk(tree))]
    assert len(cli) == 1
    assert _imports_param_messages(modules[cli[0]])


# ------------------------------------------------------------------------- the CLI, typed values

def vehicle_sim_cli(*args):
    """Run ``vehicle-sim ARGS`` and return the CompletedProcess (text output)."""
    return subprocess.run([sys.executable, '-m', CLI_MODULE, *args], env=peer_env(),
                          capture_output=True, text=True, timeout=CLI_TIMEOUT_S)


@pytest.fixture(scope='module')
def typed_node():
    """Yield a node of this process with a parameter of each array type, spun on a thread."""
    from vehicle_sim.transport.dds import DdsNode
    node = DdsNode('typed', NS, args=['--ros-args', '--disable-rosout-logs'])
    for name, value in (('blob', b'\x01\x02'), ('flags', [True, False]),
                        ('gains', [1.0, 2.5]), ('names', ['a', 'b'])):
        node.declare_parameter(name, value)
    stop = threading.Event()

    def spin():
        while not stop.is_set():
            node.spin_once(0.05)

    spinner = threading.Thread(target=spin, daemon=True)
    spinner.start()
    try:
        yield node
    finally:
        stop.set()
        spinner.join()
        node.shutdown()


@pytest.mark.parametrize('name, shown', [
    ('blob', 'Byte values are: [1, 2]'),
    ('flags', 'Boolean values are: [True, False]'),
    ('gains', 'Double values are: [1.0, 2.5]'),
    ('names', "String values are: ['a', 'b']"),
])
def test_cli_param_get_shows_array_values_like_ros2_param(typed_node, name, shown):
    result = vehicle_sim_cli('param', 'get', f'{NS}/typed', name)
    assert (result.returncode, result.stdout) == (0, shown + '\n'), result.stderr


def test_cli_param_set_sends_a_mixed_number_list_as_doubles(typed_node):
    result = vehicle_sim_cli('param', 'set', f'{NS}/typed', 'gains', '[3, 4.5]')
    assert (result.returncode, result.stdout) == (0, 'Set parameter successful\n'), \
        result.stderr
    assert typed_node.get_parameter('gains') == [3.0, 4.5]


def test_cli_param_set_of_a_mixed_list_sends_a_string_that_the_node_refuses(typed_node):
    # Like rcl, a value YAML cannot make a parameter type of is a string.
    result = vehicle_sim_cli('param', 'set', f'{NS}/typed', 'names', '[1, a]')
    assert result.returncode == 1
    # The types by rclcpp's names (not their codes {9}, {4}) and the value.
    assert ('Setting parameter failed: Wrong parameter type, parameter {names} is of type '
            "{string_array}, setting it to {string} '[1, a]' is not allowed." in result.stderr)
    assert typed_node.get_parameter('names') == ['a', 'b']
