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
Every parameter table: one core ParamSpec kind, declared through one helper, documented, shipped.

The four nodes (automobile, ackermann_to_differential, autoware_automobile, diff_robot) and the
car and robot presets use :class:`vehicle_sim.core.specs.param_spec.ParamSpec`; every node
declares its
table through ``ros/node_support.declare_parameters``, refuses a bad value naming the parameter,
its value and the valid range, and does not start. The docs tables are generated from the tables
(``DOC_TABLES``) and ``config/*.yaml`` holds every parameter with its default, or a value whose
difference is explained in ``CONFIG_DIFFERENCES``.
"""

import math
from pathlib import Path

import pytest

from vehicle_sim.config import read_yaml
from vehicle_sim.core.bridge.params import BRIDGE_PARAM_SPECS
from vehicle_sim.core.car.params import CAR_PARAM_SPECS
from vehicle_sim.core.diffdrive.params import ROBOT_PARAM_SPECS
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.param_spec import (
    parameter_table_markdown,
    ParamSpec,
    table_defaults,
    validate_table,
)
from vehicle_sim.physics.diff_robot import load_robot
from vehicle_sim.ros import sim_params
from vehicle_sim.ros.autoware_automobile_node import AUTOWARE_PARAMETERS
from vehicle_sim.ros.bridge_node import BRIDGE_NODE_PARAMETERS
from vehicle_sim.ros.diff_robot_node import ROBOT_NODE_PARAMETERS
from vehicle_sim.ros.node_support import node_parameter_table, USE_SIM_TIME
from vehicle_sim.transport import TransportError

REPO_ROOT = Path(__file__).resolve().parent.parent
NAMESPACE = '/test_ros_parameters'

NODE_TABLES = {
    'automobile': sim_params.AUTOMOBILE_PARAMETERS,
    'ackermann_to_differential': BRIDGE_NODE_PARAMETERS,
    'autoware_automobile': AUTOWARE_PARAMETERS,
    'diff_robot': ROBOT_NODE_PARAMETERS,
}
PRESET_TABLES = {'car': CAR_PARAM_SPECS, 'robot': ROBOT_PARAM_SPECS, 'bridge': BRIDGE_PARAM_SPECS}

AUTOMOBILE_ROW = (('automobile parameters', '', '', '', '',
                   '`car_model`, `world`, `synchronous`, `time_step_ms`, ... '
                   '(docs/ros_interface.md)'),)

# (doc, the line the table follows, the generated table)
DOC_TABLES = (
    ('docs/ros_interface.md', '## Parameters', sim_params.parameter_table_markdown),
    ('docs/autoware.md', 'Bridge (`config/bridge.yaml`',
     lambda: node_parameter_table(BRIDGE_NODE_PARAMETERS)),
    ('docs/autoware.md', 'Simulated robot node (`config/diff_robot.yaml`',
     lambda: node_parameter_table(ROBOT_NODE_PARAMETERS)),
    ('docs/autoware.md', 'Robot presets (`config/robots/*.yaml`',
     lambda: parameter_table_markdown(ROBOT_PARAM_SPECS, 'field')),
    ('docs/bridge_kinematics.md', '## Parameters',
     lambda: parameter_table_markdown(BRIDGE_PARAM_SPECS)),
    ('docs/end_to_end.md', 'Parameters of autoware_automobile',
     lambda: node_parameter_table(AUTOWARE_PARAMETERS, AUTOMOBILE_ROW)),
)

CONFIG_FILES = {
    'automobile.yaml': sim_params.AUTOMOBILE_PARAMETERS,
    'bridge.yaml': BRIDGE_NODE_PARAMETERS,
    'diff_robot.yaml': ROBOT_NODE_PARAMETERS,
}
# (file, parameter) -> why the shipped value is not the default
CONFIG_DIFFERENCES = {
    ('bridge.yaml', 'wheel_base'): "the caster robot's tread (docs/autoware.md: L = tread)",
    ('bridge.yaml', 'wheel_tread'): "the caster robot's tread",
    ('diff_robot.yaml', 'wheel_joints'): "the caster robot's joints written out",
}


# --------------------------------------------------------------------------------------------
# The tables


ALL_TABLES = sorted({**NODE_TABLES, **PRESET_TABLES}.items())


@pytest.mark.parametrize('name, specs', ALL_TABLES, ids=[name for name, _ in ALL_TABLES])
def test_every_table_is_made_of_core_param_specs_with_valid_defaults(name, specs):
    assert all(type(spec) is ParamSpec for spec in specs)
    keys = [spec.key for spec in specs]
    assert len(keys) == len(set(keys)), 'duplicate keys'
    assert all(spec.doc for spec in specs)
    # every default passes the table's own validation
    values = validate_table(specs, {}, name)
    assert set(values) == {spec.attr for spec in specs}


@pytest.mark.parametrize('name', sorted(NODE_TABLES))
def test_node_parameters_are_read_only_and_floats_have_units(name):
    for spec in NODE_TABLES[name]:
        assert spec.read_only, spec.key
        if spec.kind == 'float':
            assert spec.unit, spec.key


@pytest.mark.parametrize('value, fragment', [
    (0.0, 'p = 0.0: must be > 0'),
    (math.nan, 'p = nan: must be finite and > 0'),
    ('1', "p = '1': must be a number"),
    (True, 'p = True: must be a number'),
])
def test_refusal_names_parameter_value_and_range(value, fragment):
    assert ParamSpec('p', kind='float', default=1.0, gt=0.0).refusal(value) == fragment


def test_refusal_of_int_enum_list_and_extra_rule():
    step = ParamSpec('step', kind='int', default=10, ge=1, le=1000)
    assert step.refusal(0) == 'step = 0: must be in 1 .. 1000'
    assert step.refusal(10.0) == 'step = 10.0: must be an integer in 1 .. 1000'
    assert step.refusal(1000) is None
    mode = ParamSpec('mode', kind='enum', default='a', choices=('a', 'b'))
    assert mode.refusal('c') == "mode = 'c': must be one of a, b"
    joints = ParamSpec('joints', kind='str_list', default=('a',),
                       check=lambda v: None if len(v) == 1 else 'exactly one joint')
    assert joints.refusal(['a', '']) == "joints = ['a', '']: must be a non-empty list of " \
        'non-empty strings'
    assert joints.refusal(['a', 'b']) == "joints = ['a', 'b']: exactly one joint"
    assert ParamSpec('w', kind='str', default='', empty=True).refusal('') is None
    assert ParamSpec('w', kind='str', default='x').refusal('') == \
        "w = '': must be a non-empty string"


def test_unknown_kind_is_refused():
    with pytest.raises(InvalidParameterError, match='unknown kind'):
        ParamSpec('p', kind='double', default=1.0)


def test_validate_table_names_source_parameter_value_and_range():
    with pytest.raises(InvalidParameterError) as info:
        validate_table(ROBOT_NODE_PARAMETERS, {'x': math.inf}, '/diff_robot/diff_robot',
                       key_word='parameter')
    assert str(info.value) == ("/diff_robot/diff_robot: parameter 'x' = inf: must be finite and "
                               '>= -1e+06 and <= 1e+06')


# --------------------------------------------------------------------------------------------
# Docs


@pytest.mark.parametrize('doc, anchor, make', DOC_TABLES,
                         ids=[f'{doc}:{anchor}' for doc, anchor, _ in DOC_TABLES])
def test_docs_contain_the_generated_table(doc, anchor, make):
    text = (REPO_ROOT / doc).read_text(encoding='utf-8')
    table = make()
    assert anchor in text
    after = text[text.index(anchor):]
    assert table in after, f'{doc}: regenerate the table after "{anchor}" from its ParamSpecs'


def _docs_text():
    return '\n'.join(path.read_text(encoding='utf-8')
                     for path in sorted((REPO_ROOT / 'docs').glob('*.md')))


@pytest.mark.parametrize('name', sorted(NODE_TABLES))
def test_every_node_parameter_is_documented_with_its_generated_row(name):
    docs = _docs_text()
    rows = node_parameter_table(NODE_TABLES[name]).splitlines()[2:]
    missing = [row for row in rows if row not in docs]
    assert not missing, missing


def test_every_robot_preset_field_is_documented_with_its_generated_row():
    docs = _docs_text()
    rows = parameter_table_markdown(ROBOT_PARAM_SPECS, 'field').splitlines()[2:]
    assert all(row in docs for row in rows)


# --------------------------------------------------------------------------------------------
# config/*.yaml


def _node_file(name):
    data = read_yaml(REPO_ROOT / 'config' / name)
    assert isinstance(data, dict) and len(data) == 1, f'{name}: one node per file'
    (node, section), = data.items()
    return node, section['ros__parameters']


def test_every_node_config_file_is_checked():
    shipped = sorted(p.name for p in (REPO_ROOT / 'config').glob('*.yaml'))
    assert shipped == sorted(CONFIG_FILES)


@pytest.mark.parametrize('name', sorted(CONFIG_FILES))
def test_config_file_lists_every_parameter_with_a_valid_value(name):
    specs = CONFIG_FILES[name]
    _, values = _node_file(name)
    assert values.pop('use_sim_time', False) is False
    assert set(values) == {spec.key for spec in specs}
    validate_table(specs, values, name, key_word='parameter')


@pytest.mark.parametrize('name', sorted(CONFIG_FILES))
def test_config_file_values_are_the_defaults_unless_explained(name):
    _, values = _node_file(name)
    defaults = table_defaults(CONFIG_FILES[name])
    differ = {key for key, value in values.items() if key in defaults and
              _plain(value) != _plain(defaults[key])}
    assert differ == {key for file, key in CONFIG_DIFFERENCES if file == name}


def _plain(value):
    return list(value) if isinstance(value, tuple) else value


def test_bridge_config_matches_the_robot_config():
    # config/bridge.yaml drives the robot of config/diff_robot.yaml (launch/bridge.launch.py).
    _, bridge = _node_file('bridge.yaml')
    _, robot = _node_file('diff_robot.yaml')
    preset = load_robot(robot['robot'])
    assert bridge['wheel_tread'] == bridge['wheel_base'] == preset.wheel_tread_m
    assert bridge['wheel_radius'] == preset.wheel_radius_m
    assert bridge['wheel_joints'] == robot['wheel_joints'] == list(preset.wheel_joints)
    assert bridge['max_wheel_speed_mps'] == 1.0          # docs/autoware.md


def test_automobile_config_is_the_generated_file():
    text = (REPO_ROOT / 'config' / 'automobile.yaml').read_text(encoding='utf-8')
    assert sim_params.params_file_text() in text


# --------------------------------------------------------------------------------------------
# Nodes: declared through the helper, refused with a clear error, not started


# The nodes that own a world are built synchronous (no stepping timer).
SYNCHRONOUS = {'synchronous': True}


def _automobile(overrides):
    from vehicle_sim.ros.automobile_node import AutomobileNode
    return AutomobileNode(['x', '--ros-args', '-r', f'__ns:={NAMESPACE}'], transport='dds',
                          parameter_overrides={**SYNCHRONOUS, **overrides})


def _autoware(overrides):
    from vehicle_sim.ros.autoware_automobile_node import AutowareAutomobileNode
    return AutowareAutomobileNode(['x', '--ros-args', '-r', f'__ns:={NAMESPACE}'],
                                  transport='dds',
                                  parameter_overrides={**SYNCHRONOUS, **overrides})


def _bridge(overrides):
    from vehicle_sim.ros.bridge_node import AckermannToDifferentialNode
    return AckermannToDifferentialNode(transport='dds', parameter_overrides=overrides,
                                       namespace=NAMESPACE)


def _robot(overrides):
    from vehicle_sim.ros.diff_robot_node import DiffRobotNode
    return DiffRobotNode(transport='dds', namespace=NAMESPACE,
                         parameter_overrides={**SYNCHRONOUS, **overrides})


NODES = {'automobile': _automobile, 'autoware_automobile': _autoware,
         'ackermann_to_differential': _bridge, 'diff_robot': _robot}


def _close(app):
    for name in ('close', 'destroy'):
        if hasattr(app, name):
            getattr(app, name)()
            return


@pytest.mark.parametrize('name', sorted(NODES))
def test_node_declares_every_parameter_of_its_table(name):
    app = NODES[name]({})
    try:
        node = app.node
        for spec in NODE_TABLES[name] + (USE_SIM_TIME,):
            assert node.has_parameter(spec.key), spec.key
            fixed = {} if name == 'ackermann_to_differential' else SYNCHRONOUS
            expected = fixed.get(spec.key, spec.default)
            assert _plain(node.get_parameter(spec.key)) == _plain(expected), spec.key
    finally:
        _close(app)


@pytest.mark.parametrize('name, overrides, expected', [
    ('diff_robot', {'x': math.nan}, 'x = nan: must be finite'),
    ('diff_robot', {'yaw': math.inf}, 'yaw = inf: must be finite'),
    ('diff_robot', {'y': -2e6}, 'y = -2000000.0: must be >= -1e+06 and <= 1e+06'),
    ('diff_robot', {'time_step_ms': 0}, 'time_step_ms = 0: must be in 1 .. 1000'),
    ('ackermann_to_differential', {'control_rate_hz': 0.0}, 'control_rate_hz = 0.0: must be > 0'),
    ('ackermann_to_differential', {'wheel_base': -0.4}, 'wheel_base = -0.4: must be > 0'),
    ('ackermann_to_differential', {'wheel_joints': ['a_joint', 'b_joint']},
     'must contain exactly one of "left" or "right"'),
    ('automobile', {'time_step_ms': 0}, 'time_step_ms = 0: must be in 1 .. 1000'),
    ('automobile', {'objects_rate': 0.0}, 'objects_rate = 0.0: must be > 0'),
    ('automobile', {'objects_rate': math.nan}, 'objects_rate = nan: must be finite'),
    ('automobile', {'objects_rate': math.inf}, 'objects_rate = inf: must be finite'),
    ('automobile', {'car_model': 'NoSuchCar'},
     "car_model = 'NoSuchCar': unknown car 'NoSuchCar'; known: BmwX5"),
    ('autoware_automobile', {'status_rate_hz': -1.0}, 'status_rate_hz = -1.0: must be > 0'),
    ('autoware_automobile', {'timeout_action': 'stop'},
     "timeout_action = 'stop': must be one of brake, coast, hold"),
])
def test_node_refuses_a_bad_value_naming_parameter_value_and_range(name, overrides, expected):
    with pytest.raises((TransportError, InvalidParameterError)) as info:
        app = NODES[name](overrides)
        _close(app)
    assert expected in str(info.value)


@pytest.mark.parametrize('module, args, expected', [
    ('bridge_node', ['-p', 'control_rate_hz:=0.0'], 'control_rate_hz = 0.0: must be > 0'),
    ('diff_robot_node', ['-p', 'x:=.nan'], 'x = nan: must be finite'),
])
def test_node_main_exits_2_with_the_reason(module, args, expected, capsys):
    import importlib
    main = importlib.import_module(f'vehicle_sim.ros.{module}').main
    status = main(['node', '--ros-args', '-r', f'__ns:={NAMESPACE}', *args])
    assert status == 2
    err = capsys.readouterr().err
    assert expected in err and 'Traceback' not in err


def test_helper_is_the_only_declaration_path():
    # Nodes never call declare_parameter themselves: one helper, one validation.
    ros_dir = REPO_ROOT / 'vehicle_sim' / 'ros'
    callers = [path.name for path in sorted(ros_dir.glob('*.py'))
               if 'declare_parameter(' in path.read_text(encoding='utf-8')]
    assert callers == ['node_support.py']
