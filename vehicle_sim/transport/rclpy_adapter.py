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
The rclpy adapter: a thin wrapper of a real ``rclpy.node.Node`` with the port API.

Written against ROS 2 Jazzy's rclpy: ``rclpy.init`` / ``Node`` / ``create_publisher(msg_type,
topic, QoSProfile)`` / ``create_service`` / ``create_client`` / ``call_async`` / ``spin_once`` /
``try_shutdown``; message classes come from the generated ``pkg.msg`` / ``pkg.srv`` modules.
Only imported when rclpy is importable. Humble's rclpy has every API used here (same
signatures, ``Executor._execute_service`` awaiting ``await_or_execute``, ``_parameter_overrides``):
the nodes run on it unchanged (``ros2 run`` / ``ros2 launch`` checked on a Humble built from
source); the one message that differs, ``sensor_msgs/msg/Range`` (no ``variance`` on Humble),
is built from the fields its class has.

Deferred service replies (a port callback returning a port Future) use rclpy's own mechanism:
the service callback is a coroutine, which rclpy's executor awaits (Jazzy ``executors.py``,
``_take_service``/``await_or_execute``) before it sends the response; it awaits an rclpy Future
that the port Future completes. Services are in a reentrant callback group: the executor holds
a service's group for as long as its callback runs, so in the node's default mutually exclusive
group a waiting callback would stop the timer that completes it (and every other callback).
"""

import collections
import importlib
import signal
import sys
import threading
from typing import Any, Dict, List, Optional

from builtin_interfaces.msg import Time as TimeMsg
from rcl_interfaces.msg import ParameterDescriptor
from rcl_interfaces.msg import SetParametersResult as RclSetParametersResult
import rclpy
from rclpy.callback_groups import ReentrantCallbackGroup
from rclpy.clock import Clock, ClockType
from rclpy.context import Context
from rclpy.duration import Duration
from rclpy.exceptions import ParameterException
from rclpy.executors import (
    ExternalShutdownException,
    ShutdownException,
    SingleThreadedExecutor,
    TimeoutException,
)
from rclpy.impl.implementation_singleton import rclpy_implementation as _rclpy
from rclpy.node import Node
from rclpy.parameter import Parameter as RclpyParameter
from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy
from rclpy.task import Future as RclpyFuture
from rclpy.utilities import get_rmw_implementation_identifier

from vehicle_sim.transport import fast_cdr, port
from vehicle_sim.transport.errors import ServiceTimeoutError, TransportError
from vehicle_sim.transport.future import Future
from vehicle_sim.transport.logger import Logger
from vehicle_sim.transport.parameter_types import (
    Parameter,
    parameter_type_of,
    run_validator,
    SetParametersResult,
    wrong_type_reason,
)
from vehicle_sim.transport.qos import as_qos, KEEP_ALL, QOS_SERVICES, RELIABLE, TRANSIENT_LOCAL
from vehicle_sim.transport.ros_args import (
    rosout_wanted,
    unknown_overrides_warning,
    without_rosout_flags,
)
from vehicle_sim.transport.ros_time import Time
from vehicle_sim.transport.stop_signals import StopSignals

# The most callbacks one spin_once runs after the first (what was ready, not a flood).
DRAIN_LIMIT = 1000


def import_type(ros_type: str):
    """Return the generated class of ``pkg/msg/Name`` or ``pkg/srv/Name``."""
    try:
        pkg, kind, name = ros_type.split('/')
        return getattr(importlib.import_module(f'{pkg}.{kind}'), name)
    except (ValueError, ImportError, AttributeError) as exc:
        raise TransportError(f'cannot import ROS type {ros_type!r}: {exc}') from None


def to_rclpy_qos(qos) -> QoSProfile:
    """Convert a port QoS (profile, depth or preset name) to an rclpy QoSProfile."""
    profile = as_qos(qos)
    kwargs = {
        'history': (HistoryPolicy.KEEP_ALL if profile.history == KEEP_ALL
                    else HistoryPolicy.KEEP_LAST),
        'depth': profile.depth,
        'reliability': (ReliabilityPolicy.RELIABLE if profile.reliability == RELIABLE
                        else ReliabilityPolicy.BEST_EFFORT),
        'durability': (DurabilityPolicy.TRANSIENT_LOCAL
                       if profile.durability == TRANSIENT_LOCAL
                       else DurabilityPolicy.VOLATILE),
        'avoid_ros_namespace_conventions': profile.avoid_ros_namespace_conventions,
    }
    if profile.lifespan_s is not None:
        kwargs['lifespan'] = Duration(nanoseconds=int(profile.lifespan_s * 1e9))
    if profile.deadline_s is not None:
        kwargs['deadline'] = Duration(nanoseconds=int(profile.deadline_s * 1e9))
    return QoSProfile(**kwargs)


class _Logger(Logger):
    def __init__(self, logger):
        self._logger = logger

    def log(self, level: int, message: str) -> None:
        # rclpy keys its logging context on the calling line and refuses another severity
        # from the same line (ValueError): one call site per severity.
        message = str(message)
        if level <= 10:
            self._logger.debug(message)
        elif level <= 20:
            self._logger.info(message)
        elif level <= 30:
            self._logger.warning(message)
        elif level <= 40:
            self._logger.error(message)
        else:
            self._logger.fatal(message)


def _serialize_message(msg) -> bytes:
    # rclpy's own serialization: the bytes its publish() would write for msg.
    from rclpy.serialization import serialize_message
    return serialize_message(msg)


class _Publisher(port.Publisher):
    """
    An rclpy publisher; ``publish_serialized`` hands bytes to rclpy's ``publish``.

    rclpy's ``Publisher.publish`` takes a message or bytes (``rcl_publish_serialized_message``),
    so the embedded transport's fast serializers (``transport/fast_cdr.py``) serve here too.
    Both calls are rclpy's own bound method: no wrapper on the hot path.
    """

    def __init__(self, publisher, ros_type: str):
        self.publisher = publisher
        self.topic_name = publisher.topic_name
        self.ros_type = ros_type
        # Instance attributes: rclpy's bound method itself, called without a wrapper.
        self.publish = self.publish_serialized = publisher.publish

    def publish(self, msg) -> None:   # noqa: F811 - the class-level form the port requires
        self.publisher.publish(msg)

    def check_message(self, msg) -> None:
        """Refuse a message of another type than the topic's (a tapped publish serializes it)."""
        if not isinstance(msg, self.publisher.msg_type):
            raise TransportError(
                f'{self.topic_name} takes {self.ros_type}, got {type(msg).__name__}')

    def get_subscription_count(self) -> int:
        return self.publisher.get_subscription_count()


