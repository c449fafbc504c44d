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
The ``vehicle-sim`` command: run the simulator and talk to a ROS 2 graph without ROS installed.

Subcommands (``vehicle-sim <command> --help`` for details)::

    run                 start the automobile node (embedded transport) with a live status line
    list                nodes, topics and services seen on the graph
    echo TOPIC          print the messages of a topic (like ``ros2 topic echo``)
    call SERVICE VALUE  call a service (like ``ros2 service call``)
    param get|set|list  the rcl_interfaces parameter services of a node (like ``ros2 param``)
    export-interfaces   write the vehicle_msgs ament package for a ROS workspace
    demo                run the end-to-end scenario and write a PNG of the paths

Everything talks over the embedded Cyclone DDS transport, with ``ROS_DOMAIN_ID`` and
``ROS_AUTOMATIC_DISCOVERY_RANGE`` honoured like a ROS 2 node does (reference/ros2_wire.md).
Exit codes: 0 success, 1 runtime failure (unknown name, timeout, rejected value), 2 usage error.
"""

import argparse
import dataclasses
import math
import os
import signal
import sys
import threading
import time
import typing
from typing import Any, Dict, List, Optional, Sequence

import yaml

EXIT_OK = 0
EXIT_FAILURE = 1
EXIT_USAGE = 2
DEFAULT_DISCOVERY_WAIT_S = 3.0
DEFAULT_LIST_WAIT_S = 1.5
DEFAULT_CALL_TIMEOUT_S = 5.0
STATUS_PERIOD_S = 0.2
PLAIN_STATUS_PERIOD_S = 1.0
# Fields generated for empty messages (ros2_wire A2); never shown, never set.
_HIDDEN_FIELDS = ('structure_needs_at_least_one_member',)
_INT_RANGES = {
    'int8': (-2 ** 7, 2 ** 7 - 1), 'uint8': (0, 2 ** 8 - 1),
    'int16': (-2 ** 15, 2 ** 15 - 1), 'uint16': (0, 2 ** 16 - 1),
    'int32': (-2 ** 31, 2 ** 31 - 1), 'uint32': (0, 2 ** 32 - 1),
    'int64': (-2 ** 63, 2 ** 63 - 1), 'uint64': (0, 2 ** 64 - 1),
}


class CliError(Exception):
    """A failure reported to the user as one message and a non-zero exit status."""

    def __init__(self, message: str, status: int = EXIT_FAILURE):
        super().__init__(message)
        self.status = status


# --------------------------------------------------------------------------------------------
# Messages as plain data (the YAML-ish view of ``ros2 topic echo``)

def to_plain(msg: Any) -> Any:
    """Return a message as nested dicts/lists/scalars in field order (for YAML output)."""
    if dataclasses.is_dataclass(msg) and not isinstance(msg, type):
        return {f.name: to_plain(getattr(msg, f.name)) for f in dataclasses.fields(msg)
                if f.name not in _HIDDEN_FIELDS}
    if isinstance(msg, (bytes, bytearray)):
        return list(msg)
    if isinstance(msg, (list, tuple)):
        return [to_plain(v) for v in msg]
    if hasattr(msg, 'get_fields_and_field_types'):  # an rclpy message
        return {name: to_plain(getattr(msg, name)) for name in msg.get_fields_and_field_types()}
    if hasattr(msg, 'tolist'):  # numpy arrays of rclpy messages
        return msg.tolist()
    return msg


class _OrderedDumper(yaml.SafeDumper):
    pass


def _represent_dict(dumper, data):
    return dumper.represent_mapping('tag:yaml.org,2002:map', data.items())


def _represent_float(dumper, value):
    if math.isnan(value):
        text = '.nan'
    elif math.isinf(value):
        text = '.inf' if value > 0 else '-.inf'
    else:
        text = repr(float(value))
    return dumper.represent_scalar('tag:yaml.org,2002:float', text)


_OrderedDumper.add_representer(dict, _represent_dict)
_OrderedDumper.add_representer(float, _represent_float)


def format_message(msg: Any) -> str:
    """Return a message as YAML (fields in definition order), like ``ros2 topic echo``."""
    plain = to_plain(msg)
    if not isinstance(plain, dict):
        plain = {'data': plain}
    return yaml.dump(plain, Dumper=_OrderedDumper, default_flow_style=False, sort_keys=False,
                     allow_unicode=True, width=1000)


def _field_shape(annotation) -> tuple:
    """
    Describe a field annotation of a generated type.

    :return: ``('message', cls)``, ``('list', element_annotation)`` or ``('scalar', py, name)``.
    """
    args = typing.get_args(annotation)
    if typing.get_origin(annotation) is typing.Annotated or (
            args and not dataclasses.is_dataclass(annotation)):
        base = args[0] if args else annotation
        meta = args[1] if len(args) > 1 else None
        if typing.get_origin(base) in (list, tuple, Sequence, typing.Sequence) or \
                str(typing.get_origin(base)) == "<class 'collections.abc.Sequence'>":
            return ('list', typing.get_args(base)[0])
        if isinstance(meta, str):
            return ('scalar', base, meta)
        return _field_shape(base)
    if dataclasses.is_dataclass(annotation):
        return ('message', annotation)
    if annotation in (bool, int, float, str):
        return ('scalar', annotation, annotation.__name__)
    return ('scalar', annotation, str(annotation))


def _coerce_scalar(value: Any, py_type, type_name: str, where: str) -> Any:
    if py_type is bool:
        if isinstance(value, bool):
            return value
        raise CliError(f'{where}: expected a boolean (true/false), got {value!r}')
    if py_type is int:
        if isinstance(value, bool) or not isinstance(value, int):
            if isinstance(value, float) and value.is_integer():
                value = int(value)
            else:
                raise CliError(f'{where}: expected an integer ({type_name}), got {value!r}')
        low, high = _INT_RANGES.get(type_name, (None, None))
        if low is not None and not low <= value <= high:
            raise CliError(f'{where}: {value} outside the {type_name} range {low}..{high}')
        return value
    if py_type is float:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise CliError(f'{where}: expected a number ({type_name}), got {value!r}')
        return float(value)
    if py_type is str:
        return value if isinstance(value, str) else yaml.safe_dump(value).strip()
    return value


def _coerce(value: Any, annotation, where: str) -> Any:
    shape = _field_shape(annotation)
    if shape[0] == 'message':
        return from_plain(shape[1], value, where)
    if shape[0] == 'list':
        if not isinstance(value, (list, tuple)):
            raise CliError(f'{where}: expected a list, got {value!r}')
        return [_coerce(v, shape[1], f'{where}[{i}]') for i, v in enumerate(value)]
    return _coerce_scalar(value, shape[1], shape[2], where)


def from_plain(cls, data: Any, where: str = 'request'):
    """
    Build a generated message from a dict (YAML), checking every field's type.

    :raises CliError: for an unknown field or a value of the wrong type.
    """
    if data is None:
        return cls()
    if not isinstance(data, dict):
        raise CliError(f'{where}: expected a mapping of fields, got {data!r}')
    fields = {f.name: f for f in dataclasses.fields(cls) if f.name not in _HIDDEN_FIELDS}
    hints = typing.get_type_hints(cls, include_extras=True)
    values = {}
    for key, value in data.items():
        if key not in fields:
            raise CliError(f'{where}: {cls.__ros_type__} has no field {key!r}; '
                           f'fields: {", ".join(fields) or "(none)"}')
        values[key] = _coerce(value, hints[key], f'{where}.{key}')
    return cls(**values)


def build_request(request_cls, value_text: Optional[str]):
    """
    Build a service request from the command-line VALUE.

    A YAML mapping (``"{value: 30}"``) sets fields by name; any other value sets the request's
    single field (``30`` for SetFloat, ``true`` for SetBool); no VALUE gives the defaults.
    """
    fields = [f.name for f in dataclasses.fields(request_cls) if f.name not in _HIDDEN_FIELDS]
    if value_text is None:
        return request_cls()
    try:
        value = yaml.safe_load(value_text)
    except yaml.YAMLError as exc:
        raise CliError(f'VALUE {value_text!r} is not valid YAML: {exc}') from None
    if isinstance(value, dict):
        return from_plain(request_cls, value)
    if len(fields) != 1:
        raise CliError(
            f'{request_cls.__ros_type__} has {len(fields)} fields ({", ".join(fields)}); '
            f'give VALUE as YAML, e.g. "{{{fields[0] if fields else "field"}: ...}}"')
    hints = typing.get_type_hints(request_cls, include_extras=True)
    shape = _field_shape(hints[fields[0]])
    if shape[0] == 'scalar' and shape[1] is str:
        value = value_text  # keep the text verbatim for string fields
    return from_plain(request_cls, {fields[0]: value})


# --------------------------------------------------------------------------------------------
# Shared helpers of the graph commands

def _absolute(name: str) -> str:
    return name if name.startswith('/') else '/' + name


def _hidden(name: str) -> bool:
    return any(token.startswith('_') for token in name.split('/') if token)


def _not_found(kind: str, name: str, candidates, wait_s: float) -> CliError:
    from vehicle_sim.graph import close_names
    close = close_names(name, candidates)
    hint = f'; did you mean: {", ".join(close)}' if close else ''
    return CliError(f'{kind} {name!r} not found on the graph after {wait_s:g} s '
                    f'(ROS_DOMAIN_ID={os.environ.get("ROS_DOMAIN_ID", "0")}){hint}')


class _Session:
    """The CLI's graph view and (created on demand) its hidden helper node."""

    def __init__(self):
        from vehicle_sim.graph import GraphView
        self.graph = GraphView()
        self._node = None

    @property
    def node(self):
        if self._node is None:
            from vehicle_sim.transport import dds
            from vehicle_sim.transport.selection import create_node
            self._node = create_node(
                f'_vehicle_sim_cli_{os.getpid()}', transport='dds',
                args=['--ros-args', '--disable-rosout-logs', '--log-level', 'warn'])
            self.graph.ignore_participant(dds.participant_guid())
        return self._node

    def close(self):
        if self._node is not None:
            self._node.shutdown()
        self.graph.close()

    def service_type(self, service: str, given: Optional[str], wait_s: float) -> str:
        if given:
            return _check_service_type(given)
        found = self.graph.wait_until(lambda: service in self.graph.services(), wait_s)
        if not found:
            raise _not_found('service', service, self.graph.services(), wait_s)
        types = sorted(self.graph.services()[service])
        if len(types) > 1:
            raise CliError(f'service {service} has several types ({", ".join(types)}); '
                           'pick one with --type')
        return _check_service_type(types[0])


