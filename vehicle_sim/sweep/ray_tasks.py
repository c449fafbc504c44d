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
The Ray backend: one Ray task per case (``ray`` is the optional ``ray`` extra).

``ray.init()`` starts Ray on this machine (``num_cpus`` = the workers, no dashboard) unless it
is initialised already in this process; with an address it joins that cluster
(``ray.init(address=...)``: ``auto``, ``ray://head:10001``, ``head:6379``), after
:func:`check_address` has joined it once within a deadline. At most ``workers``
tasks are in flight (default: the cluster's CPUs), so that a case's timeout counts from about
when it starts; a task past it is cancelled (its worker process killed) and becomes the case's
error, as does a task whose worker died. Each task writes the case's output to the case's log
when the results folder is reachable from its machine, and returns it otherwise.

The scenario travels as text; the files it names (a controller, a world file) must be at the
same paths on the cluster's machines, and ``vehicle_sim`` installed there (docs/sweeps.md).
"""

import os
import subprocess
import sys
import tempfile
import time

from vehicle_sim.sweep.local import log_tail
from vehicle_sim.sweep.worker import error_record, run_case_logged

RAY_EXTRA_HINT = "--backend ray needs ray: pip install 'vehicle_sim[ray]' (or pip install ray)"
# How long joining a Ray cluster may take (--ray-connect-timeout) [s].
DEFAULT_CONNECT_TIMEOUT_S = 30.0
# Joins the cluster at argv[1] and leaves it, in a child process: where no Ray answers,
# ray.init(address=...) retries for about 14 minutes, deaf to Ctrl-C, and a child is
# killed at the deadline for sure (Ray's own retry settings are internal and version-bound).
_PROBE = 'import sys, ray; ray.init(address=sys.argv[1], log_to_driver=False); ray.shutdown()'


def require_ray():
    """Import ray, or raise SweepError naming the extra."""
    try:
        import ray
    except ImportError:
        from vehicle_sim.sweep.grid import SweepError
        raise SweepError(RAY_EXTRA_HINT) from None
    return ray


def check_address(address, timeout_s=DEFAULT_CONNECT_TIMEOUT_S):
    """
    Join the Ray cluster at ``address`` once, in a child process, within ``timeout_s``.

    Nothing to check when Ray is initialised in this process already (:func:`run_ray` uses it).

    :raises SweepError: one line naming the address: nothing answered within ``timeout_s``, or
        Ray refused it (its last line of error).
    """
    from vehicle_sim.sweep.grid import SweepError
    if require_ray().is_initialized():
        return
    try:
        probe = subprocess.run([sys.executable, '-c', _PROBE, address], capture_output=True,
                               text=True, stdin=subprocess.DEVNULL, timeout=timeout_s)
    except subprocess.TimeoutExpired:
        raise SweepError(f'--ray-address {address}: no Ray cluster answered within '
                         f'{timeout_s:g} s (--ray-connect-timeout); is Ray running there '
                         f'(ray status --address {address})?') from None
    if probe.returncode != 0:
        lines = [line.strip() for line in probe.stderr.splitlines() if line.strip()]
        why = lines[-1] if lines else f'exit status {probe.returncode}'
        # Ray's last line is its generic 'Failed to connect'; the cause (a refused
        # authentication token, a version mismatch) is a ray.exceptions line above it.
        causes = [line for line in lines[:-1] if line.startswith('ray.exceptions.')]
        if causes:
            why += f' ({causes[-1]})'
        raise SweepError(f'--ray-address {address}: cannot join that Ray cluster: {why}')


def ray_case(work, log_path):
    """
    Run one case as a Ray task; return (record, the log's text or None).

    Its output goes to ``log_path``, or to a temporary file on a machine where the results
    folder is not (whose text is returned; None when it is in ``log_path``).
    """
    local = os.path.isdir(os.path.dirname(log_path))
    path = log_path if local else os.path.join(tempfile.mkdtemp(), 'case.log')
    record = run_case_logged(work, path)
    if local:
        return record, None
    with open(path, encoding='utf-8', errors='replace') as log:
        text = log.read()
    os.remove(path)
    return record, text


def run_ray(works, workers, timeout_s, address, log_path, done):
    """Run the cases as Ray tasks; call ``done(record)`` as each finishes (see run_local)."""
    ray = require_ray()
    started_here = not ray.is_initialized()
    if started_here:
        if address:
            ray.init(address=address, log_to_driver=False)
        else:
            ray.init(num_cpus=workers or os.cpu_count() or 1, include_dashboard=False,
                     log_to_driver=False)
    flight = {}         # ref -> (work, submitted at)
    try:
        capacity = workers or max(1, int(ray.cluster_resources().get('CPU', 1)))
        task = ray.remote(num_cpus=1, max_retries=0)(ray_case)
        pending = list(reversed(works))
        while pending or flight:
            while pending and len(flight) < capacity:
                work = pending.pop()
                flight[task.remote(work, log_path(work))] = (work, time.monotonic())
            wait_s = None
            if timeout_s is not None:
                now = time.monotonic()
                wait_s = max(0.0, min(t + timeout_s - now for _, t in flight.values()))
            ready, _ = ray.wait(list(flight), num_returns=1, timeout=wait_s)
            now = time.monotonic()
            for ref in ready:
                work, submitted = flight.pop(ref)
                done(_collect(ray, ref, work, log_path(work), now - submitted))
            if timeout_s is not None:
                for ref, (work, submitted) in list(flight.items()):
                    if now - submitted >= timeout_s:
                        ray.cancel(ref, force=True)
                        del flight[ref]
                        done(error_record(
                            work, f'timed out: still running after {timeout_s:g} s (the Ray '
                            'task was cancelled, its worker killed); its log ends:\n'
                            + log_tail(log_path(work)), now - submitted))
    except KeyboardInterrupt:
        for ref in flight:
            ray.cancel(ref, force=True)
        raise
    finally:
        if started_here:
            ray.shutdown()


def _collect(ray, ref, work, path, elapsed_s):
    try:
        record, text = ray.get(ref)
    except ray.exceptions.RayError as error:
        return error_record(work, f'the Ray task running this case failed ({type(error).__name__})'
                            f': {error}\nits log ends:\n{log_tail(path)}', elapsed_s)
    if text is not None:
        with open(path, 'w', encoding='utf-8') as log:
            log.write(text)
    return record
