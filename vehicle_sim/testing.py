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
pytest plugin: test ROS 2 code against the simulator with plain pytest, no launch_testing.

Enable it with ``-p vehicle_sim.testing`` (or ``pytest_plugins = ['vehicle_sim.testing']`` in a
``conftest.py``); an installed vehicle_sim registers it as the pytest11 plugin of the same name,
``vehicle_sim.testing``, so naming it again is harmless.

The ``automobile_node`` fixture starts the automobile node in **synchronous** mode in a
subprocess and yields an :class:`AutomobileSim` whose ``client`` is a node on the selected
transport (``VEHICLE_SIM_TRANSPORT``: rclpy on a ROS 2 machine, else the embedded Cyclone DDS
transport). Time only moves when the test calls ``client.step(...)``, so assertions on published
values and on ``/clock`` are deterministic::

    def test_car_moves(automobile_node):
        car = automobile_node.client
        assert car.call('set_cruising_speed', 30.0).success
        car.step(200)                                   # 200 basic steps = 2.0 s
        assert car.latest('current_speed').data > 0.0

Options: ``@pytest.mark.vehicle_sim(car='TeslaModel3', namespace='/sim',
params={'friction': 1.2}, topics=('current_speed',))``, or
``@pytest.mark.parametrize('automobile_node', ['BmwX5'], indirect=True)`` for the car model;
``--vehicle-sim-car`` sets the default model and the ini option ``vehicle_sim_topics`` the
default topics. ``topics`` names the topics the client subscribes to before the first step
(``/clock`` is always one); the default is every Float64Stamped topic. Fewer topics make each
step cheaper (every subscribed topic is a delivery per step); a topic first used later is
subscribed then and misses what was published before (``latest()`` says so at once).