def _check_service_type(srv_type: str) -> str:
    from vehicle_msgs_py import known_services
    from vehicle_msgs_py.types import normalize_type_name
    try:
        srv_type = normalize_type_name(srv_type)
    except ValueError as exc:
        raise CliError(str(exc)) from None
    srv_type = srv_type.replace('/msg/', '/srv/')
    if srv_type not in known_services():
        raise CliError(f'service type {srv_type} is not known to vehicle_sim '
                       f'(known: {", ".join(known_services())})')
    return srv_type


def _check_message_type(ros_type: str) -> str:
    from vehicle_msgs_py import known_types
    from vehicle_msgs_py.types import normalize_type_name
    try:
        ros_type = normalize_type_name(ros_type)
    except ValueError as exc:
        raise CliError(str(exc)) from None
    if ros_type not in known_types():
        from vehicle_sim.graph import close_names
        close = close_names(ros_type, known_types())
        hint = f'; did you mean: {", ".join(close)}' if close else ''
        raise CliError(f'message type {ros_type} is not known to vehicle_sim{hint}')
    return ros_type


def _call(node, srv_type: str, service: str, request, timeout_s: float):
    from vehicle_sim.transport.port import ServiceTimeoutError
    client = node.create_client(srv_type, service)
    if not client.wait_for_service(timeout_s):
        raise CliError(f'service {service} is not available (no matched server within '
                       f'{timeout_s:g} s)')
    try:
        return client.call(request, timeout_s)
    except ServiceTimeoutError:
        raise CliError(f'no reply from {service} within {timeout_s:g} s') from None


