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
The action layouts have one source, core's table: the environment and the policy node offer it.

The Gym environment (gym/controls.py, its ``control`` option) and the policy node
(ros/policy_actions.py) offer exactly the layouts of ``vehicle_sim/core/learning/actions.py``
(the node: those of a car), with its entries, and set the same setters with the same values for
the same action and forward speed: a layout added, or its rule changed, on one side only fails
here.
"""

import os
from types import SimpleNamespace

import numpy as np
import pytest

from vehicle_sim.core.learning import actions
from vehicle_sim.core.learning.objects_table import ObjectsTableSpec
from vehicle_sim.gym import controls, options
from vehicle_sim.ros import automobile_interfaces as itf
from vehicle_sim.ros import policy_actions

CAR_LAYOUTS = actions.layouts_of(actions.CAR)


class RecordingLogic:
    """A car's driver logic that records its setters' calls (asymmetric Webots limits)."""

    min_steering_angle_rad = -0.6        # Webots: + = right
    max_steering_angle_rad = 0.5
    max_cruising_speed_kmh = 180.0

    def __init__(self):
        self.calls = []
        for method in controls.CAR_SETTERS.values():
            setattr(self, method, lambda value, method=method: self.calls.append((method, value)))


class Body:
    """The car's body: its forward speed as body_twist gives it."""

    forward_mps = 0.0

    def body_twist(self):
        return (self.forward_mps, 0.0, 0.0), (0.0, 0.0, 0.0)


class Lanes:
    """The car's VehicleLanes: its lane state as the environment's step left it."""

    state = SimpleNamespace(offset_m=0.0, heading_error_rad=0.0)


class Objects:
    """The ego's objects part: its table's spec and the last observation's table."""

    spec = ObjectsTableSpec(count=3, range_m=80.0, speed_scale_mps=40.0)
    table = np.zeros((3, 7), dtype=np.float32)

    def last_table(self):
        return self.table


def _table(*rows):
    """Return an objects table of (x [m], y [m], relative vx [m/s]) rows (range 80, 40 m/s)."""
    table = np.zeros((3, 7), dtype=np.float32)
    for i, (x, y, vx) in enumerate(rows):
        table[i, :5] = (1.0, x / 80.0, y / 80.0, vx / 40.0, 0.0)
        table[i, 5] = 1.0
    return table


# Objects tables the guard reads: none ahead, a slower car 30 m ahead in the lane, one at rest
# 20 m ahead, a slower car in the next lane (not a lead).
TABLES = (_table(), _table((30.0, 0.3, -6.0)), _table((20.0, -0.5, -50.0), (-15.0, 0.0, 3.0)),
          _table((25.0, 3.7, -8.0)))


def _car():
    car = SimpleNamespace(logic=RecordingLogic(), body=Body())
    return car, SimpleNamespace(name='ego', car=car, body=car.body)


def test_the_environment_and_the_node_offer_exactly_the_table_s_layouts():
    assert tuple(actions.LAYOUTS) == ('speed_steering', 'braking_speed_steering',
                                      'guarded_speed_steering', 'lane_speed',
                                      'throttle_steering', 'twist')
    assert options.CONTROLS == ('auto',) + tuple(actions.LAYOUTS)
    assert controls.CONTROLS == tuple(actions.LAYOUTS)
    assert tuple(policy_actions.LAYOUTS) == CAR_LAYOUTS == (
        'speed_steering', 'braking_speed_steering', 'guarded_speed_steering', 'lane_speed',
        'throttle_steering')
    for name, layout in policy_actions.LAYOUTS.items():
        assert layout is actions.LAYOUTS[name]
    # every setter of a layout is the vehicle's: a car's a driver logic method and an
    # automobile service of the same unit, a robot's its body's
    for layout in actions.LAYOUTS.values():
        assert len(layout.names) == len(layout.units) == len(layout.halt)
        for setter in layout.setters:
            vehicle, unit = actions.SETTERS[setter]
            assert vehicle == layout.vehicle
            if vehicle == actions.CAR:
                assert setter in controls.CAR_SETTERS
                assert itf.service(policy_actions.service_of(setter)).unit == unit
            else:
                assert setter in controls.ROBOT_SETTERS
    assert set(controls.CAR_SETTERS) == {s for s, (v, _) in actions.SETTERS.items()
                                         if v == actions.CAR}
    assert set(controls.ROBOT_SETTERS) == {s for s, (v, _) in actions.SETTERS.items()
                                           if v == actions.ROBOT}


