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
The ``robot/time_step`` service of synchronous nodes: stepping in chunks from the node's loop.

A request for ``value`` ms (0 = one basic step, else a positive multiple of the basic step) is
queued and answered, with a deferred reply (transport port), once its own steps are done. The
steps run from a timer of the node, at most ``CHUNK_S`` of wall time at once; between two
chunks the node serves its other requests and notices SIGINT/SIGTERM. A request of one basic
step that finds nothing queued is one chunk anyway: it is stepped in the service callback and
answered at once, without the deferred reply and the timer (a test stepping one step at a time
sends thousands). Hence, however long a request is:

* the node answers other requests meanwhile; a setter takes effect at the next basic step;
* a second ``time_step`` waits its turn (first come, first served) and is answered when its own
  steps are done;
* the node stops within a chunk of a signal (the queued requests are not answered).

No upper bound on one request is needed: any ``int32`` value in ms is accepted (2147483640 ms is
about 2.1e8 basic steps of 10 ms).
"""

import collections
import time
from typing import Callable

from vehicle_sim.transport.future import Future

# Wall time of basic steps run at once before the node looks at its other work again [s].
CHUNK_S = 0.02
# Period of the stepping timer while requests are queued ("as soon as possible") [s].
RUN_PERIOD_S = 1e-6
# Tolerance when checking that a duration is a multiple of a (float) basic step.
MULTIPLE_TOLERANCE = 1e-9


class _Request:
    __slots__ = ('remaining', 'response', 'future')

    def __init__(self, steps, response):
        self.remaining = steps
        self.response = response
        self.future = Future()


class TimeStepService:
    """
    Validates ``robot/time_step`` requests and runs them, in order, in chunks.

    :param node: the node (transport port) whose timer runs the steps.
    :param step_ms: the basic time step [ms].
    :param step_once: advances the world by one basic step (and publishes).
    :param synchronous: False refuses every request (the world runs in real time).
    :param chunk_s: wall time of steps run at once [s].
    """

    def __init__(self, node, step_ms: float, step_once: Callable[[], object],
                 synchronous: bool, chunk_s: float = CHUNK_S):
        self._node = node
        self._logger = node.get_logger()
        self.step_ms = step_ms
        self._step_once = step_once
        self.synchronous = synchronous
        self._chunk_s = chunk_s
        self._queue = collections.deque()
        self._timer = None
        # True while a one-step request is stepped in its callback: a request served from
        # inside that step (the node serves requests between physics and publishing) queues.
        self._stepping = False

    @property
    def queued(self) -> int:
        """How many requests wait for (or are in) their steps."""
        return len(self._queue)

    def steps_for(self, duration_ms: int):
        """Return the number of basic steps of ``duration_ms``, or None when it is refused."""
        if duration_ms == 0:
            return 1
        if duration_ms < 0:
            return None
        steps = duration_ms / self.step_ms
        if abs(steps - round(steps)) > MULTIPLE_TOLERANCE * max(1.0, steps):
            return None
        return int(round(steps))

    def handle(self, name: str, request, response):
        """
        Serve one request: the response at once when refused or stepped at once, else a Future.

        :param name: the service name, for the log.
        """
        duration_ms = request.value
        if not self.synchronous:
            self._logger.warn(f'{name}: refused: the node is not synchronous '
                              '(set the parameter synchronous:=true)')
            response.success = False
            return response
        steps = self.steps_for(duration_ms)
        if steps is None:
            self._logger.warn(f'{name}: refused {duration_ms} ms: must be 0 (one step) or a '
                              f'positive multiple of the basic time step {self.step_ms:g} ms')
            response.success = False
            return response
        response.success = True
        if steps == 1 and not self._queue and not self._stepping and self._node.ok():
            self._stepping = True
            try:
                self._step_once()
            finally:
                self._stepping = False
            return response
        queued = _Request(steps, response)
        self._queue.append(queued)
        if self._timer is None:
            self._timer = self._node.create_timer(RUN_PERIOD_S, self._run)
        elif len(self._queue) == 1:
            self._timer.reset()
        return queued.future

    def _run(self):
        """Run basic steps for up to ``chunk_s`` of wall time; answer what is complete."""
        deadline = time.monotonic() + self._chunk_s
        while self._queue:
            current = self._queue[0]
            while current.remaining > 0:
                if not self._node.ok():
                    return   # SIGINT/SIGTERM: stop at once, the node is going down
                self._step_once()
                current.remaining -= 1
                if current.remaining and time.monotonic() >= deadline:
                    return
            self._queue.popleft()
            current.future.set_result(current.response)
            if self._queue:
                # Back to the executor before the next request's steps, so that this reply goes
                # out first: rclpy sends a deferred reply when its coroutine resumes, at the
                # executor's next turn (the timer fires again at once).
                return
        self._timer.cancel()

    def close(self):
        """Stop stepping; queued requests stay unanswered."""
        self._queue.clear()
        if self._timer is not None:
            self._timer.cancel()
