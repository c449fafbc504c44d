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
``vehicle-sim record``, ``play`` and ``bag info``: MCAP recordings of the graph's topics.

Like ``ros2 bag record -s mcap``, ``ros2 bag play`` and ``ros2 bag info`` (docs/record_replay.md);
the files are rosbag2's (:mod:`vehicle_sim.recording`). ``record`` subscribes on the CLI's hidden
helper node and writes each message's bytes as they arrived; ``play`` republishes a file from a
node called ``vehicle_sim_player``.
"""

from datetime import datetime, timezone
import os
import sys
import time

from vehicle_sim.tools.command import (
    CliError,
    EXIT_FAILURE,
    EXIT_OK,
    EXIT_USAGE,
    install_stop_handlers,
)

# How often ``record`` looks for new topics on the graph (rosbag2: every 100 ms).
TOPIC_POLL_S = 0.1
DEFAULT_CLOCK_HZ = 40.0     # ros2 bag play --clock's default rate


def _recording_error(error, status=EXIT_FAILURE):
    return CliError(str(error), status)


def default_output(now=None) -> str:
    """Return rosbag2's default name, ``rosbag2_YYYY_MM_DD-HH_MM_SS.mcap``."""
    return (now or datetime.now()).strftime('rosbag2_%Y_%m_%d-%H_%M_%S') + '.mcap'


# --------------------------------------------------------------------------------------------
# record

def add_record_arguments(parser) -> None:
    from vehicle_sim.recording.bag_writer import COMPRESSIONS, DEFAULT_COMPRESSION
    parser.description = ("Record topics of the graph into an MCAP file (rosbag2's format): "
                          'the named TOPICS, or every topic with -a. Stops at Ctrl-C or after '
                          '--duration.')
    parser.add_argument('topics', nargs='*', metavar='TOPIC')
    parser.add_argument('-a', '--all', action='store_true', help='every topic on the graph')
    parser.add_argument('-o', '--output', metavar='FILE.mcap',
                        help='the file (default: rosbag2_<date>-<time>.mcap)')
    parser.add_argument('--duration', type=float, metavar='S',
                        help='stop after S seconds (wall clock)')
    parser.add_argument('--compression', choices=COMPRESSIONS, default=DEFAULT_COMPRESSION,
                        help=f'chunk compression (default {DEFAULT_COMPRESSION})')
    parser.add_argument('--use-sim-time', action='store_true',
                        help='log times from /clock instead of the wall clock')


