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
``robot/time_step`` runs in chunks from the node's loop (issue 7, item 3), over the wire.

The automobile and diff_robot nodes run in subprocesses. However long a step request is, the
node answers other requests meanwhile, a second request waits its turn and is answered after
its own steps, and SIGTERM ends the node. Sim-time assertions are exact (deterministic);
waits are generous bounds on outcomes.
"""

import signal

from automobile_helpers import (
    make_client_node,
    NodeProcess,
    stamp_of,
    VehicleClient,
    wait_for,
    wait_node_matched,
    WAIT_S,
)
import pytest

from vehicle_sim.ros import robot_interfaces as ri
from vehicle_sim.ros.time_step import TimeStepService

pytestmark = pytest.mark.transport

SET_INT = 'vehicle_msgs/srv/SetInt'
# A valid multiple of the 10 ms basic step: about 2.1e8 steps, hours of work.
HUGE_MS = 2147483640


@pytest.fixture
def tester():
    node = make_client_node('time_step_tester')
    yield node
    node.shutdown()


def _time_step_client(node, name, node_fqn):
    # Returned once the node ``node_fqn`` (just started) has matched the client: a request
    # written before would be lost (docs/transport.md, "A service just discovered")
    client = node.create_client(SET_INT, name)
    assert client.wait_for_service(WAIT_S), name
    wait_node_matched(node, f'{node_fqn}/get_parameters', 'rcl_interfaces/srv/GetParameters')
    return client, node.srv(SET_INT).Request


@pytest.mark.parametrize('stop_signal', [signal.SIGTERM, signal.SIGINT], ids=['TERM', 'INT'])
def test_automobile_serves_setters_and_getters_while_a_huge_time_step_runs(tester, stop_signal):
    ns = f'ts_huge_{stop_signal.name.lower()}'
    process = NodeProcess('--ros-args', '-r', f'__ns:=/{ns}', '-p', 'synchronous:=true')
    try:
        car = VehicleClient(tester, ns)
        step, request = _time_step_client(tester, f'/{ns}/robot/time_step', f'/{ns}/automobile')
        car.subscribe('automobile/current_speed')
        huge = step.call_async(request(value=HUGE_MS))
        # The steps are running: sim time advances, and the node answers meanwhile.
        getter = tester.create_client('vehicle_msgs/srv/GetFloat', f'/{ns}/robot/get_time')
        assert getter.wait_for_service(WAIT_S)
        get_time = tester.srv('vehicle_msgs/srv/GetFloat').Request
        assert wait_for(lambda: getter.call(get_time(), WAIT_S).value > 0.5), process.text()
        setter = tester.create_client('vehicle_msgs/srv/SetFloat',
                                      f'/{ns}/automobile/set_cruising_speed')
        assert setter.wait_for_service(WAIT_S)
        set_speed = tester.srv('vehicle_msgs/srv/SetFloat').Request(value=20.0)
        assert setter.call(set_speed, WAIT_S).success is True
        # The setter took effect while the same request keeps stepping: the car speeds up.
        assert wait_for(lambda: car.latest.get('automobile/current_speed') is not None
                        and car.latest['automobile/current_speed'].data > 1.0, spin=tester)
        assert not huge.done()
        process.proc.send_signal(stop_signal)
        assert process.wait() == 0, process.text()
        assert not huge.done()   # never answered: its steps were not done
    finally:
        process.stop()


def test_automobile_answers_queued_time_steps_in_order_after_their_own_steps(tester):
    process = NodeProcess('--ros-args', '-r', '__ns:=/ts_fifo', '-p', 'synchronous:=true')
    try:
        step, request = _time_step_client(tester, '/ts_fifo/robot/time_step',
                                          '/ts_fifo/automobile')
        getter = tester.create_client('vehicle_msgs/srv/GetFloat', '/ts_fifo/robot/get_time')
        assert getter.wait_for_service(WAIT_S)
        get_time = tester.srv('vehicle_msgs/srv/GetFloat').Request
        start_s = getter.call(get_time(), WAIT_S).value
        answered, time_at_first = [], []

        def on_first(future):
            answered.append('first')
            time_at_first.append(getter.call_async(get_time()))

        first = step.call_async(request(value=3000))   # 300 basic steps
        second = step.call_async(request(value=500))   # 50 basic steps, queued behind
        first.add_done_callback(on_first)
        second.add_done_callback(lambda future: answered.append('second'))
        assert tester.spin_until(lambda: second.done() and time_at_first
                                 and time_at_first[0].done(), WAIT_S), process.text()
        assert answered == ['first', 'second']
        assert first.result().success and second.result().success
        # The first was answered once its 300 steps were done (the second's may have begun).
        assert start_s + 3.0 - 1e-9 <= time_at_first[0].result().value <= start_s + 3.5 + 1e-9
        # After both: exactly 350 basic steps.
        assert getter.call(get_time(), WAIT_S).value == pytest.approx(start_s + 3.5, abs=1e-9)
    finally:
        process.stop()


def test_diff_robot_serves_and_stops_while_a_huge_time_step_runs(tester):
    process = NodeProcess('--ros-args', '-r', '__ns:=/ts_robot', '-p', 'synchronous:=true',
                          module='vehicle_sim.ros.diff_robot_node')
    try:
        joint_states = []
        tester.create_subscription(ri.ROBOT_JOINT_STATES.ros_type,
                                   '/ts_robot/diff_robot/joint_states', joint_states.append,
                                   ri.ROBOT_JOINT_STATES.qos)
        step, request = _time_step_client(tester, '/ts_robot/diff_robot/robot/time_step',
                                          '/ts_robot/diff_robot')
        huge = step.call_async(request(value=HUGE_MS))
        assert wait_for(lambda: joint_states and stamp_of(joint_states[-1]) > 0.5,
                        spin=tester), process.text()
        # Its parameter services answer meanwhile.
        params = tester.create_client('rcl_interfaces/srv/GetParameters',
                                      '/ts_robot/diff_robot/get_parameters')
        assert params.wait_for_service(WAIT_S)
        answer = params.call(tester.srv('rcl_interfaces/srv/GetParameters').Request(
            names=['synchronous']), WAIT_S)
        assert [v.bool_value for v in answer.values] == [True]
        process.proc.send_signal(signal.SIGTERM)
        assert process.wait() == 0, process.text()
        assert not huge.done()
    finally:
        process.stop()


class _Logger:
    def __init__(self):
        self.warnings = []

    def warn(self, message):
        self.warnings.append(message)


class _Node:
    """Just enough of a port node for TimeStepService: a logger and manual timers."""

    def __init__(self):
        self.logger = _Logger()
        self.timers = []
        self.stopping = False

    def ok(self):
        return not self.stopping

    def get_logger(self):
        return self.logger

    def create_timer(self, period_s, callback):
        timer = _Timer(callback)
        self.timers.append(timer)
        return timer


class _Timer:
    def __init__(self, callback):
        self.callback = callback
        self.cancelled = False

    def cancel(self):
        self.cancelled = True

    def reset(self):
        self.cancelled = False


class _Response:
    success = None


class _Request:
    def __init__(self, value):
        self.value = value


@pytest.mark.parametrize('value, steps', [(0, 1), (10, 1), (30, 3), (HUGE_MS, HUGE_MS // 10)])
def test_time_step_service_converts_a_duration_to_basic_steps(value, steps):
    service = TimeStepService(_Node(), 10, lambda: None, synchronous=True)
    assert service.steps_for(value) == steps


@pytest.mark.parametrize('value', [-10, 7, 15])
def test_time_step_service_refuses_what_is_not_a_multiple_and_queues_nothing(value):
    node = _Node()
    service = TimeStepService(node, 10, lambda: None, synchronous=True)
    response = service.handle('/robot/time_step', _Request(value), _Response())
    assert response.success is False and service.queued == 0 and not node.timers
    assert 'refused' in node.logger.warnings[0]


def test_time_step_service_runs_requests_in_order_one_chunk_at_a_time():
    node, steps = _Node(), []
    # chunk_s 0: one basic step per timer call, so each call is one chunk boundary.
    service = TimeStepService(node, 10, lambda: steps.append(1), synchronous=True, chunk_s=0.0)
    first = service.handle('/robot/time_step', _Request(30), _Response())
    second = service.handle('/robot/time_step', _Request(0), _Response())
    (timer,) = node.timers
    done = []
    first.add_done_callback(lambda f: done.append(('first', len(steps))))
    second.add_done_callback(lambda f: done.append(('second', len(steps))))
    while not timer.cancelled:
        timer.callback()
    assert done == [('first', 3), ('second', 4)]
    assert first.result().success and second.result().success
    # A later request of more than one step re-arms the same timer.
    service.handle('/robot/time_step', _Request(20), _Response())
    assert node.timers == [timer] and not timer.cancelled


@pytest.mark.parametrize('value', [0, 10])
def test_time_step_service_steps_one_step_in_the_callback_when_nothing_is_queued(value):
    node, steps = _Node(), []
    service = TimeStepService(node, 10, lambda: steps.append(1), synchronous=True)
    response = _Response()
    assert service.handle('/robot/time_step', _Request(value), response) is response
    assert response.success is True and steps == [1]
    assert service.queued == 0 and not node.timers


def test_time_step_service_queues_a_one_step_request_served_during_a_one_step_request():
    # The node serves requests between the physics and the publishing of a step: a second
    # one-step request arriving then is answered after the first, with its own step.
    node, steps, inner = _Node(), [], []

    def step_once():
        steps.append(1)
        if len(steps) == 1:
            inner.append(service.handle('/robot/time_step', _Request(0), _Response()))

    service = TimeStepService(node, 10, step_once, synchronous=True)
    outer = service.handle('/robot/time_step', _Request(0), _Response())
    assert outer.success is True and steps == [1]
    (second,) = inner
    assert not second.done() and service.queued == 1
    (timer,) = node.timers
    timer.callback()
    assert second.result().success is True and steps == [1, 1] and timer.cancelled


def test_time_step_service_queues_a_one_step_request_once_the_node_is_stopping():
    node, steps = _Node(), []
    service = TimeStepService(node, 10, lambda: steps.append(1), synchronous=True)
    node.stopping = True
    request = service.handle('/robot/time_step', _Request(0), _Response())
    node.timers[0].callback()
    assert steps == [] and not request.done()


def test_time_step_service_stops_stepping_once_the_node_is_stopping():
    node, steps = _Node(), []
    service = TimeStepService(node, 10, lambda: steps.append(1), synchronous=True)
    request = service.handle('/robot/time_step', _Request(HUGE_MS), _Response())
    node.stopping = True   # a signal arrived
    node.timers[0].callback()
    assert steps == [] and not request.done()
