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
The graph commands of ``vehicle-sim``: ``list``, ``echo``, ``call`` and ``param``.

They read the graph through :class:`~vehicle_sim.transport.dds.graph.GraphView` and talk to it
through a hidden helper node (``_vehicle_sim_cli_<pid>``) on the embedded transport, created only
when a command needs one.
"""

import argparse
import os
import sys
import time
from typing import Optional

from vehicle_sim.tools.command import (
    CliError,
    EXIT_FAILURE,
    EXIT_OK,
    EXIT_USAGE,
    install_stop_handlers,
)
from vehicle_sim.tools.message_yaml import (
    Abbreviation,
    build_request,
    field_path,
    format_message,
    format_plain,
    pick_field,
)

DEFAULT_DISCOVERY_WAIT_S = 3.0
DEFAULT_LIST_WAIT_S = 1.5
DEFAULT_CALL_TIMEOUT_S = 5.0


# --------------------------------------------------------------------------------------------
# Shared helpers of the graph commands

def absolute_name(name: str) -> str:
    return name if name.startswith('/') else '/' + name


def _hidden(name: str) -> bool:
    return any(token.startswith('_') for token in name.split('/') if token)


def _not_found(kind: str, name: str, graph, candidates, wait_s: float,
               hint: str = '', status: int = EXIT_FAILURE) -> CliError:
    from vehicle_sim.transport.dds.graph import close_names
    close = close_names(name, candidates)
    hint = (f'; did you mean: {", ".join(close)}' if close else '') + hint
    if not graph.participants():
        hint += '; ' + _nothing_found(graph.domain_id)
    return CliError(f'{kind} {name!r} not found on the graph after {wait_s:g} s '
                    f'(ROS_DOMAIN_ID={graph.domain_id}){hint}', status)


def _nothing_found(domain_id: int) -> str:
    """Say which domain and discovery range saw no other participant at all, and the rule."""
    from vehicle_sim.transport.dds import domain_config
    discovery = domain_config.discovery_range()
    if domain_config.localhost_only():
        setting = f'ROS_LOCALHOST_ONLY=1 ({discovery})'
    elif os.environ.get('ROS_AUTOMATIC_DISCOVERY_RANGE', '').strip():
        setting = f'ROS_AUTOMATIC_DISCOVERY_RANGE={discovery}'
    else:
        setting = f'ROS_AUTOMATIC_DISCOVERY_RANGE unset ({discovery})'
    return (f'no other DDS participant seen at all on domain {domain_id} with {setting}: '
            'both sides must use the same ROS_DOMAIN_ID and the same discovery range '
            '(README, "Try it")')


class GraphSession:
    """The CLI's graph view and (created on demand) its hidden helper node."""

    def __init__(self):
        from vehicle_sim.transport.dds.graph import GraphView
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

    def resolve_type(self, kind: str, name: str, given: Optional[str], wait_s: float,
                     must_exist: bool = True, hint: str = '',
                     status: int = EXIT_FAILURE) -> str:
        """
        Return a topic's or service's type: ``given`` (checked against the graph) or the graph's.

        :param kind: ``'topic'`` or ``'service'``.
        :param given: the user's ``--type`` / TYPE, or None.
        :param must_exist: fail when the name is not on the graph after ``wait_s``; else a
            given type is used as it is (a topic whose publisher comes later).
        :param hint: added to the not-found error, raised with ``status``.
        :raises CliError: the name is not on the graph, has several types, or has another type
            than the one given (naming both, at once).
        """
        graph = self.graph
        types_of = graph.services if kind == 'service' else graph.topics
        check = _check_service_type if kind == 'service' else _check_message_type
        wanted = check(given) if given else None
        look_s = wait_s if wanted is None or must_exist else min(wait_s, 1.0)
        if not graph.wait_until(lambda: name in types_of(), look_s):
            if wanted is not None and not must_exist:
                return wanted
            raise _not_found(kind, name, graph, types_of(), wait_s, hint, status)
        on_graph = sorted(types_of()[name])
        if wanted is not None:
            if wanted not in on_graph:
                raise CliError(f'{kind} {name} has type {" and ".join(on_graph)} on the graph, '
                               f'not {wanted} (the type given)')
            return wanted
        if len(on_graph) > 1:
            raise CliError(f'{kind} {name} has several types ({", ".join(on_graph)}); '
                           'pick one with --type')
        return check(on_graph[0])


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
        from vehicle_sim.transport.dds.graph import close_names
        close = close_names(ros_type, known_types())
        hint = f'; did you mean: {", ".join(close)}' if close else ''
        raise CliError(f'message type {ros_type} is not known to vehicle_sim{hint}')
    return ros_type