# --------------------------------------------------------------------------------------------
# list

def cmd_list(args) -> int:
    session = _Session()
    try:
        session.graph.wait(args.wait)
        graph = session.graph
        nodes = [n for n in graph.node_names() if args.all or not _hidden(n)]
        topics = {k: v for k, v in graph.topics().items() if args.all or not _hidden(k)}
        services = {k: v for k, v in graph.services().items() if args.all or not _hidden(k)}
        print('nodes:')
        for name in nodes:
            print(f'  {name}')
        print('topics:')
        for name in sorted(topics):
            print(f'  {name} [{", ".join(sorted(topics[name]))}]')
        print('services:')
        for name in sorted(services):
            print(f'  {name} [{", ".join(sorted(services[name]))}]')
    finally:
        session.close()
    return EXIT_OK


# --------------------------------------------------------------------------------------------
# echo

def cmd_echo(args) -> int:
    from vehicle_sim.transport.port import (
        BEST_EFFORT,
        QosProfile,
        RELIABLE,
        TRANSIENT_LOCAL,
        VOLATILE,
    )
    topic = _absolute(args.topic)
    count = 1 if args.once else args.count
    if count is not None and count < 1:
        raise CliError('--count must be >= 1', EXIT_USAGE)
    session = _Session()
    try:
        graph = session.graph
        if args.type:
            ros_type = _check_message_type(args.type)
            graph.wait_until(lambda: bool(graph.publishers(topic)), min(args.wait, 1.0))
        else:
            if not graph.wait_until(lambda: topic in graph.topics(), args.wait):
                raise _not_found('topic', topic, graph.topics(), args.wait)
            types = sorted(graph.topics()[topic])
            if len(types) > 1:
                raise CliError(f'topic {topic} has several types ({", ".join(types)}); '
                               'pick one with --type')
            ros_type = _check_message_type(types[0])
        # ros2 topic echo: reliable / transient local only when every publisher offers it.
        publishers = graph.publishers(topic)
        qos = QosProfile(
            depth=10,
            reliability=RELIABLE if all(p.reliable for p in publishers) else BEST_EFFORT,
            durability=(TRANSIENT_LOCAL if publishers and all(p.transient_local
                                                              for p in publishers)
                        else VOLATILE))
        received = []

        def on_message(msg):
            if count is not None and len(received) >= count:
                return
            received.append(msg)
            sys.stdout.write(format_message(msg) + '---\n')
            sys.stdout.flush()

        node = session.node
        node.create_subscription(ros_type, topic, on_message, qos)
        stop = _install_stop_handlers()
        deadline = None if args.timeout is None else time.monotonic() + args.timeout
        while not stop.is_set() and (count is None or len(received) < count):
            if deadline is not None and time.monotonic() >= deadline:
                raise CliError(f'no message on {topic} within {args.timeout:g} s'
                               if not received else
                               f'got {len(received)} of {count} messages on {topic} within '
                               f'{args.timeout:g} s')
            node.spin_once(0.05)
    finally:
        session.close()
    return EXIT_OK