def cmd_record(args) -> int:
    from vehicle_sim.recording import qos_text
    from vehicle_sim.recording.bag_writer import BagWriter, check_output, RecordingError
    from vehicle_sim.recording.recorder import CLOCK_TOPIC, Recorder
    from vehicle_sim.tools.graph_commands import absolute_name, GraphSession
    if args.all == bool(args.topics):
        raise CliError('give the TOPICS to record or -a (every topic), not both', EXIT_USAGE)
    if args.duration is not None and not args.duration > 0.0:
        raise CliError(f'--duration must be > 0 s, got {args.duration:g}', EXIT_USAGE)
    path = args.output or default_output()
    try:
        check_output(path)
        writer = BagWriter(path, args.compression)
    except RecordingError as error:
        raise _recording_error(error, EXIT_USAGE) from None
    errors = []
    recorder = Recorder(writer, args.use_sim_time, on_error=errors.append)
    wanted = None if args.all else {absolute_name(t) for t in args.topics}
    session = GraphSession()
    subscribed, refused = set(), set()
    try:
        node = session.node
        graph = session.graph
        stop = install_stop_handlers()

        def subscribe_new():
            for topic, types in sorted(graph.topics().items()):
                if topic in subscribed or topic in refused or (
                        wanted is not None and topic not in wanted):
                    continue
                publishers = graph.publishers(topic)
                if not publishers:
                    continue
                if len(types) != 1:
                    refused.add(topic)
                    print(f'warning: {topic} has several types ({", ".join(sorted(types))}): '
                          'not recorded', file=sys.stderr)
                    continue
                ros_type = next(iter(types))
                offered = qos_text.dump([qos_text.discovered_entry(p.reliable, p.transient_local)
                                         for p in publishers])
                try:
                    write = recorder.channel(topic, ros_type, offered)
                    node.create_subscription(ros_type, topic, write,
                                             _subscription_qos(publishers), raw=True)
                except Exception as error:  # noqa: BLE001 - a type we cannot subscribe to
                    refused.add(topic)
                    print(f'warning: {topic} ({ros_type}): not recorded: {error}',
                          file=sys.stderr)
                    continue
                subscribed.add(topic)
                print(f"Subscribed to topic '{topic}'", flush=True)

        if args.use_sim_time and (wanted is not None and CLOCK_TOPIC not in wanted):
            from vehicle_sim.transport.qos import QosProfile
            node.create_subscription('rosgraph_msgs/msg/Clock', CLOCK_TOPIC,
                                     recorder.follow_clock, QosProfile(depth=1), raw=True)
        end_s = None if args.duration is None else time.monotonic() + args.duration
        next_poll = 0.0
        print(f'Recording to {path}', flush=True)
        while not stop.is_set() and not errors and (end_s is None or time.monotonic() < end_s):
            now = time.monotonic()
            if now >= next_poll:
                graph.refresh()
                subscribe_new()
                next_poll = now + TOPIC_POLL_S
            node.spin_once(TOPIC_POLL_S / 2)
    finally:
        session.close()
        error = recorder.close()
    if error:
        raise CliError(error)
    if wanted is not None and wanted - subscribed:
        print(f'warning: never seen on the graph, not recorded: '
              f'{", ".join(sorted(wanted - subscribed))}', file=sys.stderr)
    print(recorder.summary())
    return EXIT_OK


def _subscription_qos(publishers):
    # As ros2 bag record adapts: reliable / transient local only when every publisher offers it.
    from vehicle_sim.transport.qos import (
        BEST_EFFORT,
        QosProfile,
        RELIABLE,
        TRANSIENT_LOCAL,
        VOLATILE,
    )
    return QosProfile(
        depth=100,
        reliability=RELIABLE if all(p.reliable for p in publishers) else BEST_EFFORT,
        durability=TRANSIENT_LOCAL if all(p.transient_local for p in publishers) else VOLATILE)


# --------------------------------------------------------------------------------------------
# play

def add_play_arguments(parser) -> None:
    parser.description = ("Republish an MCAP recording's topics with their recorded QoS at "
                          'their recorded pace.')
    parser.add_argument('file', metavar='FILE', help='an MCAP file or a rosbag2 folder')
    parser.add_argument('--rate', type=float, default=1.0, metavar='R',
                        help='playback speed (default 1.0)')
    parser.add_argument('--loop', action='store_true', help='play again from the start')
    parser.add_argument('--start', type=float, default=0.0, metavar='S',
                        help='skip the first S seconds of the recording')
    parser.add_argument('--topics', nargs='+', metavar='TOPIC', help='only these topics')
    parser.add_argument('--clock', type=float, nargs='?', const=DEFAULT_CLOCK_HZ,
                        metavar='HZ', help='publish /clock from the recorded time, HZ times a '
                                           f'second (default {DEFAULT_CLOCK_HZ:g})')
    parser.add_argument('--delay', type=float, default=0.0, metavar='S',
                        help='wait S seconds after creating the publishers (for subscribers '
                             'to match) before playing')


