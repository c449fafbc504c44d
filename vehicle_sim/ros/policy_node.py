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
A trained policy drives a car of the automobile node: ``vehicle-sim policy run MODEL.zip``.

The node reads the ego's topics (:mod:`.policy_interfaces`), builds the policy's observation as
the Gym environment does (:mod:`.policy_observation`) and writes its action as the car's
Webots-level setters (:mod:`.policy_actions`), at the policy's rate on simulated time:

- the node answers on a grid of simulated time, every :func:`answer_period_s`: the objects'
  period (``objects_rate``, as the automobile node schedules them: core's SampleSchedule)
  when the policy reads them, else the policy's period;
- a *tick* is a grid /clock at a multiple of the policy's period (the card's action_repeat x
  time_step: the environment's env step), and the first grid /clock (with ``objects``: the
  first step the objects are published); at a tick the node waits until the odometry, lane
  state and objects stamped at that time have arrived (or later ones: a node running in real
  time does not wait for the policy, and its newest messages are read), asks the policy
  (``predict(obs, deterministic=True)``) and calls the setters, one after another in the
  environment's order (a brake sent before the throttle that leaves cruise control would
  reach a car still cruising); a tick that falls due while they are answered (a node running
  in real time) comes once they have;
- at every grid /clock, once a tick's setters answered, it publishes the action in force on
  ``<ns>/policy/action``: the scenario runner's lockstep topic (``sync_period`` = the grid), so
  that a scenario waits for the policy and runs as fast as the policy keeps up. Before the
  first tick the car keeps its start state (at rest, as after the environment's reset).

Errors end the node with a message (:attr:`PolicyNode.error`): a period that is not a whole
number of the node's basic steps (a policy faster than the simulation), the automobile
services not there, the topics of a tick not arriving within ``timeout_s`` (wall clock; the
message names the topics waited for), a setter that refuses a value.
"""

import math
import time

import numpy as np

from vehicle_sim.core.sensors.sampling import SampleSchedule
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.traffic.params import OBJECTS_RATE
from vehicle_sim.ros import automobile_interfaces as itf
from vehicle_sim.ros import policy_interfaces as pi
from vehicle_sim.ros.endpoints import Outputs, subscribe
from vehicle_sim.ros.policy_observation import LANE, OBJECTS, stamp_s
from vehicle_sim.transport.first_call import call_until_answered
from vehicle_sim.transport.selection import create_node

# How often the node checks its wall-clock deadlines [s].
WATCH_PERIOD_S = 0.05
# Default wall-clock bound on a tick's topics and the services' appearance [s].
DEFAULT_TIMEOUT_S = 30.0


class PolicyNode:
    """
    The policy driver: a policy, an observation builder and an action writer on the transport.

    :param policy: any object with ``predict(obs, deterministic=True)`` -> (action, state).
    :param builder: ObservationBuilder of the policy's keys.
    :param writer: ActionWriter of the policy's action layout.
    :param period_s: the policy's period [s] (action_repeat x time_step).
    :param namespace: the vehicle's namespace ('' = the default car).
    :param timeout_s: wall-clock bound on the services' appearance and on each tick's topics.
    :param objects_rate_hz: the rate the automobile node publishes the objects at (its
        ``objects_rate``, or the world's ``traffic: objects_rate``).
    """

    def __init__(self, policy, builder, writer, period_s, namespace='', timeout_s=None,
                 args=None, transport=None, node_name=pi.POLICY_NODE_NAME,
                 objects_rate_hz=OBJECTS_RATE.default):
        if not (math.isfinite(period_s) and period_s > 0.0):
            raise InvalidParameterError(f'policy period {period_s!r} s: must be > 0')
        self.policy = policy
        self.builder = builder
        self.writer = writer
        self.period_s = float(period_s)
        self.namespace = namespace.strip('/')
        self.timeout_s = DEFAULT_TIMEOUT_S if timeout_s is None else float(timeout_s)
        if not (math.isfinite(objects_rate_hz) and objects_rate_hz > 0.0):
            raise InvalidParameterError(f'objects rate {objects_rate_hz!r} Hz: must be > 0')
        self.objects_rate_hz = float(objects_rate_hz)
        self._objects_due = None        # SampleSchedule of the objects (with 'objects')
        self._objects_step = None       # the last step the objects were due
        self.error = None
        self.ticks = 0                  # ticks acted on
        self._tick_step = 0             # the basic step of the last tick
        self.answers = 0                # /policy/action messages published
        self.last_obs = None
        self.action = None              # the physical action in force
        self._latest = {}               # input row -> latest message
        self._pending = None            # tick time waiting for its topics, or None
        self._pending_since = None
        self._calls = None              # a tick's setters still to answer, in call order
        self._deferred = None           # (step, time) of a tick due while they were answered
        self._clock_deadline = None
        self.node = create_node(node_name, args=args, transport=transport)
        try:
            self._setup()
        except BaseException:
            self.node.shutdown()
            raise

    def _name(self, name):
        return itf.vehicle_name(name, self.namespace)

    def _setup(self):
        node = self.node
        self.inputs = [pi.ODOM_IN]
        if LANE in self.builder.keys or self.writer.layout.reads_lane:
            self.inputs.append(pi.LANE_STATE_IN)
        # the objects table: the policy's key, or the guard of guarded_speed_steering
        self._reads_objects = OBJECTS in self.builder.keys or self.writer.layout.reads_objects
        if self._reads_objects:
            self.inputs.append(pi.OBJECTS_IN)
        self._subs = subscribe(node, {row: self._keeper(row) for row in self.inputs},
                               resolve=self._name)
        self._subs += subscribe(node, {pi.TF_STATIC_IN: self.builder.frames.add})
        self._clients = {name: node.create_client(pi.service_type(name), self._name(name))
                         for name in self.writer.services}
        step_name = 'robot/get_basic_time_step'
        step_client = node.create_client(pi.service_type(step_name), self._name(step_name))
        self._wait_for_services(dict(self._clients, **{step_name: step_client}))
        request = node.srv(pi.service_type(step_name)).Request()
        # a getter, sent again until answered: the answer says that the automobile node has
        # matched the setters' clients too (created before), so their first calls arrive
        step_ms = call_until_answered(step_client, request, self.timeout_s).value
        self.step_s = step_ms / 1000.0
        self.repeat = check_period(self.period_s, step_ms)
        reads_objects = self._reads_objects
        self.answer_steps = check_period(
            answer_period_s(self.period_s, self.objects_rate_hz, reads_objects), step_ms,
            what='the objects period' if reads_objects else 'policy period')
        if reads_objects:
            self._objects_due = SampleSchedule.from_rate(self.objects_rate_hz, self.step_s)
        self._outputs = Outputs(node, (pi.ACTION,), resolve=self._name)
        self._watch = node.create_timer(WATCH_PERIOD_S, self._check_deadlines)
        self._clock_deadline = time.monotonic() + self.timeout_s
        # last: the /clock subscription is what the scenario runner waits for to start time
        self._clock, = subscribe(node, {pi.CLOCK_IN: self._on_clock})
        node.announce_ready(
            f'policy driver ready: {self.writer.control} on /{self._name("")}automobile/*, '
            f'observation {", ".join(self.builder.keys)}, every {self.period_s:g} s '
            f'({self.repeat} basic steps of {step_ms:g} ms)')

    def _wait_for_services(self, clients):
        deadline = time.monotonic() + self.timeout_s
        missing = list(clients)
        while missing and time.monotonic() < deadline:
            missing = [name for name in missing if not clients[name].service_is_ready()]
            if missing:
                self.node.spin_once(0.02)
        if missing:
            raise InvalidParameterError(
                f'no automobile node serves {", ".join("/" + self._name(n) for n in missing)} '
                f'after {self.timeout_s:g} s (is it running, with a car of namespace '
                f'{self.namespace or "(none)"!r}?)')

    # ---------------------------------------------------------------- inputs
    def _keeper(self, row):
        def keep(msg):
            self._latest[row] = msg
            if self._pending is not None:
                self._try_tick()
        return keep

    def _on_clock(self, msg):
        if self.error is not None:
            return
        now_s = msg.clock.sec + msg.clock.nanosec * 1e-9
        self._clock_deadline = None
        step = int(round(now_s / self.step_s))
        if self._objects_due is not None and self._objects_due.due(step):
            self._objects_step = step
        if step % self.answer_steps:
            return          # between the grid's times
        if self._pending is not None:
            return          # a tick still waits for its topics (free-running sim)
        ready = self._objects_due is None or self._objects_step is not None
        # a tick at each multiple of the policy's period; a node running in real time may skip
        # the /clock of one (it does not wait for the policy): then the first /clock past it
        due = ready and (self.action is None
                         or step // self.repeat > self._tick_step // self.repeat)
        if self._calls is not None:
            # the last tick's setters are still being answered (free-running sim): a tick due
            # now comes once they have answered
            if due:
                self._deferred = (step, now_s)
            return
        if due:
            self._tick(step, now_s)
        else:
            self._answer()

    def _tick(self, step, now_s):
        self._tick_step = step
        self._pending = now_s
        self._pending_since = time.monotonic()
        self._try_tick()

    def _wanted_s(self, row, tick_s):
        # the stamp a tick reads of an input: the tick's (the objects are due then too)
        return tick_s

    def _missing(self, tick_s):
        # the input rows with no message stamped at the tick's time or later: in lockstep the
        # tick's own (the runner waits for the answer); a node running in real time goes on
        # without the policy, so its newest messages may be later than the tick: those are read
        half = 0.5 * self.step_s
        return [row for row in self.inputs
                if row not in self._latest
                or stamp_s(self._latest[row]) < self._wanted_s(row, tick_s) - half]

    def _try_tick(self):
        tick_s = self._pending
        if self._missing(tick_s):
            return
        self._pending = None
        latest = self._latest
        try:
            obs = self.builder.build(latest[pi.ODOM_IN], latest.get(pi.LANE_STATE_IN),
                                     latest.get(pi.OBJECTS_IN))
            action, _ = self.policy.predict(obs, deterministic=True)
            values = self.writer.physical(np.asarray(action))
            odom = latest[pi.ODOM_IN]
            table = None
            if self.writer.layout.reads_objects:
                table = obs[OBJECTS] if OBJECTS in obs else self.builder.objects(
                    odom, latest[pi.OBJECTS_IN], odom.twist.twist.linear.x,
                    odom.twist.twist.linear.y)
            commands = self.writer.setters(values, odom.twist.twist.linear.x,
                                           latest.get(pi.LANE_STATE_IN), table)
        except (InvalidParameterError, ValueError) as error:
            self._fail(f'at /clock {tick_s:.3f} s: {error}')
            return
        self.last_obs = obs
        self.ticks += 1
        self._tick_s = tick_s
        self._next_action = values
        self._calls = list(commands)
        self._call_next()

    def _call_next(self):
        # one setter after another, in the layout's order (the environment's): a brake sent
        # before the throttle that leaves cruise control would reach a car still cruising
        name, value = self._calls[0]
        request = self.node.srv(pi.service_type(name)).Request()
        request.value = value
        future = self._clients[name].call_async(request)
        future.add_done_callback(self._on_reply)

    def _on_reply(self, future):
        calls = self._calls
        if calls is None:
            return
        name, value = calls[0]
        error = future.exception()
        if error is None and not future.result().success:
            error = 'refused (success=false)'
        if error is not None:
            self._calls = None
            self._fail(f'at /clock {self._tick_s:.3f} s: /{self._name(name)} {value:g}: '
                       f'{error}')
            return
        del calls[0]
        if calls:
            self._call_next()
            return
        self._calls = None
        self.action = self._next_action
        self._answer()
        deferred, self._deferred = self._deferred, None
        if deferred is not None and self.error is None:
            self._tick(*deferred)

    def _answer(self):
        # the action in force (none before the first tick: the car as it started)
        self._outputs.publish(pi.ACTION.cadence, self)
        self.answers += 1

    # ---------------------------------------------------------------- errors
    def _check_deadlines(self):
        now = time.monotonic()
        if self._clock_deadline is not None and now > self._clock_deadline:
            self._fail(f'no /clock within {self.timeout_s:g} s (is the simulation running?)')
        elif self._pending is not None and now - self._pending_since > self.timeout_s:
            tick_s = self._pending
            waited = ', '.join(self._describe(row, tick_s) for row in self._missing(tick_s))
            self._fail(f'at /clock {tick_s:.3f} s: waited {self.timeout_s:g} s for {waited}')

    def _describe(self, row, tick_s):
        name = row.name if row.name.startswith('/') else '/' + self._name(row.name)
        last = self._latest.get(row)
        got = 'none received' if last is None else f'the last stamped {stamp_s(last):.3f} s'
        return f'{name} stamped {self._wanted_s(row, tick_s):.3f} s ({got})'

    def _fail(self, text):
        if self.error is None:
            self.error = text
            self.node.get_logger().error(text)
            self.node.request_shutdown()

    def destroy(self):
        """Leave the graph."""
        self.node.shutdown()


def answer_period_s(period_s, objects_rate_hz, reads_objects):
    """
    Return the node's answer grid [s]: the objects' period, else the policy's.

    With ``objects`` the policy's period must be a whole number of the objects' periods (the
    objects at a tick are those of its time).

    :raises InvalidParameterError: naming both periods when it is not.
    """
    if not reads_objects:
        return period_s
    objects_s = 1.0 / objects_rate_hz
    ratio = period_s / objects_s
    if ratio < 1.0 - 1e-9 or abs(ratio - round(ratio)) > 1e-6:
        raise InvalidParameterError(
            f"policy period {period_s * 1000.0:g} ms is not a whole number of the objects' "
            f'period {objects_s * 1000.0:g} ms ({objects_rate_hz:g} Hz): the objects would be '
            "older than the policy's observation (a world's traffic: objects_rate, the node's "
            'objects_rate parameter or --objects-rate)')
    return objects_s


def check_period(period_s, step_ms, what='policy period'):
    """
    Return the basic steps per period; refuse a period that is not a whole number of them.

    :param period_s: the policy's period [s].
    :param step_ms: the simulation's basic time step [ms].
    :raises InvalidParameterError: naming both: a period shorter than a step (a policy rate
        above the simulation's) or not a multiple of it.
    """
    steps = period_s * 1000.0 / step_ms
    if steps < 1.0 - 1e-9:
        raise InvalidParameterError(
            f'{what} {period_s * 1000.0:g} ms ({1.0 / period_s:g} Hz) is shorter than '
            f"the simulation's basic step {step_ms:g} ms ({1000.0 / step_ms:g} Hz): a policy "
            'cannot act faster than the simulation steps')
    if abs(steps - round(steps)) > 1e-6:
        raise InvalidParameterError(
            f'{what} {period_s * 1000.0:g} ms is not a whole number of the '
            f"simulation's basic steps of {step_ms:g} ms ({steps:g} steps)")
    return int(round(steps))