# Lane states (offset [m], heading error [rad]) the lane_speed law steers from.
LANE_STATES = ((0.0, 0.0), (1.2, -0.03), (-1.8, 0.05))
# The bounds: steering + = left (the car's limits swapped), speed min(top, 20 m/s); lane_speed
# a lateral offset of up to 4 m either way and forward speeds only.
BOUNDS = {
    'speed_steering': ((-0.5, -5.0), (0.6, 20.0)),
    'braking_speed_steering': ((-0.5, -5.0), (0.6, 20.0)),
    'guarded_speed_steering': ((-0.5, -5.0), (0.6, 20.0)),
    'lane_speed': ((-4.0, 0.0), (4.0, 20.0)),
    'throttle_steering': ((-0.5, 0.0, 0.0), (0.6, 1.0, 1.0)),
}


@pytest.mark.parametrize('name', CAR_LAYOUTS)
def test_the_environment_and_the_node_set_the_same_values(name):
    car, vehicle = _car()
    lanes = Lanes()
    objects = Objects()
    control = controls.make_control(name, vehicle, None, 5.0, None, lanes, objects)
    layout = actions.LAYOUTS[name]
    assert control.layout is layout
    assert control.names == layout.names and control.units == layout.units
    assert np.array_equal(control.low, np.float32(BOUNDS[name][0]))
    assert np.array_equal(control.high, np.float32(BOUNDS[name][1]))
    writer = policy_actions.ActionWriter(name, control.low, control.high, (-1.0, 1.0),
                                         control.steering_bounds, objects.spec)
    assert writer.services == tuple(policy_actions.service_of(s) for s in layout.setters)
    rng = np.random.default_rng(3)
    samples = [control.low, control.high, (control.low + control.high) / 2]
    samples += list(rng.uniform(control.low, control.high, size=(20, len(layout.names))))
    seen = set()
    steered = set()
    for sample in samples:
        for forward in (-3.0, 0.0, 3.0, 14.5, 17.0, 25.0):
            for (offset, heading_error), table in zip(LANE_STATES * 2, TABLES * 2):
                physical = control.check(np.float32(sample))
                car.logic.calls.clear()
                car.body.forward_mps = forward
                lanes.state = SimpleNamespace(offset_m=offset, heading_error_rad=heading_error)
                objects.table = table
                control.apply(physical)
                in_process = [(setter, value) for (method, value) in car.logic.calls
                              for setter in controls.CAR_SETTERS
                              if controls.CAR_SETTERS[setter] == method]
                # the node reads the same from the car's lane_state message and the table it
                # builds from the objects topic
                message = SimpleNamespace(offset=offset, heading_error=heading_error)
                assert writer.setters(physical, forward, message, table) == [
                    (policy_actions.service_of(setter), value) for setter, value in in_process]
                seen.add(tuple(setter for setter, _ in in_process))
                steered.add(in_process[0])
    # the braking layouts both brake and cruise over these speeds; the others set one way
    assert len(seen) == (2 if layout.reads_speed else 1)
    # lane_speed steers by the lane state: within the car's limits, both ways
    if name == 'lane_speed':
        angles = {value for setter, value in steered}
        assert min(angles) < -0.1 and max(angles) > 0.1
        assert all(-0.6 <= angle <= 0.5 for angle in angles)     # Webots' limits, + = right
    car.logic.calls.clear()
    control.halt()
    # a halt brakes (throttle 0, brake 1, or a stand asked of the cruise control); lane_speed
    # steers on toward its lane's centre meanwhile
    halted = car.logic.calls[1:] if name == 'lane_speed' else car.logic.calls
    assert halted and all(value in (0.0, 1.0) for _, value in halted)


