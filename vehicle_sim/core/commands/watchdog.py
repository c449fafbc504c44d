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
Command timeout on the node clock: what to publish when commands stop arriving.

Time is passed in (``now_s``, seconds on the node clock, sim time included), never read here, so
tests inject it and need no sleep (time is an argument). Freshness is judged by *receipt* time:
the node
calls :meth:`CommandWatchdog.feed` when it accepts a command, not with the message stamp.
"""

import math

from vehicle_sim.core.specs.errors import InvalidCommandError, InvalidParameterError

TIMEOUT_ACTIONS = ('brake', 'coast', 'hold')
DEFAULT_TIMEOUT_S = 0.5
DEFAULT_TIMEOUT_ACTION = 'brake'


class CommandWatchdog:
    """
    Decide, at a given time, whether the last accepted command may still be applied.

    Actions once stale: ``'brake'`` publishes the stop command (zero wheel speeds, immediately,
    without the acceleration ramp), ``'coast'`` publishes nothing (the drive's own timeout or
    friction takes over), ``'hold'`` keeps re-publishing the last command. A timeout of 0 disables
    the watchdog: the last command is always passed through. Before the first accepted command
    the watchdog is stale (when enabled). A clock that jumps backwards (now < last feed, e.g. a
    sim-time reset) counts as stale, the safe side, until the next command is fed.
    """

    def __init__(self, timeout_s=DEFAULT_TIMEOUT_S, action=DEFAULT_TIMEOUT_ACTION):
        """
        Create a watchdog.

        :param timeout_s: maximum age [s] of the last accepted command; 0 disables.
        :param action: 'brake', 'coast' or 'hold'.
        :raises InvalidParameterError: for a negative or non-finite timeout or an unknown action.
        """
        if isinstance(timeout_s, bool) or not isinstance(timeout_s, (int, float)) \
                or not math.isfinite(timeout_s) or timeout_s < 0.0:
            raise InvalidParameterError(
                f'command_timeout_s = {timeout_s!r}: must be a finite number >= 0 (0 disables)')
        if action not in TIMEOUT_ACTIONS:
            raise InvalidParameterError(
                f'timeout_action = {action!r}: must be one of {", ".join(TIMEOUT_ACTIONS)}')
        self._timeout_s = float(timeout_s)
        self._action = action
        self._last_feed_s = None

    @property
    def timeout_s(self):
        return self._timeout_s

    @property
    def action(self):
        return self._action

    @property
    def enabled(self):
        return self._timeout_s > 0.0

    @property
    def last_feed_s(self):
        return self._last_feed_s

    def feed(self, now_s):
        """
        Record that a command was accepted at ``now_s``; call it only for accepted commands.

        :param now_s: node-clock time of receipt [s].
        :raises InvalidCommandError: for a non-finite time (state unchanged).
        """
        if isinstance(now_s, bool) or not isinstance(now_s, (int, float)) \
                or not math.isfinite(now_s):
            raise InvalidCommandError(f'watchdog time now_s = {now_s!r} must be finite')
        self._last_feed_s = float(now_s)

    def reset(self):
        """Forget the last command (the watchdog becomes stale when enabled)."""
        self._last_feed_s = None

    def is_stale(self, now_s):
        """
        Tell whether the last accepted command is too old at ``now_s``.

        :param now_s: node-clock time [s].
        :return: False when disabled; True before the first feed, after a backwards clock jump,
            or when ``now_s - last_feed_s > timeout_s`` (an age equal to the timeout is fresh).
        """
        if not self.enabled:
            return False
        if self._last_feed_s is None:
            return True
        age_s = now_s - self._last_feed_s
        return age_s < 0.0 or age_s > self._timeout_s

    def output(self, now_s, last_command, brake_command):
        """
        Return what the node should publish at ``now_s``.

        :param now_s: node-clock time [s].
        :param last_command: the last applied command, or None if there was none.
        :param brake_command: the stop command to publish for action 'brake'.
        :return: ``last_command`` while fresh (or when disabled); once stale: ``brake_command``
            for 'brake', None (publish nothing) for 'coast', ``last_command`` for 'hold'
            (None if no command was ever accepted).
        """
        if not self.is_stale(now_s):
            return last_command
        if self._action == 'brake':
            return brake_command
        if self._action == 'coast':
            return None
        return last_command