class _Subscription(port.Subscription):
    def __init__(self, node: Node, subscription):
        self._node = node
        self.subscription = subscription
        self.topic_name = subscription.topic_name

    def get_publisher_count(self) -> int:
        return self._node.count_publishers(self.topic_name)


class _Client(port.Client):
    def __init__(self, wrapper: 'RclpyNode', client, name: str):
        self._wrapper = wrapper
        self.client = client
        self.service_name = name

    def service_is_ready(self) -> bool:
        return self.client.service_is_ready()

    def wait_for_service(self, timeout_s: Optional[float] = None) -> bool:
        return self.client.wait_for_service(timeout_sec=timeout_s)

    def call_async(self, request):
        return self.client.call_async(request)

    def call(self, request, timeout_s: float = 5.0):
        future = self.client.call_async(request)
        self._wrapper.executor.spin_until_future_complete(future, timeout_sec=timeout_s)
        if not future.done():
            self.client.remove_pending_request(future)
            raise ServiceTimeoutError(
                f'no reply from {self.service_name} within {timeout_s} s')
        return future.result()


class RclpyNode(port.NodePort):
    """
    The port on a real rclpy Node.

    :param name: node name.
    :param namespace: node namespace.
    :param args: the command line (None: ``sys.argv``, as rclpy reads it). Given to the node as
        ``cli_args`` where its context is initialised already, else the arguments the node's
        own context is initialised with (below); ``--disable-rosout-logs`` keeps this node off
        /rosout either way (rclpy's ``enable_rosout=False``), as on the embedded transport.
    :param parameter_overrides: parameter values that win over the command line.
    :param context: the rclpy Context to run on; None = rclpy's default context where it is
        initialised (a node main: :func:`run_rclpy_node`, or the user's ``rclpy.init()``), else a
        Context of this node's own, initialised here and shut down with the node. So a node
        built where nothing initialised rclpy (vehicle_sim.testing's client, a scenario run over
        the wire, a node built in a script) leaves the default context to the user's own
        ``rclpy.init()``, and its arguments never become the process's global ROS arguments.
    """

    def __init__(self, name: str, namespace: str = '', args=None,
                 parameter_overrides: Optional[Dict[str, Any]] = None, context=None):
        cli_args = None
        self._shutdown_requested = False
        self._own_context = None
        rosout = rosout_wanted(sys.argv if args is None else args)
        if context is None and not rclpy.ok():
            context = self._own_context = Context()
            # rclpy configures the process's logging from the first context initialised (until
            # every context is shut down): without the rosout flags, so that a helper keeping
            # itself off /rosout does not keep the user's nodes off it too
            context.init(without_rosout_flags(sys.argv if args is None else args))
        elif not rclpy.ok(context=context):
            rclpy.init(args=args, context=context)
        elif args:
            cli_args = list(args)
        self._context = context
        try:
            self.node = Node(
                name, namespace=namespace or None, context=context, cli_args=cli_args,
                parameter_overrides=[RclpyParameter(k, value=v)
                                     for k, v in (parameter_overrides or {}).items()],
                enable_rosout=rosout)
        except _rclpy.RCLError as error:
            self._shut_own_context()
            # rcl says only 'error creating node'; the RMW printed its reason (a DDS
            # configuration it refused, say) on stderr just before
            raise TransportError(
                f'rclpy could not create node {name!r} ({error}): the lines of '
                f'{get_rmw_implementation_identifier()} above say why') from None
        self._name = self.node.get_name()
        self._namespace = self.node.get_namespace()
        self._declaring = False
        self._overrides_checked = False
        self._validators: Dict[str, Any] = {}
        self._user_callbacks: List[Any] = []
        self.node.add_on_set_parameters_callback(self._on_set_parameters)
        self._logger = _Logger(self.node.get_logger())
        self._steady = Clock(clock_type=ClockType.STEADY_TIME)
        self._services_group = ReentrantCallbackGroup()
        # call_soon's queue, run by the executor when the guard condition fires.
        self._soon = collections.deque()
        self._soon_guard = self.node.create_guard_condition(self._run_soon)
        # One executor per node, so that nodes of a private Context (tests) spin too.
        self.executor = SingleThreadedExecutor(context=context)
        self.executor.add_node(self.node)

    def get_name(self) -> str:
        return self._name

    def get_namespace(self) -> str:
        return self._namespace

    def msg(self, ros_type: str):
        return import_type(ros_type)

    def srv(self, srv_type: str):
        return import_type(srv_type)

    def serializer(self, ros_type: str):
        return fast_cdr.SERIALIZERS.get(ros_type)

    def create_publisher(self, ros_type: str, topic: str, qos=None):
        publisher = _Publisher(self.node.create_publisher(import_type(ros_type), topic,
                                                          to_rclpy_qos(qos)), ros_type)
        return self._tap(publisher, ros_type, qos, _serialize_message)

    def call_soon(self, callback) -> None:
        # A guard condition is rclpy's thread-safe way to wake its executor.
        self._soon.append(callback)
        self._soon_guard.trigger()

    def _run_soon(self) -> None:
        while self._soon:
            self._soon.popleft()()

    def create_subscription(self, ros_type: str, topic: str, callback, qos=None, *,
                            raw: bool = False):
        return _Subscription(self.node, self.node.create_subscription(
            import_type(ros_type), topic, callback, to_rclpy_qos(qos), raw=raw))

    def deserialize(self, ros_type: str, data: bytes):
        from rclpy.serialization import deserialize_message
        return deserialize_message(bytes(data), import_type(ros_type))

    def deserialize_as(self, message_class, data: bytes):
        from rclpy.serialization import deserialize_message
        return deserialize_message(bytes(data), message_class)

    def serialize(self, msg) -> bytes:
        from rclpy.serialization import serialize_message
        return serialize_message(msg)

    def create_service(self, srv_type: str, name: str, callback, qos=QOS_SERVICES):
        executor = self.executor

        async def serve(request, response):
            result = callback(request, response)
            if isinstance(result, Future):
                waiting = RclpyFuture(executor=executor)
                result.add_done_callback(lambda done: _complete(waiting, done))
                result = await waiting
            return result

        service = self.node.create_service(import_type(srv_type), name, serve,
                                           qos_profile=to_rclpy_qos(qos),
                                           callback_group=self._services_group)
        if self._publish_taps:
            self._tap_service(self.node.resolve_service_name(name), srv_type, callback)
        return service

    def create_client(self, srv_type: str, name: str, qos=QOS_SERVICES):
        client = self.node.create_client(import_type(srv_type), name,
                                         qos_profile=to_rclpy_qos(qos))
        return _Client(self, client, self.node.resolve_service_name(name))

    def create_timer(self, period_s: float, callback):
        return self.node.create_timer(period_s, callback, clock=self._steady)

    def now(self) -> Time:
        return Time(self.node.get_clock().now().nanoseconds)

    def time_msg(self, t: Optional[Time] = None):
        t = self.now() if t is None else t
        return TimeMsg(sec=t.sec, nanosec=t.nanosec)

    def get_logger(self) -> Logger:
        return self._logger

    # Parameters: validators and port callbacks run inside one rclpy on-set callback.

    def _on_set_parameters(self, params) -> RclSetParametersResult:
        if self._declaring:  # checked in declare_parameter (like the embedded transport)
            return RclSetParametersResult(successful=True)
        for param in params:
            reason = run_validator(self._validators.get(param.name), param.value)
            if reason:
                return RclSetParametersResult(successful=False, reason=reason)
        converted = [Parameter(p.name, p.value) for p in params]
        for callback in self._user_callbacks:
            result = callback(converted)
            if not result.successful:
                return RclSetParametersResult(successful=False, reason=result.reason)
        return RclSetParametersResult(successful=True)

    def declare_parameter(self, name: str, default: Any, *, description: str = '',
                          validator=None, read_only: bool = False,
                          additional_constraints: str = '') -> Any:
        descriptor = ParameterDescriptor(description=description, read_only=read_only,
                                         additional_constraints=additional_constraints)
        # Only an override (-p, params file, parameter_overrides) is validated, not the default;
        # rclpy keeps the overrides in Node._parameter_overrides (Foxy..Jazzy).
        override = self.node._parameter_overrides.get(name)
        if override is not None:
            if isinstance(default, float) and override.type_ == RclpyParameter.Type.INTEGER:
                # '-p gain:=2' for a double, as on the embedded transport
                override = RclpyParameter(name, value=float(override.value))
                self.node._parameter_overrides[name] = override
            reason = (wrong_type_reason(name, parameter_type_of(default),
                                             override.value)
                      or run_validator(validator, override.value))
            if reason:
                raise TransportError(
                    f'parameter {name!r} override {override.value!r} rejected: {reason}')
        self._declaring = True
        try:
            value = self.node.declare_parameter(name, default, descriptor).value
        except ParameterException as exc:
            raise TransportError(f'parameter {name!r}: {exc}') from None
        finally:
            self._declaring = False
        if validator is not None:
            self._validators[name] = validator
        return value

    def get_parameter(self, name: str) -> Any:
        try:
            return self.node.get_parameter(name).value
        except ParameterException as exc:
            raise TransportError(str(exc)) from None

    def has_parameter(self, name: str) -> bool:
        return self.node.has_parameter(name)

    def set_parameters(self, parameters: List[Parameter]) -> List[SetParametersResult]:
        results = []
        for p in parameters:
            if not self.node.has_parameter(p.name):
                results.append(SetParametersResult(False, f'parameter {p.name!r} is not declared'))
                continue
            (r,) = self.node.set_parameters([RclpyParameter(p.name, value=p.value)])
            results.append(SetParametersResult(r.successful, r.reason))
        return results

    def add_on_set_parameters_callback(self, callback) -> None:
        self._user_callbacks.append(callback)

    def spin_once(self, timeout_s: Optional[float] = None) -> None:
        if not self._overrides_checked and self.node is not None:
            # The node's parameters are declared by its first spin; rclpy keeps the overrides
            # (-p, params files, parameter_overrides) in Node._parameter_overrides (Jazzy).
            self._overrides_checked = True
            warning = unknown_overrides_warning(self.node._parameter_overrides,
                                                self.node.get_parameters_by_prefix(''))
            if warning:
                self._logger.warning(warning)
        executor = self.executor
        executor.spin_once(timeout_sec=timeout_s)
        # The port's spin_once handles what is ready; rclpy's runs one callback (one message of
        # one subscription). Run the rest of what is ready now, without waiting, as rclpy's own
        # SingleThreadedExecutor runs a handler; a bounded number, so a flood cannot hold us.
        # Each handler triggers the executor's guard condition, so the wait after it can come
        # back with nothing else (rclpy then raises TimeoutException): only a second empty
        # wait in a row means that nothing is ready.
        empty = 0
        for _ in range(DRAIN_LIMIT):
            try:
                handler, _, _ = executor.wait_for_ready_callbacks(timeout_sec=0.0)
            except TimeoutException:
                empty += 1
                if empty == 2:
                    return
                continue
            except ShutdownException:
                return
            empty = 0
            handler()
            if handler.exception() is not None:
                raise handler.exception()
            handler.result()

    def spin(self) -> None:
        while self.ok():  # returns once shutdown() was called, like the embedded transport
            try:
                self.spin_once(0.1)
            except Exception:
                # A signal shuts the context down while a callback runs (rclpy's handler acts
                # at once), so the callback's next publish raises: the shutdown, not an error.
                if self.ok():
                    raise

    def request_shutdown(self) -> None:
        self._shutdown_requested = True

    def ok(self) -> bool:
        return (self.node is not None and not self._shutdown_requested
                and rclpy.ok(context=self._context))

    def shutdown(self) -> None:
        if self.node is not None:
            self.executor.remove_node(self.node)
            self.node.destroy_node()
            self.node = None
            if self._own_context is not None:
                self.executor.shutdown()
            self._shut_own_context()

    def _shut_own_context(self) -> None:
        if self._own_context is not None:
            self._own_context.try_shutdown()
            self._own_context = None


