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
``vehicle-sim teleop``: drive the car (or the differential robot) from the keyboard.

An ordinary node on the transport port (the embedded Cyclone DDS transport, or rclpy on a ROS 2
machine): it publishes ``cmd_vel`` at a fixed rate from the keys (:mod:`.teleop_keys`) and shows
commanded and measured speed and steering on one line, measured from the vehicle's odometry
and, for the car, its ``automobile/steering_angle``. docs/drive.md, "Teleop".
"""

import os
import select
import sys
import termios
import time
import tty

from vehicle_sim.tools.command import CliError, EXIT_OK, EXIT_USAGE, install_stop_handlers
from vehicle_sim.tools.teleop_keys import KeyDecoder, status_line, TeleopLimits, TeleopState

DEFAULT_RATE_HZ = 20.0
NODE_NAME = 'teleop'


def add_arguments(parser):
    """Add the teleop options to its subparser."""
    parser.add_argument('--namespace', default='', metavar='NS',
                        help="the vehicle's namespace (car: /NS/cmd_vel; robot: "
                             '/NS/diff_robot/cmd_vel)')
    parser.add_argument('--robot', action='store_true',
                        help='drive the differential robot (/diff_robot) instead of the car')
    parser.add_argument('--stamped', action='store_true',
                        help='send geometry_msgs/TwistStamped (the node parameter '
                             'cmd_vel_stamped:=true)')
    parser.add_argument('--rate', type=float, default=DEFAULT_RATE_HZ, metavar='HZ',
                        help=f'cmd_vel rate (default {DEFAULT_RATE_HZ:g} Hz)')
    parser.add_argument('--max-speed', type=float, metavar='MPS',
                        help='speed reached by holding up/down [m/s] (default: car 5, robot '
                             '0.5)')
    parser.add_argument('--accel', type=float, metavar='MPS2',
                        help='how fast the speed rises while a key is held [m/s^2] (default: '
                             'car 2, robot 0.5)')
    parser.add_argument('--yaw-rate', type=float, default=1.0, metavar='RADPS',
                        help='robot: yaw rate of left/right [rad/s] (default 1)')
    parser.add_argument('--curvature', type=float, default=0.15, metavar='PER_M',
                        help='car: path curvature of left/right [1/m] (default 0.15)')


# The interface tables are imported where used: `vehicle-sim` builds this parser for every
# command, and they pull in numpy and the message definitions.


def topic_names(namespace, robot):
    """Return (cmd_vel, odom, steering or None) topic names of the vehicle."""
    from vehicle_sim.ros import automobile_interfaces as itf
    from vehicle_sim.ros import robot_interfaces as ri
    prefix = '/' + namespace.strip('/') if namespace.strip('/') else ''
    if robot:
        base = f'{prefix}/{ri.ROBOT_NODE_NAME}'
        return f'{base}/{itf.CMD_VEL.name}', f'{base}/{ri.ROBOT_ODOM.name}', None
    return (f'{prefix}/{itf.CMD_VEL.name}', f'{prefix}/{itf.ODOM.name}',
            f'{prefix}/{itf.topic("automobile/steering_angle").name}')


class Teleop:
    """The teleop node: a cmd_vel publisher and the measured state it shows."""

    def __init__(self, namespace='', robot=False, stamped=False, transport=None):
        from vehicle_sim.core.specs.units import webots_steering_to_ros
        from vehicle_sim.ros import automobile_interfaces as itf
        from vehicle_sim.transport.selection import create_node
        self._to_rep103 = webots_steering_to_ros
        self.robot = robot
        self.node = node = create_node(NODE_NAME, args=['--ros-args', '--disable-rosout-logs'],
                                       transport=transport)
        cmd_vel, odom, steering = topic_names(namespace, robot)
        self.row = itf.CMD_VEL_INPUTS[stamped]
        self._stamped = stamped
        self.publisher = node.create_publisher(self.row.ros_type, cmd_vel, self.row.qos)
        self.cmd_vel_name = cmd_vel
        self.speed_mps = None
        self.steering = None         # car: steering angle [rad, + left]; robot: yaw rate
        self._subs = [node.create_subscription(itf.ODOM.ros_type, odom, self._on_odom)]
        if steering is not None:
            self._subs.append(node.create_subscription(itf.FLOAT64_STAMPED, steering,
                                                       self._on_steering))

    def _on_odom(self, msg):
        self.speed_mps = msg.twist.twist.linear.x
        if self.robot:
            self.steering = msg.twist.twist.angular.z

    def _on_steering(self, msg):
        self.steering = self._to_rep103(msg.data)   # Webots sign on automobile/*

    def send(self, speed_mps, yaw_rate_radps):
        """Publish one cmd_vel."""
        msg = self.node.msg(self.row.ros_type)()
        twist = msg
        if self._stamped:
            msg.header.stamp = self.node.time_msg()
            twist = msg.twist
        twist.linear.x = float(speed_mps)
        twist.angular.z = float(yaw_rate_radps)
        self.publisher.publish(msg)

    def close(self):
        self.node.shutdown()


def _limits(args):
    robot = args.robot
    max_speed = args.max_speed if args.max_speed is not None else (0.5 if robot else 5.0)
    accel = args.accel if args.accel is not None else (0.5 if robot else 2.0)
    try:
        return TeleopLimits(max_speed, accel, args.yaw_rate, args.curvature, robot)
    except ValueError as error:
        raise CliError(str(error), EXIT_USAGE)


def cmd_teleop(args) -> int:
    """Run teleop until q, Ctrl-C or SIGTERM; refuse a stdin that is not a terminal."""
    if not (args.rate > 0.0 and args.rate < 1000.0):
        raise CliError(f'--rate {args.rate:g}: must be in (0, 1000) Hz', EXIT_USAGE)
    limits = _limits(args)
    stdin = sys.stdin
    if not stdin.isatty():
        raise CliError('stdin is not a terminal: teleop reads keys from an interactive '
                       'terminal (run it in a terminal, not with input redirected or piped)')
    teleop = Teleop(args.namespace, args.robot, args.stamped)
    try:
        return _loop(teleop, TeleopState(limits), stdin.fileno(), 1.0 / args.rate)
    finally:
        teleop.close()


def _loop(teleop, state, fd, period_s) -> int:
    stop = install_stop_handlers()
    decoder = KeyDecoder()
    saved = termios.tcgetattr(fd)
    out = sys.stdout
    out.write(f'teleop: {teleop.cmd_vel_name} ({teleop.row.ros_type}) at '
              f'{1.0 / period_s:g} Hz\n')
    try:
        tty.setcbreak(fd)
        next_s = time.monotonic()
        while not stop.is_set() and not state.quit:
            timeout_s = max(0.0, next_s - time.monotonic())
            ready, _, _ = select.select([fd], [], [], timeout_s)
            now_s = time.monotonic()
            if ready:
                data = os.read(fd, 64)
                if not data:            # the terminal went away
                    break
                for key in decoder.feed(data):
                    state.press(key, now_s)
            teleop.node.spin_once(0.0)
            if now_s >= next_s:
                command = state.command(now_s)
                teleop.send(*command)
                out.write('\r' + status_line(command, teleop.speed_mps, teleop.steering,
                                             teleop.robot) + '\x1b[K')
                out.flush()
                next_s += period_s
                if next_s < now_s:      # fell behind: keep the rate, skip the backlog
                    next_s = now_s + period_s
        teleop.send(0.0, 0.0)          # leave the vehicle stopping
        return EXIT_OK
    finally:
        termios.tcsetattr(fd, termios.TCSADRAIN, saved)
        out.write('\n')
        out.flush()