def test_the_node_refuses_a_robot_layout_and_the_environment_a_mismatched_one():
    from vehicle_sim.core.specs.errors import InvalidParameterError
    with pytest.raises(InvalidParameterError, match="control 'twist': the automobile node is "
                                                    'driven by speed_steering, '
                                                    'braking_speed_steering, '
                                                    'guarded_speed_steering, lane_speed, '
                                                    'throttle_steering'):
        policy_actions.ActionWriter('twist', (-1.0, -1.0), (1.0, 1.0))
    _, vehicle = _car()
    with pytest.raises(ValueError, match="control 'twist' does not fit the ego 'ego', a car; "
                                         'valid: speed_steering, braking_speed_steering, '
                                         'guarded_speed_steering, lane_speed, '
                                         'throttle_steering'):
        controls.make_control('twist', vehicle)
    with pytest.raises(InvalidParameterError, match="control 'lane_speed' reads the lane "
                                                    'state: the world has no lanes'):
        controls.make_control('lane_speed', vehicle)
    # the guard reads the objects table: none without the option 'objects', in process or in
    # the node's card
    with pytest.raises(InvalidParameterError, match="control 'guarded_speed_steering' reads "
                                                    r'the objects table \(its headway guard\): '
                                                    "give the option 'objects'"):
        controls.make_control('guarded_speed_steering', vehicle, lanes=Lanes())
    with pytest.raises(InvalidParameterError, match="control 'guarded_speed_steering' reads "
                                                    r'the objects table \(its headway guard\): '
                                                    'the environment has none'):
        policy_actions.ActionWriter('guarded_speed_steering', (-0.5, 0.0), (0.5, 20.0),
                                    (-1.0, 1.0), (-0.5, 0.5))
    writer = policy_actions.ActionWriter('guarded_speed_steering', (-0.5, 0.0), (0.5, 20.0),
                                         (-1.0, 1.0), (-0.5, 0.5), Objects.spec)
    with pytest.raises(ValueError, match="control 'guarded_speed_steering' reads the objects "
                                         'table: none given'):
        writer.setters((0.0, 10.0), 10.0, SimpleNamespace(offset=0.0, heading_error=0.0))
    # the node's writer needs the environment's steering bounds for lane_speed's law: none
    # given is refused, not steered within (0, 0)
    with pytest.raises(InvalidParameterError, match="control 'lane_speed' steers by a law "
                                                    'within the steering bounds of its '
                                                    'environment: none given'):
        policy_actions.ActionWriter('lane_speed', (-4.0, 0.0), (4.0, 20.0))
    # nor without the car's lane state: refused, not steered as if centred
    writer = policy_actions.ActionWriter('lane_speed', (-4.0, 0.0), (4.0, 20.0), (-1.0, 1.0),
                                         (-0.02, 0.02))
    with pytest.raises(ValueError, match="control 'lane_speed' reads the lane state: no "
                                         'lane_state message'):
        writer.setters((1.0, 10.0), 10.0)
    with pytest.raises(ValueError, match='lane_speed steers within the steering bounds of its '
                                         'environment: none given'):
        actions.LAYOUTS['lane_speed'].values((1.0, 10.0), actions.Reading(10.0))


def _docs_action_rows():
    path = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                        'docs', 'gym.md')
    with open(path, encoding='utf-8') as stream:
        section = stream.read().split('\n## Actions\n', 1)[1].split('\n## ', 1)[0]
    rows = {}
    for line in section.splitlines():
        cells = [cell.strip() for cell in line.strip().strip('|').split('|')]
        if line.startswith('| `') and len(cells) == 4:
            rows[cells[0].split('`')[1]] = (cells[1], cells[2])
    return rows


def test_docs_actions_table_lists_the_tables_layouts_with_their_vehicles_and_units():
    # docs/gym.md's Actions table is prose for people; it must name exactly the layouts of the
    # one table, each for its vehicle, with one entry per action entry in the table's units.
    rows = _docs_action_rows()
    assert set(rows) == set(actions.LAYOUTS)
    for name, layout in actions.LAYOUTS.items():
        vehicle, entries = rows[name]
        assert vehicle == layout.vehicle, name
        while entries.startswith('as `'):     # 'as `speed_steering`; ...': that row's entries
            entries = rows[entries.split('`')[1]][1]
        parts = entries.split(';')
        assert len(parts) == len(layout.names), (name, parts)
        for part, unit in zip(parts, layout.units):
            assert f'[{unit or "0, 1"}]' in part, (name, part, unit)