def _call(node, srv_type: str, service: str, request, timeout_s: float):
    from vehicle_sim.transport.errors import ServiceTimeoutError
    client = node.create_client(srv_type, service)
    if not client.wait_for_service(timeout_s):
        raise CliError(f'service {service} is not available (no matched server within '
                       f'{timeout_s:g} s)')
    try:
        return client.call(request, timeout_s)
    except ServiceTimeoutError as error:   # 'no reply from ... within ... s', and why if known
        raise CliError(str(error)) from None


# --------------------------------------------------------------------------------------------
# list

def cmd_list(args) -> int:
    session = GraphSession()
    try:
        session.graph.wait(args.wait)
        graph = session.graph
        _print_list(graph, args.all)
        for warning in graph.warnings:
            sys.stderr.write(f'warning: {warning}\n')
    finally:
        session.close()
    return EXIT_OK


def _print_list(graph, show_all: bool) -> None:
    """Print nodes, topics, services and participants (DDS vendor, distribution)."""
    from vehicle_msgs_py import distro
    foreign = {n.fqn: n.distro for n in graph.nodes() if n.distro and n.distro != graph.distro}
    nodes = [n for n in graph.node_names() if show_all or not _hidden(n)]
    topics = {k: v for k, v in graph.topics().items() if show_all or not _hidden(k)}
    services = {k: v for k, v in graph.services().items() if show_all or not _hidden(k)}
    print('nodes:')
    for name in nodes:
        mark = f'  ({distro.title(foreign[name])})' if name in foreign else ''
        print(f'  {name}{mark}')
    print('topics:')
    for name in sorted(topics):
        print(f'  {name} [{", ".join(sorted(topics[name]))}]')
    print('services:')
    for name in sorted(services):
        print(f'  {name} [{", ".join(sorted(services[name]))}]')
    print('participants:')
    for participant in graph.participants():
        shown = [n for n in participant.nodes if show_all or not _hidden(n)]
        if not show_all and participant.nodes and not shown:
            continue   # only hidden nodes (another vehicle-sim command)
        details = [participant.vendor]
        if participant.distro:
            details.append(f'ROS 2 {distro.title(participant.distro)}')
            nodes_text = f': {", ".join(shown)}' if shown else ''
        else:   # Fast DDS sends its transient-local data only after ~3 s
            nodes_text = ' (no ros_discovery_info received: not ROS, or try a longer --wait)'
        print(f'  {participant.guid.hex()} [{"; ".join(details)}]{nodes_text}')


# --------------------------------------------------------------------------------------------
# echo

def add_topic_arguments(parser) -> None:
    """Add what every topic command takes: TOPIC, ``--type`` and ``--wait``."""
    parser.add_argument('topic', metavar='TOPIC')
    parser.add_argument('--type', metavar='T', help='message type (default: from the graph)')
    parser.add_argument('--wait', type=float, default=DEFAULT_DISCOVERY_WAIT_S, metavar='S',
                        help='how long to look for the topic')


# ros2 topic echo's --truncate-length default.
DEFAULT_TRUNCATE_LENGTH = 128


