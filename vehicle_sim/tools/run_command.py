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

"""``vehicle-sim run``: the automobile node on the embedded transport, with a live status line."""

import os
import sys
import time
from typing import Any, Dict, Optional

from vehicle_sim.tools.command import CliError, EXIT_USAGE

STATUS_PERIOD_S = 0.2
PLAIN_STATUS_PERIOD_S = 1.0
# How often the node checks whether the status line is due [s] (wall clock).
STATUS_POLL_S = 0.05

_MODES = {-1: 'UNDEFINED', 0: 'SPEED', 1: 'TORQUE'}
_INDICATORS = {0: 'off', 1: 'right', 2: 'left'}


def status_line(time_s: float, status, factor: Optional[float] = None) -> str:
    """
    Return the one-line status of a car.

    :param time_s: simulated time [s].
    :param status: a ``CarStatus`` (vehicle_sim.core.car.logic).
    :param factor: the real-time factor the node achieved over the last second (simulated
        time per wall time); None before the first second: shown as '-'.
    """
    mode = _MODES.get(int(status.control_mode), str(status.control_mode))
    if status.hazard_flashers:
        indicator = 'hazard'
    else:
        indicator = _INDICATORS.get(int(status.indicator), str(status.indicator))
    lit = [side for side, on in (('L', status.left_indicator_light),
                                 ('R', status.right_indicator_light)) if on]
    if lit:
        indicator += ' [' + ''.join(lit) + ']'
    rpm = f'{status.rpm:6.0f}' if int(status.control_mode) == 1 else '     -'
    speed = round(status.current_speed_kmh, 2) + 0.0   # no '-0.00' for a car at rest
    achieved = '      -' if factor is None else f'{factor:6.2f}x'
    return (f't {time_s:9.2f} s | {speed:7.2f} km/h | rpm {rpm} | '
            f'gear {status.gear:2d} | {mode:<9} | indicator {indicator} | '
            f'real time {achieved}')


class _StatusOutput:
    """
    Live status: one refreshed line on a terminal, periodic plain lines otherwise.

    On a terminal the status line stays the last line: while it is installed, whatever is
    written to ``sys.stdout`` or ``sys.stderr`` (log lines) first erases it, starts at column 0,
    and the status is drawn again below once the line is complete.

    :param enabled: False for ``--no-status``.
    :param stdout: the output stream (default ``sys.stdout``).
    :param stderr: the error stream (default ``sys.stderr``).
    """

    def __init__(self, enabled: bool, stdout=None, stderr=None):
        self.enabled = enabled
        self._stdout = sys.stdout if stdout is None else stdout
        self._stderr = sys.stderr if stderr is None else stderr
        if self._stderr.isatty():
            self.stream, self.live = self._stderr, True
        elif self._stdout.isatty():
            self.stream, self.live = self._stdout, True
        else:
            self.stream, self.live = self._stdout, False
        self.period_s = STATUS_PERIOD_S if self.live else PLAIN_STATUS_PERIOD_S
        self._next = 0.0
        self._line = ''          # the status line last rendered
        self._shown = False      # it is on the screen now
        self._open_line = False  # another writer left a line without its newline
        self._saved = None

    def install(self) -> None:
        """Route ``sys.stdout`` and ``sys.stderr`` around the live status line."""
        if self.enabled and self.live and self._saved is None:
            # Only streams on the terminal share its line; a redirected one is left alone.
            self._saved = (sys.stdout, sys.stderr)
            if self._stdout.isatty():
                sys.stdout = _AroundStatus(self._stdout, self)
            if self._stderr.isatty():
                sys.stderr = _AroundStatus(self._stderr, self)

    def maybe_show(self, now_s: float, render) -> None:
        if not self.enabled or now_s < self._next:
            return
        self._next = now_s + self.period_s
        line = render()
        if self.live:
            if self._open_line:
                self.stream.write('\n')
                self._open_line = False
            self._erase()
            self._line = line
            self._draw()
        else:
            self.stream.write(line + '\n')
        self.stream.flush()

    def _draw(self) -> None:
        self.stream.write('\r' + self._line)
        self._shown = True

    def _erase(self) -> None:
        if self._shown:
            self.stream.write('\r' + ' ' * len(self._line) + '\r')
            self._shown = False

    def before_write(self) -> None:
        """Clear the status line so that another writer starts at column 0."""
        if self._shown:
            self._erase()
            self.stream.flush()

    def after_write(self, text: str) -> None:
        """Draw the status line again below a completed line."""
        if not text:
            return
        self._open_line = not text.endswith('\n')
        if not self._open_line and self._line:
            self._draw()
            self.stream.flush()

    def finish(self) -> None:
        if self._saved is not None:
            sys.stdout, sys.stderr = self._saved
            self._saved = None
        if self.enabled and self.live and (self._shown or self._open_line):
            self.stream.write('\n')
            self.stream.flush()
            self._shown = self._open_line = False


class _AroundStatus:
    """A text stream that writes around the live status line of a :class:`_StatusOutput`."""

    def __init__(self, stream, status: _StatusOutput):
        self._stream = stream
        self._status = status

    def write(self, text: str) -> int:
        self._status.before_write()
        count = self._stream.write(text)
        self._stream.flush()
        self._status.after_write(text)
        return count

    def __getattr__(self, name):
        return getattr(self._stream, name)