Scenario files: ``run_scenario(path, seed=None)`` runs one and returns its result (each
criterion's verdict and measured value), and files named ``scenario_*.yaml`` are collected as
tests, one per criterion (docs/scenarios.md)::

    def test_stops_before_the_wall():
        result = run_scenario('scenarios/stop_before_obstacle.yaml')
        assert result.passed
        assert result.criterion('reach_goal').value < 5.0     # seconds

Isolation: unless already set, the plugin confines DDS traffic to the loopback interface
(``ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST``) and picks a ROS_DOMAIN_ID from the pid, before
any DDS participant exists; the node subprocess inherits both.
"""

from dataclasses import dataclass, field
import itertools
import os
import signal
import subprocess
import sys
import tempfile
import time
from typing import Any, Callable, Dict, Iterable, List, Optional, Tuple

import pytest

from vehicle_sim.transport.fast_cdr import leading_stamp_ns

# Generous bound for the node subprocess to come up (PyBullet import, discovery).
START_TIMEOUT_S = 60.0
# Bound for a reply or a message that the simulation is known to produce.
DEFAULT_TIMEOUT_S = 10.0
STOP_TIMEOUT_S = 10.0
MAX_HISTORY = 10000
DEFAULT_CAR = 'Car'
# ini option: the topics the fixture's client subscribes to before the first step.
TOPICS_INI = 'vehicle_sim_topics'
_client_ids = itertools.count(1)


# --------------------------------------------------------------------------------------------
# Plugin hooks

def pytest_addoption(parser):
    group = parser.getgroup('vehicle_sim')
    group.addoption('--vehicle-sim-car', default=None, metavar='MODEL',
                    help=f'default car model of the automobile_node fixture ({DEFAULT_CAR})')
    parser.addini(TOPICS_INI, type='args', default=None,
                  help='topics the automobile_node client subscribes to before the first step '
                       '(/clock always; default: every Float64Stamped topic)')


def pytest_configure(config):
    os.environ.setdefault('ROS_AUTOMATIC_DISCOVERY_RANGE', 'LOCALHOST')
    os.environ.setdefault('ROS_DOMAIN_ID', str(1 + os.getpid() % 101))
    config.addinivalue_line(
        'markers', 'vehicle_sim(car=None, namespace=None, params=None, topics=None): options '
                   'of the automobile_node fixture (car model, node namespace, node parameters, '
                   'topics subscribed before the first step)')


def pytest_collect_file(parent, file_path):
    from fnmatch import fnmatch

    from vehicle_sim.scenarios.pytest_items import PATTERN, ScenarioFile
    if fnmatch(file_path.name, PATTERN):
        return ScenarioFile.from_parent(parent, path=file_path)
    return None


def run_scenario(path, seed=None, **options):
    """
    Run a scenario file; return its ScenarioResult (``passed``, ``criteria``, ``criterion(name)``).

    :param path: the scenario file.
    :param seed: overrides the file's seed.
    :param options: ``repeat``, ``gui`` (see vehicle_sim.scenarios.runner.run_scenario).
    """
    from vehicle_sim.scenarios.runner import run_scenario as run
    return run(path, seed=seed, **options)


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
    (``current_speed``, ``set_gear``, ``clock``); types come from ``vehicle_sim.ros.interfaces``.

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
        from vehicle_sim.ros import interfaces as itf
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
        from vehicle_sim.graph import close_names
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
            self._clients[full] = client
        request = self.node.srv(spec.srv_type).Request()
        if value is not None:
            fields = [f for f in _field_names(request)
                      if f != 'structure_needs_at_least_one_member']
            if len(fields) != 1:
                raise ValueError(f'{full} request has fields {fields}: build it yourself')
            setattr(request, fields[0], type(getattr(request, fields[0]))(value))
        return client.call(request, timeout_s)

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


# --------------------------------------------------------------------------------------------
# The node process

class AutomobileSim:
    """
    A synchronous automobile node in a subprocess and a client to drive it.

    :param car: car preset name.
    :param namespace: node namespace ('' = root: endpoints under /automobile).
    :param params: extra node parameters ``{name: value}``.
    :param transport: transport of node and client (default: ``VEHICLE_SIM_TRANSPORT``).
    :param topics: the topics the client subscribes to before the first step (see
        :class:`AutomobileClient`; None: every Float64Stamped topic).
    """

    def __init__(self, car: str = DEFAULT_CAR, namespace: str = '',
                 params: Optional[Dict[str, Any]] = None, transport: Optional[str] = None,
                 start_timeout_s: float = START_TIMEOUT_S,
                 topics: Optional[Iterable[str]] = None):
        self.car = car
        self.namespace = '/' + namespace.strip('/') if namespace.strip('/') else ''
        params = dict(params or {})
        params.setdefault('car_model', car)
        params['synchronous'] = True
        command = [sys.executable, '-m', 'vehicle_sim.ros.automobile_node', '--ros-args']
        for name, value in params.items():
            command += ['-p', f'{name}:={_ros_arg_value(value)}']
        if self.namespace:
            command += ['-r', f'__ns:={self.namespace}']
        env = dict(os.environ)
        env['PYTHONUNBUFFERED'] = '1'
        if transport:
            env['VEHICLE_SIM_TRANSPORT'] = transport
        self._log = tempfile.TemporaryFile(mode='w+')
        self.process = subprocess.Popen(command, env=env, stdout=self._log,
                                        stderr=subprocess.STDOUT, text=True)
        self.client = None
        try:
            period_ms = float(params.get('publish_period_ms', 0) or 0)
            self.client = AutomobileClient(self.namespace, transport=transport,
                                           publish_period_s=period_ms / 1000.0, topics=topics)
            self.client.wait_until_ready(start_timeout_s,
                                         alive=lambda: self.process.poll() is None)
        except BaseException as exc:
            self.close()
            raise RuntimeError(f'the automobile node did not start ({exc}); its output:\n'
                               f'{self.output()}') from exc

    def output(self) -> str:
        """Return what the node printed so far (stdout and stderr)."""
        self._log.flush()
        self._log.seek(0)
        return self._log.read()

    def close(self) -> int:
        """Leave the graph, stop the node (SIGTERM, then SIGKILL) and return its exit status."""
        if self.client is not None:
            self.client.close()
            self.client = None
        if self.process.poll() is None:
            self.process.send_signal(signal.SIGTERM)
            try:
                self.process.wait(STOP_TIMEOUT_S)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
        return self.process.returncode


def _ros_arg_value(value: Any) -> str:
    if isinstance(value, bool):
        return 'true' if value else 'false'
    if isinstance(value, str):
        return value if value else "''"
    return repr(value) if isinstance(value, float) else str(value)


@pytest.fixture
def automobile_node(request):
    """
    Start a synchronous automobile node in a subprocess; yield an :class:`AutomobileSim`.

    Options: marker ``vehicle_sim(car=..., namespace=..., params=..., topics=...)``; indirect
    parametrization with a car model name; ``--vehicle-sim-car``; ini ``vehicle_sim_topics``.
    """
    options: Dict[str, Any] = {}
    ini_topics = request.config.getini(TOPICS_INI)
    if ini_topics:
        options['topics'] = tuple(ini_topics)
    marker = request.node.get_closest_marker('vehicle_sim')
    if marker is not None:
        options.update(marker.kwargs)
        if marker.args:
            options.setdefault('car', marker.args[0])
    if getattr(request, 'param', None) is not None:
        param = request.param
        options.update(param if isinstance(param, dict) else {'car': param})
    options.setdefault('car', request.config.getoption('--vehicle-sim-car') or DEFAULT_CAR)
    sim = AutomobileSim(**options)
    try:
        yield sim
    finally:
        sim.close()
