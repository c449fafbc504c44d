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


"""The highway overtaking scenario (scenarios/highway_overtake.yaml) and the overtake criterion."""

import math
from pathlib import Path

import pytest
import yaml

from vehicle_sim.core.geometry.footprint import Outline
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.scenarios.criteria import Sample, validate_criterion
from vehicle_sim.scenarios.overtake_criterion import Overtake
from vehicle_sim.scenarios.runner import run_scenario
from vehicle_sim.scenarios.scene import CriteriaScene
from vehicle_sim.scenarios.schema import load_scenario
from vehicle_sim.scenarios.yaml_lines import ScenarioError

ROOT = Path(__file__).resolve().parent.parent
OVERTAKE = ROOT / 'scenarios' / 'highway_overtake.yaml'
LANE_WIDTH_M = 3.75
MIDDLE_Y_M = -1.5 * LANE_WIDTH_M        # the car's lane on the straight (y = -5.625 m)


def test_the_webots_controller_overtakes_the_slow_cars_and_comes_back():
    result = run_scenario(OVERTAKE)
    assert result.passed, [c.detail for c in result.criteria]
    assert result.error is None
    passed = result.criterion('overtake')
    assert passed.value == 3                        # both cars of its lane and the right lane's
    for name in ('traffic_0', 'traffic_1', 'traffic_2'):
        assert f'{name} at ' in passed.detail
    assert result.criterion('no_collision').value == 0
    lane = result.criterion('stay_in_lane')
    assert 'crossed no solid line' in lane.detail
    assert lane.value < 0.5 * LANE_WIDTH_M + 0.01   # on a lane at every step (lane changes)
    back = result.criterion('reach_lanelet')
    assert back.value < 36.0
    # it drove in the fast lane beside the slow cars: one lane left of its own on the straight
    track = result.tracks['Car']
    straight = [y for x, y in zip(track.x_m, track.y_m) if x < 590.0]
    assert max(straight) == pytest.approx(MIDDLE_Y_M + LANE_WIDTH_M, abs=0.4)
    assert min(straight) == pytest.approx(MIDDLE_Y_M, abs=0.05)
    # smooth lane changes: the lateral acceleration (speed x yaw rate over 0.1 s) stays small
    assert max_lateral_acceleration(track) < 2.0


def max_lateral_acceleration(track, half=5):
    worst = 0.0
    for i in range(half, len(track.time_s) - half):
        dt = track.time_s[i + half] - track.time_s[i - half]
        speed = math.hypot(track.x_m[i + half] - track.x_m[i - half],
                           track.y_m[i + half] - track.y_m[i - half]) / dt
        turn = math.remainder(track.yaw_rad[i + half] - track.yaw_rad[i - half], 2.0 * math.pi)
        worst = max(worst, abs(speed * turn / dt))
    return worst


def test_cruising_without_the_controller_runs_into_the_first_slow_car(tmp_path):
    data = yaml.safe_load(OVERTAKE.read_text(encoding='utf-8'))
    data['driver'] = {'commands': [{'t': 0.0, 'cruising_speed': 100.0}]}
    data['duration'] = 15.0
    path = tmp_path / 'overtake_blind.yaml'
    path.write_text(yaml.safe_dump(data), encoding='utf-8')
    result = run_scenario(path)
    assert not result.passed
    collision = result.criterion('no_collision')
    assert collision.value >= 1 and 'traffic_0' in collision.detail
    assert result.criterion('overtake').value == 0


def outline():
    return Outline(-0.5, 4.5, -1.0, 1.0)


def overtake(frames, values=None, duration_s=10.0):
    """Feed (time, ego x, [(name, x, y, yaw), ...]) frames; return the result."""
    values = dict({'min_count': 1, 'lateral_m': 8.0, 'within_s': None}, **(values or {}))
    criterion = Overtake('overtake', 'Car', values, duration_s)
    now = []
    criterion.bind(CriteriaScene(
        {'Car': outline()}, traffic=lambda: [(n, x, y, yaw, 4.0, 1.8) for n, x, y, yaw in now]))
    for time_s, ego_x, cars in frames:
        now[:] = cars
        criterion.observe(Sample(time_s, ego_x, 0.0, 0.0, 20.0))
    return criterion.result()


def test_a_car_ahead_then_behind_counts_as_passed():
    # its box (4 m long) wholly ahead of the front (x 4.5) at t 0, wholly behind the rear at t 2
    result = overtake([(0.0, 0.0, [('t0', 10.0, 3.75, 0.0)]),
                       (1.0, 10.0, [('t0', 12.0, 3.75, 0.0)]),
                       (2.0, 20.0, [('t0', 14.0, 3.75, 0.0)])])
    assert result.passed and result.value == 1 and result.unit == 'vehicle'
    assert 't0 at 2.00 s' in result.detail