def _complete(waiting: RclpyFuture, done: Future) -> None:
    """Pass a port Future's outcome to the rclpy Future a service coroutine awaits."""
    if done.exception() is not None:
        waiting.set_exception(done.exception())
    else:
        waiting.set_result(done.result())


def create_rclpy_node(name: str, namespace: str = '', args=None, parameter_overrides=None,
                      **kwargs) -> RclpyNode:
    """Create an RclpyNode (the factory behind ``selection.create_node``)."""
    return RclpyNode(name, namespace, args=args, parameter_overrides=parameter_overrides,
                     **kwargs)


def run_rclpy_node(node_factory, args=None) -> int:
    """
    Jazzy main shape: init, build, try spin, finally destroy_node and try_shutdown.

    The first SIGINT ends the run (a KeyboardInterrupt while spinning, as Python's default handler
    raises; during start-up it is recorded and the node is shut down once built); every later one
    is ignored, so that it cannot interrupt the shutdown: under ``ros2 launch``
    a Ctrl-C reaches the node twice (from the terminal, then forwarded by launch), and a second
    KeyboardInterrupt inside ``destroy_node`` would print a traceback and end the process with
    -2. The handlers are installed before ``rclpy.init``, which chains rclpy's own SIGINT and
    SIGTERM handling (context shutdown) in front of them. This is a process's main: when it
    returns, SIGINT stays ignored while the process ends (Python's finalization would otherwise
    reset it to the default action, and a late second SIGINT would still kill the process with
    -2). SIGTERM is only recorded: rclpy's handler shuts the context down, however often it
    comes. Exit status and the ready line follow transport/stop_signals.py.

    :param node_factory: ``node_factory(args)`` returning a NodePort or an object with ``.node``.
    :param args: the command line.
    :return: the process exit status: 0, or 128 + the signal number for a signal that came
        before the node was ready.
    """
    stop = StopSignals()
    spinning = []
    ending = []

    def on_sigint(signum, frame):
        if stop.signum is None and not ending:
            stop.on_signal(signum)
            # Only while spinning: during start-up the interrupt would land anywhere, also
            # between the node's construction and the name that lets the finally destroy it.
            # rclpy's own handler has shut the context down either way.
            if spinning:
                raise KeyboardInterrupt

    def on_sigterm(signum, frame):
        stop.on_signal(signum)

    previous = {}
    if threading.current_thread() is threading.main_thread():
        previous = {signal.SIGINT: signal.signal(signal.SIGINT, on_sigint),
                    signal.SIGTERM: signal.signal(signal.SIGTERM, on_sigterm)}

    def restore():
        for signum, handler in previous.items():
            signal.signal(signum, handler)

    try:
        rclpy.init(args=args)   # rclpy's SIGINT/SIGTERM handling, before anything is built
    except BaseException:
        restore()
        raise
    node = None
    with stop:
        try:
            app = node_factory(args)
            node = app if isinstance(app, port.NodePort) else app.node
            spinning.append(True)
            stop.spin(node)      # not after a signal during start-up: straight to the shutdown
        except (KeyboardInterrupt, ExternalShutdownException):
            pass
        except Exception:
            # A signal during start-up shuts the context down under the node being built, which
            # then fails to create its next entity: that is the requested shutdown, not an error.
            if rclpy.ok():
                raise
        finally:
            ending.append(True)   # from here on a SIGINT is ignored
            if node is not None:
                node.shutdown()
            rclpy.try_shutdown()
            if previous:
                restore()
                if stop.signum is not None:
                    # A signal ended the node: the process is ending, and under ros2 launch a
                    # second Ctrl-C follows the first, which must not raise into its exit. A
                    # main that returned by itself (exit 2, say) leaves the caller's handlers as
                    # they were: SIG_IGN would stay in force, in the process and in every child
                    # it starts later.
                    signal.signal(signal.SIGINT, signal.SIG_IGN)
    return stop.exit_status