def _install_stop_handlers() -> threading.Event:
    """Turn SIGINT/SIGTERM into an event so that the helper node leaves the graph cleanly."""
    stop = threading.Event()
    if threading.current_thread() is threading.main_thread():
        for signum in (signal.SIGINT, signal.SIGTERM):
            signal.signal(signum, lambda *_: stop.set())
    return stop


# --------------------------------------------------------------------------------------------
# call

def cmd_call(args) -> int:
    from vehicle_msgs_py import service_types
    service = _absolute(args.service)
    session = _Session()
    try:
        srv_type = session.service_type(service, args.type, args.wait)
        request = build_request(service_types(srv_type).request, args.value)
        response = _call(session.node, srv_type, service, request, args.timeout)
        sys.stdout.write(format_message(response))
    finally:
        session.close()
    return EXIT_OK


# --------------------------------------------------------------------------------------------
# param

# ParameterType code -> how ``ros2 param get`` introduces the value.
_PARAM_LABELS = {
    1: 'Boolean value is', 2: 'Integer value is', 3: 'Double value is', 4: 'String value is',
    5: 'Byte values are', 6: 'Boolean values are', 7: 'Integer values are',
    8: 'Double values are', 9: 'String values are',
}


def _param_node(session: _Session, name: str, wait_s: float) -> str:
    fqn = _absolute(name)
    graph = session.graph
    if not graph.wait_until(lambda: graph.find_node(fqn) is not None, wait_s):
        raise _not_found('node', fqn, graph.node_names(), wait_s)
    return fqn


