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
A test-side ROS node that drives a synchronous automobile node: :class:`AutomobileClient`.

It subscribes to the node's topics before the first step (so discovery loses nothing), keeps
each topic's messages as bytes and decodes them when looked at, calls the node's services by
their short names and steps the simulation through ``robot/time_step``. The pytest plugin
(:mod:`vehicle_sim.testing`) gives tests one through its ``automobile_node`` fixture.
"""

from dataclasses import dataclass, field
import itertools
import os
import time
from typing import Any, Callable, Dict, Iterable, List, Optional, Tuple

from vehicle_sim.transport.fast_cdr import leading_stamp_ns
from vehicle_sim.transport.first_call import call_until_answered

# Bound for a reply or a message that the simulation is known to produce.
DEFAULT_TIMEOUT_S = 10.0
MAX_HISTORY = 10000
_client_ids = itertools.count(1)


# --------------------------------------------------------------------------------------------
# Time stamps

def stamp_ns(msg: Any) -> int:
    """Return a message's time stamp [ns]: ``header.stamp``, or ``clock`` for a Clock."""
    stamp = msg.clock if hasattr(msg, 'clock') else msg.header.stamp
    return int(stamp.sec) * 1_000_000_000 + int(stamp.nanosec)


def stamp_s(msg: Any) -> float:
    """Return the time stamp of a message in seconds."""
    return stamp_ns(msg) * 1e-9


# --------------------------------------------------------------------------------------------
# The client

@dataclass
class _Topic:
    """
    A subscribed topic: what came in, decoded when first looked at.

    The subscription keeps each message's bytes; a test looks at few of the messages of every
    step (the newest, mostly), so decoding them all on receipt would cost the test's CPU for
    nothing.
    """

    name: str
    ros_type: str
    decode: Callable[[bytes], Any]
    items: List[Any] = field(default_factory=list)   # bytes, or the message once decoded
    subscription: Any = None
    # The client's step count when subscribed (None: before the client's first request).
    subscribed_at_step: Optional[int] = None
    # The type's CDR starts with its stamp (Header-led types, Clock): read without decoding.
    leading_stamp: bool = False

    def add(self, data: bytes) -> None:
        items = self.items
        items.append(data)
        if len(items) > MAX_HISTORY:
            del items[:len(items) - MAX_HISTORY]

    def __len__(self) -> int:
        return len(self.items)

    def __getitem__(self, index: int):
        item = self.items[index]
        if isinstance(item, bytes):
            item = self.items[index] = self.decode(item)
        return item

    def stamp_ns(self, index: int) -> Optional[int]:
        """Return the stamp of a message [ns] (None for a type without one), decoding if needed."""
        item = self.items[index]
        if self.leading_stamp and isinstance(item, bytes):
            found = leading_stamp_ns(item)
            if found is not None:
                return found
        msg = self[index]
        return stamp_ns(msg) if _has_stamp(msg) else None

    @property
    def messages(self) -> List[Any]:
        """Every message kept (oldest first), decoded."""
        return [self[index] for index in range(len(self.items))]


