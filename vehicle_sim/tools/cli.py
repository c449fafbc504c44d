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
The ``vehicle-sim`` command: run the simulator and talk to a ROS 2 graph without ROS installed.

Subcommands (``vehicle-sim <command> --help`` for details)::

    run                 start the automobile node (embedded transport) with a live status line
    list                nodes, topics and services seen on the graph
    echo TOPIC          print the messages of a topic (like ``ros2 topic echo``)
    pub TOPIC [TYPE] V  publish to a topic (like ``ros2 topic pub``)
    hz TOPIC            the rate of a topic (like ``ros2 topic hz``)
    call SERVICE VALUE  call a service (like ``ros2 service call``)
    param get|set|list  the rcl_interfaces parameter services of a node (like ``ros2 param``)
    export-interfaces   write the vehicle_msgs ament package for a ROS workspace
    demo                run the end-to-end scenario and write a PNG of the paths
    teleop              drive the car (or --robot) from the keyboard through cmd_vel
    scenario FILE       run a scenario file headless: criteria, JUnit XML, plot, exit status
    sweep SCENARIO      run a scenario over a grid of values and seeds, in parallel (local or Ray)
    record TOPICS|-a    record topics into an MCAP file (like ``ros2 bag record -s mcap``)
    play FILE           republish a recording (like ``ros2 bag play``)
    bag info FILE       a recording's topics, types, counts, duration (like ``ros2 bag info``)
    policy run|evaluate a trained policy drives the car over ROS; its evaluation in process
                        and over ROS

Everything talks over the embedded Cyclone DDS transport, with ``ROS_DOMAIN_ID`` and
``ROS_AUTOMATIC_DISCOVERY_RANGE`` honoured like a ROS 2 node does (docs/transport.md).
Exit codes: 0 success, 1 runtime failure (unknown name, timeout, rejected value), 2 usage error.

