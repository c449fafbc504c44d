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
Sweeps give the same merged results on 1 and 2 local workers and on Ray (docs/sweeps.md).

60 variants of scenarios/stop_before_obstacle.yaml, shortened to 3 s: four basic time steps
(which change the physics and so the measured values) x three speed limits x five seeds.
"""

import csv
import json
import os
from pathlib import Path
import subprocess
import sys
from xml.etree import ElementTree

import pytest

from vehicle_sim.sweep import run_sweep

REPO = Path(__file__).resolve().parent.parent
SCENARIO = str(REPO / 'scenarios' / 'stop_before_obstacle.yaml')
SETS = ['duration=3', 'time_step_ms=8,10,16,20', 'criteria.2.limit=5.5,6,7']
SEEDS = '0:5'
CASES = 4 * 3 * 5


def _table(folder):
    with open(os.path.join(folder, 'results.csv'), encoding='utf-8') as file:
        return list(csv.reader(file))


@pytest.fixture(scope='module')
def one_worker(tmp_path_factory):
    out = tmp_path_factory.mktemp('one')
    return run_sweep(SCENARIO, SETS, SEEDS, str(out), workers=1, timeout_s=120.0)


@pytest.fixture(scope='module')
def two_workers(tmp_path_factory):
    out = tmp_path_factory.mktemp('two')
    return run_sweep(SCENARIO, SETS, SEEDS, str(out), workers=2, timeout_s=120.0)


def test_sweep_runs_every_combination_in_grid_order(one_worker):
    assert one_worker.total == CASES and len(one_worker.records) == CASES
    assert not one_worker.interrupted
    rows = _table(one_worker.out_dir)
    assert rows[0][:6] == ['case', 'duration', 'time_step_ms', 'criteria.2.limit', 'seed',
                           'status']
    assert len(rows) == CASES + 1
    # the first axis slowest, the seeds fastest
    assert [r[2] for r in rows[1:6]] == ['8'] * 5 and [r[4] for r in rows[1:6]] == list('01234')
    assert [r[3] for r in rows[1:16:5]] == ['5.5', '6', '7']
    statuses = {r[5] for r in rows[1:]}
    assert statuses == {'pass', 'fail'}, statuses      # the 5.5 m/s limit fails, 7 passes
    limit_col = rows[0].index('criteria.2.limit')
    speed_col = rows[0].index('max_speed.passed')
    for row in rows[1:]:
        assert row[speed_col] == ('false' if row[limit_col] == '5.5' else 'true'), row
    # the time step changes the physics: the measured values differ between its values
    sha = rows[0].index('odometry_sha256')
    assert len({r[sha] for r in rows[1:]}) == 4


def test_sweep_tables_are_identical_on_one_and_two_workers(one_worker, two_workers):
    assert _table(one_worker.out_dir) == _table(two_workers.out_dir)
    assert one_worker.records == [dict(r, wall_time_s=one_worker.records[i]['wall_time_s'])
                                  for i, r in enumerate(two_workers.records)]


def test_sweep_junit_has_a_testcase_per_case_and_criterion(one_worker):
    root = ElementTree.parse(os.path.join(one_worker.out_dir, 'junit.xml')).getroot()
    suite = root.find('testsuite')
    cases = suite.findall('testcase')
    assert len(cases) == CASES * 4 == int(suite.get('tests'))
    failed = [c for c in cases if c.find('failure') is not None]
    assert len(failed) == int(suite.get('failures')) == 4 * 5     # max_speed at 5.5 m/s
    assert {c.get('name') for c in failed} == {'max_speed'}
    assert suite.get('errors') == '0'
    assert cases[0].get('classname') == ('sweep.stop_before_obstacle[duration=3 time_step_ms=8 '
                                         'criteria.2.limit=5.5 seed=0]')


def test_sweep_writes_a_record_and_log_per_case_and_a_summary_plot(one_worker):
    folder = one_worker.out_dir
    records = os.listdir(os.path.join(folder, 'cases'))
    assert len(records) == CASES
    with open(os.path.join(folder, 'cases', records[0]), encoding='utf-8') as file:
        record = json.load(file)
    log = os.path.join(folder, 'logs', f'{record["case_id"]}.log')
    with open(log, encoding='utf-8') as file:
        assert 'braking: obstacle' in file.read()       # the controller's prints
    pytest.importorskip('matplotlib', reason='the summary plot needs matplotlib (plot extra)')
    assert one_worker.files['plot'].endswith('summary.png')
    assert os.path.getsize(one_worker.files['plot']) > 10000


def test_sweep_tables_are_identical_on_ray(one_worker, tmp_path):
    try:
        import ray
    except ImportError:
        pytest.skip("ray is not installed (pip install 'vehicle_sim[ray]'): the Ray backend is "
                    'not tested')
    try:
        # Ray started by the sweep itself: ray.init(num_cpus=2, include_dashboard=False)
        result = run_sweep(SCENARIO, SETS, SEEDS, str(tmp_path), workers=2, backend='ray',
                           timeout_s=120.0)
        assert not ray.is_initialized()     # the sweep shut down the Ray it started
    finally:
        if ray.is_initialized():
            ray.shutdown()
    assert result.count('error') == 0, [r['error'] for r in result.records if r['error']]
    assert _table(str(tmp_path)) == _table(one_worker.out_dir)


def test_sweep_command_prints_plain_progress_lines_and_exits_1_on_a_failing_case(tmp_path):
    out = tmp_path / 'cli'
    command = [sys.executable, '-m', 'vehicle_sim', 'sweep', SCENARIO, '--set', 'duration=3',
               '--set', 'criteria.2.limit=5.5,7', '--workers', '2', '--out', str(out)]
    done = subprocess.run(command, capture_output=True, text=True, timeout=120)
    assert done.returncode == 1, done.stderr
    lines = done.stderr.splitlines()
    assert lines[0].startswith('[1/2] ') and lines[1].startswith('[2/2] '), done.stderr
    assert 'FAIL  duration=3 criteria.2.limit=5.5 seed=0' in done.stderr
    assert '1 passed, 1 failed, 0 errors of 2 cases' in done.stdout
    assert f'wrote {out}/results.csv' in done.stdout


def test_sweep_of_a_served_scenario_gives_each_running_case_a_domain_of_its_own(tmp_path,
                                                                                 monkeypatch):
    # A topic criterion serves the car over ROS (embedded DDS): each case claims a domain from
    # the base up; this test's base keeps clear of the domains the test configuration picks.
    base = 120 + int(os.environ['ROS_DOMAIN_ID']) % 100
    monkeypatch.setenv('VEHICLE_SIM_SWEEP_DOMAIN_BASE', str(base))
    # (the embedded transport's start line names the domain, also where rclpy is importable)
    monkeypatch.setenv('VEHICLE_SIM_TRANSPORT', 'dds')
    served = str(REPO / 'test' / 'scenarios' / 'served_topic.yaml')
    result = run_sweep(served, ['driver.commands.0.cruising_speed=10,30'], out_dir=str(tmp_path),
                       workers=2, timeout_s=120.0)
    assert [r['status'] for r in result.records] == ['fail', 'pass']
    first = result.records[0]['criteria'][0]
    assert first['name'] == 'topic' and 9.0 < first['value'] < 10.0     # eventually > 15 km/h
    for record in result.records:
        with open(os.path.join(tmp_path, 'logs', f'{record["case_id"]}.log'),
                  encoding='utf-8') as log:
            text = log.read()
        assert any(f'on domain {d} ' in text for d in (base, base + 1)), text


def test_run_sweep_works_from_a_script_without_a_main_guard(tmp_path):
    # The workers are programs of their own: the caller's script is not run again in them (as
    # multiprocessing's spawn would, starting workers from every worker).
    script = tmp_path / 'notebook_like.py'
    script.write_text(
        'from vehicle_sim.sweep import run_sweep\n'
        f'result = run_sweep({SCENARIO!r}, ["duration=1,2"], out_dir={str(tmp_path / "o")!r},\n'
        '                   workers=2, timeout_s=60)\n'
        'print("STATUSES", [r["status"] for r in result.records], result.count("error"))\n')
    done = subprocess.run([sys.executable, str(script)], capture_output=True, text=True,
                          timeout=120, cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert 'STATUSES' in done.stdout and done.stdout.count('STATUSES') == 1
    assert done.stdout.strip().endswith('0'), done.stdout     # no errors
