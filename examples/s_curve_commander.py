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
An Autoware-style commander: an S-curve of control commands, timed by /clock.

It publishes ``autoware_control_msgs/msg/Control`` on ``/control/command/control_cmd`` every
20 ms of simulated time: straight at 0.8 m/s for 2 s, one S (steering tire angle
0.28 · sin(2π t / 6 s), + = left) over 6 s, straight again for 1 s, then v = 0. The
``ackermann_to_differential`` bridge turns that into wheel speeds for a differential robot
(scenarios/bridge_s_curve.yaml runs both as the scenario's processes).

Written against vehicle_sim's transport port, so it runs on the embedded transport and, as an
rclpy node, on a ROS 2 machine::

    python examples/s_curve_commander.py            # needs a /clock publisher (a simulation)
"""

import math
import sys

from vehicle_sim.transport import create_node, run_node

SPEED_MPS = 0.8
AMPLITUDE_RAD = 0.28
STRAIGHT_S, S_CURVE_S, AFTER_S = 2.0, 6.0, 1.0
PERIOD_S = 0.020
CONTROL = 'autoware_control_msgs/msg/Control'
TOPIC = '/control/command/control_cmd'


def command_at(t_s):
    """Return (speed [m/s], steering tire angle [rad, + left]) at simulated time t_s."""
    if t_s < STRAIGHT_S:
        return SPEED_MPS, 0.0
    if t_s < STRAIGHT_S + S_CURVE_S:
        return SPEED_MPS, AMPLITUDE_RAD * math.sin(2.0 * math.pi * (t_s - STRAIGHT_S) / S_CURVE_S)
    if t_s < STRAIGHT_S + S_CURVE_S + AFTER_S:
        return SPEED_MPS, 0.0
    return 0.0, 0.0


class SCurveCommander:
    """Publishes the S-curve once per 20 ms period of /clock."""

    def __init__(self, args=None):
        self.node = node = create_node('s_curve_commander', args=args)
        self._pub = node.create_publisher(CONTROL, TOPIC)
        self._msg = node.msg(CONTROL)
        self._last_period = None
        node.create_subscription('rosgraph_msgs/msg/Clock', '/clock', self._on_clock,
                                 'clock')

    def _on_clock(self, msg):
        now_s = msg.clock.sec + msg.clock.nanosec * 1e-9
        # once per period, on the first /clock of each (at 0, 20, 40 ms ... when none is lost)
        period = math.floor(now_s / PERIOD_S + 1e-6)
        if period == self._last_period:
            return
        self._last_period = period
        speed, steer = command_at(now_s)
        command = self._msg()
        command.stamp = msg.clock
        command.longitudinal.velocity = speed
        command.lateral.steering_tire_angle = steer
        self._pub.publish(command)


def main(args=None):
    """Run until SIGINT/SIGTERM."""
    return run_node(lambda argv: SCurveCommander(argv).node, sys.argv if args is None else args)


if __name__ == '__main__':
    sys.exit(main())