This module parses the command line and dispatches; each command lives in its own module of
:mod:`vehicle_sim.tools` (``graph_commands``, ``topic_commands``, ``run_command``, ``demo``).
"""

import argparse
import os
import sys
from typing import List, Optional

from vehicle_sim.tools.command import CliError, EXIT_FAILURE, EXIT_OK
from vehicle_sim.tools.foxglove_options import add_arguments as add_foxglove_arguments
from vehicle_sim.tools.graph_commands import (
    add_abbreviation_arguments,
    add_topic_arguments,
    cmd_call,
    cmd_echo,
    cmd_list,
    cmd_param,
    DEFAULT_CALL_TIMEOUT_S,
    DEFAULT_DISCOVERY_WAIT_S,
    DEFAULT_LIST_WAIT_S,
)
from vehicle_sim.tools.run_command import cmd_run
from vehicle_sim.tools.topic_commands import (
    add_hz_arguments,
    add_pub_arguments,
    cmd_hz,
    cmd_pub,
    PUB_USAGE,
)

# --------------------------------------------------------------------------------------------
# export-interfaces, demo

def cmd_export(args) -> int:
    from vehicle_msgs_py import export
    return export.main([args.dest_dir])


def cmd_teleop(args) -> int:
    from vehicle_sim.tools.teleop import cmd_teleop as run_teleop
    return run_teleop(args)


def cmd_demo(args) -> int:
    from vehicle_sim.tools import demo
    demo.run_demo(args.out, args.car, args.short)
    return EXIT_OK


# --------------------------------------------------------------------------------------------
# parser

def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog='vehicle-sim',
        description='PyBullet car simulator with the Webots automobile API and ROS 2 nodes; '
                    'graph tools on the embedded Cyclone DDS transport.')
    sub = parser.add_subparsers(dest='command', metavar='COMMAND')
    sub.required = True

    run = sub.add_parser('run', help='start the automobile node with a live status line',
                         description='Start the automobile node on the embedded transport. '
                                     'Arguments after -- are ROS arguments '
                                     '(e.g. -- --ros-args -p publish_period_ms:=20).')
    run.add_argument('--car', metavar='MODEL', help='car preset (e.g. BmwX5, TeslaModel3)')
    run.add_argument('--world', metavar='FILE', help='world file (config/worlds/*.yaml)')
    run.add_argument('--real-time-factor', type=float, metavar='F',
                     help='simulated seconds per wall-clock second (default: node default)')
    run.add_argument('--synchronous', action='store_true',
                     help='advance time only through /robot/time_step calls')
    run.add_argument('--duration', type=float, metavar='S',
                     help='stop after S wall-clock seconds')
    run.add_argument('--no-status', action='store_true', help='no status line')
    run.add_argument('--gui', action='store_true',
                     help="open PyBullet's window with a chase camera following the first "
                          'vehicle (needs an X display; keys: docs/drive.md)')
    add_foxglove_arguments(run)
    run.add_argument('--record', metavar='FILE.mcap',
                     help='record every topic the node publishes, from its first step, into '
                          'an MCAP file (docs/record_replay.md)')
    run.add_argument('ros_args', nargs=argparse.REMAINDER,
                     help='ROS arguments after --')
    run.set_defaults(func=cmd_run)

    lst = sub.add_parser('list', help='nodes, topics and services on the graph')
    lst.add_argument('--wait', type=float, default=DEFAULT_LIST_WAIT_S, metavar='S',
                     help=f'discovery time (default {DEFAULT_LIST_WAIT_S:g} s)')
    lst.add_argument('-a', '--all', action='store_true',
                     help='also hidden names (a token starting with _)')
    lst.set_defaults(func=cmd_list)

    echo = sub.add_parser('echo', help='print the messages of a topic')
    add_topic_arguments(echo)
    echo.add_argument('--once', action='store_true', help='print one message and exit')
    echo.add_argument('--count', type=int, metavar='N', help='print N messages and exit')
    echo.add_argument('--field', metavar='A.B',
                      help='print only this field of each message (e.g. data, twist.linear)')
    echo.add_argument('--rate', type=float, metavar='HZ',
                      help='print at most HZ messages a second (the others are skipped)')
    echo.add_argument('--timeout', type=float, metavar='S',
                      help='stop after S seconds; fail when no message came (or, with '
                           '--once/--count, fewer than asked for)')
    add_abbreviation_arguments(echo)
    echo.set_defaults(func=cmd_echo)

    pub = sub.add_parser('pub', help='publish a message to a topic', usage=PUB_USAGE)
    add_pub_arguments(pub)
    pub.set_defaults(func=cmd_pub)

    hz = sub.add_parser('hz', help="print a topic's rate")
    add_hz_arguments(hz)
    hz.set_defaults(func=cmd_hz)

    call = sub.add_parser('call', help='call a service',
                          description='VALUE is the single request field of the Set*/Get* '
                                      'types (30, true) or a YAML request ("{value: 30}").')
    call.add_argument('service', metavar='SERVICE')
    call.add_argument('value', metavar='VALUE', nargs='?')
    call.add_argument('--type', metavar='T', help='service type (default: from the graph)')
    call.add_argument('--timeout', type=float, default=DEFAULT_CALL_TIMEOUT_S, metavar='S',
                      help=f'reply timeout (default {DEFAULT_CALL_TIMEOUT_S:g} s)')
    call.add_argument('--wait', type=float, default=DEFAULT_DISCOVERY_WAIT_S, metavar='S',
                      help='how long to look for the service')
    call.set_defaults(func=cmd_call)

    param = sub.add_parser('param', help='get, set or list the parameters of a node')
    param_sub = param.add_subparsers(dest='param_command', metavar='ACTION')
    param_sub.required = True
    for action, helptext in (('get', 'print a parameter'), ('set', 'set a parameter'),
                             ('list', 'list parameter names')):
        p = param_sub.add_parser(action, help=helptext)
        p.add_argument('node', metavar='NODE', help='fully-qualified node name, e.g. /automobile')
        if action != 'list':
            p.add_argument('name', metavar='NAME')
        if action == 'set':
            p.add_argument('value', metavar='VALUE', help='YAML value: 2.5, true, text, [1, 2]')
        p.add_argument('--timeout', type=float, default=DEFAULT_CALL_TIMEOUT_S, metavar='S')
        p.add_argument('--wait', type=float, default=DEFAULT_DISCOVERY_WAIT_S, metavar='S',
                       help='how long to look for the node')
    param.set_defaults(func=cmd_param)

    export = sub.add_parser('export-interfaces',
                            help='write the vehicle_msgs ament package into DIR')
    export.add_argument('dest_dir', metavar='DIR', help='e.g. <workspace>/src')
    export.set_defaults(func=cmd_export)

    demo = sub.add_parser('demo', help='run the end-to-end scenario, write a PNG '
                                       '(docs/end_to_end.md)')
    from vehicle_sim.tools.demo import add_arguments as add_demo_arguments
    add_demo_arguments(demo)
    demo.set_defaults(func=cmd_demo)

    teleop = sub.add_parser('teleop', help='drive the car (or --robot) from the keyboard',
                            description='Arrows or WASD drive, space stops, q quits; sends '
                                        'cmd_vel at a fixed rate (docs/drive.md).')
    from vehicle_sim.tools.teleop import add_arguments as add_teleop_arguments
    add_teleop_arguments(teleop)
    teleop.set_defaults(func=cmd_teleop)

    scenario = sub.add_parser('scenario', help='run a scenario file and judge its criteria '
                                               '(docs/scenarios.md)')
    from vehicle_sim.tools.scenario_command import add_arguments as add_scenario_arguments
    from vehicle_sim.tools.scenario_command import cmd_scenario
    add_scenario_arguments(scenario)
    scenario.set_defaults(func=cmd_scenario)

    sweep = sub.add_parser('sweep', help='run a scenario over a grid of values and seeds, in '
                                         'parallel (docs/sweeps.md)')
    from vehicle_sim.tools.sweep_command import add_arguments as add_sweep_arguments
    from vehicle_sim.tools.sweep_command import cmd_sweep
    add_sweep_arguments(sweep)
    sweep.set_defaults(func=cmd_sweep)
    policy = sub.add_parser('policy', help='a trained policy drives the car over ROS; its '
                                           'evaluation in process and over ROS '
                                           '(docs/learning.md)')
    from vehicle_sim.tools.policy_command import add_arguments as add_policy_arguments
    add_policy_arguments(policy)

    from vehicle_sim.tools import record_commands
    record = sub.add_parser('record', help='record topics into an MCAP file '
                                           '(docs/record_replay.md)')
    record_commands.add_record_arguments(record)
    record.set_defaults(func=record_commands.cmd_record)
    play = sub.add_parser('play', help='republish an MCAP recording')
    record_commands.add_play_arguments(play)
    play.set_defaults(func=record_commands.cmd_play)
    bag = sub.add_parser('bag', help="a recording's summary (bag info FILE)")
    record_commands.add_bag_arguments(bag)
    bag.set_defaults(func=record_commands.cmd_bag)
    return parser


def main(argv: Optional[List[str]] = None) -> int:
    """
    Run the ``vehicle-sim`` command.

    :param argv: arguments without the program name; default ``sys.argv[1:]``.
    :return: the exit status (0 success, 1 failure, 2 usage error).
    """
    argv = sys.argv[1:] if argv is None else list(argv)
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return args.func(args)
    except CliError as exc:
        print(f'vehicle-sim {args.command}: {exc}', file=sys.stderr)
        return exc.status
    except KeyboardInterrupt:
        return 130
    except BrokenPipeError:
        # The reader of our output went away (`vehicle-sim list | head`): not an error.
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return EXIT_OK
    except Exception as exc:  # noqa: BLE001 - transport errors are reported, not traced
        from vehicle_sim.core.specs.errors import VehicleSimError
        if isinstance(exc, VehicleSimError):
            print(f'vehicle-sim {args.command}: {exc}', file=sys.stderr)
            return EXIT_FAILURE
        raise


if __name__ == '__main__':
    sys.exit(main())


def teleop_main(argv: Optional[List[str]] = None) -> int:
    """
    Run ``vehicle-sim teleop`` as the ``teleop`` executable (``ros2 run vehicle_sim teleop``).

    ``ros2 run`` may append ROS arguments (``--ros-args ...``); teleop takes its settings as
    options (``--namespace``, ``--robot``, ...), so those are dropped.
    """
    from vehicle_sim.transport.ros_args import parse_ros_args
    argv = sys.argv[1:] if argv is None else list(argv)
    return main(['teleop', *parse_ros_args(argv).non_ros_args])
