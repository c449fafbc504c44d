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
Synchronous stepping over ROS: real-time factor of ``robot/time_step`` vs ``Driver.step``.

The automobile node runs in a subprocess (embedded DDS transport, loopback-only discovery) in
synchronous mode with every topic published each basic step (the default); this process
subscribes to ``/automobile/current_speed`` and ``/clock`` (so the traffic is real), sets the
car cruising at 30 km/h and calls ``robot/time_step`` for 1000 basic steps in one request, a
few times. The wall time of the call gives the real-time factor. After each request, the same
car (ToyotaPrius, 10 ms) steps 1000 times in this process through ``Driver.step``; the median of
the ratios of the two per-step costs, request by request, is the cost of ROS (issue 10 targets:
>= 40x real time; <= 2.5x in-process).

Run: ``.venv/bin/python benchmarks/bench_ros_sync.py [--repeats N] [--steps N] [--profile]``;
``--profile`` runs one request under cProfile inside the node and prints its top functions.
"""

import argparse
import os
import statistics
import subprocess
import sys
import time

from bench_common import process_cpu_s, use_free_domain

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, REPO_ROOT)

CAR = 'ToyotaPrius'
STEP_MS = 10
TARGET_RTF = 40.0
TARGET_RATIO = 2.5
SPEED_KMH = 30.0


def _node_command(profile_path=None):
    command = [sys.executable, '-m', 'vehicle_sim.ros.automobile_node', '--ros-args',
               '-p', f'car_model:={CAR}', '-p', 'synchronous:=true',
               '-p', f'time_step_ms:={STEP_MS}']
    if profile_path:    # the node exits normally on SIGTERM, so cProfile writes its file
        command[1:1] = ['-m', 'cProfile', '-o', profile_path]
    return command


def measure_ros(steps, repeats, profile_path=None, between=None, command=None):
    """
    Return the wall and node CPU seconds of each ``robot/time_step`` request, the counts.

    :param between: called after each request (the in-process block of the same run, so
        that the two sides of the ratio are interleaved and a change of load hits both).
    :param command: the node's command line (default: the automobile node, as above).
    """
    from vehicle_sim.transport.dds import DdsNode
    env = dict(os.environ, PYTHONPATH=REPO_ROOT + os.pathsep + os.environ.get('PYTHONPATH', ''))
    command = command or _node_command(profile_path)
    proc = subprocess.Popen(command, env=env, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)
    client = DdsNode('bench_ros_sync')
    received = {'speed': 0, 'clock': 0}
    try:
        client.create_subscription(
            'vehicle_msgs/msg/Float64Stamped', '/automobile/current_speed',
            lambda msg: received.__setitem__('speed', received['speed'] + 1))
        client.create_subscription(
            'rosgraph_msgs/msg/Clock', '/clock',
            lambda msg: received.__setitem__('clock', received['clock'] + 1))
        time_step = client.create_client('vehicle_msgs/srv/SetInt', '/robot/time_step')
        cruise = client.create_client('vehicle_msgs/srv/SetFloat',
                                      '/automobile/set_cruising_speed')
        if not (time_step.wait_for_service(60.0) and cruise.wait_for_service(60.0)):
            raise RuntimeError('the automobile node did not come up')
        set_int = client.srv('vehicle_msgs/srv/SetInt').Request
        if not cruise.call(client.srv('vehicle_msgs/srv/SetFloat').Request(value=SPEED_KMH),
                           10.0).success:
            raise RuntimeError('set_cruising_speed refused')
        time_step.call(set_int(value=200 * STEP_MS), 60.0)    # past the start transient
        walls, cpus = [], []
        for _ in range(repeats):
            cpu0 = process_cpu_s(proc.pid)
            start = time.perf_counter()
            response = time_step.call(set_int(value=steps * STEP_MS), 120.0)
            walls.append(time.perf_counter() - start)
            cpus.append(process_cpu_s(proc.pid) - cpu0)
            if not response.success:
                raise RuntimeError('robot/time_step refused')
            if between is not None:
                between()
        client.spin_once(0.2)
    finally:
        client.shutdown()
        proc.terminate()
        proc.wait(30)
    return walls, cpus, received


class InProcessCar:
    """The same car stepped through ``Driver.step()`` in this process, a block at a time."""

    def __init__(self, steps):
        from vehicle_sim.webots import Car
        self.steps = steps
        self.walls = []
        self.car = Car(CAR)
        self.car.setCruisingSpeed(SPEED_KMH)
        for _ in range(200):
            self.car.step()

    def block(self):
        step = self.car.step
        start = time.perf_counter()
        for _ in range(self.steps):
            step()
        self.walls.append(time.perf_counter() - start)

    def close(self):
        self.car.close()


_READER = """
import time
from vehicle_sim.transport.dds import DdsNode
node = DdsNode("bench_ros_sync_reader")
node.create_subscription("rosgraph_msgs/msg/Clock", "/clock", lambda m: None)
node.create_subscription("vehicle_msgs/msg/Float64Stamped", "/bench_node/automobile/current_speed",
                         lambda m: None)
