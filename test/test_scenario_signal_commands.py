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


"""Scenario commands that force a traffic light group: ``{t, signal: {group, state}}``."""

import re

import pytest
import yaml

from vehicle_sim.scenarios import runner
from vehicle_sim.scenarios.schema import load_scenario
from vehicle_sim.scenarios.yaml_lines import ScenarioError

EAST, WEST = 4000100101, 4000100151


def road(name, start, yaw, lights=True):
    return {'name': name, 'start': {'x': start[0], 'y': start[1], 'yaw': yaw},
            'segments': [{'type': 'straight', 'length': 44},
                         {'type': 'intersection', 'length': 12, 'signals': lights},
                         {'type': 'straight', 'length': 44}]}


def scenario(tmp_path, commands, lights=True):
    """Write a scenario on a signalised four-way crossing; return its path."""
    data = {'world': {'vehicles': [{'name': 'ego', 'model': 'ToyotaPrius',
                                    'pose': {'x': -40.0, 'y': -1.75, 'yaw': 0.0}}],
                      'roads': [road('ew', (-50, 0), 0.0, lights),
                                road('ns', (0, -50), 1.5707963267948966, lights)]},
            'duration': 2.5,
            'driver': {'commands': commands},
            'criteria': [{'kind': 'no_collision'}]}
    path = tmp_path / 's.yaml'
    path.write_text(yaml.safe_dump(data, sort_keys=False))
    return path


def test_a_forced_state_is_what_the_controller_reads_from_its_time(tmp_path, monkeypatch):
    path = scenario(tmp_path, [{'t': 0.0, 'brake_intensity': 1.0},
                               {'t': 1.0, 'signal': {'group': EAST, 'state': 'red'}},
                               {'t': 1.0, 'signal': {'group': WEST, 'state': 'off'}},
                               {'t': 2.0, 'signal': {'group': EAST, 'state': 'plan'}}])
    spec = load_scenario(str(path))
    assert spec.driver.commands[1].signals == ((EAST, 'red'),)
    sims = []

    class Watched(runner.LocalSim):
        def __init__(self, *args, **kwargs):
            super().__init__(*args, **kwargs)
            sims.append(self)

    seen = {}

    def progress(time_s, duration_s):
        controller = sims[0].signals.controller
        seen[round(time_s, 2)] = (controller.state(EAST), controller.state(WEST))

    monkeypatch.setattr(runner, 'LocalSim', Watched)
    result = runner.run_scenario(spec, progress=progress)
    assert result.passed
    # the plan: east green for its first 20 s, west red; the command acts from its step on
    assert seen[0.99] == ('green', 'red') and seen[1.0] == ('green', 'red')
    assert seen[1.01] == ('red', 'off') and seen[1.99] == ('red', 'off')
    assert seen[2.01] == ('green', 'off')          # east follows its plan again, west held


@pytest.mark.parametrize('signal, fragment', [
    ({'group': 123, 'state': 'red'}, 'signal.group = 123: traffic light group 123 is not in '
     'the map (its groups: 4000100101, 4000100151, 4000200101, 4000200151)'),
    ({'group': EAST, 'state': 'blue'}, "signal: field 'state' = 'blue': must be one of red, "
     'yellow, green, off, plan'),
    ({'group': 'east', 'state': 'red'}, "signal: field 'group' = 'east': must be an integer"),
    ({'group': EAST}, "signal: field 'state' is required"),
    ({'group': EAST, 'state': 'red', 'for': 3}, "signal: unknown field 'for'"),
])
def test_a_bad_signal_command_is_refused_at_load_naming_the_field(tmp_path, signal, fragment):
    path = scenario(tmp_path, [{'t': 0.0, 'brake_intensity': 1.0},
                               {'t': 1.0, 'signal': signal}])
    with pytest.raises(ScenarioError) as error:
        load_scenario(str(path))
    assert re.match(rf'{re.escape(str(path))}:\d+: ', str(error.value)), str(error.value)
    assert fragment in str(error.value), str(error.value)


def test_a_signal_command_in_a_world_without_lights_is_refused_at_load(tmp_path):
    path = scenario(tmp_path, [{'t': 1.0, 'signal': {'group': EAST, 'state': 'red'}}],
                    lights=False)
    with pytest.raises(ScenarioError, match=r'signal.group = 4000100101: traffic light group '
                       r'4000100101 is not in the map \(its groups: none\)'):
        load_scenario(str(path))
