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
SIGINT and SIGTERM in a node process: one rule for ``run_node`` on every transport.

* A node is *ready* once it has announced it (:meth:`NodePort.announce_ready`, the
  ``automobile ready: ...`` line), or, for a node that announces nothing, once its start-up
  returned.
* A signal before the node is ready: the node never announces ready, leaves the graph, and the
  process exits with 128 + the signal number (130 for Ctrl-C, 143 for SIGTERM). That is the
  status a shell shows for a command a signal ended, so it is the same whatever moment of the
  start-up the signal hit (the interpreter, the imports, the node's construction).
* A signal once the node is ready: the node stops, leaves the graph and the process exits 0,
  as an rclpy node does.
* A node still spinning :data:`FORCED_EXIT_S` after the first signal (inside a heavy step) is
  ended at once (``os._exit``, exit status 0). Python runs signal handlers between two bytecodes
  of the main thread, never inside a C call: the node's loop notices a signal only when the
  current PyBullet call returns, and a heavy step (several big sensors) is many such calls. The
  sensor sizes are bounded so that one call stays well under half a second (docs/sensors.md),
  so the watchdog thread, which also needs the interpreter, gets it in time: the process ends
  within a second of the signal. A forced exit does not delete the DDS participant: other
  processes stop listing the node when its lease expires. Start-up (light: the world is built,
  nothing is sampled) and shutdown (leaving the graph) are never cut short.

Only one :class:`StopSignals` is current in a process (the running ``run_node``).
"""

import os
import sys
import threading

# How long a node may take to stop after the first SIGINT/SIGTERM before it is ended [s].
FORCED_EXIT_S = 0.3

_current = None


class StopSignals:
    """The first stop signal of a process main, whether the node was ready, and the watchdog."""

    def __init__(self):
        self.signum = None
        self.before_ready = False
        self._ready = False
        self._spinning = False
        self._signalled = threading.Event()
        self._spin_over = threading.Event()
        threading.Thread(target=self._watch, name='stop_signals', daemon=True).start()

    def __enter__(self):
        global _current
        _current = self
        return self

    def __exit__(self, *exc):
        global _current
        _current = None
        self._spin_over.set()
        self._signalled.set()   # the watchdog thread ends
        return False

    def spin(self, node):
        """Make the node ready and spin it, unless a signal came first (then return at once)."""
        if not self.mark_ready():
            return
        self._spinning = True
        try:
            node.spin()
        finally:
            self._spinning = False
            self._spin_over.set()

    def on_signal(self, signum):
        """Record a stop signal (from a signal handler); only the first one counts."""
        if self.signum is None:
            self.before_ready = not self._ready
            self.signum = signum
            self._signalled.set()

    def mark_ready(self) -> bool:
        """
        Make the node ready unless a signal came first; return whether it is ready.

        ``_ready`` is set before the signal is looked at: a handler running in between sees a
        ready node, and the caller then announces it (exit 0 with the ready line).
        """
        self._ready = True
        return not self.before_ready

    @property
    def exit_status(self) -> int:
        """0, or 128 + the signal number when a signal came before the node was ready."""
        return 128 + self.signum if self.before_ready else 0

    def _watch(self):
        self._signalled.wait()
        if not self._spin_over.wait(FORCED_EXIT_S) and self._spinning:
            for stream in (sys.stdout, sys.stderr):
                try:
                    stream.flush()
                except Exception:  # noqa: BLE001 - ending anyway
                    pass
            os._exit(self.exit_status)


def mark_ready() -> bool:
    """Make the running node ready (see :class:`StopSignals`); True outside ``run_node``."""
    stop = _current
    return True if stop is None else stop.mark_ready()
