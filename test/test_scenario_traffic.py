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

import csv
from pathlib import Path
import subprocess
import sys

import pytest
import yaml

from vehicle_sim.core.geometry.footprint import Outline
from vehicle_sim.scenarios.criteria import MinGap, Sample
from vehicle_sim.scenarios.runner import run_scenario
from vehicle_sim.scenarios.scene import CriteriaScene

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
    criterion.bind(CriteriaScene({'Car': outline()}, traffic=lambda: traffic))
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
    criterion.bind(CriteriaScene({'Car': outline()}))
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


# scenarios/cut_in.yaml with the traffic car cutting in at 8 s at 40 % of the limit: it swerves
# into the car's side (its centre beside the car's corridor all along), which hits it at 9.33 s
HIT_VARIANT = ('world.traffic.placed.0.change_at=8', 'world.traffic.placed.0.speed_factor=0.4')
# CLI sweep: interpreter start, one 30 s run of the cut-in (about 7 s)
SWEEP_TIMEOUT_S = 300.0


def test_min_gap_and_overtake_fail_when_the_car_hits_the_traffic_car(tmp_path):
    data = yaml.safe_load(CUT_IN.read_text(encoding='utf-8'))
    placed = data['world']['traffic']['placed'][0]
    placed['change_at'], placed['speed_factor'] = 8.0, 0.4
    data['criteria'].append({'kind': 'overtake', 'min': 1})
    data['driver']['controller'] = str(ROOT / 'examples' / 'acc_controller.py')
    path = tmp_path / 'cut_in_hit.yaml'
    path.write_text(yaml.safe_dump(data), encoding='utf-8')
    result = run_scenario(path)
    hit = result.criterion('no_collision')
    assert not hit.passed and hit.detail == '1 collision: traffic_0 at 9.33 s'
    gap = result.criterion('min_gap')
    assert not gap.passed
    assert gap.value == 0.0                     # contact: the gap reached zero
    assert 'touched traffic_0 at 9.33 s' in gap.detail
    # the car drove on past the traffic car it had hit (which stands where it was hit):
    # not an overtake
    overtake = result.criterion('overtake')
    assert not overtake.passed and overtake.value == 0
    assert 'traffic_0 touched at 9.33 s' in overtake.detail


def test_a_sweep_row_of_the_hit_has_min_gap_0_failed(tmp_path):
    command = Path(sys.executable).with_name('vehicle-sim')
    out = tmp_path / 'sweep'
    args = [str(command), 'sweep', str(CUT_IN), '--out', str(out), '--no-progress']
    for item in HIT_VARIANT:
        args += ['--set', item]
    run = subprocess.run(args, capture_output=True, text=True, timeout=SWEEP_TIMEOUT_S)
    assert run.returncode == 1, run.stdout + run.stderr           # a case failed
    with open(out / 'results.csv', encoding='utf-8') as file:
        (row,) = list(csv.DictReader(file))
    assert (row['status'], row['no_collision'], row['no_collision.passed']) == \
        ('fail', '1', 'false')
    assert (float(row['min_gap']), row['min_gap.passed']) == (0.0, 'false')
