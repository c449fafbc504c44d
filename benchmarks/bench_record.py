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
The cost of recording (docs/record_replay.md), measured in one run and printed as ratios.

1. In-process step with every topic recorded ÷ without: three synchronous automobile nodes in
   this process (ToyotaPrius, 10 ms, cruising at 30 km/h), stepped in interleaved blocks: one
   plain (no subscriber: its topics are skipped), one whose publishers are tapped by a tap that
   drops the bytes (every message built and serialized, as for a subscriber; no DDS reader is
   matched, so none is written to DDS), one recorded into an MCAP file (``--record``). The
   target row is recorded ÷ plain (target <= 1.3x); recorded ÷ published says what the
   recording itself costs beyond building the messages.
2. ROS-synchronous real-time factor with a recorder attached (target >= 40x): the node in a
   subprocess as ``vehicle-sim run --synchronous --record FILE``, driven through
   ``robot/time_step`` as ``bench_ros_sync.py`` does; the same without ``--record`` right after.
3. Recorder memory over a long run: the recorded node stepped through 10 simulated minutes
   (60000 steps; ``--quick`` 1 minute); this process's RSS at the start and the end.

Run: ``.venv/bin/python benchmarks/bench_record.py [--quick]``.
"""

import argparse
import os
import statistics
import sys
import tempfile
import time

from bench_common import process_cpu_s, use_free_domain

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, REPO_ROOT)

CAR = 'ToyotaPrius'
STEP_MS = 10
TARGET_RATIO = 1.3
TARGET_RTF = 40.0


def rss_mib() -> float:
    """Return this process's resident set size [MiB] (Linux /proc)."""
    with open('/proc/self/status', encoding='ascii') as status:
        for line in status:
            if line.startswith('VmRSS:'):
                return int(line.split()[1]) / 1024.0
    return float('nan')


def _node(name, tap=None, path=None):
    from vehicle_sim.recording.recorder import record_node
    from vehicle_sim.ros.automobile_node import AutomobileNode, NODE_NAME
    from vehicle_sim.transport import create_node
    node = create_node(NODE_NAME, args=['bench', '--ros-args', '-r', f'__ns:=/{name}',
                                        '-p', 'synchronous:=true', '-p', f'car_model:={CAR}',
                                        '-p', f'time_step_ms:={STEP_MS}'], transport='dds')
    recorder = None
    if path is not None:
        recorder = record_node(node, path)
    elif tap is not None:
        node.tap_publishers(tap)
    app = AutomobileNode(node=node)
    app.vehicles[''].logic.set_cruising_speed_kmh(30.0)
    app.step(200)
    return app, recorder


def measure_in_process(blocks, steps, folder):
    """
    Return (recorded ÷ plain, recorded ÷ published, figures per step) as medians.

    The figures [us per step]: the wall time of each node (``plain``, ``published``,
    ``recorded``), and for each the CPU time of this process (``*_cpu``); ``writer_cpu`` is
    the CPU time of the recorder's writer process; ``built_ratio`` is published ÷ plain (what
    building every message costs, before any recording).
    """
    plain, _ = _node('bench_plain')
    published, _ = _node('bench_published', tap=lambda *_: (lambda data: None))
    recorded, recorder = _node('bench_recorded', path=os.path.join(folder, 'inproc.mcap'))
    writer = getattr(recorder.writer, '_process', None)
    times = {k: [] for k in ('plain', 'published', 'recorded', 'plain_cpu', 'published_cpu',
                             'recorded_cpu', 'writer_cpu')}
    try:
        for _ in range(blocks):
            for name, app in (('plain', plain), ('published', published),
                              ('recorded', recorded)):
                writer_start = process_cpu_s(writer.pid) if writer is not None else 0.0
                cpu = time.process_time()
                start = time.perf_counter()
                app.step(steps)
                times[name].append((time.perf_counter() - start) / steps)
                times[name + '_cpu'].append((time.process_time() - cpu) / steps)
                if name == 'recorded' and writer is not None:
                    times['writer_cpu'].append(
                        (process_cpu_s(writer.pid) - writer_start) / steps)
    finally:
        recorder.close()
        for app in (plain, published, recorded):
            app.close()
    ratio_plain = statistics.median(r / p for r, p in zip(times['recorded'], times['plain']))
    ratio_published = statistics.median(
        r / p for r, p in zip(times['recorded'], times['published']))
    per_step = {k: statistics.median(v) * 1e6 if v else float('nan')
                for k, v in times.items()}
    per_step['built_ratio'] = statistics.median(
        b / p for b, p in zip(times['published'], times['plain']))
    return ratio_plain, ratio_published, per_step


