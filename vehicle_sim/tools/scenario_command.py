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
``vehicle-sim scenario FILE``: run a scenario file headless and judge it (docs/scenarios.md).

Prints each criterion with its measured value, optionally writes JUnit XML (``--junit``) and a
trajectory plot (``--plot``, needs matplotlib). Exit status: 0 when every criterion passes, 1
when one fails or the run itself failed (a controller raised, a process died), 2 for a usage
error, an invalid scenario file or ``--plot`` without matplotlib.
"""

import math
import os
import signal
import sys
import threading
import time

from vehicle_sim.tools.command import CliError, EXIT_FAILURE, EXIT_OK, EXIT_USAGE
from vehicle_sim.tools.foxglove_options import add_arguments as add_foxglove_arguments
from vehicle_sim.tools.foxglove_options import live_view_address

BAR_WIDTH = 30
BAR_PERIOD_S = 0.1          # a tty progress bar redraws at most this often (wall clock)
PLAIN_STEPS = 4             # elsewhere, a line at each quarter of the duration
MAX_REPEAT = 1000           # --repeat: so that one command cannot run for ever


def add_arguments(parser):
    """Add the ``scenario`` arguments to its sub-parser."""
    parser.add_argument('file', metavar='FILE', help='scenario file (.yaml)')
    parser.add_argument('--junit', metavar='OUT.xml', help="write JUnit XML (pytest's format)")
    parser.add_argument('--seed', type=int, metavar='N', help="override the file's seed")
    parser.add_argument('--gui', action='store_true', help="open PyBullet's window")
    parser.add_argument('--plot', metavar='OUT.png', help='write a trajectory plot (matplotlib)')
    parser.add_argument('--repeat', type=int, default=1, metavar='N',
                        help='run N times and report the spread of the measured values '
                             '(external processes are not deterministic)')
    parser.add_argument('--no-progress', action='store_true', help='no progress display')
    add_foxglove_arguments(parser)
    parser.add_argument('--no-wait-client', action='store_true',
                        help='with --foxglove: start at once (by default the run waits for a '
                             'Foxglove client to connect before its first step)')
    parser.add_argument('--real-time-factor', type=float, metavar='F',
                        help='simulated seconds per wall-clock second, 0 = as fast as possible '
                             '(default: 1 with --foxglove, else as fast as possible; an '
                             "external driver: its file's real_time_factor); the results do "
                             'not depend on it')
    parser.add_argument('--record', metavar='FILE.mcap',
                        help='record every topic of the run into an MCAP file (the simulation '
                             'is served over ROS; with --repeat, the last run)')


class ScenarioProgress:
    """A scenario run's progress: a bar on a terminal, a line per quarter elsewhere."""

    def __init__(self, stream, name):
        self.stream = stream
        self.name = name
        self.tty = stream.isatty()
        self._last = 0.0
        self._quarter = 0

    def __call__(self, time_s, duration_s):
        fraction = min(1.0, time_s / duration_s)
        if self.tty:
            now = time.monotonic()
            if now - self._last < BAR_PERIOD_S and fraction < 1.0:
                return
            self._last = now
            filled = int(round(fraction * BAR_WIDTH))
            self.stream.write(f'\r{self.name} [{"#" * filled}{"." * (BAR_WIDTH - filled)}] '
                              f'{time_s:7.2f} / {duration_s:g} s')
            self.stream.flush()
        elif fraction >= (self._quarter + 1) / PLAIN_STEPS - 1e-9:
            self._quarter = int(fraction * PLAIN_STEPS + 1e-9)
            print(f'{self.name}: t = {time_s:.2f} / {duration_s:g} s', file=self.stream)

    def done(self):
        if self.tty:
            self.stream.write('\n')
            self.stream.flush()


def _shown(value):
    return '-' if value is None else f'{value:.4g}'


def report_lines(result):
    """Return the printed report of a ScenarioResult: one line per criterion, then the verdict."""
    lines = []
    for criterion in result.criteria:
        mark = 'PASS' if criterion.passed else 'FAIL'
        value = ('-' if criterion.value is None else
                 f'{criterion.value:.4g} {criterion.unit}'.strip())
        line = f'  {mark}  {criterion.name}: {value}  ({criterion.detail})'
        if result.spread and criterion.name in result.spread:
            low, high = result.spread[criterion.name]
            line += f' [over {result.runs} runs: min {_shown(low)}, max {_shown(high)}]'
        lines.append(line)
    lines.extend(f'  note: {note}' for note in result.notes)
    if result.error:
        lines.append(f'  ERROR run: {result.error}')
    passed = sum(c.passed for c in result.criteria)
    verdict = 'PASS' if result.passed else 'FAIL'
    lines.append(f'{verdict}: {passed}/{len(result.criteria)} criteria passed; '
                 f'{result.sim_time_s:g} s simulated in {result.wall_time_s:.2f} s; '
                 f'odometry sha256 {result.odometry_sha256[:16]}')
    if not result.deterministic:
        lines.append('note: an external controller drives this scenario: runs are not '
                     'deterministic (use --repeat N for the spread)')
    return lines


