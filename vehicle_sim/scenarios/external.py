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
External controllers: the driver's processes, the runner's ROS node, lockstep and pacing.

The scenario's world is served over ROS (:class:`~.sim.ServedSim`); the runner's own node
(:class:`TopicWatcher`) subscribes to the topic criteria's topics and to the lockstep (``sync``)
topics, and counts the /clock subscribers to know when the processes are up. The processes
run in their own process groups; they are stopped with SIGINT, then SIGTERM, then SIGKILL.
"""

import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time

from vehicle_sim.scenarios.criteria import TopicPredicate
from vehicle_sim.scenarios.pacing import Pacer
from vehicle_sim.scenarios.yaml_lines import ScenarioError
from vehicle_sim.transport.qos import BEST_EFFORT, QosProfile, RELIABLE

_EPS_S = 1e-9
PROCESS_STOP_TIMEOUT_S = 5.0
# Wall time left to external processes after the last step, for their last messages.
DRAIN_S = 0.2

# Deep reader queues: a criterion judges every message, also when the runner spins less often
# than the nodes publish (external processes publish on their own clocks).
JUDGE_DEPTH = 10000
_JUDGE_RELIABLE = QosProfile(depth=JUDGE_DEPTH, reliability=RELIABLE)
_JUDGE_BEST_EFFORT = QosProfile(depth=JUDGE_DEPTH, reliability=BEST_EFFORT)


class TopicWatcher:
    """The runner's node: the topic criteria's subscriptions and the /clock subscriber count."""

    def __init__(self, sim, criteria, transport, sync=()):
        from vehicle_sim.transport import create_node
        from vehicle_sim.transport.qos import QOS_CLOCK
        self.sim = sim
        self.node = create_node('scenario_runner', transport=transport)
        self.world = sim.world
        self._subs = []
        for criterion in criteria:
            if isinstance(criterion, TopicPredicate):
                qos = _JUDGE_BEST_EFFORT if criterion.values['best_effort'] else _JUDGE_RELIABLE
                self._subs.append(self.node.create_subscription(
                    criterion.values['ros_type'], criterion.values['topic'],
                    self._callback(criterion), qos))
        self.sync_counts = []
        self.sync_wanted = [count for _, _, count in sync]
        self._sync_subs = []            # (topic, its subscription)
        for topic, ros_type, _ in sync:
            index = len(self.sync_counts)
            self.sync_counts.append(0)
            sub = self.node.create_subscription(ros_type, topic, self._counter(index))
            self._sync_subs.append((topic, sub))
            self._subs.append(sub)
        # Never publishes: it matches the /clock subscribers, to count them.
        self._clock = self.node.create_publisher('rosgraph_msgs/msg/Clock', '/clock',
                                                 QOS_CLOCK)

    def _callback(self, criterion):
        def on_message(msg):
            criterion.message(msg, _stamp_s(msg, self.world.time_s))
        return on_message

    def _counter(self, index):
        def on_message(msg):
            self.sync_counts[index] += 1
        return on_message

    def await_sync(self, before, timeout_s):
        """
        Spin until every sync topic has its count of messages beyond the counts ``before``.

        The served robots then take what reached this process with them (one participant per
        process: a message this node has read is in their readers too), so the next step runs
        on the controller's answer, not on the one before.

        :return: None, or the index of a topic short of its count after ``timeout_s`` (wall
            clock).
        """
        deadline = time.monotonic() + timeout_s
        while True:
            waiting = [i for i, (now, then, wanted)
                       in enumerate(zip(self.sync_counts, before, self.sync_wanted))
                       if now - then < wanted]
            if not waiting:
                self.sim.spin()
                return None
            if time.monotonic() > deadline:
                return waiting[0]
            self.spin()
            time.sleep(0.0002)

    def clock_subscribers(self):
        return self._clock.get_subscription_count()

    def sync_unmatched(self):
        """Return the sync topics whose subscription has matched no publisher yet."""
        return [topic for topic, sub in self._sync_subs if sub.get_publisher_count() < 1]

    def spin(self):
        self.sim.spin()
        self.node.spin_once(0.0)

    def drain(self, wall_s=DRAIN_S):
        end = time.monotonic() + wall_s
        while time.monotonic() < end:
            self.spin()
            time.sleep(0.001)

    def close(self):
        self.node.shutdown()


def _stamp_s(msg, default_s):
    # The time a message is about: its header stamp (or a Clock's clock), else its receipt.
    stamp = getattr(getattr(msg, 'header', None), 'stamp', None) or getattr(msg, 'clock', None)
    if stamp is None:
        return default_s
    return stamp.sec + stamp.nanosec * 1e-9


def run_processes(spec, sim, criteria, transport):
    """
    Start the driver's processes, step the served world at the real-time factor.

    With ``sync`` topics, time waits after every sync period for the controller's answer
    (lockstep); a wait that times out ends the run with an error.
    """
    driver = spec.driver
    watcher = TopicWatcher(sim, criteria, transport, driver.sync)
    processes = _Processes(driver.processes, spec.seed,
                           os.path.dirname(os.path.abspath(spec.source)), spec.source)
    try:
        processes.start()
        wanted = (len(driver.processes) if driver.clock_subscribers < 0
                  else driver.clock_subscribers)
        deadline = time.monotonic() + driver.startup_timeout_s
        # Time starts once the processes listen to /clock and this node has matched their sync
        # topics' publishers: an answer written before this reader matched its writer would be
        # lost (a late-matching reader starts at the writer's next sample), and lockstep with it
        while watcher.clock_subscribers() < wanted or watcher.sync_unmatched():
            error = processes.failed()
            if error:
                return error
            if time.monotonic() > deadline:
                unmatched = watcher.sync_unmatched()
                return (f'{watcher.clock_subscribers()} of {wanted} /clock subscriber(s)'
                        + (f', no publisher of {", ".join(unmatched)}' if unmatched else '')
                        + f' after {driver.startup_timeout_s:g} s: the processes did not come '
                        'up\n' + processes.output())
            watcher.spin()
            time.sleep(0.01)
        pacer = Pacer(driver.real_time_factor, watcher.spin)
        pacer.start()
        step_s = spec.time_step_ms / 1000.0
        sync_every = max(1, int(round(driver.sync_period_s / step_s)))
        steps = 0
        while sim.world.time_s < spec.duration_s - _EPS_S:
            before = list(watcher.sync_counts)
            now_s = sim.step()
            steps += 1
            watcher.spin()
            if driver.sync and steps % sync_every == 0:
                late = watcher.await_sync(before, driver.sync_timeout_s)
                if late is not None:
                    topic, _, count = driver.sync[late]
                    missing = 'no message' if count == 1 else f'fewer than {count} messages'
                    return (f'lockstep: {missing} on {topic} within '
                            f'{driver.sync_timeout_s:g} s (wall) after /clock {now_s:.3f} s\n'
                            + processes.output())
            pacer.wait(now_s)
            error = processes.failed()
            if error:
                return error
        watcher.drain()
        return None
    finally:
        processes.stop()
        watcher.close()


class _Processes:
    """
    The driver's subprocesses, each in its own process group, output to a temporary file.

    They run in the scenario file's folder (relative paths in their command lines work).
    """

    def __init__(self, commands, seed, cwd, source):
        self.source = source
        self.commands = commands
        self.seed = seed
        self.cwd = cwd
        self.procs = []
        self._folder = tempfile.mkdtemp(prefix='vehicle_sim_scenario_')

    def start(self):
        env = dict(os.environ, VEHICLE_SIM_SEED=str(self.seed))
        for index, argv in enumerate(self.commands):
            # 'python' is the runner's own interpreter (its environment, its vehicle_sim)
            executable = (sys.executable if argv[0] == 'python' else
                          shutil.which(argv[0]) or argv[0])
            log = open(os.path.join(self._folder, f'process{index}.log'), 'wb')
            try:
                proc = subprocess.Popen([executable] + list(argv[1:]), stdout=log,
                                        stderr=subprocess.STDOUT, env=env, cwd=self.cwd,
                                        start_new_session=True)
            except OSError as error:
                log.close()
                raise ScenarioError(self.source, None,
                                    f'cannot start {" ".join(argv)}: {error}') from None
            self.procs.append((argv, proc, log))

    def failed(self):
        """Return why a process ended with a failure status, or None."""
        for argv, proc, _ in self.procs:
            code = proc.poll()
            if code not in (None, 0):
                return f'process {" ".join(argv)} exited with status {code}\n' + self.output()
        return None

    def output(self, tail=2000):
        parts = []
        for index, (argv, _, log) in enumerate(self.procs):
            log.flush()
            with open(os.path.join(self._folder, f'process{index}.log'), 'rb') as stream:
                text = stream.read().decode('utf-8', 'replace')[-tail:]
            parts.append(f'--- {" ".join(argv)}\n{text}')
        return '\n'.join(parts)

    def stop(self):
        """SIGINT each process group, then SIGTERM, then SIGKILL, each after a grace time."""
        for sig in (signal.SIGINT, signal.SIGTERM, signal.SIGKILL):
            alive = [proc for _, proc, _ in self.procs if proc.poll() is None]
            if not alive:
                break
            for proc in alive:
                try:
                    os.killpg(proc.pid, sig)
                except ProcessLookupError:
                    pass
            end = time.monotonic() + PROCESS_STOP_TIMEOUT_S
            while time.monotonic() < end and any(p.poll() is None for p in alive):
                time.sleep(0.02)
        for _, proc, log in self.procs:
            proc.wait()
            log.close()
        shutil.rmtree(self._folder, ignore_errors=True)