def cmd_param(args) -> int:
    from vehicle_msgs_py import service_types
    from vehicle_sim.transport.dds import param_messages
    from vehicle_sim.transport.params import parse_parameter_value
    from vehicle_sim.transport.port import TransportError
    session = _Session()
    try:
        fqn = _param_node(session, args.node, args.wait)
        node = session.node
        if args.param_command == 'list':
            srv = 'rcl_interfaces/srv/ListParameters'
            response = _call(node, srv, f'{fqn}/list_parameters',
                             service_types(srv).request(), args.timeout)
            for name in sorted(response.result.names):
                print(f'  {name}')
            return EXIT_OK
        srv = 'rcl_interfaces/srv/GetParameters'
        response = _call(node, srv, f'{fqn}/get_parameters',
                         service_types(srv).request(names=[args.name]), args.timeout)
        current = response.values[0] if response.values else None
        if args.param_command == 'get':
            if current is None or current.type not in _PARAM_LABELS:
                raise CliError(f'parameter {args.name!r} is not set on {fqn}')
            value = param_messages.from_value_msg(current)
            if current.type == 1:
                value = 'True' if value else 'False'
            elif current.type == 5:
                value = list(value)   # bytes shown as numbers
            print(f'{_PARAM_LABELS[current.type]}: {value}')
            return EXIT_OK
        value = parse_parameter_value(args.value)
        if current is not None and current.type == 3 and isinstance(value, int) and \
                not isinstance(value, bool):
            value = float(value)  # '2' for a double parameter: what the user means
        srv = 'rcl_interfaces/srv/SetParameters'
        types = service_types(srv)
        try:
            parameter = param_messages.to_parameter_msg(args.name, value)
        except TransportError as exc:
            raise CliError(str(exc)) from None
        response = _call(node, srv, f'{fqn}/set_parameters',
                         types.request(parameters=[parameter]), args.timeout)
        result = response.results[0] if response.results else None
        if result is None or not result.successful:
            reason = result.reason if result is not None else 'no result'
            raise CliError(f'Setting parameter failed: {reason}')
        print('Set parameter successful')
    finally:
        session.close()
    return EXIT_OK


# --------------------------------------------------------------------------------------------
# export-interfaces, demo

def cmd_export(args) -> int:
    from vehicle_msgs_py import export
    return export.main([args.dest_dir])


def cmd_demo(args) -> int:
    from vehicle_sim import demo
    demo.run_demo(args.out, args.car, args.short)
    return EXIT_OK


# --------------------------------------------------------------------------------------------
# run

_MODES = {-1: 'UNDEFINED', 0: 'SPEED', 1: 'TORQUE'}
_INDICATORS = {0: 'off', 1: 'right', 2: 'left'}


