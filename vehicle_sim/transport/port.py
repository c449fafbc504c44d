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
conventions, as rmw_cyclonedds does). This module holds the abstract port: publishers,
subscriptions, services, clients, timers and the node. Its adapter-neutral parts live beside it,
as rclpy splits them: ``errors``, ``qos``, ``names``, ``parameter_types``, ``ros_time``,
``logger``, ``future`` and ``reader_gate``.
"""

import abc
import time
from typing import Any, Callable, List, Optional, Tuple

from vehicle_sim.transport import stop_signals
from vehicle_sim.transport.errors import TransportError
from vehicle_sim.transport.future import Future
from vehicle_sim.transport.logger import Logger
from vehicle_sim.transport.names import fully_qualified_node_name
from vehicle_sim.transport.parameter_types import (
    OnSetParametersCallback,
    Parameter,
    SetParametersResult,
    Validator,
)
from vehicle_sim.transport.publish_tap import FunctionTap, PublishTap, tap_publisher
from vehicle_sim.transport.qos import as_qos, QosProfile
from vehicle_sim.transport.reader_gate import ALWAYS_OPEN, ReaderGate
from vehicle_sim.transport.ros_time import Time


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


class ServiceServer(abc.ABC):
    """A service server, as ``create_service`` returns it (not an interface table's row)."""

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

    _publish_taps: Tuple[PublishTap, ...] = ()

    def add_publish_tap(self, tap: PublishTap) -> None:
        """
        Attach ``tap`` to the node's publishers and to the services created from now on.

        Publishers created before (the node's own ``/rosout`` and ``/parameter_events``) are
        tapped too, but a row whose reader gate a node read at wiring keeps that gate: attach
        the tap before the node creates its endpoints (see PublishTap).
        """
        self._publish_taps = tuple(self._publish_taps) + (tap,)
        for publisher, ros_type, qos, serialize in getattr(self, '_tappable', ()):
            self._apply_taps((tap,), publisher, ros_type, qos, serialize)

    def tap_publishers(self, tap: Callable[[str, str, 'QosProfile'], Optional[Callable]]) -> None:
        """
        Hand every message this node publishes to ``tap`` too, as its CDR bytes (a recorder).

        The function form of :meth:`add_publish_tap`: ``tap(topic, ros_type, qos)`` is called
        once for each publisher of the node, those created before and after, and returns
        ``write(data)`` (called with the bytes of each message, after it is sent) or None to
        leave that publisher alone. A tapped publisher's gate stays open: every message is
        built, whether a subscriber is matched or not. Several taps may be attached (a recorder
        and a live view).
        """
        self.add_publish_tap(FunctionTap(tap))

    def _tap(self, publisher: Publisher, ros_type: str, qos, serialize) -> Publisher:
        # For the adapters' create_publisher: remember the publisher (a tap attached later
        # taps it too) and hand its messages to the taps attached so far.
        qos = as_qos(qos)
        if '_tappable' not in self.__dict__:
            self._tappable = []
        self._tappable.append((publisher, ros_type, qos, serialize))
        if self._publish_taps:
            self._apply_taps(self._publish_taps, publisher, ros_type, qos, serialize)
        return publisher

    @staticmethod
    def _apply_taps(taps, publisher, ros_type, qos, serialize) -> None:
        sinks = [sink for sink in (tap.topic(publisher.topic_name, ros_type, qos)
                                   for tap in taps) if sink is not None]
        if sinks:
            tap_publisher(publisher, sinks, serialize)

    def _tap_service(self, service_name: str, srv_type: str, callback) -> None:
        # For the adapters' create_service.
        for tap in self._publish_taps:
            tap.service(service_name, srv_type, callback)

    def call_soon(self, callback: Callable[[], None]) -> None:
        """
        Run ``callback()`` on the node's thread at its next spin (or ``serve_pending``).

        The one method of the port that another thread may call: a server running its own
        threads (the Foxglove live view) hands the node its requests this way.
        """
        raise TransportError('this transport cannot run callbacks from another thread')

    @abc.abstractmethod
    def create_subscription(self, ros_type: str, topic: str, callback, qos=None, *,
                            raw: bool = False) -> Subscription:
        """
        Call ``callback(message)`` for each message received on ``topic``.

        :param raw: hand the callback each message's serialized bytes (CDR with its 4-byte
            encapsulation header, as rclpy's ``raw=True``) instead of the message; decode one
            later with :meth:`deserialize` (a reader that keeps many messages and looks at few).
        """

    def deserialize(self, ros_type: str, data: bytes):
        """Return the message of ``ros_type`` whose serialized bytes are ``data``."""
        return self.msg(ros_type).deserialize(bytes(data))

    def deserialize_as(self, message_class, data: bytes):
        """Return the message of ``message_class`` (a ``msg()`` or ``srv()`` class) in ``data``."""
        return message_class.deserialize(bytes(data))

    def serialize(self, msg) -> bytes:
        """Return the serialized bytes of ``msg`` (CDR with its 4-byte encapsulation header)."""
        return bytes(msg.serialize())

    @abc.abstractmethod
    def create_service(self, srv_type: str, name: str, callback) -> ServiceServer:
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