def measure_ros_rtf(steps, repeats, folder):
    """Return (RTF with --record, RTF without), the node run by ``vehicle-sim run``."""
    import bench_ros_sync
    path = os.path.join(folder, 'ros.mcap')
    base = [sys.executable, '-m', 'vehicle_sim.tools.cli', 'run', '--no-status', '--synchronous',
            '--car', CAR]
    node_args = ['--', '--ros-args', '-p', f'time_step_ms:={STEP_MS}']
    rtf = {}
    for name, extra in (('recorded', ['--record', path]), ('plain', [])):
        walls, _, received = bench_ros_sync.measure_ros(steps, repeats,
                                                        command=base + extra + node_args)
        if not received['speed']:
            raise RuntimeError(f'{name}: the subscriber received nothing')
        rtf[name] = steps * STEP_MS / 1000.0 / statistics.median(walls)
    return rtf['recorded'], rtf['plain'], os.path.getsize(path)


def measure_memory(steps, folder):
    """Return (RSS at the start, RSS at the end [MiB], file size [bytes], steps per second)."""
    path = os.path.join(folder, 'long.mcap')
    app, recorder = _node('bench_long', path=path)
    try:
        app.step(1000)
        start_rss = rss_mib()
        start = time.perf_counter()
        app.step(steps)
        elapsed = time.perf_counter() - start
        end_rss = rss_mib()
    finally:
        recorder.close()
        app.close()
    return start_rss, end_rss, os.path.getsize(path), steps / elapsed


def figures(quick=False):
    with tempfile.TemporaryDirectory(prefix='bench_record_') as folder:
        ratio_plain, ratio_published, per_step = measure_in_process(
            5 if quick else 15, 200 if quick else 400, folder)
        rtf_recorded, rtf_plain, ros_size = measure_ros_rtf(1000, 3 if quick else 5, folder)
        start_rss, end_rss, size, rate = measure_memory(6000 if quick else 60000, folder)
    return {'ratio_plain': ratio_plain, 'ratio_published': ratio_published,
            'per_step_us': per_step, 'rtf_recorded': rtf_recorded, 'rtf_plain': rtf_plain,
            'ros_file_bytes': ros_size, 'rss_start_mib': start_rss, 'rss_end_mib': end_rss,
            'long_file_bytes': size, 'long_steps_per_s': rate,
            'long_sim_s': (6000 if quick else 60000) * STEP_MS / 1000.0}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--quick', action='store_true', help='fewer samples, a shorter long run')
    options = parser.parse_args(argv)
    use_free_domain()
    found = figures(options.quick)
    steps = found['per_step_us']
    print(f'{CAR}, {STEP_MS} ms, synchronous, every topic each step')
    print(f'  in process: plain {steps["plain"]:.0f} us per step, every topic published '
          f'{steps["published"]:.0f} us, recorded {steps["recorded"]:.0f} us; recorded / plain '
          f'{found["ratio_plain"]:.2f}x (target <= {TARGET_RATIO:g}x), recorded / published '
          f'{found["ratio_published"]:.2f}x')
    print(f'  every topic built, not recorded / plain {steps["built_ratio"]:.2f}x: what recording '
          'every topic costs at least over a node whose topics nobody reads')
    print(f'  CPU per step of the node\'s process: plain {steps["plain_cpu"]:.0f} us, published '
          f'{steps["published_cpu"]:.0f} us, recorded {steps["recorded_cpu"]:.0f} us (+ '
          f'{steps["writer_cpu"]:.0f} us in the writer process)')
    print(f'  over ROS (robot/time_step, 1000 steps): real-time factor '
          f'{found["rtf_recorded"]:.1f}x with --record (target >= {TARGET_RTF:g}x), '
          f'{found["rtf_plain"]:.1f}x without')
    print(f'  long run: {found["long_sim_s"]:g} s simulated at {found["long_steps_per_s"]:.0f} '
          f'steps/s, RSS {found["rss_start_mib"]:.1f} MiB at the start, '
          f'{found["rss_end_mib"]:.1f} MiB at the end; file '
          f'{found["long_file_bytes"] / 2**20:.1f} MiB')
    return 0


if __name__ == '__main__':
    sys.exit(main())
