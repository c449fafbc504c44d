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
:func:`run_sweep`: the Python API of sweeps, which ``vehicle-sim sweep`` wraps.

A scenario runs for every combination of values and seeds, in parallel, with merged reports
(docs/sweeps.md). The cases run on a backend of :data:`BACKENDS` (``local`` worker processes,
``ray`` tasks): a backend is one :class:`Backend` row, its module imported only when it runs.
"""

from dataclasses import dataclass, field
import hashlib
import os
from typing import Callable, Dict, List, Optional

from vehicle_sim.core.specs.registry import register
from vehicle_sim.sweep import results
from vehicle_sim.sweep.grid import (
    Axis,
    build_cases,
    Case,
    check_variants,
    key_path,
    parse_seeds,
    parse_set,
    SweepError,
)

DEFAULT_TIMEOUT_S = 600.0
MAX_WORKERS = 1024


@dataclass(frozen=True)
class Backend:
    """
    A sweep backend: where the cases run.

    :param name: its name (``--backend``, ``run_sweep(backend=...)``).
    :param run: ``run(todo, workers, timeout_s, address, case_log, finished)``: run
        ``worker.run_case_logged(work, case_log(work))`` for every payload of ``todo`` (at most
        ``workers`` at once; None = as many as it has CPUs), calling ``finished(record)`` for
        each (an error record for a case whose process died or ran past ``timeout_s``).
    :param check: ``check()`` before anything is read: raises SweepError when an optional
        package it needs is missing (None: nothing to check).
    :param connect: ``connect(address, timeout_s)`` once the input is valid, for a backend that
        joins a cluster at ``--ray-address`` (None: it takes no address).
    :param doc: one line for ``vehicle-sim sweep --help``.
    """

    name: str
    run: Callable
    check: Optional[Callable] = None
    connect: Optional[Callable] = None
    doc: str = ''


BACKENDS: Dict[str, Backend] = {}


def register_backend(backend: Backend) -> Backend:
    """Add a sweep backend to :data:`BACKENDS` (its name must be new)."""
    return register(BACKENDS, backend, 'sweep backend')


def _run_local(todo, workers, timeout_s, address, case_log, finished):
    from vehicle_sim.sweep.local import run_local
    run_local(todo, int(workers or os.cpu_count() or 1), timeout_s, case_log, finished)


def _run_ray(todo, workers, timeout_s, address, case_log, finished):
    from vehicle_sim.sweep.ray_tasks import run_ray
    run_ray(todo, workers, timeout_s, address, case_log, finished)


def _require_ray():
    from vehicle_sim.sweep.ray_tasks import require_ray
    require_ray()


def _connect_ray(address, timeout_s):
    from vehicle_sim.sweep.ray_tasks import check_address, DEFAULT_CONNECT_TIMEOUT_S
    check_address(address, timeout_s or DEFAULT_CONNECT_TIMEOUT_S)


register_backend(Backend('local', _run_local, doc='worker processes on this machine'))
register_backend(Backend('ray', _run_ray, _require_ray, _connect_ray, doc='Ray tasks'))


@dataclass
class SweepResult:
    """
    The outcome of a sweep.

    :param records: every finished case's record (dict), in grid order; this run's and, with
        resume, the earlier ones' (filled at the end; ``done`` and ``count`` while it runs).
    :param total: the number of cases in the grid.
    :param interrupted: Ctrl-C stopped it (the finished cases are in ``records`` and on disk).
    :param files: {'table': path, 'parquet': path, 'junit': path, 'plot': path} written.
    :param skipped: cases found in the folder and not run again (resume).
    """

    out_dir: str
    records: List[dict]
    total: int
    keys: List[str]
    interrupted: bool = False
    files: Dict[str, str] = field(default_factory=dict)
    skipped: int = 0
    notes: List[str] = field(default_factory=list)
    done: int = 0
    counts: Dict[str, int] = field(default_factory=dict)

    def add(self, record):
        """Count a finished case (its record goes in ``records`` at the end)."""
        self.done += 1
        self.counts[record['status']] = self.counts.get(record['status'], 0) + 1

    def count(self, status):
        """Return how many finished cases have this status ('pass', 'fail', 'error')."""
        return self.counts.get(status, 0)

    @property
    def passed(self):
        """Tell whether every case of the grid ran and passed."""
        return self.done == self.total and self.count('pass') == self.total


def _axes(sets):
    if isinstance(sets, dict):
        axes = []
        for key, values in sets.items():
            values = tuple(values) if isinstance(values, (list, tuple)) else (values,)
            if not values:
                raise SweepError(f'--set {key}: no values')
            axes.append(Axis(str(key), key_path(str(key)), values))
        return axes
    return [parse_set(text) for text in sets]


def _seeds(seeds):
    if seeds is None:
        return None
    if isinstance(seeds, str):
        return parse_seeds(seeds)
    seeds = [int(s) for s in seeds]
    return parse_seeds(','.join(str(s) for s in seeds)) if seeds else parse_seeds('')


@dataclass
class Plan:
    """A validated sweep: the scenario (absolute path, text, name), axes, seeds and cases."""

    source: str
    content: str
    name: str
    axes: List[Axis]
    seeds: Optional[List[int]]
    cases: List[Case]
    specs: Dict[str, object]


def plan(scenario, sets=(), seeds=None) -> Plan:
    """
    Read the scenario and validate its variants (grid.check_variants); nothing runs.

    :raises SweepError: an unreadable or invalid scenario, a bad ``--set`` or ``--seeds``.
    """
    from vehicle_sim.scenarios.schema import scenario_from_data
    from vehicle_sim.scenarios.yaml_lines import load_with_lines, ScenarioError
    source = os.path.abspath(str(scenario))
    try:
        with open(source, 'rb') as file:
            raw = file.read()
        content = raw.decode('utf-8')
    except (OSError, UnicodeDecodeError) as error:
        raise SweepError(f'{scenario}: cannot read: {getattr(error, "strerror", None) or error}'
                         ) from None
    try:
        data, lines = load_with_lines(content, source)
        base = scenario_from_data(data, lines, source)
    except ScenarioError as error:
        raise SweepError(str(error)) from None
    axes = _axes(sets)
    seed_list = _seeds(seeds)
    cases = build_cases(axes, seed_list, base.seed)
    specs = check_variants(data, lines, source, axes, cases, scenario_from_data)
    return Plan(source, content, base.name, axes, seed_list, cases, specs)


def run_sweep(scenario, sets=(), seeds=None, out_dir='sweep', workers=None, backend='local',
              ray_address=None, timeout_s=DEFAULT_TIMEOUT_S, resume=False, progress=None,
              plot=True, started=None, ray_connect_timeout_s=None) -> SweepResult:
    """
    Run a scenario for every combination of ``sets`` and ``seeds``; write the merged results.

    :param scenario: the scenario file.
    :param sets: ``['actors.0.speed=4,6', ...]`` (the CLI's ``--set``) or ``{'actors.0.speed':
        [4, 6], ...}``.
    :param seeds: None (the file's seed), ``'0:100'`` (0 to 99), or a list of ints.
    :param out_dir: the results folder (docs/sweeps.md: its layout).
    :param workers: parallel cases (local: worker processes; ray: tasks in flight); None = the
        CPUs (of this machine, or of the Ray cluster).
    :param backend: a name of :data:`BACKENDS`: 'local' or 'ray'.
    :param ray_address: the Ray cluster to join (``ray.init(address=...)``); None starts Ray
        here (unless it is already initialised in this process).
    :param timeout_s: a case's longest run (wall clock); past it the case is an error; None =
        no limit.
    :param resume: skip the cases whose records are in ``out_dir`` already.
    :param progress: ``progress(record, result)`` after each case (``result`` a SweepResult so
        far), e.g. :class:`~.progress.Progress`.
    :param plot: write summary.png when matplotlib imports.
    :param started: ``started(result)`` once the input is valid, before the first case runs.
    :param ray_connect_timeout_s: how long joining the cluster at ``ray_address`` may take;
        None = ``ray_tasks.DEFAULT_CONNECT_TIMEOUT_S`` (30 s).
    :raises SweepError: bad input (nothing has run), an address where no Ray cluster answers
        within ``ray_connect_timeout_s`` among them.
    """
    if backend not in BACKENDS:
        raise SweepError(f'--backend {backend!r}: one of {", ".join(BACKENDS)}')
    if workers is not None and not 1 <= int(workers) <= MAX_WORKERS:
        raise SweepError(f'--workers {workers}: must be 1 .. {MAX_WORKERS}')
    if timeout_s is not None and not 0 < timeout_s < float('inf'):
        raise SweepError(f'--timeout {timeout_s}: must be > 0 s')
    chosen = BACKENDS[backend]
    if ray_address is not None and chosen.connect is None:
        raise SweepError('--ray-address needs --backend '
                         + ' or '.join(b.name for b in BACKENDS.values() if b.connect))
    if ray_connect_timeout_s is not None and not 0 < ray_connect_timeout_s < float('inf'):
        raise SweepError(f'--ray-connect-timeout {ray_connect_timeout_s}: must be > 0 s')
    if chosen.check is not None:
        chosen.check()
    planned = plan(scenario, sets, seeds)
    if ray_address is not None:
        chosen.connect(ray_address, ray_connect_timeout_s)
    source, content, cases = planned.source, planned.content, planned.cases
    keys = [axis.key for axis in planned.axes]
    manifest = {'scenario': source,
                'scenario_sha256': hashlib.sha256(content.encode()).hexdigest(),
                'sets': [[axis.key, list(axis.values)] for axis in planned.axes],
                'seeds': planned.seeds}
    existing = results.prepare(out_dir, manifest, resume)
    ids = {case.case_id for case in cases}
    done_records = {i: r for i, r in existing.items() if i in ids}
    result = SweepResult(out_dir, [], len(cases), keys, skipped=len(done_records))
    for record in done_records.values():
        result.add(record)
    from vehicle_sim.sweep.worker import payload
    todo = [payload(case, source, content) for case in cases
            if case.case_id not in done_records]

    def finished(record):
        results.save_record(out_dir, record)
        done_records[record['case_id']] = record
        result.add(record)
        if progress is not None:
            progress(record, result)

    if started is not None:
        started(result)

    def case_log(work):
        return results.log_path(out_dir, work['case_id'])

    try:
        if todo:
            chosen.run(todo, workers, timeout_s, ray_address, case_log, finished)
    except KeyboardInterrupt:
        result.interrupted = True
    result.records = _ordered(cases, done_records)
    _write_reports(result, planned.name, source, plot)
    return result


def _ordered(cases, records):
    return [records[c.case_id] for c in cases if c.case_id in records]


def _write_reports(result, name, source, plot):
    out_dir = result.out_dir
    written = results.write_table(out_dir, result.records, result.keys)
    result.files['table'] = written[0]
    if len(written) > 1:
        result.files['parquet'] = written[1]
    result.files['junit'] = results.write_junit(out_dir, result.records, name, source)
    if plot and result.records:
        from vehicle_sim.sweep.plot import plot_summary, PlotUnavailable
        try:
            result.files['plot'] = plot_summary(out_dir, result.records, result.keys, name)
        except PlotUnavailable as error:
            result.notes.append(str(error))
