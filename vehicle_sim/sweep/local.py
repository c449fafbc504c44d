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

Each worker is a Python interpreter started as ``python -m vehicle_sim.sweep.worker FD``
(:func:`~.worker.worker_main`): a program of its own, so that the caller's main script is never
run again in it (as multiprocessing's spawn would), in a session of its own, so that a Ctrl-C
at the terminal reaches only the sweep, which stops it. It talks to the sweep over a socket
pair (multiprocessing's Connection: pickled messages) and runs the cases it is sent in its own
process, its output in the case's log. The sweep waits on the workers' sockets: a record comes
back as the case's result; a worker whose socket closes (it died: a segfault, ``os._exit``) or
that runs past the per-case timeout is killed and its case becomes an error record with the end
of its log; a fresh worker takes its place for the cases left.

A signal also ends that wait (:class:`SignalWakeup`): Python raises Ctrl-C's KeyboardInterrupt in
the main thread only when it runs bytecode again, so a SIGINT whose handler ran in another thread
of this process, or in the main thread just before it blocked in ``poll``, would otherwise wait
for the next record or the case's timeout.
"""

from multiprocessing.connection import Connection, wait
import os
import signal
import socket
import subprocess
import sys
import threading
import time

from vehicle_sim.sweep.worker import error_record

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


def _environment():
    # The worker imports this vehicle_sim, installed or not.
    import vehicle_sim
    root = os.path.dirname(os.path.dirname(os.path.abspath(vehicle_sim.__file__)))
    env = dict(os.environ)
    env['PYTHONPATH'] = os.pathsep.join(p for p in (root, env.get('PYTHONPATH')) if p)
    return env


class SignalWakeup:
    """
    A socket that becomes readable when a signal with a Python handler arrives.

    While it is entered (in the main thread), Python's C-level signal handler writes the
    signal's number to it (:func:`signal.set_wakeup_fd`), in whichever thread it runs, before
    or during a wait: waiting on :attr:`waitables` too, the wait returns, and Python runs the
    handler (Ctrl-C: KeyboardInterrupt) as soon as the main thread runs bytecode. Elsewhere
    (not the main thread, which alone handles signals) it does nothing and
    :attr:`waitables` is empty.
    """

    def __init__(self):
        self.reader = None
        self.writer = None
        self.previous = -1

    @property
    def waitables(self):
        """Return what to wait on besides the workers' sockets: [the socket] or []."""
        return [self.reader] if self.reader is not None else []

    def __enter__(self):
        if threading.current_thread() is not threading.main_thread():
            return self
        reader, writer = socket.socketpair()
        reader.setblocking(False)
        writer.setblocking(False)
        try:
            self.previous = signal.set_wakeup_fd(writer.fileno(), warn_on_full_buffer=False)
        except ValueError:      # not the main interpreter: its signals are not ours
            reader.close()
            writer.close()
            return self
        self.reader, self.writer = reader, writer
        return self

    def drain(self, ready):
        """Empty the socket when it is among ``ready`` (what the wait returned)."""
        if self.reader is None or self.reader not in ready:
            return
        try:
            while self.reader.recv(4096):
                pass
        except (BlockingIOError, InterruptedError):
            pass

    def __exit__(self, *exc):
        if self.reader is not None:
            signal.set_wakeup_fd(self.previous)
            self.reader.close()
            self.writer.close()
            self.reader = self.writer = None
        return False


class _Worker:
    """One worker process and the case it runs (None when idle)."""

    def __init__(self, env):
        ours, theirs = socket.socketpair()
        try:
            self.process = subprocess.Popen(
                [sys.executable, '-m', 'vehicle_sim.sweep.worker', str(theirs.fileno())],
                pass_fds=(theirs.fileno(),), stdin=subprocess.DEVNULL, env=env,
                start_new_session=True)
        finally:
            theirs.close()
        self.connection = Connection(ours.detach())
        self.work = None
        self.log_path = None
        self.started = 0.0

    def send(self, work, log_path):
        self.work, self.log_path, self.started = work, log_path, time.monotonic()
        self.connection.send((work, log_path))

    def receive(self):
        """Return the record sent back, or None when the worker died (its socket closed)."""
        try:
            return self.connection.recv()
        except (EOFError, OSError):
            return None

    def kill(self):
        if self.process.poll() is None:
            self.process.kill()
        try:
            self.process.wait(KILL_WAIT_S)
        except subprocess.TimeoutExpired:
            pass
        self.connection.close()

    def stop(self):
        try:
            self.connection.send(None)
            self.process.wait(KILL_WAIT_S)
        except (OSError, subprocess.TimeoutExpired):
            pass
        self.kill()


def _died(worker):
    try:
        code = worker.process.wait(KILL_WAIT_S)
    except subprocess.TimeoutExpired:
        code = None
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
    env = _environment()
    pending = list(reversed(works))
    pool = []
    with SignalWakeup() as wakeup:
        try:
            while pending or pool:
                while len(pool) < min(workers, len(pool) + len(pending)):
                    pool.append(_Worker(env))
                for worker in pool:
                    if worker.work is None and pending:
                        work = pending.pop()
                        worker.send(work, log_path(work))
                for worker in [w for w in pool if w.work is None]:    # nothing left for it
                    worker.stop()
                    pool.remove(worker)
                if not pool:
                    break
                wait_s = None
                if timeout_s is not None:
                    wait_s = max(0.0, min(w.started + timeout_s for w in pool) - time.monotonic())
                ready = wait([w.connection for w in pool] + wakeup.waitables, wait_s)
                wakeup.drain(ready)
                now = time.monotonic()
                for worker in list(pool):
                    if worker.connection in ready:
                        record = worker.receive()
                        if record is None:
                            record = error_record(worker.work, _died(worker), now - worker.started)
                            worker.kill()
                            pool.remove(worker)
                    elif timeout_s is not None and now - worker.started >= timeout_s:
                        worker.kill()
                        pool.remove(worker)
                        record = error_record(
                            worker.work, f'timed out: still running after {timeout_s:g} s (the '
                            'worker process was killed); its log ends:\n'
                            + log_tail(worker.log_path), now - worker.started)
                    else:
                        continue
                    worker.work = None
                    done(record)
        finally:
            for worker in pool:
                if worker.work is not None:
                    worker.kill()
                else:
                    worker.stop()
