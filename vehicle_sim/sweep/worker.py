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
Running one variant of a sweep in a worker process, and the local workers' loop.

A case runs in whatever process the backend gives it (a local worker process or a Ray task).

A case travels as a plain dict (the scenario's text and file name, its overrides and seed) and
comes back as a plain dict, the case's record (:func:`run_case`): picklable, JSON-able, the same
whichever process ran it. Its output (the controller's prints, a crash's traceback) goes to a
log file (:func:`run_case_logged`).
"""

import faulthandler
import fcntl
import numbers
import os
import signal
import sys
import tempfile
import time
import traceback

from vehicle_sim.sweep.grid import apply_override, Axis, key_path

# ROS 2's domain ids run 0..232 (the ports of higher ones do not fit in 16 bits on Linux).
MAX_DOMAIN_ID = 232


def payload(case, source, content):
    """Return what a backend sends for one case: the scenario's text and name, overrides, seed."""
    return {'case_id': case.case_id, 'index': case.index, 'label': case.label,
            'overrides': [list(item) for item in case.overrides], 'seed': case.seed,
            'source': source, 'content': content}


def error_record(work, message, wall_time_s=0.0):
    """Return the record of a case that did not run to a result (a crash, a timeout, a refusal)."""
    return _record(work, 'error', [], message, '', 0.0, wall_time_s, True)


def _record(work, status, criteria, error, sha, sim_time_s, wall_time_s, deterministic):
    return {'case_id': work['case_id'], 'index': work['index'], 'label': work['label'],
            'overrides': work['overrides'], 'seed': work['seed'], 'status': status,
            'criteria': criteria, 'error': error, 'odometry_sha256': sha,
            'sim_time_s': sim_time_s, 'wall_time_s': wall_time_s,
            'deterministic': deterministic}


def _plain(value):
    if value is None or isinstance(value, bool):
        return value
    if isinstance(value, numbers.Integral):
        return int(value)
    return float(value)


def run_case(work):
    """
    Run one case in this process and return its record.

    The scenario's own errors (a controller that raised, a refused command) are the record's
    ``error``; only a crash of the process itself (or a hang) loses the record, and the backend
    writes an error record instead.
    """
    from vehicle_sim.scenarios.runner import run_scenario
    from vehicle_sim.scenarios.schema import scenario_from_data
    from vehicle_sim.scenarios.yaml_lines import load_with_lines
    start = time.monotonic()
    try:
        data, lines = load_with_lines(work['content'], work['source'])
        for key, value in work['overrides']:
            apply_override(data, Axis(key, key_path(key), (value,)), value)
        spec = scenario_from_data(data, lines, work['source'])
        with DomainClaim(spec.served):
            result = run_scenario(spec, seed=work['seed'])
    except Exception as error:  # noqa: BLE001 - the case's error, the other cases go on
        return error_record(work, f'{type(error).__name__}: {error}\n'
                            + traceback.format_exc(limit=-4), time.monotonic() - start)
    criteria = [{'name': c.name, 'kind': c.kind, 'passed': bool(c.passed),
                 'value': _plain(c.value), 'unit': c.unit, 'detail': c.detail}
                for c in result.criteria]
    status = 'error' if result.error else ('pass' if result.passed else 'fail')
    return _record(work, status, criteria, result.error, result.odometry_sha256,
                   float(result.sim_time_s), time.monotonic() - start, result.deterministic)


class DomainClaim:
    """
    A served scenario's ROS domain: the first free id from VEHICLE_SIM_SWEEP_DOMAIN_BASE up.

    Free means that no other case on this machine holds it: each case holds a lock file per id
    while it runs, so parallel workers (local processes or Ray tasks) never share a domain.
    """

    def __init__(self, served):
        self.served = served
        self.lock = None
        self.saved = None

    def __enter__(self):
        if not self.served:
            return self
        base = int(os.environ.get('VEHICLE_SIM_SWEEP_DOMAIN_BASE',
                                  int(os.environ.get('ROS_DOMAIN_ID', '0')) + 1))
        folder = os.path.join(tempfile.gettempdir(), 'vehicle_sim_sweep_domains')
        os.makedirs(folder, exist_ok=True)
        for domain in range(base, MAX_DOMAIN_ID + 1):
            handle = open(os.path.join(folder, f'{domain}.lock'), 'w')
            try:
                fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except OSError:
                handle.close()
                continue
            self.lock = handle
            self.saved = os.environ.get('ROS_DOMAIN_ID')
            os.environ['ROS_DOMAIN_ID'] = str(domain)
            return self
        raise RuntimeError(f'no free ROS domain id from {base} to {MAX_DOMAIN_ID} for this '
                           'served scenario')

    def __exit__(self, *exc):
        if self.lock is not None:
            if self.saved is None:
                os.environ.pop('ROS_DOMAIN_ID', None)
            else:
                os.environ['ROS_DOMAIN_ID'] = self.saved
            self.lock.close()
        return False


def run_case_logged(work, log_path):
    """Run one case with this process's stdout and stderr (file descriptors 1, 2) in a log."""
    sys.stdout.flush()
    sys.stderr.flush()
    saved = os.dup(1), os.dup(2)
    with open(log_path, 'wb') as log:
        os.dup2(log.fileno(), 1)
        os.dup2(log.fileno(), 2)
    try:
        print(f'case {work["label"]} (pid {os.getpid()})', flush=True)
        return run_case(work)
    finally:
        sys.stdout.flush()
        sys.stderr.flush()
        os.dup2(saved[0], 1)
        os.dup2(saved[1], 2)
        os.close(saved[0])
        os.close(saved[1])


def worker_loop(connection):
    """
    Run a local worker process: receive (case, log path), send back its record; None ends it.

    Ctrl-C is the sweep's to handle (it stops the workers); a fatal signal's traceback goes
    to the case's log (faulthandler writes to file descriptor 2).
    """
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    faulthandler.enable(file=sys.__stderr__, all_threads=True)
    while True:
        try:
            message = connection.recv()
        except EOFError:
            return
        if message is None:
            return
        work, log_path = message
        connection.send(run_case_logged(work, log_path))


def worker_main(argv=None):
    """``python -m vehicle_sim.sweep.worker FD``: the worker loop on the socket FD (local.py)."""
    from multiprocessing.connection import Connection
    argv = sys.argv[1:] if argv is None else argv
    connection = Connection(int(argv[0]))
    try:
        worker_loop(connection)
    finally:
        connection.close()


if __name__ == '__main__':
    worker_main()
