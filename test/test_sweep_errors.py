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
Errors of single cases, --resume and Ctrl-C.

A crashing, a hanging and a raising variant become their cases' errors, with their logs, and
the other cases complete (local workers and Ray); --resume; Ctrl-C keeps what finished.
"""

import csv
import os
from pathlib import Path
import re
import signal
import socket
import subprocess
import sys
import threading
import time
from xml.etree import ElementTree

from conftest import scaled_s
import pytest

from vehicle_sim.sweep import run_sweep, SweepError

REPO = Path(__file__).resolve().parent.parent
SCENARIO = str(REPO / 'scenarios' / 'stop_before_obstacle.yaml')
GOOD = '../examples/lidar_stop_controller.py'
# Well above a 2 s case's run (about 0.1 s, 1 s with a fresh worker's imports).
TIMEOUT_S = scaled_s(8.0)
# Ray's counts from the task's submission, a fresh Ray worker's start-up and imports included
# (27 s for the first cases at a load average of 8 on 2 cores).
RAY_TIMEOUT_S = scaled_s(60.0)
# Generous bound for a sweep command that gives up on a Ray address after 5 s (interpreter and
# Ray imports, twice).
NO_RAY_COMMAND_BOUND_S = scaled_s(180.0)
# Generous bound for an event of a sweep on 1 worker: its third case started, or its return after
# a Ctrl-C.
EVENT_BOUND_S = scaled_s(60.0)


@pytest.fixture
def controllers(tmp_path):
    """Write controllers that crash the process, hang, and raise."""
    scripts = {
        'crash': 'import os\nprint("about to abort", flush=True)\nos.abort()\n',
        'hang': 'import time\nprint("about to hang", flush=True)\ntime.sleep(3600)\n',
        'raise': 'raise RuntimeError("this controller fails on purpose")\n',
    }
    paths = {}
    for name, text in scripts.items():
        path = tmp_path / f'{name}.py'
        path.write_text(text)
        paths[name] = str(path)
    return paths


def _sets(controllers):
    names = ','.join([controllers['crash'], GOOD, controllers['hang'], controllers['raise'],
                      '../examples/blind_controller.py'])
    return ['duration=2', f'driver.controller={names}']


def _by_script(result):
    return {dict(r['overrides'])['driver.controller'].rsplit('/', 1)[-1]: r
            for r in result.records}


def _check_errors(result, out, timeout_s=TIMEOUT_S):
    assert len(result.records) == 5
    by = _by_script(result)
    assert by['lidar_stop_controller.py']['status'] == 'fail'      # reach_goal needs 2.77 s
    assert by['blind_controller.py']['status'] == 'fail'
    crash, hang, raised = by['crash.py'], by['hang.py'], by['raise.py']
    assert crash['status'] == hang['status'] == raised['status'] == 'error'
    assert 'died' in crash['error'] or 'WorkerCrashedError' in crash['error'], crash['error']
    assert 'about to abort' in crash['error']               # the end of its log
    assert hang['error'].startswith(f'timed out: still running after {timeout_s:g} s')
    assert 'about to hang' in hang['error']
    assert 'this controller fails on purpose' in raised['error']
    suite = ElementTree.parse(os.path.join(out, 'junit.xml')).getroot().find('testsuite')
    assert suite.get('errors') == '3'
    errors = [c for c in suite.findall('testcase') if c.find('error') is not None]
    assert [c.get('name') for c in errors] == ['run'] * 3
    with open(os.path.join(out, 'results.csv'), encoding='utf-8') as file:
        rows = list(csv.DictReader(file))
    assert [r['status'] for r in rows] == ['error', 'fail', 'error', 'error', 'fail']
    assert rows[2]['error'].startswith('timed out')


def test_sweep_reports_crashing_hanging_and_raising_variants_as_errors(controllers, tmp_path):
    out = str(tmp_path / 'out')
    result = run_sweep(SCENARIO, _sets(controllers), out_dir=out, workers=2,
                       timeout_s=TIMEOUT_S)
    _check_errors(result, out)
    crash = _by_script(result)['crash.py']
    assert 'killed by signal 6' in crash['error']
    with open(os.path.join(out, 'logs', f'{crash["case_id"]}.log'), encoding='utf-8') as log:
        assert 'Fatal Python error: Aborted' in log.read()      # faulthandler's traceback


def test_sweep_on_ray_reports_crashing_and_hanging_variants_as_errors(controllers, tmp_path):
    try:
        import ray
    except ImportError:
        pytest.skip("ray is not installed (pip install 'vehicle_sim[ray]'): the Ray backend is "
                    'not tested')
    out = str(tmp_path / 'out')
    try:
        result = run_sweep(SCENARIO, _sets(controllers), out_dir=out, workers=2,
                           backend='ray', timeout_s=RAY_TIMEOUT_S)
    finally:
        if ray.is_initialized():
            ray.shutdown()
    _check_errors(result, out, RAY_TIMEOUT_S)


def test_sweep_resume_runs_only_the_missing_cases(tmp_path):
    out = str(tmp_path / 'out')
    sets = ['duration=2', 'criteria.2.limit=5,6,7']
    first = run_sweep(SCENARIO, sets, out_dir=out, workers=1)
    with open(os.path.join(out, 'results.csv'), encoding='utf-8') as file:
        table = file.read()
    os.remove(os.path.join(out, 'cases', f'{first.records[1]["case_id"]}.json'))
    with pytest.raises(SweepError, match='holds 2 finished case.*--resume'):
        run_sweep(SCENARIO, sets, out_dir=out, workers=1)
    ran = []
    again = run_sweep(SCENARIO, sets, out_dir=out, workers=1, resume=True,
                      progress=lambda record, result: ran.append(record['label']))
    assert ran == ['duration=2 criteria.2.limit=6 seed=0']
    assert again.skipped == 2 and len(again.records) == 3
    with open(os.path.join(out, 'results.csv'), encoding='utf-8') as file:
        assert file.read() == table
    with pytest.raises(SweepError, match='another sweep'):
        run_sweep(SCENARIO, ['duration=2', 'criteria.2.limit=5,8'], out_dir=out, resume=True)


def test_sweep_command_ctrl_c_keeps_the_finished_cases(controllers, tmp_path):
    out = tmp_path / 'out'
    names = ','.join([GOOD, '../examples/blind_controller.py', controllers['hang']])
    command = [sys.executable, '-m', 'vehicle_sim', 'sweep', SCENARIO, '--set', 'duration=2',
               '--set', f'driver.controller={names}', '--workers', '1', '--out', str(out)]
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                               text=True)
    try:
        for line in process.stderr:         # plain progress lines: not a terminal
            if line.startswith('[2/3]'):
                break
        process.send_signal(signal.SIGINT)  # the third case hangs: stop the sweep there
        stdout, stderr = process.communicate(timeout=EVENT_BOUND_S)
    finally:
        if process.poll() is None:
            process.kill()
            process.wait()
    assert process.returncode == 130, stderr
    assert 'interrupted: 2 of 3 cases kept; --resume runs the others' in stderr
    with open(out / 'results.csv', encoding='utf-8') as file:
        rows = list(csv.DictReader(file))
    assert [r['status'] for r in rows] == ['fail', 'fail']
    assert len(os.listdir(out / 'cases')) == 2


def _wait_for(predicate, timeout_s):
    deadline = time.monotonic() + timeout_s
    while not predicate() and time.monotonic() < deadline:
        time.sleep(0.02)
    return predicate()


def _hanging_case_pid(logs):
    for path in logs.glob('*.log'):
        text = path.read_text(errors='replace')
        if 'about to hang' in text:
            return int(re.search(r'\(pid (\d+)\)', text).group(1))
    return None


def test_sweep_stops_at_a_ctrl_c_whose_handler_ran_outside_its_wait(controllers, tmp_path):
    # A SIGINT's C handler runs in whichever thread the kernel gives it to (numpy's OpenBLAS
    # threads among them), or in the main thread just before it blocks in poll(); Python raises
    # the KeyboardInterrupt in the main thread only once it runs bytecode again. Sent to another
    # thread while the sweep waits on the hanging third case, Ctrl-C must still end that wait
    # (else it lasted until the case's 600 s timeout).
    out = tmp_path / 'out'
    names = ','.join([GOOD, '../examples/blind_controller.py', controllers['hang']])
    returned = threading.Event()
    outcome = {}

    def interrupt_the_wait():
        pid = _wait_for(lambda: _hanging_case_pid(out / 'logs'), EVENT_BOUND_S)
        if pid is None:
            return
        signal.pthread_kill(threading.get_ident(), signal.SIGINT)  # its handler runs here
        outcome['stopped'] = returned.wait(EVENT_BOUND_S)
        if not outcome['stopped']:
            os.kill(pid, signal.SIGKILL)    # the sweep did not stop: end its wait another way

    helper = threading.Thread(target=interrupt_the_wait, daemon=True)
    helper.start()
    try:
        result = run_sweep(SCENARIO, ['duration=2', f'driver.controller={names}'],
                           out_dir=str(out), workers=1, timeout_s=3 * EVENT_BOUND_S)
    finally:
        returned.set()
        helper.join()
    assert outcome == {'stopped': True}
    assert result.interrupted
    assert [r['status'] for r in result.records] == ['fail', 'fail']


def test_sweep_command_exits_2_naming_a_ray_address_where_nothing_answers(tmp_path):
    try:
        import ray  # noqa: F401
    except ImportError:
        pytest.skip("ray is not installed (pip install 'vehicle_sim[ray]'): the Ray backend is "
                    'optional')
    out = tmp_path / 'out'
    # A port bound on loopback but never listened on: connections to it are refused.
    with socket.socket() as unused:
        unused.bind(('127.0.0.1', 0))
        address = f'127.0.0.1:{unused.getsockname()[1]}'
        done = subprocess.run(
            [sys.executable, '-m', 'vehicle_sim', 'sweep', SCENARIO, '--backend', 'ray',
             '--ray-address', address, '--ray-connect-timeout', '5', '--out', str(out)],
            capture_output=True, text=True, timeout=NO_RAY_COMMAND_BOUND_S)
    assert done.returncode == 2
    assert re.fullmatch(
        re.escape(f'vehicle-sim sweep: --ray-address {address}: ')
        + '(' + re.escape(f'no Ray cluster answered within 5 s (--ray-connect-timeout); is Ray '
                          f'running there (ray status --address {address})?')
        + '|cannot join that Ray cluster: .*)\n', done.stderr)
    assert not out.exists() and done.stdout == ''