def status_line(time_s: float, status) -> str:
    """
    Return the one-line status of a car.

    :param time_s: simulated time [s].
    :param status: a ``CarStatus`` (vehicle_sim.core.car_logic).
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
    return (f't {time_s:9.2f} s | {speed:7.2f} km/h | rpm {rpm} | '
            f'gear {status.gear:2d} | {mode:<9} | indicator {indicator}')


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


def cmd_run(args) -> int:
    from vehicle_sim.core.errors import VehicleSimError
    ros_args = list(args.ros_args or [])
    if ros_args and ros_args[0] == '--':
        ros_args = ros_args[1:]
    overrides: Dict[str, Any] = {}
    if args.car:
        overrides['car_model'] = args.car
    if args.world:
        overrides['world'] = args.world
    if args.real_time_factor is not None:
        overrides['real_time_factor'] = float(args.real_time_factor)
    if args.synchronous:
        overrides['synchronous'] = True
    if args.duration is not None and args.duration < 0:
        raise CliError('--duration must be >= 0', EXIT_USAGE)
    # The CLI runs on the embedded transport unless the user asked for another one.
    transport = os.environ.get('VEHICLE_SIM_TRANSPORT') or 'dds'
    from vehicle_sim.ros.automobile_node import AutomobileNode
    try:
        app = AutomobileNode(['vehicle-sim', *ros_args], transport=transport,
                             parameter_overrides=overrides)
    except (VehicleSimError, ValueError) as exc:
        raise CliError(str(exc), EXIT_USAGE) from None
    node = app.node
    output = _StatusOutput(not args.no_status)

    def render():
        vehicles = app.vehicles
        if not vehicles:
            return f't {app.world.time_s:9.2f} s | no vehicle'
        namespace = '' if '' in vehicles else sorted(vehicles)[0]
        line = status_line(app.world.time_s, vehicles[namespace].logic.status())
        if len(vehicles) > 1:
            line = f'[{namespace or "/"} +{len(vehicles) - 1}] ' + line
        return line

    stop = _install_stop_handlers()
    start = time.monotonic()
    try:
        output.install()
        while not stop.is_set() and node.ok():
            now = time.monotonic()
            if args.duration is not None and now - start >= args.duration:
                break
            node.spin_once(0.05)
            output.maybe_show(time.monotonic(), render)
    finally:
        output.finish()
        app.close()
    return EXIT_OK


# --------------------------------------------------------------------------------------------
# parser

def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog='vehicle-sim',
        description='PyBullet car simulator with the Webots automobile API and ROS 2 nodes; '
                    'graph tools on the embedded Cyclone DDS transport.')
    sub = parser.add_subparsers(dest='command', metavar='COMMAND')
    sub.required = True

    run = sub.add_parser('run', help='start the automobile node with a live status line',
                         description='Start the automobile node on the embedded transport. '
                                     'Arguments after -- are ROS arguments '
                                     '(e.g. -- --ros-args -p publish_period_ms:=20).')
    run.add_argument('--car', metavar='MODEL', help='car preset (e.g. BmwX5, TeslaModel3)')
    run.add_argument('--world', metavar='FILE', help='world file (config/worlds/*.yaml)')
    run.add_argument('--real-time-factor', type=float, metavar='F',
                     help='simulated seconds per wall-clock second (default: node default)')
    run.add_argument('--synchronous', action='store_true',
                     help='advance time only through /robot/time_step calls')
    run.add_argument('--duration', type=float, metavar='S',
                     help='stop after S wall-clock seconds')
    run.add_argument('--no-status', action='store_true', help='no status line')
    run.add_argument('ros_args', nargs=argparse.REMAINDER,
                     help='ROS arguments after --')
    run.set_defaults(func=cmd_run)

    lst = sub.add_parser('list', help='nodes, topics and services on the graph')
    lst.add_argument('--wait', type=float, default=DEFAULT_LIST_WAIT_S, metavar='S',
                     help=f'discovery time (default {DEFAULT_LIST_WAIT_S:g} s)')
    lst.add_argument('-a', '--all', action='store_true',
                     help='also hidden names (a token starting with _)')
    lst.set_defaults(func=cmd_list)

    echo = sub.add_parser('echo', help='print the messages of a topic')
    echo.add_argument('topic', metavar='TOPIC')
    echo.add_argument('--type', metavar='T', help='message type (default: from the graph)')
    echo.add_argument('--once', action='store_true', help='print one message and exit')
    echo.add_argument('--count', type=int, metavar='N', help='print N messages and exit')
    echo.add_argument('--timeout', type=float, metavar='S',
                      help='fail when the messages did not come within S seconds')
    echo.add_argument('--wait', type=float, default=DEFAULT_DISCOVERY_WAIT_S, metavar='S',
                      help='how long to look for the topic')
    echo.set_defaults(func=cmd_echo)

    call = sub.add_parser('call', help='call a service',
                          description='VALUE is the single request field of the Set*/Get* '
                                      'types (30, true) or a YAML request ("{value: 30}").')
    call.add_argument('service', metavar='SERVICE')
    call.add_argument('value', metavar='VALUE', nargs='?')
    call.add_argument('--type', metavar='T', help='service type (default: from the graph)')
    call.add_argument('--timeout', type=float, default=DEFAULT_CALL_TIMEOUT_S, metavar='S',
                      help=f'reply timeout (default {DEFAULT_CALL_TIMEOUT_S:g} s)')
    call.add_argument('--wait', type=float, default=DEFAULT_DISCOVERY_WAIT_S, metavar='S',
                      help='how long to look for the service')
    call.set_defaults(func=cmd_call)

    param = sub.add_parser('param', help='get, set or list the parameters of a node')
    param_sub = param.add_subparsers(dest='param_command', metavar='ACTION')
    param_sub.required = True
    for action, helptext in (('get', 'print a parameter'), ('set', 'set a parameter'),
                             ('list', 'list parameter names')):
        p = param_sub.add_parser(action, help=helptext)
        p.add_argument('node', metavar='NODE', help='fully-qualified node name, e.g. /automobile')
        if action != 'list':
            p.add_argument('name', metavar='NAME')
        if action == 'set':
            p.add_argument('value', metavar='VALUE', help='YAML value: 2.5, true, text, [1, 2]')
        p.add_argument('--timeout', type=float, default=DEFAULT_CALL_TIMEOUT_S, metavar='S')
        p.add_argument('--wait', type=float, default=DEFAULT_DISCOVERY_WAIT_S, metavar='S',
                       help='how long to look for the node')
    param.set_defaults(func=cmd_param)

    export = sub.add_parser('export-interfaces',
                            help='write the vehicle_msgs ament package into DIR')
    export.add_argument('dest_dir', metavar='DIR', help='e.g. <workspace>/src')
    export.set_defaults(func=cmd_export)

    demo = sub.add_parser('demo', help='run the end-to-end scenario, write a PNG '
                                       '(docs/end_to_end.md)')
    from vehicle_sim.demo import add_arguments as add_demo_arguments
    add_demo_arguments(demo)
    demo.set_defaults(func=cmd_demo)
    return parser


def main(argv: Optional[List[str]] = None) -> int:
    """
    Run the ``vehicle-sim`` command.

    :param argv: arguments without the program name; default ``sys.argv[1:]``.
    :return: the exit status (0 success, 1 failure, 2 usage error).
    """
    argv = sys.argv[1:] if argv is None else list(argv)
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return args.func(args)
    except CliError as exc:
        print(f'vehicle-sim {args.command}: {exc}', file=sys.stderr)
        return exc.status
    except KeyboardInterrupt:
        return 130
    except BrokenPipeError:
        # The reader of our output went away (`vehicle-sim list | head`): not an error.
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return EXIT_OK
    except Exception as exc:  # noqa: BLE001 - transport errors are reported, not traced
        from vehicle_sim.core.errors import VehicleSimError
        if isinstance(exc, VehicleSimError):
            print(f'vehicle-sim {args.command}: {exc}', file=sys.stderr)
            return EXIT_FAILURE
        raise


if __name__ == '__main__':
    sys.exit(main())