print("READY", flush=True)
end = time.monotonic() + 120.0
while time.monotonic() < end:
    node.spin_once(0.1)
"""


def measure_node_in_process(steps, repeats):
    """
    Return the node's CPU per step [us] in this process: no subscriber, two in another one.

    The two subscribe to ``/clock`` and ``current_speed``, as in :func:`measure_ros`. The
    difference is what delivering samples to another process costs the publisher.
    """
    from vehicle_sim.ros.automobile_node import AutomobileNode
    app = AutomobileNode(['bench', '--ros-args', '-r', '__ns:=/bench_node', '-p',
                          'synchronous:=true', '-p', f'car_model:={CAR}'], transport='dds')
    reader = None
    try:
        app.vehicles[''].logic.set_cruising_speed_kmh(SPEED_KMH)
        app.step(200)

        def cpu_per_step():
            start = time.process_time()
            app.step(steps)
            return (time.process_time() - start) / steps * 1e6

        alone = min(cpu_per_step() for _ in range(repeats))
        reader = subprocess.Popen([sys.executable, '-c', _READER], stdout=subprocess.PIPE,
                                  text=True)
        reader.stdout.readline()
        publishers = list(app._fleet_outputs.publishers.values()) + list(
            app._vehicles[0].outputs.publishers.values())
        deadline = time.monotonic() + 30.0
        while sum(p.get_subscription_count() for p in publishers) < 2:
            if time.monotonic() > deadline:
                raise RuntimeError('the reader did not match')
            time.sleep(0.02)
        matched = min(cpu_per_step() for _ in range(repeats))
    finally:
        if reader is not None:
            reader.kill()
            reader.wait()
        app.close()
    return alone, matched


def figures(steps=1000, repeats=5):
    """
    Return the figures of one run (medians).

    ``ros_rtf``, ``ros_us`` (wall per step over ROS), ``node_cpu_us`` (the node's CPU per step),
    ``inproc_us`` (``Driver.step``), ``ratio`` (ROS / in process, wall: the median of the
    ratios of each request to the in-process block run right after it).
    """
    in_process = InProcessCar(steps)
    try:
        in_process.block()      # warm, as the node is by its first request
        in_process.walls.clear()
        walls, cpus, received = measure_ros(steps, repeats, between=in_process.block)
    finally:
        in_process.close()
    if not received['speed'] or not received['clock']:
        raise RuntimeError(f'the subscribers received nothing: {received}')
    ros, cpu = statistics.median(walls), statistics.median(cpus)
    inproc = statistics.median(in_process.walls)
    ratio = statistics.median(w / i for w, i in zip(walls, in_process.walls))
    alone, matched = measure_node_in_process(steps // 2, repeats)
    sim_s = steps * STEP_MS / 1000.0
    return {'ros_rtf': sim_s / ros, 'ros_us': ros / steps * 1e6, 'node_cpu_us': cpu / steps * 1e6,
            'inproc_us': inproc / steps * 1e6, 'ratio': ratio,
            'node_alone_cpu_us': alone, 'node_matched_cpu_us': matched}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--steps', type=int, default=1000)
    parser.add_argument('--repeats', type=int, default=5)
    parser.add_argument('--profile', action='store_true')
    options = parser.parse_args(argv)
    use_free_domain()
    if options.profile:
        import pstats
        import tempfile
        path = os.path.join(tempfile.mkdtemp(), 'node.prof')
        measure_ros(options.steps, options.repeats, profile_path=path)
        pstats.Stats(path).sort_stats('tottime').print_stats(30)
        pstats.Stats(path).sort_stats('cumulative').print_stats(40)
        return 0
    result = figures(options.steps, options.repeats)
    print(f'{CAR}, {STEP_MS} ms, {options.steps} steps per robot/time_step, every topic each '
          f'step, subscribers on current_speed and /clock')
    print(f'  over ROS  : {result["ros_us"]:7.1f} us per step, real-time factor '
          f'{result["ros_rtf"]:5.1f}x (target >= {TARGET_RTF:g}x); the node\'s CPU '
          f'{result["node_cpu_us"]:.1f} us per step')
    print(f'  in process: {result["inproc_us"]:7.1f} us per step; ROS / in process '
          f'{result["ratio"]:.2f}x (target <= {TARGET_RATIO:g}x)')
    print(f'  the node stepped in process: CPU {result["node_alone_cpu_us"]:.0f} us per step '
          f'without a subscriber, {result["node_matched_cpu_us"]:.0f} us with subscribers to '
          '/clock and current_speed in another process')
    return 0


if __name__ == '__main__':
    sys.exit(main())
