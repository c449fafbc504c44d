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
The local backend: N worker processes on this machine, one case at a time each.

Each worker is a spawned Python process (:func:`~.worker.worker_loop`) that runs the cases it
is sent in its own process, its output in the case's log. The parent waits on the workers'
pipes and process handles together: a record comes back as the case's result; a worker that
dies (a segfault, ``os._exit``) or runs past the per-case timeout is killed and its case
becomes an error record with the end of its log; a fresh worker takes its place for the cases
left.
"""

import multiprocessing
from multiprocessing.connection import wait
import time

from vehicle_sim.sweep.worker import error_record, worker_loop

LOG_TAIL_CHARS = 4000       # the end of a dead worker's log, quoted in the case's error
KILL_WAIT_S = 5.0


def log_tail(path):
    """Return the last LOG_TAIL_CHARS characters of a log file ('' when it cannot be read)."""
    try:
        with open(path, 'rb') as log:
            text = log.read().decode('utf-8', 'replace')
    except OSError:
        return ''
    return text[-LOG_TAIL_CHARS:]


class _Worker:
    """One worker process and the case it runs (None when idle)."""

    def __init__(self, context):
        self.connection, child = context.Pipe()
        self.process = context.Process(target=worker_loop, args=(child,), daemon=True)
        self.process.start()
        child.close()
        self.work = None
        self.log_path = None
        self.started = 0.0

    def send(self, work, log_path):
        self.work, self.log_path, self.started = work, log_path, time.monotonic()
        self.connection.send((work, log_path))

    def kill(self):
        if self.process.is_alive():
            self.process.kill()
        self.process.join(KILL_WAIT_S)
        self.connection.close()

    def stop(self):
        try:
            self.connection.send(None)
        except OSError:
            pass
        self.process.join(KILL_WAIT_S)
        self.kill()


def _died(worker):
    code = worker.process.exitcode
    how = (f'killed by signal {-code}' if code is not None and code < 0 else
           f'exited with status {code}')
    tail = log_tail(worker.log_path)
    return f'the worker process running this case died ({how}); its log ends:\n{tail}'


def run_local(works, workers, timeout_s, log_path, done):
    """
    Run the cases on ``workers`` processes; call ``done(record)`` as each finishes.

    :param works: the cases' payload dicts, in order.
    :param timeout_s: a case's longest run (wall clock) before it is killed; None = no limit.
    :param log_path: ``log_path(work)`` -> the case's log file.
    :param done: called in this process with each record, in the order they finish.
    """
    context = multiprocessing.get_context('spawn')
    pending = list(reversed(works))
    pool = []
    try:
        while pending or any(w.work is not None for w in pool):
            for worker in pool:
                if worker.work is None and pending:
                    work = pending.pop()
                    worker.send(work, log_path(work))
            while len(pool) < workers and pending:
                worker = _Worker(context)
                work = pending.pop()
                worker.send(work, log_path(work))
                pool.append(worker)
            busy = [w for w in pool if w.work is not None]
            wait_s = None
            if timeout_s is not None:
                now = time.monotonic()
                wait_s = max(0.0, min(w.started + timeout_s - now for w in busy))
            ready = wait([w.connection for w in busy] + [w.process.sentinel for w in busy],
                         wait_s)
            now = time.monotonic()
            for worker in busy:
                record = None
                if worker.connection in ready or worker.process.sentinel in ready:
                    try:
                        if worker.connection.poll():
                            record = worker.connection.recv()
                    except (EOFError, OSError):
                        record = None
                    if record is None and not worker.process.is_alive():
                        record = error_record(worker.work, _died(worker), now - worker.started)
                        _replace(pool, worker, context)
                if record is None and timeout_s is not None and (
                        now - worker.started >= timeout_s):
                    worker.kill()
                    record = error_record(
                        worker.work, f'timed out: still running after {timeout_s:g} s (the '
                        f'worker process was killed); its log ends:\n{log_tail(worker.log_path)}',
                        now - worker.started)
                    _replace(pool, worker, context)
                if record is not None:
                    worker.work = None
                    done(record)
    finally:
        for worker in pool:
            if worker.work is not None:
                worker.kill()
            else:
                worker.stop()


def _replace(pool, worker, context):
    # A dead or killed worker's place goes to a fresh one when there is work for it.
    worker.kill()
    worker.work = None
    pool.remove(worker)