def _ros_arguments(after):
    """
    Return the ROS arguments given after ``--``; anything else there is refused.

    The node would ignore it without a word (``-- -p friction:=2`` sets nothing: ``-p`` is a
    ROS argument only inside ``--ros-args``).
    """
    from vehicle_sim.transport import TransportError
    from vehicle_sim.transport.ros_args import parse_ros_args
    ros_args = list(after or [])
    if ros_args and ros_args[0] == '--':
        ros_args = ros_args[1:]
    try:
        stray = parse_ros_args(ros_args).non_ros_args
    except TransportError as error:
        raise CliError(str(error), EXIT_USAGE) from None
    if stray:
        raise CliError(f"arguments after '--' must be ROS arguments after --ros-args, e.g. "
                       f"'-- --ros-args -p friction:=2'; not understood: {' '.join(stray)}",
                       EXIT_USAGE)
    return ros_args


def _config_file(subdir, option, value):
    """Check ``--car``/``--world`` before the node joins the graph; return the value."""
    from vehicle_sim.config import find_config
    from vehicle_sim.core.specs.errors import InvalidParameterError
    try:
        find_config(subdir, value)
    except InvalidParameterError as error:
        raise CliError(f'{option} {value}: {error}', EXIT_USAGE) from None
    return value


def cmd_run(args) -> int:
    """
    Run the automobile node through the transport's ``run_node``, as the node mains do.

    So SIGINT/SIGTERM are handled from before anything is built: a signal during start-up
    abandons it and leaves nothing on the graph; a signal while running ends the spin and the
    node leaves the graph (exit 0). The status line and ``--duration`` are timers of the node.
    """
    from vehicle_sim.core.specs.errors import VehicleSimError
    from vehicle_sim.ros.automobile_node import AutomobileNode
    from vehicle_sim.tools.foxglove_options import live_view_address
    from vehicle_sim.transport import run_node
    ros_args = _ros_arguments(args.ros_args)
    overrides: Dict[str, Any] = {}
    if args.car:
        overrides['car_model'] = _config_file('cars', '--car', args.car)
    if args.world:
        overrides['world'] = _config_file('worlds', '--world', args.world)
    if args.real_time_factor is not None:
        overrides['real_time_factor'] = float(args.real_time_factor)
    if args.synchronous:
        overrides['synchronous'] = True
    if args.duration is not None and args.duration < 0:
        raise CliError('--duration must be >= 0', EXIT_USAGE)
    if args.gui:
        from vehicle_sim.physics.gui import gui_unavailable_reason
        reason = gui_unavailable_reason()   # before the node joins the graph
        if reason is not None:
            raise CliError(f'--gui: {reason}', EXIT_USAGE)
        overrides['gui'] = True
    live_view = live_view_address(args)   # before the node joins the graph
    if live_view is not None:
        overrides['foxglove_host'], overrides['foxglove'] = live_view
    # The CLI runs on the embedded transport unless the user asked for another one.
    transport = os.environ.get('VEHICLE_SIM_TRANSPORT') or 'dds'
    record = getattr(args, 'record', None)
    if record:
        from vehicle_sim.recording.bag_writer import check_output, RecordingError, require_mcap
        try:
            check_output(record)        # before the node joins the graph
            require_mcap()
        except RecordingError as error:
            raise CliError(f'--record: {error}', EXIT_USAGE) from None
    recorders = []
    output = _StatusOutput(not args.no_status)

    def render(app):
        vehicles = app.vehicles
        if not vehicles:
            return f't {app.world.time_s:9.2f} s | no vehicle'
        namespace = '' if '' in vehicles else sorted(vehicles)[0]
        line = status_line(app.world.time_s, vehicles[namespace].logic.status(),
                           app.achieved_real_time_factor)
        if len(vehicles) > 1:
            line = f'[{namespace or "/"} +{len(vehicles) - 1}] ' + line
        return line

    def build(node_args):
        try:
            node = None
            if record:
                node = _recorded_node(node_args, transport, overrides, record, recorders)
            app = AutomobileNode(node_args, transport=transport, parameter_overrides=overrides,
                                 node=node)
        except (VehicleSimError, ValueError) as exc:
            for recorder in recorders:
                recorder.close()
            raise CliError(str(exc), EXIT_USAGE) from None
        node = app.node
        if output.enabled:
            output.install()
            node.create_timer(STATUS_POLL_S,
                              lambda: output.maybe_show(time.monotonic(), lambda: render(app)))
        if args.duration is not None:
            if args.duration == 0.0:
                node.request_shutdown()
            else:
                def stop():
                    timer.cancel()
                    node.request_shutdown()
                timer = node.create_timer(args.duration, stop)
        return app

    # As for the node mains, run_node shuts the node down (it leaves the graph); the world goes
    # with the process (closing the app after that would touch the destroyed node's timers).
    try:
        return run_node(build, ['vehicle-sim', *ros_args], transport=transport)
    finally:
        output.finish()
        for recorder in recorders:
            recorder.close()
            print(recorder.summary(), file=sys.stderr)


def _recorded_node(node_args, transport, overrides, path, recorders):
    """Create the automobile node with its publishers tapped into a recording of ``path``."""
    from vehicle_sim.recording.recorder import record_node
    from vehicle_sim.ros.automobile_node import NODE_NAME
    from vehicle_sim.transport import create_node
    node = create_node(NODE_NAME, args=node_args, transport=transport,
                       parameter_overrides=overrides)
    try:
        recorders.append(record_node(node, path))
    except BaseException:
        node.shutdown()
        raise
    return node
