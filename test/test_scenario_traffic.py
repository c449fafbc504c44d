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


"""The cut-in scenario and the min_gap criterion (scenarios/cut_in.yaml, scenarios/criteria.py)."""

from pathlib import Path

import pytest
import yaml

from vehicle_sim.core.geometry.footprint import Outline
from vehicle_sim.scenarios.criteria import MinGap, Sample
from vehicle_sim.scenarios.runner import run_scenario
from vehicle_sim.scenarios.scene import Scene

ROOT = Path(__file__).resolve().parent.parent
CUT_IN = ROOT / 'scenarios' / 'cut_in.yaml'


def test_the_acc_controller_keeps_its_gap_when_a_car_cuts_in():
    result = run_scenario(CUT_IN)
    assert result.passed, [c.detail for c in result.criteria]
    gap = result.criterion('min_gap')
    assert 5.0 < gap.value < 20.0             # it came close, and kept away
    assert 'traffic_0' in gap.detail
    assert result.criterion('no_collision').value == 0


def test_without_the_acc_the_car_runs_into_the_cut_in(tmp_path):
    data = yaml.safe_load(CUT_IN.read_text(encoding='utf-8'))
    data['driver'] = {'commands': [{'t': 0.0, 'cruising_speed': 90.0}]}
    path = tmp_path / 'cut_in_blind.yaml'
    path.write_text(yaml.safe_dump(data), encoding='utf-8')
    result = run_scenario(path)
    assert not result.passed
    assert not result.criterion('min_gap').passed
    assert result.criterion('min_gap').value < 5.0


def outline():
    return Outline(-0.5, 4.5, -1.0, 1.0)


def gap_of(traffic, sample, values=None):
    criterion = MinGap('min_gap', 'Car', values or {'min_m': 5.0, 'after_s': 0.0}, 10.0)
    criterion.bind(Scene({'Car': outline()}, traffic=lambda: traffic))
    criterion.observe(sample)
    return criterion.result()


def test_min_gap_measures_bumper_to_bumper_in_the_corridor_only():
    ahead = ('t0', 20.0, 0.0, 0.0, 4.0, 1.8)               # rear at 18: 13.5 m from the front
    beside = ('t1', 8.0, 3.75, 0.0, 4.0, 1.8)              # the next lane: not in the corridor
    behind = ('t2', -10.0, 0.0, 0.0, 4.0, 1.8)
    result = gap_of([ahead, beside, behind], Sample(1.0, 0.0, 0.0, 0.0, 10.0))
    assert result.value == pytest.approx(13.5) and result.passed
    # half in the corridor (1.0 + 0.9 > 1.6 m aside): counts
    half = ('t3', 12.0, 1.6, 0.0, 4.0, 1.8)
    assert gap_of([half], Sample(1.0, 0.0, 0.0, 0.0, 10.0)).value == pytest.approx(5.5)
    # turned: the car heads north, the traffic car 10 m north of it
    north = ('t4', 0.0, 10.0, 1.5707963267948966, 4.0, 1.8)
    assert gap_of([north], Sample(1.0, 0.0, 0.0, 1.5707963267948966, 10.0)).value == \
        pytest.approx(3.5)
    assert not gap_of([north], Sample(1.0, 0.0, 0.0, 1.5707963267948966, 10.0)).passed


def test_min_gap_waits_for_after_and_fails_without_traffic():
    close = ('t0', 7.0, 0.0, 0.0, 4.0, 1.8)
    early = gap_of([close], Sample(1.0, 0.0, 0.0, 0.0, 10.0), {'min_m': 5.0, 'after_s': 2.0})
    assert early.passed and early.value is None
    criterion = MinGap('min_gap', 'Car', {'min_m': 5.0, 'after_s': 0.0}, 10.0)
    criterion.bind(Scene({'Car': outline()}))
    criterion.observe(Sample(1.0, 0.0, 0.0, 0.0, 10.0))
    result = criterion.result()
    assert not result.passed and 'no traffic' in result.detail


def actor_scenario(tmp_path, speed_control):
    data = {
        'name': f'actor_{speed_control}',
        'world': {'vehicles': [
            {'name': 'ego', 'model': 'Car', 'pose': {'x': 40.0, 'y': 0.0, 'yaw': 0.0}},
            {'name': 'other', 'namespace': 'other', 'model': 'ToyotaPrius',
             'pose': {'x': 0.0, 'y': 0.0, 'yaw': 0.0}}]},
        'vehicle': 'ego',
        'duration': 15.0,
        'actors': [{'vehicle': 'other', 'speed': 8.0, 'waypoints': [[120.0, 0.0]],
                    'speed_control': speed_control}],
        'driver': {'commands': [{'t': 0.0, 'cruising_speed': 0.0, 'brake_intensity': 1.0}]},
        'criteria': [{'kind': 'no_collision', 'vehicle': 'other'}],
    }
    path = tmp_path / f'actor_{speed_control}.yaml'
    path.write_text(yaml.safe_dump(data), encoding='utf-8')
    return run_scenario(path)


def test_an_idm_actor_stops_behind_the_vehicle_ahead_a_waypoint_actor_hits_it(tmp_path):
    idm = actor_scenario(tmp_path, 'idm')
    assert idm.passed, [c.detail for c in idm.criteria]
    track = idm.tracks['other']
    # the Prius's front (rear axle + 3.585 m) stands IDM's minimum gap s0 = 2 m behind the
    # Car's rear (x = 40 - 0.5 m)
    gap = 40.0 - 0.5 - (track.x_m[-1] + 3.585)
    assert gap == pytest.approx(2.0, abs=0.3)
    blind = actor_scenario(tmp_path, 'waypoints')
    assert not blind.passed
    assert blind.criterion('no_collision').value >= 1