def prepare_output(path, option):
    """
    Make ``path``'s folder (as pytest's ``--junitxml`` does) before the run, or refuse at once.

    :param path: the file ``--junit`` or ``--plot`` will write.
    :param option: the option's name, for the message.
    :raises CliError: (exit 2) when the file cannot be written there; nothing has run yet.
    """
    folder = os.path.dirname(os.path.abspath(path))
    if os.path.isdir(path):
        raise CliError(f'{option} {path}: is a folder, not a file', EXIT_USAGE)
    try:
        os.makedirs(folder, exist_ok=True)
    except OSError as error:
        raise CliError(f'{option} {path}: cannot create its folder: {error.strerror}',
                       EXIT_USAGE) from None
    if not os.access(folder, os.W_OK | os.X_OK) or (
            os.path.exists(path) and not os.access(path, os.W_OK)):
        raise CliError(f'{option} {path}: not writable', EXIT_USAGE)


def _pace(args, spec, live_view):
    """
    Return the run's real-time factor: ``--real-time-factor``, 1 for a watched run, or None.

    None: the scenario's own pace (an external driver's ``real_time_factor``, else as fast as
    possible).

    :raises CliError: a factor that is not a finite number >= 0, or one that would make the run
        last longer than a scenario may (as the file's ``real_time_factor``).
    """
    from vehicle_sim.scenarios.driver_schema import MAX_DURATION_S
    factor = args.real_time_factor
    if factor is None:       # a watched run at real time; an external driver at its own
        return 1.0 if live_view is not None and spec.driver.kind != 'processes' else None
    if not (math.isfinite(factor) and factor >= 0.0):
        raise CliError(f'--real-time-factor {factor:g}: must be a number >= 0 (0 = as fast as '
                       'possible)', EXIT_USAGE)
    if factor > 0.0 and spec.duration_s / factor > MAX_DURATION_S:
        raise CliError(f'--real-time-factor {factor:g}: the {spec.duration_s:g} s scenario '
                       f'would last {spec.duration_s / factor:g} s of wall clock; at most '
                       f'{MAX_DURATION_S:g} s', EXIT_USAGE)
    return factor


def _waiting(url):
    print(f'waiting for a Foxglove client on {url} (Foxglove app: Open connection, Foxglove '
          'WebSocket; --no-wait-client starts at once)', file=sys.stderr, flush=True)


def _exit_on_sigterm():
    if threading.current_thread() is threading.main_thread():
        def handler(signum, frame):
            raise SystemExit(128 + signum)
        signal.signal(signal.SIGTERM, handler)


def cmd_scenario(args) -> int:
    """Run ``vehicle-sim scenario``."""
    from vehicle_sim.recording.bag_writer import RecordingError
    from vehicle_sim.scenarios.runner import run_scenario
    from vehicle_sim.scenarios.schema import load_scenario
    from vehicle_sim.scenarios.yaml_lines import ScenarioError
    if not 1 <= args.repeat <= MAX_REPEAT:
        raise CliError(f'--repeat {args.repeat}: must be 1 .. {MAX_REPEAT}', EXIT_USAGE)
    if args.seed is not None and args.seed < 0:
        raise CliError(f'--seed {args.seed}: must be >= 0', EXIT_USAGE)
    if args.plot:
        from vehicle_sim.scenarios.plot import PlotUnavailable, require
        try:
            require()
        except PlotUnavailable as error:
            raise CliError(str(error), EXIT_USAGE) from None
    try:
        spec = load_scenario(args.file)
    except ScenarioError as error:
        raise CliError(str(error), EXIT_USAGE) from None
    for option, path in (('--junit', args.junit), ('--plot', args.plot),
                         ('--record', args.record)):
        if path:
            prepare_output(path, option)
    live_view = live_view_address(args)
    pace = _pace(args, spec, live_view)
    if args.no_wait_client and live_view is None:
        raise CliError('--no-wait-client needs --foxglove [PORT]', EXIT_USAGE)
    if args.record:
        from vehicle_sim.recording.bag_writer import require_mcap
        try:
            require_mcap()
        except RecordingError as error:
            raise CliError(f'--record: {error}', EXIT_USAGE) from None
    seed = spec.seed if args.seed is None else args.seed
    print(f'scenario {spec.name} ({args.file}), seed {seed}, {spec.duration_s:g} s, driver: '
          f'{spec.driver.kind}')
    progress = None if args.no_progress else ScenarioProgress(sys.stderr, spec.name)
    _exit_on_sigterm()      # so that the driver's processes are stopped on the way out
    try:
        result = run_scenario(spec, seed=args.seed, gui=args.gui, progress=progress,
                              repeat=args.repeat, foxglove=live_view, record=args.record,
                              real_time_factor=pace,
                              wait_for_client=None if args.no_wait_client else _waiting)
    except ScenarioError as error:
        raise CliError(str(error), EXIT_FAILURE) from None
    except RecordingError as error:
        raise CliError(f'--record: {error}', EXIT_USAGE) from None
    finally:
        if progress is not None:
            progress.done()
    for line in report_lines(result):
        print(line)
    if args.record:
        print(f'recorded {args.record}' + ('' if result.passed else
                                           f' (replay it: vehicle-sim play {args.record})'))
    if args.junit:
        from vehicle_sim.scenarios.junit import write_junit
        write_junit(result, args.junit)
        print(f'wrote {args.junit}')
    if args.plot:
        from vehicle_sim.scenarios.plot import plot_result
        plot_result(result, args.plot)
        print(f'wrote {args.plot}')
    return EXIT_OK if result.passed else EXIT_FAILURE
