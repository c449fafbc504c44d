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
highway_traffic over ROS in real time: does it hold real time, and with how much headroom.

Target: >= 5x headroom with a subscriber on every topic, and with ``--record`` (issue 28). The
node runs as users start it, ``vehicle-sim run --world highway_traffic`` (real_time_factor 1,
60 traffic cars, the objects and markers at their default 10 Hz), in a subprocess. This process
finds the node's topics on the graph and subscribes to every one of them with its writer's QoS
(raw: the bytes are counted, not decoded, so that the subscriber's Python does not stand in for
the node's cost), or only to /clock. Over a window of wall time it reads:

- the achieved real-time factor: simulated time (from /clock) / wall time (1 = holds real time);
- the headroom: simulated time / CPU time of the node's process and its children (the
  recorder's writer): the real-time factor it would reach with a core to itself, i.e. how many
  times over it could keep real time. On a shared machine this moves much less with other
  people's work than a wall-clock figure.

Printed beside: the node with no subscriber but /clock, and with a subscriber on every topic and
``objects_rate`` 100 (the objects and markers each 10 ms step, as before they had their own
rate).

Run: ``.venv/bin/python benchmarks/bench_traffic_ros.py [--quick]``.
"""

import argparse
import os
import subprocess
import sys
import tempfile
import time

from bench_common import process_cpu_s, use_free_domain

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, REPO_ROOT)

WORLD = 'highway_traffic'
TARGET_HEADROOM = 5.0
OBJECTS = '/perception/object_recognition/objects'


def _tree_cpu_s(pid):
    # CPU of a process and of its live children (the recorder's writer process) [s].
    total = process_cpu_s(pid)
    try:
        with open(f'/proc/{pid}/task/{pid}/children', encoding='ascii') as children:
            for child in children.read().split():
                total += process_cpu_s(int(child))
    except OSError:
        pass
    return total


def measure(seconds, every_topic=True, record=None, node_args=(), warmup_s=2.0):
    """
    Return {achieved, headroom, cpu_share, wall_s, messages, topics} of one run of the node.

    :param every_topic: subscribe to every topic the node publishes, else to /clock only.
    :param record: an .mcap path for ``--record``, or None.
    :param node_args: ROS arguments for the node (``('-p', 'objects_rate:=100.0')``).
    """
    from vehicle_sim.transport import dds
    from vehicle_sim.transport.dds import DdsNode
    from vehicle_sim.transport.dds.graph import GraphView
    from vehicle_sim.transport.qos import BEST_EFFORT, QosProfile, TRANSIENT_LOCAL
    env = dict(os.environ, PYTHONPATH=REPO_ROOT + os.pathsep + os.environ.get('PYTHONPATH', ''))
    command = [sys.executable, '-m', 'vehicle_sim.tools.cli', 'run', '--world', WORLD,
               '--no-status', '--real-time-factor', '1']
    if record:
        command += ['--record', record]
    if node_args:
        command += ['--', '--ros-args', *node_args]
    proc = subprocess.Popen(command, env=env, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)
    listener = DdsNode('bench_traffic_listener')
    graph = GraphView()
    graph.ignore_participant(dds.participant_guid())
    counts = {}
    clock = []
    try:
        if not graph.wait_until(lambda: graph.publishers(OBJECTS), 120.0):
            raise RuntimeError(f'{WORLD}: no {OBJECTS} publisher within 120 s')
        graph.wait(1.0)          # every writer of the node announced
        topics = {topic: graph.publishers(topic)[0] for topic in graph.topics()
                  if graph.publishers(topic)}
        subs = [listener.create_subscription(
            'rosgraph_msgs/msg/Clock', '/clock',
            lambda msg: clock.append(msg.clock.sec + msg.clock.nanosec * 1e-9),
            QosProfile(depth=1, reliability=BEST_EFFORT))]
        for topic, writer in topics.items() if every_topic else ():
            if topic == '/clock':
                continue
            counts[topic] = 0
            qos = QosProfile(depth=10, reliability='reliable' if writer.reliable else BEST_EFFORT,
                             durability=TRANSIENT_LOCAL if writer.transient_local else
                             'volatile')
            subs.append(listener.create_subscription(
                writer.ros_type, topic,
                lambda data, key=topic: counts.__setitem__(key, counts[key] + 1), qos, raw=True))
        deadline = time.monotonic() + 60.0
        while (not all(s.get_publisher_count() for s in subs)
               and time.monotonic() < deadline):
            listener.spin_once(0.05)
        end = time.monotonic() + warmup_s
        while time.monotonic() < end or not clock:
            listener.spin_once(0.05)
        for key in counts:
            counts[key] = 0
        sim0, cpu0, wall0 = clock[-1], _tree_cpu_s(proc.pid), time.monotonic()
        end = wall0 + seconds
        while time.monotonic() < end:
            listener.spin_once(0.05)
        sim1, cpu1, wall1 = clock[-1], _tree_cpu_s(proc.pid), time.monotonic()
    finally:
        proc.terminate()
        proc.wait(60)
        graph.close()
        listener.shutdown()
    wall_s, cpu_s, sim_s = wall1 - wall0, cpu1 - cpu0, sim1 - sim0
    return {'achieved': sim_s / wall_s, 'headroom': sim_s / cpu_s, 'cpu_share': cpu_s / wall_s,
            'wall_s': wall_s, 'messages': sum(counts.values()), 'topics': len(counts),
            'objects': counts.get(OBJECTS, 0)}


def figures(quick=False):
    """Return {case: measure(...)} for the four cases (see the module docstring)."""
    seconds = 5.0 if quick else 10.0
    found = {}
    with tempfile.TemporaryDirectory(prefix='bench_traffic_ros_') as folder:
        found['clock only'] = measure(seconds, every_topic=False)
        found['every topic'] = measure(seconds)
        found['record'] = measure(seconds, every_topic=False,
                                  record=os.path.join(folder, 'traffic.mcap'))
        found['every topic, objects each step'] = measure(
            seconds, node_args=('-p', 'objects_rate:=100.0'))
    return found


def describe(name, run):
    return (f'{name}: {run["achieved"]:.2f}x real time achieved, headroom '
            f'{run["headroom"]:.1f}x (node CPU {run["cpu_share"] * 100:.0f} % of a core); '
            f'{run["messages"] / run["wall_s"]:.0f} messages/s received on {run["topics"]} '
            f'topics, objects {run["objects"] / run["wall_s"]:.1f}/s')


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--quick', action='store_true', help='5 s windows instead of 10 s')
    options = parser.parse_args(argv)
    use_free_domain()
    found = figures(options.quick)
    print(f'{WORLD} (60 traffic cars) over ROS, vehicle-sim run at real_time_factor 1')
    for name, run in found.items():
        print('  ' + describe(name, run))
    for name in ('every topic', 'record'):
        headroom = found[name]['headroom']
        verdict = 'met' if headroom >= TARGET_HEADROOM else 'MISSED'
        print(f'  {name}: headroom {headroom:.1f}x (target >= {TARGET_HEADROOM:g}x): {verdict}')
    return 0


if __name__ == '__main__':
    sys.exit(main())