def cmd_play(args) -> int:
    from vehicle_sim.recording.bag_writer import RecordingError
    from vehicle_sim.recording.player import Player
    from vehicle_sim.tools.graph_commands import absolute_name
    from vehicle_sim.transport.selection import create_node
    if not args.delay >= 0.0:
        raise CliError(f'--delay must be >= 0 s, got {args.delay:g}', EXIT_USAGE)
    node = None
    try:
        from vehicle_sim.recording.bag_reader import read_info
        read_info(args.file)        # a broken file is refused before joining the graph
        node = create_node('vehicle_sim_player', transport='dds',
                           args=['--ros-args', '--disable-rosout-logs', '--log-level', 'warn'])
        player = Player(node, args.file, rate=args.rate, start_s=args.start,
                        topics=[absolute_name(t) for t in args.topics] if args.topics else None,
                        clock_hz=args.clock,
                        warn=lambda text: print(f'warning: {text}', file=sys.stderr))
        stop = install_stop_handlers()
        print(f'Playing {args.file}: {len(player.topics)} topics, '
              f'{player.info.duration_ns / 1e9:g} s at rate {args.rate:g}', flush=True)
        if args.delay:
            node.spin_until(stop.is_set, args.delay)
        published = player.play(stop.is_set, loop=args.loop)
    except RecordingError as error:
        raise _recording_error(error) from None
    finally:
        if node is not None:
            node.shutdown()
    print(f'published {published} messages')
    return EXIT_OK


# --------------------------------------------------------------------------------------------
# bag info

def add_bag_arguments(parser) -> None:
    bag_sub = parser.add_subparsers(dest='bag_command', metavar='ACTION')
    bag_sub.required = True
    info = bag_sub.add_parser('info', help="print a recording's topics, types, counts and "
                                           'duration')
    info.add_argument('file', metavar='FILE', help='an MCAP file or a rosbag2 folder')


def _size_text(size: int) -> str:
    value = float(size)
    for unit in ('B', 'KiB', 'MiB', 'GiB'):
        if value < 1024.0 or unit == 'GiB':
            return f'{value:.1f} {unit}' if unit != 'B' else f'{size} B'
        value /= 1024.0
    return f'{size} B'


def _time_text(ns: int) -> str:
    when = datetime.fromtimestamp(ns // 1_000_000_000, timezone.utc)
    return (f'{when.strftime("%b %d %Y %H:%M:%S")}.{ns % 1_000_000_000:09d} '
            f'({ns // 1_000_000_000}.{ns % 1_000_000_000:09d})')


def format_info(info) -> str:
    """Return ``ros2 bag info``'s text of a BagInfo."""
    label = '{:<19}'.format
    files = info.files or [os.path.basename(info.path)]
    lines = [label('Files:') + files[0], *(' ' * 19 + name for name in files[1:]),
             label('Bag size:') + _size_text(info.size),
             label('Storage id:') + info.storage_id,
             label('Duration:') + f'{info.duration_ns // 1_000_000_000}.'
                                  f'{info.duration_ns % 1_000_000_000:09d}s']
    if info.start_ns is not None:
        lines.append(label('Start:') + _time_text(info.start_ns))
        lines.append(label('End:') + _time_text(info.end_ns))
    lines.append(label('Messages:') + str(info.message_count))
    lines.append(label('Compression:') + (info.compression or 'none')
                 + (f' ({info.chunk_count} chunks)' if info.chunk_count is not None else ''))
    topics = [f'Topic: {t.name} | Type: {t.ros_type} | Count: {t.count} | '
              f'Serialization Format: {t.message_encoding}' for t in info.topics]
    lines.append(label('Topic information:') + (topics[0] if topics else ''))
    lines.extend(' ' * 19 + line for line in topics[1:])
    if not info.complete:
        lines.append('note: the file has no summary (the recording stopped early); this was '
                     'read from its records up to its last complete one')
    return '\n'.join(lines)


def cmd_bag(args) -> int:
    from vehicle_sim.recording.bag_reader import read_info
    from vehicle_sim.recording.bag_writer import RecordingError
    try:
        info = read_info(args.file)
    except RecordingError as error:
        raise _recording_error(error) from None
    print(format_info(info))
    return EXIT_OK
