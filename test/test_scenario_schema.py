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

"""Scenario files: the schema accepts the shipped files and names the line of every error."""

from pathlib import Path
import textwrap

import pytest

from vehicle_sim.scenarios.schema import load_scenario
from vehicle_sim.scenarios.yaml_lines import load_with_lines, ScenarioError

ROOT = Path(__file__).resolve().parent.parent
SHIPPED = sorted((ROOT / 'scenarios').glob('*.yaml')) + sorted(
    (ROOT / 'test' / 'scenarios').glob('*.yaml'))

# A valid scenario; each bad case below changes one line of it.
VALID = textwrap.dedent("""\
    name: sample
    world:
      vehicles:
        - {name: ego, model: Car, pose: {x: 0.0, y: 0.0, yaw: 0.0}}
        - {name: other, namespace: other, pose: {x: 0.0, y: 10.0, yaw: 0.0}}
      obstacles:
        - {name: wall, shape: box, size: [1.0, 6.0, 2.0], position: [20.0, 0.0, 1.0]}
    duration: 5.0
    actors:
      - {vehicle: other, speed: 3.0, waypoints: [[10.0, 10.0], [20.0, 10.0]]}
    driver:
      commands:
        - {t: 0.0, cruising_speed: 10.0}
        - {t: 1.0, steering_angle: 0.1}
    criteria:
      - {kind: no_collision}
      - {kind: max_speed, limit: 5.0}
    """)


def _write(tmp_path, text):
    path = tmp_path / 'scenario_sample.yaml'
    path.write_text(text, encoding='utf-8')
    return path


def _replace_line(number, new):
    lines = VALID.splitlines()
    lines[number - 1] = new
    return '\n'.join(lines) + '\n'


@pytest.mark.parametrize('path', SHIPPED, ids=lambda p: p.name)
def test_schema_shipped_scenario_files_load(path):
    spec = load_scenario(path)
    assert spec.criteria and spec.duration_s > 0.0


def test_schema_valid_sample_gives_its_values(tmp_path):
    spec = load_scenario(_write(tmp_path, VALID))
    assert spec.name == 'sample'
    assert spec.vehicle == 'ego'                      # default: the first vehicle
    assert spec.car_names == ('ego', 'other')
    assert [o.name for o in spec.world.obstacles] == ['wall']
    assert spec.driver.kind == 'commands'
    first, second = spec.driver.commands
    assert (first.t_s, first.setters) == (0.0, (('set_cruising_speed_kmh', 10.0,
                                                 'setCruisingSpeed'),))
    assert second.line == 14
    assert spec.actors[0].waypoints[1].speed_mps == 3.0
    assert spec.actors[0].speed_control == 'idm'      # default: IDM behind whatever is ahead
    assert [c.name for c in spec.criteria] == ['no_collision', 'max_speed']
    assert spec.criteria[1].values == {'limit_mps': 5.0}


def test_yaml_lines_maps_paths_to_their_lines():
    data, lines = load_with_lines('a: 1\nb:\n  - x: 2\n  - y: [3,\n      4]\n', 'f')
    assert data == {'a': 1, 'b': [{'x': 2}, {'y': [3, 4]}]}
    assert lines[('a',)] == 1
    assert lines[('b', 0, 'x')] == 3
    assert lines[('b', 1, 'y')] == 4
    assert lines[('b', 1, 'y', 1)] == 5


