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
``vehicle-sim sweep SCENARIO --set key=v1,v2 ... --out DIR``: a scenario over a grid.

The scenario runs for every combination of values and seeds, in parallel, with one merged
report (docs/sweeps.md).

Exit status: 0 every case passed; 1 a case failed or errored; 2 bad input (a ``--set``, the
scenario, the folder, a ``--ray-address`` where no Ray answers; nothing ran); 130 stopped by
Ctrl-C (the finished cases are kept and merged; ``--resume`` runs the rest).
"""

import sys

from vehicle_sim.tools.command import CliError, EXIT_FAILURE, EXIT_OK, EXIT_USAGE

EXIT_INTERRUPTED = 130


def add_arguments(parser):
    """Add the ``sweep`` arguments to its sub-parser."""
    from vehicle_sim.sweep.ray_tasks import DEFAULT_CONNECT_TIMEOUT_S
    from vehicle_sim.sweep.run import BACKENDS, DEFAULT_TIMEOUT_S
    parser.add_argument('scenario', metavar='SCENARIO', help='scenario file (.yaml)')
    parser.add_argument('--set', dest='sets', action='append', default=[],
                        metavar='KEY=V1,V2,...',
                        help='a scenario key (dotted path, e.g. actors.0.speed) and its values '
                             '(YAML scalars); repeat for a grid of every combination')
    parser.add_argument('--seeds', metavar='A:B',
                        help="seeds A to B-1 (or N,N,...) for every combination (default: the "
                             "file's seed)")
    parser.add_argument('--workers', type=int, metavar='N',
                        help='cases run at once (default: the CPUs)')
    parser.add_argument('--backend', choices=tuple(BACKENDS), default='local',
                        help='where the cases run: ' + '; '.join(
                            f'{b.name}: {b.doc}' for b in BACKENDS.values()) + ' (default local)')
    parser.add_argument('--ray-address', metavar='ADDR',
                        help='join this Ray cluster (e.g. auto, ray://head:10001); default: '
                             'start Ray here')
    parser.add_argument('--ray-connect-timeout', type=float, metavar='S',
                        help='how long joining the cluster at --ray-address may take (default '
                             f'{DEFAULT_CONNECT_TIMEOUT_S:g} s); past it the sweep exits 2')
    parser.add_argument('--timeout', type=float, default=DEFAULT_TIMEOUT_S, metavar='S',
                        help=f'longest run of one case, wall clock (default {DEFAULT_TIMEOUT_S:g}'
                             ' s); past it the case is an error')
    parser.add_argument('--out', required=True, metavar='DIR', help='results folder')
    parser.add_argument('--resume', action='store_true',
                        help='skip the cases whose results are in DIR already')
    parser.add_argument('--no-progress', action='store_true', help='no progress display')


def cmd_sweep(args) -> int:
    """Run ``vehicle-sim sweep``."""
    from vehicle_sim.sweep.grid import SweepError
    from vehicle_sim.sweep.progress import Progress
    from vehicle_sim.sweep.run import run_sweep
    shown = None

    def progress(record, result):
        nonlocal shown
        if shown is None:
            shown = Progress(sys.stderr, result.total, result.skipped)
        shown(record, result)

    def started(result):
        print(f'sweep {args.scenario}: {result.total} cases, backend {args.backend}'
              + (f'; {result.skipped} done already (--resume)' if result.skipped else ''),
              flush=True)

    try:
        result = run_sweep(args.scenario, args.sets, args.seeds, args.out, args.workers,
                           args.backend, args.ray_address, args.timeout, args.resume,
                           None if args.no_progress else progress, started=started,
                           ray_connect_timeout_s=args.ray_connect_timeout)
    except SweepError as error:
        raise CliError(str(error), EXIT_USAGE) from None
    finally:
        if shown is not None:
            shown.done()
    print(f'{result.count("pass")} passed, {result.count("fail")} failed, '
          f'{result.count("error")} errors of {result.total} cases')
    for record in result.records:
        if record['status'] == 'error':
            first = record['error'].strip().splitlines()[0] if record['error'].strip() else ''
            print(f'  ERROR {record["label"]}: {first} (log: {args.out}/logs/'
                  f'{record["case_id"]}.log)')
    for note in result.notes:
        print(f'note: {note}')
    for path in result.files.values():
        print(f'wrote {path}')
    if result.interrupted:
        print(f'interrupted: {len(result.records)} of {result.total} cases kept; --resume runs '
              'the others', file=sys.stderr)
        return EXIT_INTERRUPTED
    return EXIT_OK if result.passed else EXIT_FAILURE