@pytest.mark.parametrize('frames, why', [
    ([(0.0, 0.0, [('t0', 5.0, 3.75, 0.0)]), (1.0, 20.0, [('t0', 10.0, 3.75, 0.0)])],
     'beside at first (overlapping the front), never wholly ahead'),
    ([(0.0, 0.0, [('t0', 10.0, 3.75, 0.0)]), (1.0, 10.0, [('t0', 10.0, 3.75, 0.0)])],
     'ahead, then beside: not behind the rear yet'),
    ([(0.0, 0.0, [('t0', 10.0, 3.75, math.pi)]), (1.0, 20.0, [('t0', 5.0, 3.75, math.pi)])],
     'driving the other way'),
    ([(0.0, 0.0, [('t0', 10.0, 9.0, 0.0)]), (1.0, 20.0, [('t0', 12.0, 9.0, 0.0)])],
     'farther than lateral from the axis'),
])
def test_a_car_not_passed_does_not_count(frames, why):
    result = overtake(frames)
    assert not result.passed, why
    assert result.value == 0


def test_a_pass_after_the_deadline_does_not_count_and_several_are_counted():
    frames = [(0.0, 0.0, [('t0', 10.0, 3.75, 0.0), ('t1', 10.0, -3.75, 0.0)]),
              (1.0, 20.0, [('t0', 12.0, 3.75, 0.0), ('t1', 19.0, -3.75, 0.0)]),
              (3.0, 40.0, [('t0', 14.0, 3.75, 0.0), ('t1', 20.0, -3.75, 0.0)])]
    both = overtake(frames, {'min_count': 2})
    assert both.passed and both.value == 2 and both.unit == 'vehicles'
    early = overtake(frames, {'min_count': 2, 'within_s': 2.0})
    assert not early.passed and early.value == 1
    assert 't0 at 1.00 s' in early.detail and 't1' not in early.detail


def test_overtake_without_traffic_fails_saying_so():
    criterion = Overtake('overtake', 'Car', {'min_count': 1, 'lateral_m': 8.0,
                                             'within_s': None}, 10.0)
    criterion.bind(CriteriaScene({'Car': outline()}))
    criterion.observe(Sample(1.0, 0.0, 0.0, 0.0, 10.0))
    result = criterion.result()
    assert not result.passed and 'no traffic' in result.detail


def test_overtake_values_are_validated_naming_the_field(tmp_path):
    assert validate_criterion('overtake', {}) == {'min_count': 1, 'lateral_m': 8.0,
                                                  'within_s': None}
    with pytest.raises(InvalidParameterError, match="'min'"):
        validate_criterion('overtake', {'min': 0})
    text = OVERTAKE.read_text(encoding='utf-8').replace('    min: 2\n', '    min: -1\n')
    path = tmp_path / 'bad_overtake.yaml'
    path.write_text(text.replace('../examples/', str(ROOT / 'examples') + '/'), encoding='utf-8')
    with pytest.raises(ScenarioError, match='min'):
        load_scenario(path)


def test_the_controller_overtakes_in_the_traffic_of_highway_traffic_yaml(tmp_path):
    # the world of config/worlds/highway_traffic.yaml (60 cars at 60 to 100 km/h, MOBIL lane
    # changes) with the scenario's car and its distance sensors
    world = yaml.safe_load((ROOT / 'config' / 'worlds' / 'highway_traffic.yaml').read_text(
        encoding='utf-8'))
    data = yaml.safe_load(OVERTAKE.read_text(encoding='utf-8'))
    data['world'] = {'vehicles': data['world']['vehicles'], 'roads': world['roads'],
                     'traffic': world['traffic']}
    data['driver'] = {'controller': str(ROOT / 'examples' / 'highway_overtake.py')}
    data['duration'] = 40.0
    data['criteria'] = [
        {'kind': 'no_collision'},
        {'kind': 'overtake', 'min': 2},
        {'kind': 'stay_in_lane'},
        {'kind': 'min_gap', 'min': 5.0},
        # a car ahead at the start: it moves to the right lane, then overtakes on the left
        {'kind': 'reach_lanelet', 'name': 'right_lane', 'lanelet': 100003, 'within': 5.0},
        {'kind': 'reach_lanelet', 'name': 'back_left', 'lanelet': 100002, 'min_s': 450.0},
    ]
    path = tmp_path / 'highway_traffic_overtake.yaml'
    path.write_text(yaml.safe_dump(data), encoding='utf-8')
    result = run_scenario(path)
    assert result.passed, [c.detail for c in result.criteria]
    assert result.criterion('overtake').value >= 2
    assert result.criterion('min_gap').value > 5.0