@pytest.mark.parametrize('line, new, fragment', [
    (1, 'nam: sample', "unknown field 'nam'"),
    (8, 'duration: -5.0', "field 'duration' = -5.0"),
    (4, '    - {name: ego, model: Car, pose: {x: 0.0, y: .nan, yaw: 0.0}}', 'pose'),
    (4, '    - {name: ego, model: NoSuchCar}', 'NoSuchCar'),
    (7, '    - {name: wall, shape: cone, size: [1, 1, 1], position: [1, 0, 1]}', 'cone'),
    (10, '  - {vehicle: nobody, waypoints: [[1.0, 1.0]]}', "vehicle 'nobody'"),
    (10, '  - {vehicle: ego, waypoints: [[1.0, 1.0]]}', 'vehicle under test'),
    (10, '  - {vehicle: other, waypoints: [[1.0]]}', 'waypoint [1.0]'),
    (13, '    - {t: 0.0, cruise: 10.0}', "unknown setter 'cruise'"),
    # the entry after it (t = 1.0) is the one out of order
    (14, '    - {t: 1.0, steering_angle: 0.1}\n    - {t: 0.5, brake_intensity: 0.5}',
     'time order'),
    (13, "    - {t: 0.0, cruising_speed: 'fast'}", 'must be a finite number'),
    (13, '    - {t: 0.0, gear: 1.5}', 'must be an integer'),
    (16, '  - {kind: no_colision}', "kind 'no_colision'"),
    (17, '  - {kind: max_speed, limit: 0.0}', "field 'limit' = 0.0"),
    (17, '  - {kind: max_speed, lim: 5.0}', "unknown field 'lim'"),
    (17, '  - {kind: stay_on_path, path: [[0, 0]], max_distance: 1.0}', 'path'),
    (17, '  - {kind: no_collision, vehicle: ghost}', "vehicle 'ghost'"),
    (17, '  - {kind: topic, topic: /a, type: std_msgs/msg/Float64, field: data, op: "=<", '
         'value: 1}', "field 'op'"),
    (5, '    - {name: other, namespace: other, pose: {x: 0.0, y: 10.0, yaw: [0.0}}',
     'not valid YAML'),
])
def test_schema_error_names_the_line(tmp_path, line, new, fragment):
    path = _write(tmp_path, _replace_line(line, new))
    with pytest.raises(ScenarioError) as caught:
        load_scenario(path)
    error = caught.value
    assert fragment in str(error)
    assert str(error).startswith(f'{path}:{error.line}: ')
    # a YAML syntax error is reported where the parser noticed it (the end of the flow)
    expected = (line, line + 1) if 'YAML' in fragment else (
        (line + 1,) if 'time order' in fragment else (line,))
    assert error.line in expected, str(error)


def test_schema_two_driver_kinds_are_refused_at_the_driver_line(tmp_path):
    text = VALID.replace('driver:\n', 'driver:\n  controller: x.py\n')
    with pytest.raises(ScenarioError, match='exactly one of') as caught:
        load_scenario(_write(tmp_path, text))
    assert caught.value.line == 11


def test_schema_missing_controller_file_is_refused_at_its_line(tmp_path):
    text = VALID.split('driver:')[0] + 'driver:\n  controller: no_such.py\n' + \
        'criteria:' + VALID.split('criteria:')[1]
    with pytest.raises(ScenarioError, match='no such file') as caught:
        load_scenario(_write(tmp_path, text))
    assert caught.value.line == 12


def test_schema_missing_required_key_is_named(tmp_path):
    text = VALID.replace('duration: 5.0\n', '')
    with pytest.raises(ScenarioError, match="'duration'"):
        load_scenario(_write(tmp_path, text))


def test_schema_world_file_error_names_the_world_line(tmp_path):
    text = VALID.split('world:')[0] + 'world: no_such_world\n' + VALID.split(
        'duration:')[1].join(['duration:', ''])
    with pytest.raises(ScenarioError, match='no_such_world') as caught:
        load_scenario(_write(tmp_path, text))
    assert caught.value.line == 2


def test_schema_world_by_relative_path_resolves_next_to_the_scenario(tmp_path):
    (tmp_path / 'my_world.yaml').write_text('vehicles:\n  - {name: solo}\n', encoding='utf-8')
    text = 'world: my_world.yaml\nduration: 1.0\ndriver:\n  commands: [{t: 0, throttle: 0.5}]\n' \
           'criteria: [{kind: no_collision}]\n'
    spec = load_scenario(_write(tmp_path, text))
    assert spec.vehicle == 'solo'
    assert spec.world_file == str(tmp_path / 'my_world.yaml')


def test_schema_docs_show_the_generated_key_tables():
    from vehicle_sim.scenarios.schema import schema_markdown
    text = (ROOT / 'docs' / 'scenarios.md').read_text(encoding='utf-8')
    assert schema_markdown() in text


ROBOT_WITH_SENSORS = textwrap.dedent("""\
    world: {{vehicles: [{{name: Car}}]}}
    robots:
      - name: bot
        sensors: {sensors}
        pose: {{x: 0.0, y: 10.0, yaw: 0.0}}
    duration: 1.0
    driver: {{commands: [{{t: 0.0, cruising_speed: 0.0}}]}}
    criteria:
      - {{kind: no_collision}}{topic}
    """)
_SCAN_CRITERION = ("\n  - {kind: topic, topic: /bot/scan, type: sensor_msgs/msg/LaserScan, "
                   "field: range_max, op: '>', value: 0.0, mode: eventually, "
                   "best_effort: true}")


@pytest.mark.parametrize('sensors, mounted', [('[lidar]', ('lidar',)), ('all', ('all',)),
                                               ('[lidar, imu]', ('lidar', 'imu'))])
