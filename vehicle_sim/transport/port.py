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
The transport port: the Node-like interface every vehicle_sim node is written against.

Two adapters implement it with identical behaviour: ``rclpy_adapter.RclpyNode`` (a thin wrapper of
a real ``rclpy.node.Node``) and ``dds.DdsNode`` (embedded Cyclone DDS speaking ROS 2 Jazzy's wire
conventions, as rmw_cyclonedds does). This module holds the adapter-neutral parts: QoS profiles
and their presets, name resolution (done like rcl), parameter value types and the abstract port.
"""

import abc
from dataclasses import dataclass
import re
import time
from typing import Any, Callable, List, Optional, Union

from vehicle_sim.core.errors import VehicleSimError
from vehicle_sim.transport import stop_signals


class TransportError(VehicleSimError):
    """A transport-level failure: bad name, unknown type, unavailable service, timeout."""


class ServiceTimeoutError(TransportError, TimeoutError):
    """A blocking service call got no reply within its timeout."""


# --------------------------------------------------------------------------------------------
# QoS profiles

KEEP_LAST = 'keep_last'
KEEP_ALL = 'keep_all'
RELIABLE = 'reliable'
BEST_EFFORT = 'best_effort'
VOLATILE = 'volatile'
TRANSIENT_LOCAL = 'transient_local'


@dataclass(frozen=True)
class QosProfile:
    """
    A ROS QoS profile as a small value type.

    ``lifespan_s``/``deadline_s`` are None for "not specified" (DDS default: infinite).
    ``avoid_ros_namespace_conventions`` drops the ``rt/`` prefix (used for ``ros_discovery_info``).
    """

    depth: int = 10
    history: str = KEEP_LAST
    reliability: str = RELIABLE
    durability: str = VOLATILE
    lifespan_s: Optional[float] = None
    deadline_s: Optional[float] = None
    avoid_ros_namespace_conventions: bool = False

    def __post_init__(self):
        if self.history not in (KEEP_LAST, KEEP_ALL):
            raise TransportError(f'unknown QoS history {self.history!r}')
        if self.reliability not in (RELIABLE, BEST_EFFORT):
            raise TransportError(f'unknown QoS reliability {self.reliability!r}')
        if self.durability not in (VOLATILE, TRANSIENT_LOCAL):
            raise TransportError(f'unknown QoS durability {self.durability!r}')
        if self.history == KEEP_LAST and self.depth < 0:
            raise TransportError(f'QoS depth must be >= 0, got {self.depth}')


QOS_DEFAULT = QosProfile(depth=10)
QOS_SERVICES = QosProfile(depth=10)
QOS_SENSOR_DATA = QosProfile(depth=5, reliability=BEST_EFFORT)
QOS_PARAMETERS = QosProfile(depth=1000)
QOS_PARAMETER_EVENTS = QosProfile(depth=1000)
QOS_SYSTEM_DEFAULT = QosProfile(depth=1)
QOS_ROSOUT = QosProfile(depth=1000, durability=TRANSIENT_LOCAL, lifespan_s=10.0)
QOS_CLOCK = QosProfile(depth=1, reliability=BEST_EFFORT)
QOS_TF = QosProfile(depth=100)
QOS_TF_STATIC = QosProfile(depth=1, durability=TRANSIENT_LOCAL)
QOS_TF_STATIC_LISTENER = QosProfile(depth=100, durability=TRANSIENT_LOCAL)
QOS_LATCHED = QosProfile(depth=1, durability=TRANSIENT_LOCAL)
QOS_DISCOVERY_INFO_WRITER = QosProfile(
    depth=1, durability=TRANSIENT_LOCAL, avoid_ros_namespace_conventions=True)
QOS_DISCOVERY_INFO_READER = QosProfile(
    history=KEEP_ALL, durability=TRANSIENT_LOCAL, avoid_ros_namespace_conventions=True)

QOS_PRESETS = {
    'default': QOS_DEFAULT,
    'services': QOS_SERVICES,
    'sensor_data': QOS_SENSOR_DATA,
    'parameters': QOS_PARAMETERS,
    'parameter_events': QOS_PARAMETER_EVENTS,
    'system_default': QOS_SYSTEM_DEFAULT,
    'rosout': QOS_ROSOUT,
    'clock': QOS_CLOCK,
    'tf': QOS_TF,
    'tf_static': QOS_TF_STATIC,
    'tf_static_listener': QOS_TF_STATIC_LISTENER,
    'latched': QOS_LATCHED,
}


def as_qos(qos: Union[QosProfile, int, str, None]) -> QosProfile:
    """
    Normalise a QoS argument: a profile, a depth (like rclpy's ``10``) or a preset name.

    :raises TransportError: for an unknown preset name.
    """
    if qos is None:
        return QOS_DEFAULT
    if isinstance(qos, QosProfile):
        return qos
    if isinstance(qos, bool):
        raise TransportError(f'invalid QoS {qos!r}')
    if isinstance(qos, int):
        return QosProfile(depth=qos)
    if isinstance(qos, str):
        try:
            return QOS_PRESETS[qos]
        except KeyError:
            raise TransportError(
                f'unknown QoS preset {qos!r}; valid: {", ".join(sorted(QOS_PRESETS))}') from None
    raise TransportError(f'invalid QoS {qos!r}')


# --------------------------------------------------------------------------------------------
# Names (rcl_expand_topic_name + rmw_validate_full_topic_name)

MAX_TOPIC_NAME_LENGTH = 247
_TOKEN = re.compile(r'^[A-Za-z_][A-Za-z0-9_]*$')
_NODE_NAME = re.compile(r'^[A-Za-z_][A-Za-z0-9_]*$')


def validate_node_name(name: str) -> str:
    """Return ``name`` if it is a valid ROS node name, else raise TransportError."""
    if not _NODE_NAME.match(name or ''):
        raise TransportError(f'invalid node name {name!r}: use letters, digits and _')
    return name


def normalize_namespace(namespace: str) -> str:
    """
    Return the absolute form of a node namespace ('' and '/' both mean the root '/').

    :raises TransportError: when a token is invalid.
    """
    namespace = namespace or '/'
    if not namespace.startswith('/'):
        namespace = '/' + namespace
    if namespace != '/':
        namespace = namespace.rstrip('/')
        for token in namespace[1:].split('/'):
            if not _TOKEN.match(token):
                raise TransportError(f'invalid namespace {namespace!r}')
    return namespace


def resolve_name(name: str, namespace: str, node_name: str) -> str:
    """
    Expand a topic or service name to its fully-qualified form like rcl does.

    ``/x`` stays; ``x`` goes under the namespace; ``~/x`` (or ``~``) goes under
    ``<namespace>/<node_name>``.

    :raises TransportError: when the result is not a valid fully-qualified ROS name.
    """
    namespace = normalize_namespace(namespace)
    base = namespace.rstrip('/')
    if name == '~' or name.startswith('~/'):
        fqn = f'{base}/{node_name}{name[1:]}'
    elif name.startswith('/'):
        fqn = name
    else:
        fqn = f'{base}/{name}'
    if fqn == '/' or fqn.endswith('/') or '//' in fqn:
        raise TransportError(f'invalid topic or service name {name!r}')
    for token in fqn[1:].split('/'):
        if not _TOKEN.match(token):
            raise TransportError(f'invalid topic or service name {name!r} (token {token!r})')
    if len(fqn) > MAX_TOPIC_NAME_LENGTH:
        raise TransportError(f'name {fqn!r} longer than {MAX_TOPIC_NAME_LENGTH} characters')
    return fqn


def fully_qualified_node_name(namespace: str, node_name: str) -> str:
    """Return ``/ns/name`` without doubling the slash of the root namespace."""
    return normalize_namespace(namespace).rstrip('/') + '/' + node_name


# --------------------------------------------------------------------------------------------
# Parameters

# rcl_interfaces/msg/ParameterType
PARAMETER_NOT_SET = 0
PARAMETER_BOOL = 1
PARAMETER_INTEGER = 2
PARAMETER_DOUBLE = 3
PARAMETER_STRING = 4
PARAMETER_BYTE_ARRAY = 5
PARAMETER_BOOL_ARRAY = 6
PARAMETER_INTEGER_ARRAY = 7
PARAMETER_DOUBLE_ARRAY = 8
PARAMETER_STRING_ARRAY = 9


def parameter_type_of(value: Any) -> int:
    """
    Return the rcl_interfaces ParameterType code of a plain Python value.

    :raises TransportError: for a value ROS parameters cannot hold.
    """
    if value is None:
        return PARAMETER_NOT_SET
    if isinstance(value, bool):
        return PARAMETER_BOOL
    if isinstance(value, int):
        return PARAMETER_INTEGER
    if isinstance(value, float):
        return PARAMETER_DOUBLE
    if isinstance(value, str):
        return PARAMETER_STRING
    if isinstance(value, (bytes, bytearray)):
        return PARAMETER_BYTE_ARRAY
    if isinstance(value, (list, tuple)):
        if not value:
            raise TransportError('an empty list has no ROS parameter type; give a typed default')
        if all(isinstance(v, bool) for v in value):
            return PARAMETER_BOOL_ARRAY
        if all(isinstance(v, int) and not isinstance(v, bool) for v in value):
            return PARAMETER_INTEGER_ARRAY
        if all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in value):
            return PARAMETER_DOUBLE_ARRAY
        if all(isinstance(v, str) for v in value):
            return PARAMETER_STRING_ARRAY
    raise TransportError(f'value {value!r} cannot be a ROS parameter')


# rclcpp's to_string(ParameterType) names, as `ros2 param describe` prints them
PARAMETER_TYPE_NAMES = ('not set', 'bool', 'integer', 'double', 'string', 'byte_array',
                        'bool_array', 'integer_array', 'double_array', 'string_array')


def wrong_type_reason(name: str, expected: int, value: Any) -> Optional[str]:
    """
    Return why ``value`` cannot be set on a parameter of type ``expected``, or None if it can.

    rclcpp's wording ("Wrong parameter type, parameter {x} is of type {integer}, setting it to
    {string} is not allowed."), with the types named and the value quoted, on both transports.
    """
    kind = parameter_type_of(value)
    if kind == expected:
        return None
    shown = repr(value) if len(repr(value)) <= 80 else repr(value)[:77] + '...'
    return (f'Wrong parameter type, parameter {{{name}}} is of type '
            f'{{{PARAMETER_TYPE_NAMES[expected]}}}, setting it to '
            f'{{{PARAMETER_TYPE_NAMES[kind]}}} {shown} is not allowed.')


def normalize_parameter_value(value: Any) -> Any:
    """Return the canonical Python form of a parameter value (lists, bytes, floats in arrays)."""
    kind = parameter_type_of(value)
    if kind == PARAMETER_DOUBLE_ARRAY:
        return [float(v) for v in value]
    if kind in (PARAMETER_BOOL_ARRAY, PARAMETER_INTEGER_ARRAY, PARAMETER_STRING_ARRAY):
        return list(value)
    if kind == PARAMETER_BYTE_ARRAY:
        return bytes(value)
    return value


@dataclass(frozen=True)
class Parameter:
    """A parameter name and its plain Python value, as handed to on-set callbacks."""

    name: str
    value: Any

    @property
    def type_(self) -> int:
        return parameter_type_of(self.value)


@dataclass(frozen=True)
class SetParametersResult:
    """What an on-set-parameters callback returns (rcl_interfaces/msg/SetParametersResult)."""

    successful: bool
    reason: str = ''


# A validator takes the candidate value and returns None (accept) or a reason string
# (reject); raising ValueError also rejects, with the exception text as the reason.
Validator = Callable[[Any], Optional[str]]
OnSetParametersCallback = Callable[[List[Parameter]], SetParametersResult]


def run_validator(validator: Optional[Validator], value: Any) -> Optional[str]:
    """Apply a validator; return the rejection reason or None when the value is accepted."""
    if validator is None:
        return None
    try:
        reason = validator(value)
    except (ValueError, TypeError, VehicleSimError) as exc:
        return str(exc) or type(exc).__name__
    if reason is None or reason is True:
        return None
    if reason is False:
        return f'value {value!r} rejected'
    return str(reason)


# --------------------------------------------------------------------------------------------
# Time

@dataclass(frozen=True)
class Time:
    """A node-clock instant in integer nanoseconds (wall time, or sim time under use_sim_time)."""

    nanoseconds: int

    @property
    def seconds(self) -> float:
        return self.nanoseconds * 1e-9

    @property
    def sec(self) -> int:
        return self.nanoseconds // 1_000_000_000

    @property
    def nanosec(self) -> int:
        return self.nanoseconds % 1_000_000_000


# --------------------------------------------------------------------------------------------
# The port

# Severity names of rcutils' console output, by level.
LOG_LEVEL_NAMES = {10: 'DEBUG', 20: 'INFO', 30: 'WARN', 40: 'ERROR', 50: 'FATAL'}


class Logger(abc.ABC):
    """A node logger: rcutils-like console output plus /rosout."""

    @abc.abstractmethod
    def log(self, level: int, message: str) -> None:
        """Log ``message`` at ``level`` (10 debug, 20 info, 30 warn, 40 error, 50 fatal)."""

    def debug(self, message: str) -> None:
        self.log(10, message)

    def info(self, message: str) -> None:
        self.log(20, message)

    def warn(self, message: str) -> None:
        self.log(30, message)

    warning = warn

    def error(self, message: str) -> None:
        self.log(40, message)

    def fatal(self, message: str) -> None:
        self.log(50, message)


# Throttle period of repeated warnings [s] (wall time).
WARN_THROTTLE_S = 1.0


class ThrottledWarning:
    """Log a warning at most once per ``period_s`` of wall time, counting what was suppressed."""

    def __init__(self, logger: 'Logger', period_s: float = WARN_THROTTLE_S):
        """
        Create the throttle.

        :param logger: a port Logger.
        :param period_s: minimum wall time between two warnings [s].
        """
        self._logger = logger
        self._period_s = period_s
        self._last_s = None
        self.suppressed = 0
        self.count = 0

    def warn(self, message: str) -> None:
        """Count the event and log it unless one was logged less than period_s ago."""
        self.count += 1
        now_s = time.monotonic()
        if self._last_s is not None and now_s - self._last_s < self._period_s:
            self.suppressed += 1
            return
        if self.suppressed:
            message += f' ({self.suppressed} similar warnings suppressed)'
        self.suppressed = 0
        self._last_s = now_s
        self._logger.warn(message)


class Future:
    """
    A result completed later, while the node spins: a service call's reply, or a deferred reply.

    Single-threaded: ``done()``/``result()`` are read by the thread that spins the node.
    """

    def __init__(self):
        self._done = False
        self._result = None
        self._exception = None
        self._callbacks = []

    def done(self) -> bool:
        return self._done

    def result(self):
        if self._exception is not None:
            raise self._exception
        return self._result

    def exception(self):
        return self._exception

    def set_result(self, result) -> None:
        self._result = result
        self._done = True
        self._run_callbacks()

    def set_exception(self, exception: BaseException) -> None:
        self._exception = exception
        self._done = True
        self._run_callbacks()

    def add_done_callback(self, callback: Callable[['Future'], None]) -> None:
        """Call ``callback(future)`` once the future is done (at once if it already is)."""
        if self._done:
            callback(self)
        else:
            self._callbacks.append(callback)

    def _run_callbacks(self) -> None:
        callbacks, self._callbacks = self._callbacks, []
        for callback in callbacks:
            callback(self)


class ReaderGate:
    """
    Whether a message published now can reach a subscriber (``open``).

    ``open`` is False only while the transport knows that no subscriber would receive it: a
    volatile publisher of the embedded transport with no matched subscription (the message
    would go nowhere; a subscriber matching later does not get it either). A node's publishing
    loop reads it before building a message and skips the message when it is closed. Kept up to
    date by the transport, read as a plain attribute.
    """

    __slots__ = ('open',)

    def __init__(self, open_: bool = True):
        self.open = open_


# The gate of publishers whose transport does not track their subscribers: always open.
ALWAYS_OPEN = ReaderGate(True)


class Publisher(abc.ABC):
    topic_name: str
    # See ReaderGate; the embedded transport gives its volatile publishers their own.
    reader_gate: ReaderGate = ALWAYS_OPEN

    @abc.abstractmethod
    def publish(self, msg) -> None:
        """Send one message."""

    def publish_serialized(self, data: bytes) -> None:
        """
        Send one message already serialized by the node's ``serializer`` for this topic's type.

        Only a transport whose ``NodePort.serializer`` gives serializers has it.
        """
        raise TransportError(f'{self.topic_name}: this transport publishes messages only')

    def get_subscription_count(self) -> int:
        return 0


class Subscription(abc.ABC):
    topic_name: str

    def get_publisher_count(self) -> int:
        return 0


class Service(abc.ABC):
    service_name: str


class Client(abc.ABC):
    """A service client: ``wait_for_service``, ``call_async`` and a blocking ``call``."""

    service_name: str

    @abc.abstractmethod
    def service_is_ready(self) -> bool:
        """Return True when a matching server is reachable (request reader and reply writer)."""

    @abc.abstractmethod
    def wait_for_service(self, timeout_s: Optional[float] = None) -> bool:
        """Spin-free wait until the service is ready; return False on timeout."""

    @abc.abstractmethod
    def call_async(self, request) -> Future:
        """Send ``request``; the returned Future completes during a later spin of the node."""

    @abc.abstractmethod
    def call(self, request, timeout_s: float = 5.0):
        """
        Send ``request`` and spin this node until the reply arrives.

        For CLI tools and tests; never from inside a callback of the same node.

        :raises ServiceTimeoutError: when no reply came within ``timeout_s``.
        """


class Timer(abc.ABC):
    @abc.abstractmethod
    def cancel(self) -> None:
        """Stop the timer."""

    @abc.abstractmethod
    def reset(self) -> None:
        """Restart the timer (a cancelled one too): the next call is one period from now."""


class NodePort(abc.ABC):
    """
    The Node-like interface shared by both adapters.

    Types are named by their ROS names (``'std_msgs/msg/String'``, ``'vehicle_msgs/srv/SetInt'``);
    ``msg()``/``srv()`` return the adapter's classes. Names resolve like rcl. Service callbacks
    are ``callback(request, response) -> response``; a callback that cannot answer at once
    returns a :class:`Future` instead and completes it later with the response, from the node's
    own thread while it spins (a deferred reply): the node serves other requests meanwhile and
    the reply is sent when the future is done.
    """

    @abc.abstractmethod
    def get_name(self) -> str: ...

    @abc.abstractmethod
    def get_namespace(self) -> str: ...

    def get_fully_qualified_name(self) -> str:
        return fully_qualified_node_name(self.get_namespace(), self.get_name())

    @abc.abstractmethod
    def msg(self, ros_type: str):
        """Return the message class of ``ros_type`` (e.g. 'std_msgs/msg/String')."""

    @abc.abstractmethod
    def srv(self, srv_type: str):
        """Return an object with ``.Request``/``.Response`` classes of ``srv_type``."""

    def serializer(self, ros_type: str):
        """
        Return a fast serializer factory for ``ros_type``, or None (publish messages).

        The factory takes the constants of the type's message builder (``ros/messages.py``) and
        returns ``serialize(*values)`` -> the bytes that ``Publisher.publish_serialized`` takes.
        """
        return None

    @abc.abstractmethod
    def create_publisher(self, ros_type: str, topic: str, qos=None) -> Publisher: ...

    @abc.abstractmethod
    def create_subscription(self, ros_type: str, topic: str, callback, qos=None, *,
                            raw: bool = False) -> Subscription:
        """
        Call ``callback(message)`` for each message received on ``topic``.

        :param raw: hand the callback each message's serialized bytes (CDR with its 4-byte
            encapsulation header, as rclpy's ``raw=True``) instead of the message; decode one
            later with :meth:`deserialize` (a reader that keeps many messages and looks at few).
        """

    def tap_publishers(self, tap) -> None:
        """
        Hand every message this node publishes to a tap too, as its CDR bytes (a recorder).

        ``tap(topic, ros_type, qos)`` is called once for each publisher of the node, those
        created before and after, with its fully-qualified topic, type and QosProfile; it
        returns ``write(data)`` (called with the bytes of each message published, after it is
        sent) or None to leave that publisher alone. A tapped publisher's reader gate stays open:
        every message is built, whether a subscriber is matched or not.

        :raises TransportError: when the transport cannot tap its publishers, or they already are.
        """
        raise TransportError(f'{self.get_fully_qualified_name()}: this transport cannot hand '
                             'its published messages to a recorder')

    def deserialize(self, ros_type: str, data: bytes):
        """Return the message of ``ros_type`` whose serialized bytes are ``data``."""
        return self.msg(ros_type).deserialize(bytes(data))

    @abc.abstractmethod
    def create_service(self, srv_type: str, name: str, callback) -> Service:
        """
        Serve ``name``: ``callback(request, response)`` returns the response or a Future of it.

        Requests are served in arrival order; with a deferred reply, later requests (to this
        service too) are served before the reply is sent.
        """

    @abc.abstractmethod
    def create_client(self, srv_type: str, name: str) -> Client: ...

    @abc.abstractmethod
    def create_timer(self, period_s: float, callback) -> Timer:
        """Call ``callback()`` every ``period_s`` of wall (steady) time while the node spins."""

    @abc.abstractmethod
    def now(self) -> Time:
        """Return the node clock: /clock time when use_sim_time is true, else wall time."""

    @abc.abstractmethod
    def time_msg(self, t: Optional[Time] = None):
        """Return a builtin_interfaces/msg/Time for ``t`` (default: ``now()``)."""

    @abc.abstractmethod
    def get_logger(self) -> Logger: ...

    def announce_ready(self, text: str) -> None:
        """
        Log the node's ready line (info), unless a stop was asked first.

        A node interrupted in its start-up never says it is ready; under ``run_node`` the line
        also marks the moment that decides the exit status (transport/stop_signals.py).
        """
        if stop_signals.mark_ready() and self.ok():
            self.get_logger().info(text)

    @abc.abstractmethod
    def declare_parameter(self, name: str, default: Any, *, description: str = '',
                          validator: Optional[Validator] = None, read_only: bool = False,
                          additional_constraints: str = '') -> Any:
        """
        Declare a parameter once and return its value (an override from the arguments wins).

        A set request whose value has another type, or that ``validator`` rejects, fails and
        leaves the value unchanged.

        :raises TransportError: when an override is rejected by the validator or mistyped.
        """

    @abc.abstractmethod
    def get_parameter(self, name: str) -> Any:
        """Return the plain Python value of a declared parameter."""

    @abc.abstractmethod
    def has_parameter(self, name: str) -> bool: ...

    @abc.abstractmethod
    def set_parameters(self, parameters: List[Parameter]) -> List[SetParametersResult]:
        """Set parameters locally, through the same checks as a remote set."""

    @abc.abstractmethod
    def add_on_set_parameters_callback(self, callback: OnSetParametersCallback) -> None:
        """Register ``callback(params) -> SetParametersResult``, run before a set is applied."""

    @abc.abstractmethod
    def spin_once(self, timeout_s: Optional[float] = None) -> None:
        """Handle what is ready (messages, requests, replies, timers), waiting <= timeout_s."""

    @abc.abstractmethod
    def spin(self) -> None:
        """Spin until shutdown() (or a signal handled by run_node)."""

    def serve_pending(self) -> None:
        """
        From inside a callback, run the handlers of requests and messages already received.

        A long callback (a simulation step) calls it between its parts, so that a request
        waits for one part, not the whole callback. It never waits and never fires timers.
        The default does nothing: an adapter whose executor cannot run handlers from inside a
        callback (rclpy's) serves them at its next spin, as before.
        """

    def spin_until(self, predicate: Callable[[], bool], timeout_s: float) -> bool:
        """Spin until ``predicate()`` is true; return False if ``timeout_s`` passed first."""
        deadline = time.monotonic() + timeout_s
        while not predicate():
            remaining = deadline - time.monotonic()
            if remaining <= 0.0:
                return False
            self.spin_once(min(remaining, 0.05))
        return True

    @abc.abstractmethod
    def request_shutdown(self) -> None:
        """Ask spin() to return (safe from a signal handler or a callback); then shutdown()."""

    @abc.abstractmethod
    def ok(self) -> bool:
        """Return False once a shutdown was requested (SIGINT/SIGTERM) or shutdown() called."""

    @abc.abstractmethod
    def shutdown(self) -> None:
        """Leave the graph at once; safe to call from a signal handler and more than once."""

    def destroy(self) -> None:
        self.shutdown()

    def destroy_node(self) -> None:
        self.shutdown()
