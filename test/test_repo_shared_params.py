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
One row per shared simulation parameter: every entry point refuses and accepts the same values.

``time_step_ms`` (and ``friction``) are declared once, in ``core/specs/simulation.py``; the
automobile and robot nodes, scenario files, the Gymnasium environment, the Webots facade and the
end-to-end runner all take that row: the same kind, bounds, default and refusal text.
"""

import math
from pathlib import Path
import re

import pytest

from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.simulation import FRICTION, TIME_STEP_MS
from vehicle_sim.transport import TransportError

REPO_ROOT = Path(__file__).resolve().parents[1]
PACKAGE = REPO_ROOT / 'vehicle_sim'
NAMESPACE = '/test_repo_shared_params'
BAD = [0, 1001, 2.5, math.nan, 'x']
GOOD = [1, 10, 1000]
SCENARIO = """\
world:
  vehicles:
    - {{name: ego, model: Car, pose: {{x: 0.0, y: 0.0, yaw: 0.0}}}}
duration: 1.0
time_step_ms: {value}
driver:
  commands:
    - {{t: 0.0, cruising_speed: 10.0}}
criteria:
  - {{kind: no_collision}}
"""


def _yaml(value):
    return '.nan' if isinstance(value, float) and math.isnan(value) else repr(value)


def _automobile(value):
    from vehicle_sim.ros.automobile_node import AutomobileNode
    app = AutomobileNode(['x', '--ros-args', '-r', f'__ns:={NAMESPACE}'], transport='dds',
                         parameter_overrides={'synchronous': True, 'time_step_ms': value})
    step_ms = app.world.time_step_s * 1000.0
    app.close()
    return step_ms


def _robot(value):
    from vehicle_sim.ros.diff_robot_node import DiffRobotNode
    app = DiffRobotNode(transport='dds', namespace=NAMESPACE,
                        parameter_overrides={'synchronous': True, 'time_step_ms': value})
    step_ms = app.world.time_step_s * 1000.0
    app.destroy()
    return step_ms


def _scenario(value, tmp_path):
    from vehicle_sim.scenarios.schema import load_scenario
    path = tmp_path / 'step.yaml'
    path.write_text(SCENARIO.format(value=_yaml(value)))
    return load_scenario(path).time_step_ms


def _gym(value):
    from vehicle_sim.gym.drive_sim import DriveSim
    sim = DriveSim(world='default', options={'time_step_ms': value})
    step_ms = sim.world.time_step_s * 1000.0
    sim.close()
    return step_ms


def _webots(value):
    from vehicle_sim.webots.driver import Driver
    driver = Driver('Car', time_step_ms=value)
    step_ms = driver.getBasicTimeStep()
    driver.close()
    return step_ms


ENTRY_POINTS = {'automobile node': _automobile, 'diff_robot node': _robot,
                'scenario file': _scenario, 'gym options': _gym, 'webots Driver': _webots}


def _call(name, value, tmp_path):
    entry = ENTRY_POINTS[name]
    return entry(value, tmp_path) if name == 'scenario file' else entry(value)


def _reason(value):
    # The row's own refusal: '<key> = <value>: <reason>'.
    return TIME_STEP_MS.refusal(value).split(': ', 1)[1]


def test_the_row_is_an_int_in_1_to_1000_defaulting_to_10_ms():
    assert (TIME_STEP_MS.key, TIME_STEP_MS.kind, TIME_STEP_MS.default) == ('time_step_ms', 'int',
                                                                          10)
    assert (TIME_STEP_MS.ge, TIME_STEP_MS.le, TIME_STEP_MS.unit) == (1, 1000, 'ms')
    assert [TIME_STEP_MS.refusal(v) is None for v in GOOD] == [True] * len(GOOD)
    assert TIME_STEP_MS.refusal(1001) == 'time_step_ms = 1001: must be in 1 .. 1000'
    assert TIME_STEP_MS.refusal('x') == "time_step_ms = 'x': must be an integer in 1 .. 1000"


@pytest.mark.parametrize('value', BAD, ids=repr)
@pytest.mark.parametrize('name', sorted(ENTRY_POINTS))
def test_every_entry_point_refuses_a_bad_time_step_naming_it(name, value, tmp_path):
    from vehicle_sim.scenarios.yaml_lines import ScenarioError
    with pytest.raises((InvalidParameterError, TransportError, ScenarioError, ValueError)) as info:
        _call(name, value, tmp_path)
    text = str(info.value)
    assert 'time_step_ms' in text
    assert _yaml(value).strip('.') in text or repr(value) in text, text
    if name.endswith('node') and not isinstance(value, int):
        # A node's parameter is typed by its default (an integer): ROS refuses a double or a
        # string override by type before the row sees it, with the same words under rclpy.
        assert 'is of type {integer}' in text
    else:
        assert _reason(value) in text


@pytest.mark.parametrize('value', GOOD)
@pytest.mark.parametrize('name', sorted(ENTRY_POINTS))
def test_every_entry_point_accepts_the_same_time_steps(name, value, tmp_path):
    assert _call(name, value, tmp_path) == pytest.approx(value)


def test_end_to_end_runs_at_the_default_step():
    from vehicle_sim.tools import end_to_end
    assert end_to_end.DT_S == TIME_STEP_MS.default / 1000.0


def test_default_step_is_the_rows_everywhere():
    from vehicle_sim.gym.drive_sim import DriveSim
    from vehicle_sim.physics.world import DEFAULT_TIME_STEP_S
    from vehicle_sim.ros.diff_robot_node import ROBOT_NODE_PARAMETERS
    from vehicle_sim.ros.sim_params import AUTOMOBILE_PARAMETERS
    from vehicle_sim.scenarios.schema import SCENARIO_SPECS
    assert DEFAULT_TIME_STEP_S == TIME_STEP_MS.default / 1000.0
    for table in (AUTOMOBILE_PARAMETERS, ROBOT_NODE_PARAMETERS, SCENARIO_SPECS):
        assert [spec for spec in table if spec.key == 'time_step_ms'] == [TIME_STEP_MS]
    sim = DriveSim(world='default')
    try:
        assert sim.world.time_step_s * 1000.0 == TIME_STEP_MS.default
    finally:
        sim.close()


def _sources():
    return sorted(PACKAGE.rglob('*.py'))


# A declaration of a time step, or a default given to one: a ParamSpec row, a constant, a
# keyword default (time_step_s=0.010, DT_S = 0.010, default=10 on a time_step_ms row).
DECLARATION = re.compile(r"ParamSpec\(\s*'time_step_ms'")
STEP_LITERAL = re.compile(r'(?i)\b\w*(time_?step|step_s|dt_s|step_ms)\w*\s*=\s*(0\.010?|10)\b')


def test_time_step_and_friction_are_declared_once_in_the_package():
    declarations, literals, frictions = [], [], []
    for path in _sources():
        text = path.read_text(encoding='utf-8')
        name = str(path.relative_to(REPO_ROOT))
        declarations += [name for _ in DECLARATION.finditer(text)]
        frictions += [name for _ in re.finditer(r"ParamSpec\(\s*'friction'", text)]
        literals += [f'{name}: {line.strip()}' for line in text.splitlines()
                     if STEP_LITERAL.search(line)]
    assert declarations == ['vehicle_sim/core/specs/simulation.py']
    assert frictions == ['vehicle_sim/core/specs/simulation.py']
    assert literals == []


@pytest.mark.parametrize('value', [0.0, -1.0, math.nan, math.inf])
def test_world_refuses_a_bad_friction_with_the_rows_text(value):
    from vehicle_sim.physics.world import World
    with pytest.raises(ValueError) as info:
        World(friction=value)
    assert str(info.value) == FRICTION.refusal(value)