def test_schema_robot_sensors_are_names_of_its_preset(tmp_path, sensors, mounted):
    path = _write(tmp_path, ROBOT_WITH_SENSORS.format(sensors=sensors, topic=_SCAN_CRITERION))
    spec = load_scenario(path)
    assert spec.robots[0].sensors == mounted and spec.served


@pytest.mark.parametrize('sensors, fragment', [
    ('[radar]', "unknown sensor(s) ['radar']; this vehicle has lidar, imu"),
    ('lidar', "sensors 'lidar': a list of sensor names, or 'all'"),
    ('[]', "a list of sensor names, or 'all'"),
])
def test_schema_robot_sensors_refused_at_their_line(tmp_path, sensors, fragment):
    path = _write(tmp_path, ROBOT_WITH_SENSORS.format(sensors=sensors, topic=_SCAN_CRITERION))
    with pytest.raises(ScenarioError) as error:
        load_scenario(path)
    assert f'{path}:4:' in str(error.value) and fragment in str(error.value)


def test_schema_robot_sensors_need_a_served_scenario(tmp_path):
    path = _write(tmp_path, ROBOT_WITH_SENSORS.format(sensors='[lidar]', topic=''))
    with pytest.raises(ScenarioError) as error:
        load_scenario(path)
    assert f'{path}:4:' in str(error.value)
    assert 'published over ROS' in str(error.value)


def test_a_missing_required_field_is_named_without_a_placeholder_value(tmp_path):
    # Not "field 'driver' = REQUIRED: is required".
    path = tmp_path / 'no_driver.yaml'
    path.write_text('name: x\nduration: 5\nworld: {vehicles: [{name: ego}]}\n'
                    'criteria: [{type: no_collision}]\n', encoding='utf-8')
    with pytest.raises(ScenarioError) as error:
        load_scenario(str(path))
    assert str(error.value).endswith("scenario: field 'driver' is required")


def test_a_criterion_without_kind_says_kind_is_needed(tmp_path):
    # Not "criterion kind None: valid kinds: ..." for a criterion written with 'type:'.
    path = tmp_path / 'typed.yaml'
    path.write_text('duration: 5\nworld: {vehicles: [{name: ego}]}\n'
                    'driver: {commands: [{t: 0.0, cruising_speed: 5}]}\n'
                    'criteria:\n  - {type: no_collision}\n', encoding='utf-8')
    with pytest.raises(ScenarioError) as error:
        load_scenario(str(path))
    assert error.value.line == 5
    assert ("a criterion needs 'kind': one of clearance, max_speed, mean_speed, min_gap"
            in str(error.value))


SYNCED = ('duration: 1\nworld: {vehicles: [{name: ego}]}\n'
          'driver:\n  processes: [python -c pass]\n  sync_period: 0.02\n  sync:\n'
          '    - {topic: /a, type: std_msgs/msg/Float64}\n'
          '    - SECOND\n'
          'criteria: [{kind: no_collision}]\n')


def test_schema_sync_count_is_read_and_defaults_to_one_message(tmp_path):
    path = _write(tmp_path, SYNCED.replace(
        'SECOND', '{topic: /b, type: vehicle_msgs/msg/DifferentialCommand, count: 2}'))
    assert load_scenario(path).driver.sync == (
        ('/a', 'std_msgs/msg/Float64', 1), ('/b', 'vehicle_msgs/msg/DifferentialCommand', 2))


@pytest.mark.parametrize('entry, fragment', [
    ('{topic: /b, type: std_msgs/msg/Float64, count: 0}',
     'sync count = 0: must be an integer >= 1 (messages per sync period)'),
    ('{topic: /b, type: std_msgs/msg/Float64, count: 1.5}', 'sync count = 1.5: must be an '),
    ('{topic: /b, type: std_msgs/msg/Float64, count: true}', 'sync count = True: must be an '),
    ("{topic: /b, type: std_msgs/msg/Float64, count: 'two'}", "sync count = 'two': must be "),
    ('{topic: /b, type: std_msgs/msg/Float64, cnt: 2}',
     'must be {topic: /name, type: pkg/msg/Type, count: messages (optional, 1)}'),
    ('{topic: /b}', 'must be {topic: /name, type: pkg/msg/Type'),
])
def test_schema_a_bad_sync_entry_is_refused_at_its_line(tmp_path, entry, fragment):
    path = _write(tmp_path, SYNCED.replace('SECOND', entry))
    with pytest.raises(ScenarioError) as error:
        load_scenario(path)
    assert fragment in str(error.value)
    assert error.value.line == 8, str(error.value)
