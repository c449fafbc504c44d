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
One running SUMO: libsumo in this process, a sumo process over TraCI, or libsumo in a worker.

libsumo (SUMO as a Python extension) runs one simulation per process: :class:`SumoSession`
takes it when it is free (``transport: auto`` or ``libsumo``) and otherwise starts the sumo
binary of the ``eclipse-sumo`` package and talks to it over TraCI (``traci.start`` with a label of
its own), the same calls through a connection instead of the module. A second world in one process
(a Gym vector env's worlds, a test's two worlds) therefore gets TraCI; a process per world
(the async vector env) gets libsumo in each. ``transport: worker`` runs libsumo in a process of
the session's own (physics/sumo_worker.py: SUMO steps while the physics runs; any number per
process).

Every message of SUMO goes to an error log of the session's own (``--error-log``): a failed
start raises InvalidParameterError, a failure while it runs :class:`SumoError`, each with SUMO's
message (libsumo's exception text, or the log's last lines when a sumo process quit).
"""

import contextlib
import io
import itertools
import os
import shutil
import subprocess
import tempfile

from vehicle_sim.core.specs.errors import InvalidParameterError, VehicleSimError
from vehicle_sim.maps.netconvert import sumo_home
from vehicle_sim.maps.sumo_net import EXTRA_HINT, SumoUnavailable

LOG_LINES = 6          # the last lines of SUMO's error log an error quotes
_labels = itertools.count()
_libsumo_user = [None]  # the session that holds libsumo in this process


class SumoError(VehicleSimError):
    """SUMO stopped or refused a call while a world ran: SUMO's message."""


def sumo_binary():
    """Return the path of the ``sumo`` program of the ``eclipse-sumo`` package."""
    return os.path.join(sumo_home('the sumo traffic engine'), 'bin', 'sumo')


def load_libsumo():
    """Return the libsumo module, or None when it cannot load (not installed, a bad library)."""
    try:
        with contextlib.redirect_stdout(io.StringIO()):   # its pyarrow version notice
            import libsumo
    except (ImportError, OSError):
        return None
    return libsumo


def load_traci():
    """Return the traci module (the TraCI client)."""
    try:
        import traci
    except ImportError:
        raise SumoUnavailable('the sumo traffic engine needs traci (the TraCI client): '
                              + EXTRA_HINT) from None
    return traci


def _errors(module):
    # libsumo's own exception classes (its ``exceptions`` attribute is traci's), or traci's
    return (module.TraCIException, module.FatalTraCIError)


class SumoSession:
    """
    One SUMO simulation: ``api`` offers TraCI's domains (``api.vehicle``, ``api.simulation``...).

    :param args: sumo's options (the network, routes, seed, step length...).
    :param transport: 'auto', 'libsumo', 'traci' or 'worker' (core/traffic/sumo_params.py
        TRANSPORTS).
    :param source: quoted in errors ('world.yaml: traffic').
    :raises InvalidParameterError: SUMO refused to start (its message); libsumo asked for and
        taken; SumoUnavailable (maps/sumo_net.py): SUMO, libsumo (asked for) or traci not
        installed, naming the extra.
    """

    def __init__(self, args, transport='auto', source='traffic'):
        self.source = source
        binary = sumo_binary()
        libsumo = load_libsumo()
        if transport == 'libsumo':
            if libsumo is None:
                raise SumoUnavailable(f"{source}: field 'transport' = 'libsumo': libsumo does not "
                                      'load in this Python (transport: traci runs SUMO as a '
                                      'process): ' + EXTRA_HINT)
            if _libsumo_user[0] is not None or libsumo.simulation.isLoaded():
                raise InvalidParameterError(
                    f"{source}: field 'transport' = 'libsumo': this process runs a SUMO through "
                    'libsumo already (one per process): close that world first, or use '
                    'transport: traci, worker or auto')
        elif transport == 'worker' and libsumo is None:
            raise SumoUnavailable(f"{source}: field 'transport' = 'worker': libsumo does not "
                                  'load in this Python (transport: traci runs SUMO as a '
                                  'process): ' + EXTRA_HINT)
        elif transport == 'auto':
            free = libsumo is not None and _libsumo_user[0] is None and \
                not libsumo.simulation.isLoaded()
            transport = 'libsumo' if free else 'traci'
        self.transport = transport
        self._folder = tempfile.mkdtemp(prefix='vehicle_sim_sumo_')
        self.log_path = os.path.join(self._folder, 'sumo.log')
        command = [binary, *args, '--error-log', self.log_path, '--no-step-log', 'true']
        self._catch = _errors(libsumo if transport == 'libsumo' else load_traci().exceptions)
        self.refusal = self._catch[0]       # SUMO refused a call (TraCIException); it runs on
        self._libsumo = libsumo if transport == 'libsumo' else None
        self.api = None
        try:
            if transport == 'libsumo':
                with contextlib.redirect_stdout(io.StringIO()):
                    libsumo.start(command)
                _libsumo_user[0] = self
                self.api = libsumo
            elif transport == 'worker':
                from vehicle_sim.physics.sumo_worker import SumoWorker, WorkerApi
                self.api = WorkerApi(SumoWorker(command, load_traci().exceptions))
            else:
                traci = load_traci()
                label = f'vehicle_sim_{os.getpid()}_{next(_labels)}'
                with contextlib.redirect_stdout(io.StringIO()):   # its 'Retrying' notices
                    traci.start(command, label=label, stdout=subprocess.DEVNULL)
                self.api = traci.getConnection(label)
        except self._catch as error:
            message = self.message(error)
            self.close()
            raise InvalidParameterError(f'{source}: SUMO did not start: {message}') from None

    def message(self, error):
        """Return SUMO's words for ``error``: its text, else the error log's last lines."""
        text = ' '.join(str(error).split())       # one line: SUMO breaks its own
        try:
            with open(self.log_path, encoding='utf-8', errors='replace') as log:
                lines = [line.rstrip() for line in log if line.strip()]
        except OSError:
            lines = []
        lines = [line for line in lines if not line.startswith('Quitting')]
        process = getattr(self.api, '_process', None)
        status = None if process is None else process.poll()
        if status is not None:
            text += f' (the sumo process ended with status {status})'
        if lines and (not text or text.startswith('Connection closed')):
            return '; '.join(' '.join(line.split()) for line in lines[-LOG_LINES:]) + (
                f' ({text})' if text else '')
        return text or type(error).__name__

    @contextlib.contextmanager
    def errors(self, what):
        """Turn SUMO's exceptions inside into a SumoError naming ``what`` and SUMO's message."""
        try:
            yield
        except self._catch as error:
            raise SumoError(f'{self.source}: SUMO {what}: {self.message(error)}') from None

    @property
    def closed(self):
        """Whether the session was closed (or never started)."""
        return self.api is None

    def close(self):
        """End the simulation (the sumo process, or libsumo's), remove its log (idempotent)."""
        api, self.api = self.api, None
        if self._libsumo is not None:
            if _libsumo_user[0] is self:
                _libsumo_user[0] = None
            with contextlib.suppress(*self._catch):
                self._libsumo.close()
            self._libsumo = None
        elif api is not None:
            with contextlib.suppress(*self._catch, OSError):
                api.close()
        if self._folder is not None:
            shutil.rmtree(self._folder, ignore_errors=True)
            self._folder = None

    def __del__(self):
        with contextlib.suppress(Exception):
            self.close()