def _unsigned_int(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        value = -1
    if value < 0:
        raise argparse.ArgumentTypeError(f'must be an integer >= 0, got {text!r}')
    return value


def add_abbreviation_arguments(parser) -> None:
    """Add ``ros2 topic echo``'s options that shorten long strings and arrays."""
    parser.add_argument('--full-length', '-f', action='store_true',
                        help='print arrays and strings whole (by default they are cut after '
                             "--truncate-length items, with '...')")
    parser.add_argument('--truncate-length', '-l', type=_unsigned_int,
                        default=DEFAULT_TRUNCATE_LENGTH, metavar='N',
                        help='the length to truncate arrays and strings to (default '
                             f'{DEFAULT_TRUNCATE_LENGTH})')
    parser.add_argument('--no-arr', action='store_true',
                        help='print array fields as their type and length only')
    parser.add_argument('--no-str', action='store_true',
                        help='print string fields as their length only')


def abbreviation(args) -> Abbreviation:
    """Return what ``echo``'s options ask to shorten."""
    return Abbreviation(None if args.full_length else args.truncate_length, args.no_arr,
                        args.no_str)


def subscribe(session: 'GraphSession', args, on_message):
    """
    Subscribe the helper node to ``args.topic`` (type from ``args.type`` or the graph).

    QoS like ``ros2 topic echo``: reliable / transient local only when every publisher offers
    it. :return: the topic's absolute name.
    """
    from vehicle_sim.transport.qos import (
        BEST_EFFORT,
        QosProfile,
        RELIABLE,
        TRANSIENT_LOCAL,
        VOLATILE,
    )
    topic = absolute_name(args.topic)
    graph = session.graph
    ros_type = session.resolve_type('topic', topic, args.type, args.wait, must_exist=False)
    graph.wait_until(lambda: bool(graph.publishers(topic)), min(args.wait, 1.0))
    publishers = graph.publishers(topic)
    qos = QosProfile(
        depth=10,
        reliability=RELIABLE if all(p.reliable for p in publishers) else BEST_EFFORT,
        durability=(TRANSIENT_LOCAL if publishers and all(p.transient_local
                                                          for p in publishers)
                    else VOLATILE))
    field = None
    if getattr(args, 'field', None):
        from vehicle_msgs_py import types as msg_types
        field = field_path(msg_types.message_type(ros_type), args.field)
    session.node.create_subscription(ros_type, topic, lambda msg: on_message(msg, field), qos)
    return topic


class PrintRate:
    """
    Print at most ``rate_hz`` times a second (``echo --rate``); None prints every message.

    :meth:`due` takes the time, so a test steps it.
    """

    def __init__(self, rate_hz: Optional[float]):
        self._period_s = 1.0 / rate_hz if rate_hz else 0.0
        self._last_s = None

    def due(self, now_s: float) -> bool:
        """Return True (and remember ``now_s``) when a message may be printed at ``now_s``."""
        if self._last_s is not None and now_s - self._last_s < self._period_s:
            return False
        self._last_s = now_s
        return True


def cmd_echo(args) -> int:
    count = 1 if args.once else args.count
    if count is not None and count < 1:
        raise CliError('--count must be >= 1', EXIT_USAGE)
    if args.rate is not None and not args.rate > 0.0:
        raise CliError(f'--rate must be > 0 Hz, got {args.rate:g}', EXIT_USAGE)
    if args.timeout is not None and not args.timeout > 0.0:
        raise CliError(f'--timeout must be > 0 s, got {args.timeout:g}', EXIT_USAGE)
    shorten = abbreviation(args)
    session = GraphSession()
    try:
        received = []
        rate = PrintRate(args.rate)

        def on_message(msg, field):
            if (count is not None and len(received) >= count) or not rate.due(time.monotonic()):
                return
            received.append(msg)
            text = format_message(msg, shorten) if field is None else format_plain(
                pick_field(msg, field, shorten))
            sys.stdout.write(text + '---\n')
            sys.stdout.flush()

        topic = subscribe(session, args, on_message)
        node = session.node
        stop = install_stop_handlers()
        deadline = None if args.timeout is None else time.monotonic() + args.timeout
        while not stop.is_set() and (count is None or len(received) < count):
            if deadline is not None and time.monotonic() >= deadline:
                # Without --once/--count the timeout is how long to echo: an end, not a fault.
                if not received:
                    raise CliError(f'no message on {topic} within {args.timeout:g} s')
                if count is not None:
                    raise CliError(f'got {len(received)} of {count} messages on {topic} '
                                   f'within {args.timeout:g} s')
                break
            node.spin_once(0.05)
    finally:
        session.close()
    return EXIT_OK


# --------------------------------------------------------------------------------------------
# call

def cmd_call(args) -> int:
    from vehicle_msgs_py import service_types
    from vehicle_sim.tools.call_log import CallLog
    service = absolute_name(args.service)
    session = GraphSession()
    try:
        srv_type = session.resolve_type('service', service, args.type, args.wait)
        request = build_request(service_types(srv_type).request, args.value)
        log = CallLog(session.node, session.graph, service)   # subscribed before the call
        log.start()
        response = _call(session.node, srv_type, service, request, args.timeout)
        log.stop()
        sys.stdout.write(format_message(response))
        for line in log.lines():
            sys.stdout.write(line + '\n')
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


def _param_node(session: GraphSession, name: str, wait_s: float) -> str:
    fqn = absolute_name(name)
    graph = session.graph
    if not graph.wait_until(lambda: graph.find_node(fqn) is not None, wait_s):
        raise _not_found('node', fqn, graph, graph.node_names(), wait_s)
    return fqn


def cmd_param(args) -> int:
    from vehicle_msgs_py import service_types
    from vehicle_sim.transport.dds import param_messages
    from vehicle_sim.transport.errors import TransportError
    from vehicle_sim.transport.ros_args import parse_parameter_value
    session = GraphSession()
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
