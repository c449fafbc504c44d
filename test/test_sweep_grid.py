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
The variants of a sweep, the progress display, the summary plot's grid.

--set and --seeds parsed, dotted keys applied, bad input refused before anything runs (naming
the key).
"""

import io
import os
from pathlib import Path
import subprocess
import sys

import pytest

from vehicle_sim.sweep import run_sweep, SweepError
from vehicle_sim.sweep.grid import build_cases, parse_seeds, parse_set
from vehicle_sim.sweep.plot import grid_counts
from vehicle_sim.sweep.progress import Progress
from vehicle_sim.sweep.results import table_columns
from vehicle_sim.sweep.run import plan, SweepResult
from vehicle_sim.sweep.worker import DomainClaim

REPO = Path(__file__).resolve().parent.parent
SCENARIO = str(REPO / 'scenarios' / 'stop_before_obstacle.yaml')


def test_parse_set_reads_yaml_scalars():
    axis = parse_set('criteria.2.limit=4, 5.5,true,text,null')
    assert axis.key == 'criteria.2.limit' and axis.path == ('criteria', 2, 'limit')
    assert axis.values == (4, 5.5, True, 'text', None)
    assert [type(v) for v in axis.values[:2]] == [int, float]


def test_parse_seeds_takes_a_range_or_a_list():
    assert parse_seeds('0:4') == [0, 1, 2, 3]
    assert parse_seeds('7,3') == [7, 3]


def test_cases_are_every_combination_first_axis_slowest_then_seeds():
    axes = [parse_set('a=1,2'), parse_set('b=x,y,z')]
    cases = build_cases(axes, [0, 1], file_seed=5)
    assert len(cases) == 12
    assert [c.label for c in cases[:3]] == ['a=1 b=x seed=0', 'a=1 b=x seed=1', 'a=1 b=y seed=0']
    assert len({c.case_id for c in cases}) == 12
    assert build_cases(axes, None, file_seed=5)[0].seed == 5


@pytest.mark.parametrize('sets, seeds, message', [
    (['actor.0.speed=1'], None, "--set actor.0.speed: the scenario has no 'actor'; keys there: "
                                'name, description, world'),
    (['criteria.9.limit=1'], None, "--set criteria.9.limit: 'criteria.9': a list of 4 entries"),
    (['duration.x=1'], None, r"--set duration.x: 'duration' is a value \(10.0\), not a mapping"),
    (['duration=abc'], None, "--set duration=abc: .*stop_before_obstacle.yaml:8: .*field "
                             "'duration' = 'abc': must be a number"),
    (['duration=3,-1'], None, "--set duration=-1: .*field 'duration' = -1.0: must be > 0"),
    (['criteria.2.limt=1'], None, "--set criteria.2.limt=1: .*unknown field 'limt'"),
    (['driver.controller=nothere.py'], None, "--set driver.controller=nothere.py: .*controller "
                                             "'nothere.py': no such file"),
    (['duration='], None, '--set duration: an empty value'),
    (['duration=1,,2'], None, '--set duration: an empty value'),
    (['duration=1,1'], None, "--set duration: value '1' given twice"),
    (['duration=[1, 2]'], None, '--set duration: an empty value|is not a YAML scalar'),
    (['duration'], None, "--set 'duration': give key=value"),
    (['duration=1', 'duration=2'], None, '--set duration: given twice'),
    (['seed=1,2'], '0:2', '--set seed=... and --seeds: give the seeds once'),
    ([], '5:2', '--seeds 5:2: no seeds'),
    ([], 'a:b', r"--seeds 'a:b': give A:B \(seeds A to B-1\) or N\[,N...\], integers"),
    ([], '-1,2', '--seeds -1,2: seeds must be >= 0'),
    ([], '0:1000000000', '--seeds 0:1000000000: 1000000000 seeds; at most 100000'),
    (['criteria.-1.limit=1'], None, "--set criteria.-1.limit: 'criteria.-1': a list of 4 "
                                    r'entries \(index 0 .. 3\)'),
    (['duration=1,2,3', 'criteria.2.limit=1,2,3,4,5,6,7,8,9,10'], '0:4000',
     '120000 variants: at most 100000'),
])
def test_bad_sweep_input_is_refused_naming_the_key_before_anything_runs(tmp_path, sets, seeds,
                                                                         message):
    out = tmp_path / 'out'
    with pytest.raises(SweepError, match=message):
        run_sweep(SCENARIO, sets, seeds, str(out))
    assert not out.exists()


def test_bad_backend_options_are_refused(tmp_path):
    with pytest.raises(SweepError, match="--backend 'dask': one of local, ray"):
        run_sweep(SCENARIO, out_dir=str(tmp_path / 'x'), backend='dask')
    with pytest.raises(SweepError, match='--ray-address needs --backend ray'):
        run_sweep(SCENARIO, out_dir=str(tmp_path / 'x'), ray_address='auto')
    with pytest.raises(SweepError, match='--workers 0: must be 1'):
        run_sweep(SCENARIO, out_dir=str(tmp_path / 'x'), workers=0)
    with pytest.raises(SweepError, match='--ray-connect-timeout 0: must be > 0 s'):
        run_sweep(SCENARIO, out_dir=str(tmp_path / 'x'), ray_connect_timeout_s=0)
    assert not (tmp_path / 'x').exists()


def test_sweep_command_exits_2_on_a_bad_set_and_writes_nothing(tmp_path):
    out = tmp_path / 'out'
    done = subprocess.run([sys.executable, '-m', 'vehicle_sim', 'sweep', SCENARIO, '--set',
                           'criteria.2.limit=6,fast', '--out', str(out)],
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 2
    assert done.stderr.startswith('vehicle-sim sweep: --set criteria.2.limit=fast: ')
    assert "field 'limit' = 'fast': must be a number" in done.stderr
    assert not out.exists() and done.stdout == ''


def test_api_takes_a_mapping_of_values_and_a_list_of_seeds():
    planned = plan(SCENARIO, {'duration': [2, 3], 'criteria.2.limit': 6.5}, seeds=[4, 9])
    cases, specs = planned.cases, planned.specs
    assert planned.name == 'stop_before_obstacle' and planned.seeds == [4, 9]
    assert [c.label for c in cases] == ['duration=2 criteria.2.limit=6.5 seed=4',
                                        'duration=2 criteria.2.limit=6.5 seed=9',
                                        'duration=3 criteria.2.limit=6.5 seed=4',
                                        'duration=3 criteria.2.limit=6.5 seed=9']
    assert [specs[c.case_id].duration_s for c in cases] == [2.0, 2.0, 3.0, 3.0]
    assert specs[cases[0].case_id].criteria[2].values['limit_mps'] == 6.5


def _record(a, b, seed, status):
    return {'overrides': [['a', a], ['b', b]], 'seed': seed, 'status': status, 'label': '',
            'case_id': f'{a}{b}{seed}'}


def test_summary_grid_pools_the_seeds_in_each_cell():
    records = [_record(a, b, seed, status) for a, b, seed, status in [
        (1, 'x', 0, 'pass'), (1, 'x', 1, 'fail'), (2, 'x', 0, 'pass'), (2, 'x', 1, 'pass'),
        (1, 'y', 0, 'error'), (1, 'y', 1, 'fail'), (2, 'y', 0, 'pass'), (2, 'y', 1, 'error')]]
    xs, ys, cells = grid_counts(records, ['a', 'b'])
    assert xs == [1, 2] and ys == ['x', 'y']
    assert cells == {(0, 0): (1, 0, 2), (1, 0): (2, 0, 2), (0, 1): (0, 1, 2), (1, 1): (1, 1, 2)}
    xs, ys, cells = grid_counts(records, [])
    assert xs == [0, 1] and ys == [None] and cells == {(0, 0): (3, 1, 4), (1, 0): (1, 1, 4)}


class _Terminal(io.StringIO):
    def isatty(self):
        return True


def test_progress_is_a_bar_on_a_terminal_and_lines_elsewhere():
    for stream in (_Terminal(), io.StringIO()):
        result = SweepResult('out', [], 4, ['a'])
        progress = Progress(stream, total=4)
        for status in ('pass', 'fail'):
            record = {'status': status, 'label': f'a={status}'}
            result.add(record)
            progress(record, result)
        progress.done()
        text = stream.getvalue()
        if isinstance(stream, _Terminal):
            assert text.startswith('\r[') and '\r' in text[1:] and text.endswith('\n')
            assert '2/4 done, 1 passed, 1 failed, 0 errors, ETA ' in text
        else:
            lines = text.splitlines()
            assert lines[0].startswith('[1/4] PASS  a=pass  (1/4 done, 1 passed, 0 failed')
            assert lines[1].startswith('[2/4] FAIL  a=fail  (2/4 done, 1 passed, 1 failed')
            assert '\r' not in text


def test_results_folder_of_another_file_is_refused(tmp_path):
    out = tmp_path / 'out'
    run_sweep(SCENARIO, ['duration=0.5'], out_dir=str(out), workers=1)
    other = str(REPO / 'scenarios' / 'drive_into_obstacle.yaml')
    with pytest.raises(SweepError, match='holds the results of another sweep'):
        run_sweep(other, ['duration=0.5'], out_dir=str(out), resume=True)
    assert os.listdir(out / 'cases') and len(os.listdir(out / 'cases')) == 1


def test_table_columns_are_typed_for_parquet():
    records = [
        {'case_id': 'a', 'overrides': [['k', 1], ['m', 'x']], 'seed': 0, 'status': 'pass',
         'criteria': [{'name': 'c', 'value': 2, 'passed': True}], 'error': None,
         'odometry_sha256': 'h'},
        {'case_id': 'b', 'overrides': [['k', 2.5], ['m', 3]], 'seed': 1, 'status': 'error',
         'criteria': [], 'error': 'boom\nmore', 'odometry_sha256': ''}]
    columns = table_columns(records, ['k', 'm'])
    assert list(columns) == ['case', 'k', 'm', 'seed', 'status', 'c', 'c.passed', 'error',
                             'odometry_sha256']
    assert columns['m'] == ['x', '3']            # mixed types: text
    assert columns['c'] == [2.0, None] and columns['c.passed'] == [True, None]
    assert columns['error'] == ['', 'boom']


def test_sweep_writes_parquet_when_pyarrow_imports(tmp_path):
    pyarrow_parquet = pytest.importorskip(
        'pyarrow.parquet', reason='pyarrow is not installed: results.parquet is not written')
    result = run_sweep(SCENARIO, ['duration=0.5', 'criteria.2.limit=1,7'], out_dir=str(tmp_path),
                       workers=1)
    table = pyarrow_parquet.read_table(result.files['parquet']).to_pydict()
    assert table['criteria.2.limit'] == [1, 7] and table['status'] == ['fail', 'fail']
    assert table['max_speed.passed'] == [False, True]       # 0.5 s: reach_goal fails in both
    assert all(isinstance(v, float) and 0.0 < v < 7.0 for v in table['max_speed'])


def test_served_cases_hold_distinct_ros_domains(monkeypatch):
    monkeypatch.setenv('VEHICLE_SIM_SWEEP_DOMAIN_BASE', '200')
    monkeypatch.setenv('ROS_DOMAIN_ID', '7')
    with DomainClaim(True):
        first = os.environ['ROS_DOMAIN_ID']
        with DomainClaim(True):          # another case on this machine meanwhile
            second = os.environ['ROS_DOMAIN_ID']
        assert os.environ['ROS_DOMAIN_ID'] == first
    assert int(first) >= 200 and int(second) > int(first)
    assert os.environ['ROS_DOMAIN_ID'] == '7'
    with DomainClaim(False):                 # not served: the domain is left alone
        assert os.environ['ROS_DOMAIN_ID'] == '7'
