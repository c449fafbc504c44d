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
The embedded transport's executor: one WaitSet per node, timers, and the process main loop.

Single-threaded like an rclpy SingleThreadedExecutor: everything (subscription and service
callbacks, replies, timers) runs inside ``spin_once`` on the calling thread. Each reader has a
ReadCondition (any sample state) attached to the node's WaitSet with its handler; a
GuardCondition wakes the wait when a timer is (re)scheduled or a shutdown is requested.

The public ``WaitSet.wait`` says how many conditions fired, not which, so the executor asks the
conditions whether they are triggered until it has found that many, most recently fired first
(one call per condition asked, so a node whose traffic comes from a few readers finds them
at once whatever its number of readers), then runs their handlers in attach order. The
conditions are level-triggered: a reader that still holds samples, or that received some after
the wait, wakes the next wait at once. A node with services also wakes every ``CLIENT_CHECK_S``
to look for newly matched clients it cannot serve (``services.warn_unservable_clients``).
"""

import collections
import signal
import sys
import threading
import time
from typing import Callable, List, Optional

from cyclonedds.core import DDSException, GuardCondition, WaitSet

from vehicle_sim.transport import port
from vehicle_sim.transport.dds import cyclone_private
from vehicle_sim.transport.dds.context import Context
from vehicle_sim.transport.dds.services import (
    CLIENT_CHECK_S,
    PENDING_REPLY_POLL_S,
    warn_unservable_clients,
)
from vehicle_sim.transport.errors import TransportError
from vehicle_sim.transport.stop_signals import StopSignals

# How long spin() may block before it looks at shutdown requests (signals) again.
SPIN_SLICE_S = 0.1


class DdsTimer(port.Timer):
    """A periodic callback of an Executor; it does not fire in bursts when it fell behind."""

    def __init__(self, executor: 'Executor', period_s: float, callback):
        if not period_s > 0.0:
            raise TransportError(f'timer period must be > 0 s, got {period_s}')
        self._executor = executor
        self.period_s = period_s
        self.callback = callback
        self.next_due = time.monotonic() + period_s
        self.cancelled = False

    def cancel(self) -> None:
        self.cancelled = True

    def reset(self) -> None:
        self.cancelled = False
        self.next_due = time.monotonic() + self.period_s
        if not self._executor.stopped():
            self._executor.schedule(self)


class _Entry:
    """An attached condition: its attach index, its ``is_triggered`` and its handler."""

    __slots__ = ('index', 'triggered', 'handler')

    def __init__(self, index: int, condition, handler: Callable[[], None]):
        self.index = index
        self.triggered = condition.is_triggered
        self.handler = handler


class Executor:
    """
    The WaitSet, conditions, timers and services of one node.

    :param participant: the participant owning the waitset and guard condition.
    :param stopped: returns True once the node is shut down; the executor then returns from
        ``spin_once`` after the callback that shut it down.
    """

    def __init__(self, participant, stopped: Callable[[], bool]):
        self.stopped = stopped
        self._waitset = WaitSet(participant)
        self._guard = GuardCondition(participant)
        # Every condition this executor created, to delete them.
        self._conditions: List = [self._guard]
        # The attached reader conditions, most recently triggered first.
        self._recent: List[_Entry] = []
        self._timers: List[DdsTimer] = []
        self.services: List = []
        # The services holding replies whose client reply reader has not matched yet.
        self._waiting: List = []
        self._next_client_check = 0.0
        # Callbacks other threads handed over (call_soon), run by the next spin.
        self._soon = collections.deque()
        self._attach(self._guard)

    def _attach(self, condition) -> None:
        try:
            self._waitset.attach(condition)
        except DDSException as exc:
            raise TransportError(f'cannot attach {condition!r} to the waitset: {exc}') from None

    def add(self, condition, handler: Callable[[], None]) -> None:
        """Call ``handler()`` from ``spin_once`` whenever ``condition`` is triggered."""
        self._conditions.append(condition)
        self._attach(condition)
        self._recent.append(_Entry(len(self._conditions), condition, handler))

    def add_service(self, service) -> None:
        """Watch ``service`` for unservable clients and flush its pending replies."""
        service.waiting = self._waiting
        self.services.append(service)

    def create_timer(self, period_s: float, callback) -> DdsTimer:
        timer = DdsTimer(self, period_s, callback)
        self.schedule(timer)
        return timer

    def schedule(self, timer: DdsTimer) -> None:
        """Add ``timer`` (again) and re-plan the current wait."""
        if timer not in self._timers:
            self._timers.append(timer)
        self._guard.set(True)

    def call_soon(self, callback: Callable[[], None]) -> None:
        """Run ``callback()`` from the next ``spin_once``/``serve_pending`` (thread-safe)."""
        self._soon.append(callback)
        self.wake()

    def _run_soon(self) -> None:
        soon = self._soon
        while soon:
            soon.popleft()()
            if self.stopped():
                return

    def wake(self) -> None:
        """Make the current or next wait return (signal-handler safe)."""
        try:
            self._guard.set(True)
        except Exception:  # noqa: BLE001 - already deleted
            pass

    def spin_once(self, timeout_s: Optional[float] = None) -> None:
        """Wait up to ``timeout_s`` (default 1 s) for work, then run what is due."""
        now = time.monotonic()
        wait_s = SPIN_SLICE_S * 10 if timeout_s is None else max(0.0, timeout_s)
        for timer in self._timers:
            if not timer.cancelled:
                wait_s = min(wait_s, max(0.0, timer.next_due - now))
        if self._waiting:
            wait_s = min(wait_s, PENDING_REPLY_POLL_S)
        if self.services:
            wait_s = min(wait_s, max(0.0, self._next_client_check - now))
        try:
            count = self._waitset.wait(int(wait_s * 1e9))
        except DDSException:
            if self.stopped():
                return
            raise TransportError('waitset wait failed') from None
        if count:
            for entry in self._fired(count):
                entry.handler()
                if self.stopped():
                    return
        if self._soon:
            self._run_soon()
        now = time.monotonic()
        if self._waiting:
            for service in list(self._waiting):
                service.flush_pending(now)
                if not service.pending:
                    self._waiting.remove(service)
        if self.services and now >= self._next_client_check:
            self._next_client_check = now + CLIENT_CHECK_S
            warn_unservable_clients(self.services)
        for timer in list(self._timers):
            if timer.cancelled:
                self._timers.remove(timer)
            elif now >= timer.next_due:
                timer.next_due += timer.period_s
                if timer.next_due < now:  # fell behind: do not fire a burst
                    timer.next_due = now + timer.period_s
                timer.callback()
                if self.stopped():
                    return

    def serve_pending(self) -> None:
        """Run the handlers of the conditions triggered now (no wait, no timers)."""
        try:
            count = self._waitset.wait(0)
        except DDSException:
            return
        if count:
            for entry in self._fired(count):
                entry.handler()
                if self.stopped():
                    return
        if self._soon:
            self._run_soon()

    def _fired(self, count: int) -> List[_Entry]:
        """Return the ``count`` triggered entries (fewer if some went quiet), in attach order."""
        found = 1 if self._guard.take() else 0
        fired = []
        if found < count:
            recent = self._recent
            for entry in recent:
                if entry.triggered():
                    fired.append(entry)
                    found += 1
                    if found >= count:
                        break
            for entry in reversed(fired):
                if recent[0] is not entry:
                    recent.remove(entry)
                    recent.insert(0, entry)
            if len(fired) > 1:
                fired.sort(key=lambda e: e.index)
        return fired

    def close(self) -> None:
        """Detach every condition from the waitset and forget the callbacks."""
        for condition in self._conditions:
            try:
                self._waitset.detach(condition)
            except DDSException:
                pass
        self._recent = []
        self._timers = []
        self.services = []
        self._waiting.clear()

    def delete(self) -> None:
        """Delete the conditions and the waitset now (not needed when their participant goes)."""
        for condition in self._conditions:
            cyclone_private.delete_entity(condition)
        cyclone_private.delete_entity(self._waitset)


def run_dds_node(node_factory, args=None) -> int:
    """
    Build a node and spin it until SIGINT/SIGTERM, then leave the graph.

    The signal handlers are installed before anything is created, as ``rclpy.init`` does: a
    signal during start-up is remembered, the node is shut down (it leaves the graph) as soon
    as its construction returns, and the process ends cleanly; a signal while spinning makes
    ``spin()`` return. The handler never raises: an exception thrown into arbitrary start-up
    code (a lock, a class creation, a redirected descriptor) cannot be cleaned up reliably.
    Exit status and the ready line follow transport/stop_signals.py.

    :param node_factory: ``node_factory(args)`` returning a DdsNode or an object with ``.node``.
    :param args: the command line (default ``sys.argv``).
    :return: the process exit status: 0, or 128 + the signal number for a signal that came
        before the node was ready.
    """
    args = sys.argv if args is None else args
    state = {'node': None}
    stop = StopSignals()

    def on_signal(signum, frame):
        stop.on_signal(signum)
        node = state['node']
        if node is not None:
            node.request_shutdown()

    previous = {}
    if threading.current_thread() is threading.main_thread():
        for signum in (signal.SIGINT, signal.SIGTERM):
            previous[signum] = signal.signal(signum, on_signal)
    node = None
    try:
        with stop:
            try:
                app = node_factory(args)
                node = app if isinstance(app, port.NodePort) else app.node
                state['node'] = node   # from here on a signal asks spin() to return
                stop.spin(node)   # not after a signal during start-up: leave at once
            except KeyboardInterrupt:   # SIGINT under a handler of the caller's (Python's)
                stop.on_signal(signal.SIGINT)
            except BaseException:
                if stop.signum is None:
                    raise
                # Start-up failed after a signal asked to stop (e.g. an endpoint refused while
                # the process was ending): the stop is what the user asked for.
            finally:
                if node is not None:
                    node.shutdown()
                else:
                    Context.close_process()   # whatever an interrupted start-up left half-built
    finally:
        for signum, handler in previous.items():
            signal.signal(signum, handler)
    return stop.exit_status
