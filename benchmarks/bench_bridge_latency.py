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
Bridge latency: command received → wheel command published (target: p50 <= 1 ms).

1. In-process: the node's callback path (convert, validate, watchdog, kinematics, build and
   publish DifferentialCommand + Float64MultiArray on the embedded transport), timed around
   ``handle_command``.
2. Cross-process: this process publishes a Control command, the bridge (a subprocess, wall
   clock) publishes the DifferentialCommand, this process receives it; minus a bare relay
   measured in the same run (test/transport_peer.py echoing std_msgs/String through another
   process on the same transport), which is the cost of the two DDS hops alone.

Usage: ``python benchmarks/bench_bridge_latency.py [--samples N]``.
"""

import argparse
import os
import statistics
import subprocess
import sys
import time

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, REPO_ROOT)
os.environ.setdefault('ROS_AUTOMATIC_DISCOVERY_RANGE', 'LOCALHOST')
os.environ.setdefault('ROS_DOMAIN_ID', str(102 + os.getpid() % 100))

from vehicle_sim.ros import autoware_interfaces as awi  # noqa: E402
from vehicle_sim.ros import bridge_interfaces as bi  # noqa: E402
from vehicle_sim.ros.bridge_node import AckermannToDifferentialNode  # noqa: E402
from vehicle_sim.transport.dds import DdsNode  # noqa: E402

WAIT_S = 60.0


def percentiles(samples_s):
    """Return (p50, p99) in microseconds."""
    ordered = sorted(samples_s)
    p99 = ordered[min(len(ordered) - 1, int(round(0.99 * (len(ordered) - 1))))]
    return statistics.median(ordered) * 1e6, p99 * 1e6


def in_process(samples):
    bridge = AckermannToDifferentialNode(
        ['--ros-args', '--disable-stdout-logs', '-r', '__node:=bench_bridge_local', '-r',
         f'{bi.DIFFERENTIAL_COMMAND_OUT.name}:=/bench_local/differential_command', '-r',
         f'{bi.WHEEL_VELOCITIES_OUT.name}:=/bench_local/wheel_velocities', '-p',
         'vehicle_status:=false', '-r', '/control/command/control_cmd:=/bench_local/cmd'],
        transport='dds')
    msg = bridge.node.msg(awi.CONTROL)()
    msg.longitudinal.velocity, msg.lateral.steering_tire_angle = 0.4, 0.1
    times = []
    try:
        for i in range(samples + 200):
            msg.longitudinal.velocity = 0.4 + 1e-4 * (i % 7)
            start = time.perf_counter()
            bridge.handle_command(msg)
            if i >= 200:
                times.append(time.perf_counter() - start)
    finally:
        bridge.destroy()
    return percentiles(times)


def _env():
    env = dict(os.environ)
    env['PYTHONPATH'] = REPO_ROOT + os.pathsep + env.get('PYTHONPATH', '')
    return env


def _round_trips(node, publisher, make_msg, received, samples):
    times = []
    for i in range(samples + 50):
        count = len(received)
        start = time.perf_counter()
        publisher.publish(make_msg(i))
        deadline = start + 5.0
        while len(received) == count and time.perf_counter() < deadline:
            node.spin_once(0.001)
        if len(received) == count:
            continue
        if i >= 50:
            times.append(time.perf_counter() - start)
        node.spin_once(0.0)
    return times


def cross_process(samples):
    node = DdsNode('bench_client', '/bench')
    procs = [
        subprocess.Popen(
            [sys.executable, '-m', 'vehicle_sim.ros.bridge_node', '--ros-args',
             '--disable-stdout-logs', '-r', '__node:=bench_bridge', '-p', 'vehicle_status:=false',
             '-p', 'publish_wheel_velocities:=false', '-p', 'command_timeout_s:=0.0',
             '-p', 'max_accel_mps2:=0.0', '-p', 'max_decel_mps2:=0.0',
             '-r', '/control/command/control_cmd:=/bench/cmd',
             '-r', f'{bi.DIFFERENTIAL_COMMAND_OUT.name}:=/bench/out'],
            env=_env(), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL),
        subprocess.Popen(
            [sys.executable, os.path.join(REPO_ROOT, 'test', 'transport_peer.py'),
             '--ros-args', '--disable-stdout-logs', '-r', '__ns:=/bench_echo'],
            env=_env(), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL),
    ]
    try:
        got_cmd, got_echo = [], []
        cmd_pub = node.create_publisher(awi.CONTROL, '/bench/cmd')
        node.create_subscription(bi.DIFFERENTIAL_COMMAND_OUT.ros_type, '/bench/out',
                                 got_cmd.append)
        echo_pub = node.create_publisher('std_msgs/msg/String', '/bench_echo/echo_in')
        node.create_subscription('std_msgs/msg/String', '/bench_echo/echo_out', got_echo.append)
        if not node.spin_until(lambda: cmd_pub.get_subscription_count() > 0
                               and echo_pub.get_subscription_count() > 0, WAIT_S):
            raise RuntimeError('bridge or echo peer did not start')
        node.spin_until(lambda: False, 1.0)     # let discovery settle
        control = node.msg(awi.CONTROL)
        string = node.msg('std_msgs/msg/String')

        def make_control(i):
            msg = control()
            msg.longitudinal.velocity, msg.lateral.steering_tire_angle = 0.4 + 1e-4 * i, 0.1
            return msg

        bridge_times, echo_times = [], []
        for _ in range(4):   # interleave so that both see the same machine load
            bridge_times += _round_trips(node, cmd_pub, make_control, got_cmd, samples // 4)
            echo_times += _round_trips(node, echo_pub, lambda i: string(data=f'ping {i}'),
                                       got_echo, samples // 4)
        return percentiles(bridge_times), percentiles(echo_times)
    finally:
        node.shutdown()
        for proc in procs:
            proc.terminate()
        for proc in procs:
            proc.wait(WAIT_S)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[1])
    parser.add_argument('--samples', type=int, default=2000)
    options = parser.parse_args()
    p50, p99 = in_process(options.samples)
    print(f'in-process callback path (handle_command, {options.samples} commands): '
          f'p50 {p50:.1f} us, p99 {p99:.1f} us  (target p50 <= 1000 us: '
          f'{"met" if p50 <= 1000 else "MISSED"})')
    (b50, b99), (e50, e99) = cross_process(options.samples)
    print(f'cross-process publisher -> bridge -> subscriber: p50 {b50:.1f} us, p99 {b99:.1f} us')
    print(f'bare relay publisher -> echo node -> subscriber:  p50 {e50:.1f} us, p99 {e99:.1f} us')
    print(f'bridge cost over the bare relay: p50 {b50 - e50:+.1f} us, p99 {b99 - e99:+.1f} us '
          f'(target p50 <= 1000 us: {"met" if b50 - e50 <= 1000 else "MISSED"})')
    return 0


if __name__ == '__main__':
    sys.exit(main())
