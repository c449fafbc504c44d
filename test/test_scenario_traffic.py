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

import numpy as np
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


# --------------------------------------------------------- IDM actors that must slow down hard
PRIUS_FRONT_M, PRIUS_REAR_M = 3.585, 0.715      # bumpers from the rear axle (ToyotaPrius.yaml)
PRIUS_RAMP_MPS2 = 100.0 / 3.6 / 10.7             # its cruise control's ramp (time0To100)
PRIUS_FULL_BRAKE_MPS2 = 4.81                     # speed_braking.full_brake_deceleration_mps2


def _speeds_and_decelerations(track):
    # mean speeds over 0.5 s windows, and the deceleration between windows 0.5 s apart
    t, x = np.asarray(track.time_s), np.asarray(track.x_m)
    k = int(round(0.5 / float(np.median(np.diff(t)))))
    v = (x[k:] - x[:-k]) / (t[k:] - t[:-k])
    tv = 0.5 * (t[k:] + t[:-k])
    return tv, v, 0.5 * (v[:-k] + v[k:]), (v[:-k] - v[k:]) / (tv[k:] - tv[:-k])


def test_an_idm_actor_slows_to_a_lower_waypoint_speed_at_the_iidm_deceleration(tmp_path):
    # The Prius actor at 20 m/s, then waypoints asking 3 m/s, with IDM's comfortable
    # deceleration b = 4 m/s^2 (the world's traffic: idm:, no traffic vehicles). The improved
    # IDM asks -b (1 - (v0 / v)^(a delta / b)) = -4 (1 - (3 / v)^1.5) (3.6 m/s^2 at 15 m/s),
    # beyond the cruise control's 2.6 m/s^2: the actor brakes (throttle 0, brake 4 / 4.81 m/s^2
    # of full brake). Tolerance 0.4 m/s^2: the wheels' damping and rolling add about 0.3. Before:
    # IDM asked thousands of m/s^2, and the actor set a cruising speed of 0 (2.6 m/s^2).
    data = {
        'name': 'actor_slows',
        'world': {
            'vehicles': [
                {'name': 'ego', 'model': 'Car', 'pose': {'x': 0.0, 'y': 20.0, 'yaw': 0.0}},
                {'name': 'other', 'namespace': 'other', 'model': 'ToyotaPrius',
                 'pose': {'x': 0.0, 'y': 0.0, 'yaw': 0.0}}],
            'roads': [{'name': 'r', 'start': {'x': -20.0, 'y': 1.875, 'yaw': 0.0}, 'lanes': 1,
                       'lane_width': 3.75, 'speed_limit': 33.3,
                       'segments': [{'type': 'straight', 'length': 1000.0}]}],
            'traffic': {'vehicles': 0, 'idm': {'deceleration': 4.0}}},
        'vehicle': 'ego',
        'duration': 24.0,
        'actors': [{'vehicle': 'other', 'waypoints': [[250.0, 0.0, 20.0], [800.0, 0.0, 3.0]]}],
        'driver': {'commands': [{'t': 0.0, 'cruising_speed': 0.0, 'brake_intensity': 1.0}]},
        'criteria': [{'kind': 'no_collision', 'vehicle': 'other'}],
    }
    path = tmp_path / 'actor_slows.yaml'
    path.write_text(yaml.safe_dump(data), encoding='utf-8')
    _, v, mean, deceleration = _speeds_and_decelerations(run_scenario(path).tracks['other'])
    assert np.max(v) == pytest.approx(20.0, abs=0.3)     # at speed before x = 250 m
    assert v[-1] == pytest.approx(3.0, abs=0.2)           # then at the slower waypoint's speed
    after_peak = np.arange(len(mean)) > np.argmax(mean)
    braking = after_peak & (mean > 7.0) & (mean < 18.0)
    assert np.count_nonzero(braking) > 100                  # 10 ms samples: over 1 s of it
    rule = 4.0 * (1.0 - (3.0 / mean[braking]) ** 1.5)
    assert np.all(rule > PRIUS_RAMP_MPS2)
    assert np.max(np.abs(deceleration[braking] - rule)) < 0.4, \
        list(zip(mean[braking][::25], deceleration[braking][::25], rule[::25]))


def test_an_idm_actor_behind_a_car_braking_hard_brakes_too_and_stops_behind_it(tmp_path):
    # The ego Prius cruises at 20 m/s, the actor Prius (waypoint speed 25 m/s) follows it with
    # IDM; at 30 s the ego brakes fully (5 m/s^2, 40 m to a stop). IDM asks the follower more
    # than its cruise control's 2.6 m/s^2, so it brakes: up to about 4 m/s^2 (within full brake,
    # 4.8 m/s^2 plus the wheels' damping), and stops s0 = 2 m (+-0.5 m) behind it. Before,
    # its cruising speed 0 slowed it at 2.6 m/s^2 at most.
    data = {
        'name': 'leader_brakes',
        'world': {'vehicles': [
            {'name': 'ego', 'model': 'ToyotaPrius', 'pose': {'x': 60.0, 'y': 0.0, 'yaw': 0.0}},
            {'name': 'other', 'namespace': 'other', 'model': 'ToyotaPrius',
             'pose': {'x': 0.0, 'y': 0.0, 'yaw': 0.0}}]},
        'vehicle': 'ego',
        'duration': 46.0,
        'actors': [{'vehicle': 'other', 'waypoints': [[2000.0, 0.0, 25.0]]}],
        'driver': {'commands': [{'t': 0.0, 'cruising_speed': 72.0},
                                {'t': 30.0, 'throttle': 0.0, 'brake_intensity': 1.0}]},
        'criteria': [{'kind': 'no_collision', 'vehicle': 'other'}],
    }
    path = tmp_path / 'leader_brakes.yaml'
    path.write_text(yaml.safe_dump(data), encoding='utf-8')
    result = run_scenario(path)
    assert result.passed, [c.detail for c in result.criteria]
    ego, other = result.tracks['ego'], result.tracks['other']
    t, v, _, deceleration = _speeds_and_decelerations(other)
    assert v[np.searchsorted(t, 29.0)] == pytest.approx(20.0, abs=0.5)   # following at 20
    assert abs(v[-1]) < 0.05                                                # stopped
    assert 3.5 < np.max(deceleration) < PRIUS_FULL_BRAKE_MPS2 + 0.5
    gap = (ego.x_m[-1] - PRIUS_REAR_M) - (other.x_m[-1] + PRIUS_FRONT_M)
    assert gap == pytest.approx(2.0, abs=0.5)
