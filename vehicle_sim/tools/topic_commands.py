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
``vehicle-sim pub`` and ``vehicle-sim hz``: publish to a topic, measure a topic's rate.

Like ``ros2 topic pub`` and ``ros2 topic hz``, on the CLI's hidden helper node (see
:mod:`vehicle_sim.tools.graph_commands`, which also owns ``echo``).
"""

from collections import deque
import math
import re
import time
from typing import Optional, Sequence

from vehicle_sim.tools.command import CliError, EXIT_OK, EXIT_USAGE, install_stop_handlers
from vehicle_sim.tools.graph_commands import (
    absolute_name,
    add_topic_arguments,
    DEFAULT_DISCOVERY_WAIT_S,
    GraphSession,
    subscribe,
)
from vehicle_sim.tools.message_yaml import build_request, format_line

# ros2 topic pub: 1 Hz unless --rate; ros2 topic hz: a window of 10000 messages, a report
# every second.
DEFAULT_PUB_RATE_HZ = 1.0
DEFAULT_HZ_WINDOW = 10000
HZ_REPORT_PERIOD_S = 1.0
# How long the publisher stays after its last message so that it is delivered (ros2 topic
# pub's --keep-alive default) [s].
KEEP_ALIVE_S = 0.1
# pkg/msg/Name or pkg/Name: a TYPE, not VALUES.
_TYPE_NAME = re.compile(r'^[A-Za-z]\w*/(msg/)?[A-Za-z]\w*$')
PUB_USAGE = 'vehicle-sim pub TOPIC [TYPE] VALUES [--rate HZ] [--once] [--times N] [--wait S]'


# --------------------------------------------------------------------------------------------
# pub

def add_pub_arguments(parser) -> None:
    """Add the arguments of ``vehicle-sim pub``."""
    parser.description = ('VALUES is YAML ("{linear: {x: 1.0}}") or the value of a '
                          'single-field message; TYPE may be left out when the topic is on '
                          'the graph. Options go before TOPIC or after VALUES.')
    parser.add_argument('topic', metavar='TOPIC')
    parser.add_argument('type_and_values', nargs='+', metavar='[TYPE] VALUES')
    parser.add_argument('--rate', type=float, default=DEFAULT_PUB_RATE_HZ, metavar='HZ',
                        help=f'publishing rate (default {DEFAULT_PUB_RATE_HZ:g} Hz)')
    parser.add_argument('--once', action='store_true', help='publish one message and exit')
    parser.add_argument('--times', type=int, metavar='N', help='publish N messages and exit')
    parser.add_argument('--wait', type=float, default=DEFAULT_DISCOVERY_WAIT_S, metavar='S',
                        help='how long to look for the topic (and, with --once/--times, '
                             'for a subscriber)')


def split_type_and_values(words: Sequence[str]):
    """
    Return ``(TYPE or None, VALUES or None)`` of the words after TOPIC.

    :raises CliError: (usage) for more than two words.
    """
    if len(words) == 2:
        return words[0], words[1]
    if len(words) == 1:
        return (words[0], None) if _TYPE_NAME.match(words[0]) else (None, words[0])
    raise CliError(f'expected [TYPE] VALUES after the topic, got {len(words)} words: '
                   f'{" ".join(words)} (quote the YAML: "{{linear: {{x: 1.0}}}}")', EXIT_USAGE)


def _pub_qos():
    # Reliable and transient local: it matches reliable and best-effort, volatile and
    # transient-local subscribers alike, and one message reaches a subscriber matching late.
    from vehicle_sim.transport.qos import QosProfile, TRANSIENT_LOCAL
    return QosProfile(depth=1, durability=TRANSIENT_LOCAL)


def cmd_pub(args) -> int:
    from vehicle_msgs_py import types as msg_types
    topic = absolute_name(args.topic)
    given_type, values = split_type_and_values(args.type_and_values)
    times = 1 if args.once else args.times
    if times is not None and times < 1:
        raise CliError('--times must be >= 1', EXIT_USAGE)
    if not args.rate > 0.0:
        raise CliError(f'--rate must be > 0 Hz, got {args.rate:g}', EXIT_USAGE)
    session = GraphSession()
    try:
        ros_type = session.resolve_type(
            'topic', topic, given_type, args.wait, must_exist=given_type is None,
            hint=f'; give its TYPE: vehicle-sim pub {topic} TYPE VALUES', status=EXIT_USAGE)
        try:
            msg = build_request(msg_types.message_type(ros_type), values, where='message')
        except CliError as exc:
            raise CliError(str(exc), EXIT_USAGE) from None
        node = session.node
        publisher = node.create_publisher(ros_type, topic, _pub_qos())
        stop = install_stop_handlers()
        # ros2 topic pub --once / --times waits for one matching subscription first.
        if times is not None and not node.spin_until(
                lambda: stop.is_set() or publisher.get_subscription_count() > 0, args.wait):
            raise CliError(f'no subscriber of {topic} matched within {args.wait:g} s; '
                           'nothing published (is the simulator running?)')
        period_s = 1.0 / args.rate
        print(f'publisher: beginning loop (every {period_s:g} s)', flush=True)
        sent = 0
        next_s = time.monotonic()
        while not stop.is_set() and (times is None or sent < times):
            if time.monotonic() >= next_s:
                publisher.publish(msg)
                sent += 1
                print(f'publishing #{sent}: {format_line(msg)}', flush=True)
                next_s += period_s
                continue
            node.spin_once(min(next_s - time.monotonic(), 0.05))
        keep_alive = time.monotonic() + KEEP_ALIVE_S
        while time.monotonic() < keep_alive:
            node.spin_once(0.02)
    finally:
        session.close()
    return EXIT_OK


# --------------------------------------------------------------------------------------------
# hz

def add_hz_arguments(parser) -> None:
    """Add the arguments of ``vehicle-sim hz``."""
    parser.description = ('Average rate and min/max/std dev of the period over the last '
                          '--window messages, every second.')
    add_topic_arguments(parser)
    parser.add_argument('--window', type=int, default=DEFAULT_HZ_WINDOW, metavar='N',
                        help=f'messages in the window (default {DEFAULT_HZ_WINDOW})')
    parser.add_argument('--count', type=int, metavar='N',
                        help='stop after N messages, with a last report')
    parser.add_argument('--duration', type=float, metavar='S',
                        help='stop after S seconds, with a last report')


def rate_report(arrivals_s: Sequence[float]) -> Optional[str]:
    """
    Return ``ros2 topic hz``'s report of message arrival times, None for fewer than two.

    :param arrivals_s: arrival times of the messages in the window [s].
    :return: ``average rate: R`` (1 / mean period) and a tab-indented line with the min, max
        and standard deviation of the periods and the window (messages counted).
    """
    if len(arrivals_s) < 2:
        return None
    periods = [b - a for a, b in zip(arrivals_s, list(arrivals_s)[1:])]
    mean = sum(periods) / len(periods)
    rate = 1.0 / mean if mean > 0.0 else 0.0
    std_dev = math.sqrt(sum((p - mean) ** 2 for p in periods) / len(periods))
    return (f'average rate: {rate:.3f}\n'
            f'\tmin: {min(periods):.3f}s max: {max(periods):.3f}s std dev: {std_dev:.5f}s '
            f'window: {len(arrivals_s)}')


def cmd_hz(args) -> int:
    if args.window < 2:
        raise CliError(f'--window must be >= 2 messages, got {args.window}', EXIT_USAGE)
    if args.count is not None and args.count < 2:
        raise CliError(f'--count must be >= 2 messages, got {args.count}', EXIT_USAGE)
    if args.duration is not None and not args.duration > 0.0:
        raise CliError(f'--duration must be > 0 s, got {args.duration:g}', EXIT_USAGE)
    session = GraphSession()
    try:
        arrivals = deque(maxlen=args.window)
        received = [0]

        def on_message(_msg, _field):
            if args.count is None or received[0] < args.count:
                arrivals.append(time.monotonic())
                received[0] += 1

        topic = subscribe(session, args, on_message)
        node = session.node
        stop = install_stop_handlers()
        end_s = None if args.duration is None else time.monotonic() + args.duration
        report_s = time.monotonic() + HZ_REPORT_PERIOD_S
        reported = 0
        while not stop.is_set() and (args.count is None or received[0] < args.count) and \
                (end_s is None or time.monotonic() < end_s):
            node.spin_once(0.05)
            if time.monotonic() >= report_s:
                report_s += HZ_REPORT_PERIOD_S
                if received[0] == reported:
                    if reported:
                        print('no new messages', flush=True)
                elif len(arrivals) >= 2:
                    print(rate_report(arrivals), flush=True)
                    reported = received[0]
        if received[0] > reported and len(arrivals) >= 2:
            print(rate_report(arrivals), flush=True)
        if received[0] < 2:
            raise CliError(f'{received[0]} message(s) on {topic}: a rate needs two')
    finally:
        session.close()
    return EXIT_OK
