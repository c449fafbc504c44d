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
libsumo in a process of its own (``transport: worker``): SUMO steps while the physics runs.

libsumo keeps Python's interpreter lock while it steps, so in the world's process SUMO's step
and the physics take turns. Here a worker process (this module run with ``python -m``) holds
libsumo; the world's process talks to it over two pipes (multiprocessing's connections, pickled
messages):

- ``('start', command)``: libsumo.start; answered.
- ``('call', domain, name, args, kwargs)``: one of TraCI's calls (``vehicle.getLaneID``...);
  answered with its result (libsumo's own objects, such as ``simulation.findRoute``'s stage,
  as namespaces of their fields). :class:`WorkerApi` makes these look like libsumo's module.
- ``('step', prefix)``: SUMO's step, not answered: the caller goes on while SUMO steps. The
  step's readings are kept: the simulation's subscription results, every vehicle's (but ours,
  whose ids start with ``prefix``) id, front position, angle, speed and (lane, place on it,
  route index), every walking person's id, position, angle and speed (not those riding a
  vehicle), the traffic lights' subscription results (what physics/sumo_reads.py reads).
- ``('collect',)``: the kept readings of the last step, answered when the step is done.
- ``('close',)``: libsumo.close; answered; the worker ends.

A call while a step is in flight waits for the step (its readings kept for ``collect``): it
reads SUMO after that step. An error is answered as ``('error', fatal, text)``: SUMO refused the
call (TraCI's TraCIException) or failed (FatalTraCIError); :class:`SumoWorker` raises traci's
classes of them, so physics/sumo_session.py handles both transports alike. A worker that ended
(its pipe closed) raises FatalTraCIError.
"""

import contextlib
import io
from multiprocessing.connection import Connection
import os
import pickle
import subprocess
import sys
import types

from vehicle_sim.physics.sumo_reads import GetterReads

DOMAINS = ('edge', 'junction', 'lane', 'person', 'route', 'simulation', 'trafficlight',
           'vehicle', 'vehicletype')
CLOSED_TEXT = 'Connection closed by the SUMO worker.'


def _readings(libsumo, prefix):
    # What the engine reads after each step (physics/sumo_reads.py GetterReads, each vehicle's
    # lane with it; the signals' subscriptions), read here in one go.
    reads = GetterReads(None, prefix)
    vehicles = [(vid, position, angle, speed, reads.lane(libsumo, vid))
                for vid, position, angle, speed, _ in reads.vehicles(libsumo)]
    return (libsumo.simulation.getSubscriptionResults(), vehicles, reads.persons(libsumo),
            libsumo.trafficlight.getAllSubscriptionResults())


def _plain(value):
    # A result that pickles: libsumo's objects (a TraCIStage of simulation.findRoute, a
    # TraCILogic...) as namespaces of their fields, also inside a list or tuple.
    if isinstance(value, (list, tuple)):
        if value and _from_libsumo(value[0]):
            return type(value)(_plain(item) for item in value)
        return value
    if not _from_libsumo(value):
        return value
    return types.SimpleNamespace(**{
        name: _plain(getattr(value, name)) for name in dir(value)
        if not name.startswith('_') and name not in ('this', 'thisown')
        and not callable(getattr(value, name))})


def _from_libsumo(value):
    return type(value).__module__.startswith('libsumo')


def serve(read_fd, write_fd):
    """Answer the messages read on ``read_fd`` on ``write_fd`` until ``close`` (the worker)."""
    requests = Connection(read_fd, writable=False)
    answers = Connection(write_fd, readable=False)
    with contextlib.redirect_stdout(io.StringIO()):     # its pyarrow version notice
        import libsumo
    refused = libsumo.TraCIException
    kept = None
    while True:
        try:
            message = requests.recv()
        except (EOFError, KeyboardInterrupt):    # the world's process ended (or was stopped
            return                                # with Ctrl-C, which reaches this one too)
        kind = message[0]
        try:
            if kind == 'step':            # answered at 'collect'
                try:
                    libsumo.simulationStep()
                    kept = ('ok', _readings(libsumo, message[1]))
                except refused as error:
                    kept = ('error', False, str(error))
                except Exception as error:                  # libsumo's fatal errors
                    kept = ('error', True, str(error) or type(error).__name__)
                continue
            if kind == 'collect':
                answer, kept = kept, None
            elif kind == 'call':
                _, domain, name, args, kwargs = message
                answer = ('ok', _plain(getattr(getattr(libsumo, domain), name)(*args,
                                                                            **kwargs)))
            elif kind == 'start':
                with contextlib.redirect_stdout(io.StringIO()):
                    libsumo.start(message[1])
                answer = ('ok', None)
            else:                                       # close
                with contextlib.suppress(Exception):
                    libsumo.close()
                answers.send(('ok', None))
                return
        except refused as error:
            answer = ('error', False, str(error))
        except Exception as error:       # libsumo's fatal errors, and anything else
            answer = ('error', True, str(error) or type(error).__name__)
        try:
            answers.send(answer)
        except (pickle.PicklingError, TypeError, AttributeError) as error:
            answers.send(('error', True, f'the SUMO worker cannot send the answer to {kind!r}: '
                                         f'{error}'))


class SumoWorker:
    """
    The world's side of a worker process: its messages, the step in flight.

    :param command: sumo's command line (the program, then its options).
    :param exceptions: traci's exceptions module (TraCIException, FatalTraCIError).
    :raises exceptions.TraCIException / FatalTraCIError: SUMO did not start (its message).
    """

    def __init__(self, command, exceptions):
        self._refused, self._fatal = exceptions.TraCIException, exceptions.FatalTraCIError
        ours_read, theirs_write = os.pipe()
        theirs_read, ours_write = os.pipe()
        # the worker imports this package from where this process has it (installed or not)
        root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
        path = os.environ.get('PYTHONPATH')
        env = dict(os.environ, PYTHONPATH=root if not path else root + os.pathsep + path)
        self._process = subprocess.Popen(
            [sys.executable, '-m', 'vehicle_sim.physics.sumo_worker', str(theirs_read),
             str(theirs_write)], pass_fds=(theirs_read, theirs_write),
            stdout=subprocess.DEVNULL, env=env)
        os.close(theirs_read)
        os.close(theirs_write)
        self._requests = Connection(ours_write, readable=False)
        self._answers = Connection(ours_read, writable=False)
        self.in_flight = False
        self._kept = None
        try:
            self._ask(('start', list(command)))
        except BaseException:
            self.close()
            raise

    def _send(self, message):
        try:
            self._requests.send(message)
        except OSError:
            raise self._fatal(CLOSED_TEXT) from None

    def _answer(self):
        try:
            answer = self._answers.recv()
        except (EOFError, OSError):
            raise self._fatal(CLOSED_TEXT) from None
        if answer[0] == 'error':
            raise (self._fatal if answer[1] else self._refused)(answer[2])
        return answer[1]

    def _ask(self, message):
        self._send(message)
        return self._answer()

    def call(self, domain, name, args, kwargs):
        """Return the result of ``libsumo.<domain>.<name>(*args, **kwargs)`` after the step."""
        self.wait()
        return self._ask(('call', domain, name, args, kwargs))

    def step(self, prefix):
        """Start SUMO's step (the previous one collected first); return at once."""
        self.wait()
        self._send(('step', prefix))
        self.in_flight = True

    @property
    def stepped(self):
        """Whether a step was started and not collected yet (in flight, or done and kept)."""
        return self.in_flight or self._kept is not None

    def wait(self):
        """Wait for the step in flight, if one is, and keep its answer for :meth:`collect`."""
        if self.in_flight:
            self.in_flight = False
            self._send(('collect',))
            try:
                self._kept = ('ok', self._answer())
            except (self._refused, self._fatal) as error:
                self._kept = ('error', error)

    def collect(self):
        """
        Return the last step's readings: (subscription results, vehicles, persons, lights).

        :raises TraCIException / FatalTraCIError: SUMO refused or failed the step.
        """
        self.wait()
        kept, self._kept = self._kept, None
        if kept is None:
            raise RuntimeError('collect() without a step')
        if kept[0] == 'error':
            raise kept[1]
        return kept[1]

    def close(self):
        """End the worker (SUMO closed first); idempotent."""
        process, self._process = self._process, None
        if process is None:
            return
        with contextlib.suppress(self._refused, self._fatal):
            self.wait()
            self._ask(('close',))
        for connection in (self._requests, self._answers):
            connection.close()
        try:
            process.wait(timeout=10.0)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait()

    @property
    def exit_status(self):
        """The worker's exit status, or None while it runs (or after close)."""
        return None if self._process is None else self._process.poll()


class _Domain:
    # One of TraCI's domains (api.vehicle ...): each attribute a call in the worker.

    def __init__(self, worker, name):
        self._worker = worker
        self._name = name

    def __getattr__(self, attribute):
        worker, name = self._worker, self._name

        def call(*args, **kwargs):
            return worker.call(name, attribute, args, kwargs)
        call.__name__ = attribute
        return call


class WorkerApi:
    """
    TraCI's domains as libsumo offers them (``api.vehicle.getLaneID(...)``), run by a worker.

    ``simulationStep()`` steps and waits; the engine starts a step and collects it later
    through ``worker`` (:class:`SumoWorker`).
    """

    def __init__(self, worker):
        self.worker = worker
        for name in DOMAINS:
            setattr(self, name, _Domain(worker, name))

    @property
    def _process(self):
        # the worker as sumo_session.SumoSession.message reads a sumo process (its status)
        return self.worker._process

    def simulationStep(self):
        """One SUMO step, waited for (the engine overlaps its steps through ``worker``)."""
        self.worker.step('\0')
        self.worker.collect()

    def close(self):
        """End the worker."""
        self.worker.close()


if __name__ == '__main__':
    try:
        serve(int(sys.argv[1]), int(sys.argv[2]))
    except KeyboardInterrupt:             # Ctrl-C in the world's terminal: the world ends it
        pass