class AutomobileClient:
    """
    A test node driving a synchronous automobile node through its ROS interface.

    Endpoint names may be given in full (``/automobile/current_speed``, ``/clock``), relative to
    the vehicle (``automobile/current_speed``, ``robot/time_step``) or by their last part
    (``current_speed``, ``set_gear``, ``clock``); types come from
    ``vehicle_sim.ros.automobile_interfaces``.

    :param namespace: the automobile node's namespace ('' or '/' for the root).
    :param transport: 'auto', 'rclpy' or 'dds' (default: ``VEHICLE_SIM_TRANSPORT``).
    :param publish_period_s: the node's topic period (0 = each basic step).
    :param timeout_s: bound for replies and expected messages.
    :param topics: names of the topics to subscribe to before the first request, so that none
        of their messages is lost to discovery; ``/clock`` always is one (``step()`` reads it).
        None: every Float64Stamped topic. Each subscribed topic costs a delivery per step in
        both processes. A topic first used later is subscribed then: what the node published
        before is gone, so ``latest()`` of it right after that raises ``TimeoutError`` at once.
    """

    def __init__(self, namespace: str = '', transport: Optional[str] = None,
                 publish_period_s: float = 0.0, timeout_s: float = DEFAULT_TIMEOUT_S,
                 topics: Optional[Iterable[str]] = None):
        from vehicle_sim.ros import automobile_interfaces as itf
        from vehicle_sim.transport.selection import create_node
        self._itf = itf
        self.namespace = '/' + namespace.strip('/') if namespace.strip('/') else ''
        self.timeout_s = timeout_s
        self.publish_period_s = publish_period_s
        self._found: Dict[Tuple[str, str], Tuple[Any, str]] = {}   # (name, kind) -> _find
        if topics is None:
            specs = [spec for spec in itf.TOPICS
                     if spec.ros_type in (itf.FLOAT64_STAMPED, itf.CLOCK.ros_type)]
        else:
            if isinstance(topics, str):
                raise TypeError(f'topics must be a sequence of topic names, got {topics!r}')
            specs = [self._find(name, itf.TOPICS, 'topic')[0] for name in topics]
            specs = [itf.CLOCK] + [spec for i, spec in enumerate(specs)
                                   if spec is not itf.CLOCK and spec not in specs[:i]]
        self.node = create_node(f'_vehicle_sim_test_{os.getpid()}_{next(_client_ids)}',
                                transport=transport,
                                args=['--ros-args', '--disable-rosout-logs'])
        self._topics: Dict[str, _Topic] = {}
        self._clients: Dict[str, Any] = {}
        self._time_s = None       # the node's answer to robot/get_time [s]
        self._expected_s = None   # start time plus the steps this client requested [s]
        self.basic_time_step_ms = None
        self._steps = None        # step() calls since ready (None before the first request)
        # Subscriptions first: once a service reply comes back, the node has discovered every
        # reader created before the client (DDS announces endpoints in order), so no message
        # of a later step can be lost to discovery.
        for spec in specs:
            self._subscribe(spec)

    # ------------------------------------------------------------------------ names

    def _full(self, spec_name: str) -> str:
        return spec_name if spec_name.startswith('/') else f'{self.namespace}/{spec_name}'

    def _find(self, name: str, specs, kind: str):
        found = self._found.get((name, kind))    # tests ask for the same few names each step
        if found is not None:
            return found
        for spec in specs:
            full = self._full(spec.name)
            if name in (full, spec.name, spec.short_name, full.lstrip('/')):
                found = self._found[(name, kind)] = (spec, full)
                return found
        from vehicle_sim.transport.dds.graph import close_names
        names = [self._full(s.name) for s in specs]
        close = close_names(name if name.startswith('/') else '/' + name, names)
        hint = f'; did you mean: {", ".join(close)}' if close else ''
        raise KeyError(f'unknown {kind} {name!r}{hint}')

    # ------------------------------------------------------------------------ topics

    def _subscribe(self, spec) -> _Topic:
        full = self._full(spec.name)
        found = self._topics.get(full)
        if found is None:
            from vehicle_sim.transport.qos import QosProfile
            found = _Topic(full, spec.ros_type,
                           lambda data, ros_type=spec.ros_type: self.node.deserialize(ros_type,
                                                                                        data))
            first = _field_names(self.node.msg(spec.ros_type)())[:1]
            found.leading_stamp = first in (['header'], ['clock'])
            qos = QosProfile(depth=max(10, spec.qos.depth), durability=spec.qos.durability)
            found.subscription = self.node.create_subscription(
                spec.ros_type, full, found.add, qos, raw=True)
            found.subscribed_at_step = self._steps
            self._topics[full] = found
        return found

    @property
    def subscribed_topics(self) -> Tuple[str, ...]:
        """The full names of the topics subscribed so far, in the order subscribed."""
        return tuple(self._topics)

    def topic(self, name: str) -> _Topic:
        """Return the subscription record of a topic (subscribing now if needed)."""
        spec, _ = self._find(name, self._itf.TOPICS, 'topic')
        return self._subscribe(spec)

    def messages(self, name: str) -> List[Any]:
        """Return every message received on a topic so far (oldest first)."""
        self.node.spin_once(0.0)
        return self.topic(name).messages

    def _fresh_after_ns(self) -> int:
        """Stamp the newest message must reach: the last publishing step at the current time."""
        if self._expected_s is None:
            return 0
        time_s = self._expected_s
        if self.publish_period_s > 0.0:
            time_s = (time_s // self.publish_period_s) * self.publish_period_s
        # Half a basic step of slack: stamps are rounded to the step, not to the float sum.
        return int(round(time_s * 1e9)) - int(self.basic_time_step_ms * 500_000)

    def latest(self, name: str, timeout_s: Optional[float] = None):
        """
        Return the newest message of a topic published at (or after) the current sim time.

        :raises TimeoutError: when no such message arrived within the timeout.
        """
        return self._fresh(name, timeout_s)[-1]

    def _fresh(self, name: str, timeout_s: Optional[float] = None) -> _Topic:
        """Return the topic's record once its newest message is of the current sim time."""
        topic = self.topic(name)
        needed = self._fresh_after_ns()

        def fresh():
            if not len(topic):
                return False
            found = topic.stamp_ns(-1)
            return found is None or found >= needed

        if topic.subscribed_at_step is not None and topic.subscribed_at_step == self._steps:
            # Subscribed since the last step: the node published that step's message before
            # the subscription existed and publishes nothing until the next step.
            self.node.spin_once(0.0)
            if not fresh():
                raise TimeoutError(
                    f'{topic.name} was first used after the last step: its message of that '
                    'step was published before the subscription; list it in topics= '
                    '(marker vehicle_sim(topics=...)) to subscribe before the first step')
        if not self.node.spin_until(fresh, self.timeout_s if timeout_s is None else timeout_s):
            got = (f'; newest stamp {stamp_s(topic[-1]):.3f} s' if len(topic)
                   else '; nothing received')
            raise TimeoutError(f'no message on {topic.name} for sim time '
                               f'{(self._expected_s or 0.0):.3f} s{got}')
        return topic

    def wait_for(self, name: str, predicate: Callable[[Any], bool],
                 timeout_s: Optional[float] = None):
        """
        Return the first message on a topic (the newest received included) ``predicate`` accepts.

        Only spins (lets messages in); it never steps the simulation.

        :raises TimeoutError: when none did within the timeout.
        """
        topic = self.topic(name)
        index = max(0, len(topic) - 1)
        found = []

        def check():
            nonlocal index
            while index < len(topic):
                msg = topic[index]
                index += 1
                if predicate(msg):
                    found.append(msg)
                    return True
            return False

        if not self.node.spin_until(check, self.timeout_s if timeout_s is None else timeout_s):
            raise TimeoutError(f'no message on {topic.name} matched the predicate')
        return found[0]

    # ------------------------------------------------------------------------ services

    def call(self, name: str, value: Any = None, timeout_s: Optional[float] = None):
        """
        Call a service; ``value`` fills the request's single field (None: the defaults).

        :return: the response (``.success`` for setters, ``.value`` for getters).
        """
        spec, full = self._find(name, self._itf.NODE_SERVICES, 'service')
        timeout_s = self.timeout_s if timeout_s is None else timeout_s
        client = self._clients.get(full)
        if client is None:
            client = self.node.create_client(spec.srv_type, full)
            if not client.wait_for_service(timeout_s):
                raise TimeoutError(f'service {full} is not available')
            self._await_node_match(timeout_s)
            self._clients[full] = client
        request = self.node.srv(spec.srv_type).Request()
        if value is not None:
            fields = [f for f in _field_names(request)
                      if f != 'structure_needs_at_least_one_member']
            if len(fields) != 1:
                raise ValueError(f'{full} request has fields {fields}: build it yourself')
            setattr(request, fields[0], type(getattr(request, fields[0]))(value))
        return client.call(request, timeout_s)

    def _await_node_match(self, timeout_s: float) -> None:
        # A request written before the node has matched the client's request writer is lost
        # (docs/transport.md, "A service just discovered"). The answer to a getter of a client
        # made after it, sent again until answered, says the node has matched it.
        spec, full = self._find('robot/get_time', self._itf.NODE_SERVICES, 'service')
        probe = self.node.create_client(spec.srv_type, full)
        if not probe.wait_for_service(timeout_s):
            raise TimeoutError(f'service {full} is not available')
        call_until_answered(probe, self.node.srv(spec.srv_type).Request(), timeout_s)

    def sim_time(self) -> float:
        """Return the simulated time [s] (robot/get_time)."""
        self._time_s = float(self.call('robot/get_time').value)
        return self._time_s

    def step(self, steps: int = 1, ms: Optional[int] = None) -> float:
        """
        Advance the simulation by ``steps`` basic steps, or by ``ms`` milliseconds.

        :return: the simulated time after the step [s] (the stamp of the node's /clock).
        :raises AssertionError: when the node refused the step.
        """
        if self.basic_time_step_ms is None:
            self.basic_time_step_ms = int(round(self.call('robot/get_basic_time_step').value))
        if ms is None:
            if steps < 1:
                raise ValueError(f'steps must be >= 1, got {steps}')
            ms = steps * self.basic_time_step_ms
        response = self.call('robot/time_step', int(ms),
                             timeout_s=max(self.timeout_s, 0.05 * ms))
        assert response.success, (f'robot/time_step {ms} ms refused (a multiple of '
                                  f'{self.basic_time_step_ms} ms, node synchronous?)')
        self._expected_s += max(ms, self.basic_time_step_ms) / 1000.0
        self._steps += 1
        # The node publishes /clock at every step, before its reply: the /clock message of the
        # new time is the answer, without a robot/get_time round trip.
        self._time_s = self._fresh(self._itf.CLOCK.name).stamp_ns(-1) * 1e-9
        return self._time_s

    def wait_until_ready(self, timeout_s: float, alive: Callable[[], bool] = lambda: True):
        """Wait for the node's services and the subscriptions' matches; start the time base."""
        deadline = time.monotonic() + timeout_s
        while True:
            try:
                self.sim_time()
                break
            except TimeoutError:
                if not alive() or time.monotonic() >= deadline:
                    raise
        for topic in self._topics.values():
            if not self.node.spin_until(
                    lambda t=topic: t.subscription.get_publisher_count() > 0,
                    max(0.0, deadline - time.monotonic())):
                raise TimeoutError(f'{topic.name}: no publisher matched')
        self.basic_time_step_ms = int(round(self.call('robot/get_basic_time_step').value))
        self._expected_s = self._time_s
        self._steps = 0

    def close(self) -> None:
        self.node.shutdown()


def _field_names(msg) -> List[str]:
    if hasattr(msg, 'get_fields_and_field_types'):
        return list(msg.get_fields_and_field_types())
    import dataclasses
    return [f.name for f in dataclasses.fields(msg)]


def _has_stamp(msg) -> bool:
    return hasattr(msg, 'clock') or hasattr(getattr(msg, 'header', None), 'stamp')
