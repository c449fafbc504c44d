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
Cost of the Foxglove live view on the automobile node's step, printed as ratios.

Three nodes in this process (default car, 10 ms step, synchronous, stepped in-process), blocks
of steps interleaved: without a live view; with one and no client (each topic's reader gate
reads its sink's subscriber flag); with one whose every channel is forced open (each message is
built and its bytes go to the SDK, which drops them for want of a client: the forwarding cost
without the WebSocket send). Median of the block ratios. Run:
``.venv/bin/python benchmarks/bench_foxglove.py`` (needs the foxglove extra).
"""

import argparse
import os
import socket
import statistics
import time

from bench_common import use_free_domain


def _free_port():
    with socket.socket() as probe:
        probe.bind(('127.0.0.1', 0))
        return probe.getsockname()[1]


def _block(app, steps):
    start = time.perf_counter()
    app.step(steps)
    return (time.perf_counter() - start) / steps


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[1])
    parser.add_argument('--blocks', type=int, default=15)
    parser.add_argument('--steps', type=int, default=200)
    args = parser.parse_args(argv)
    os.environ.setdefault('ROS_AUTOMATIC_DISCOVERY_RANGE', 'LOCALHOST')
    use_free_domain()
    from vehicle_sim.foxglove.topics import ChannelSink
    from vehicle_sim.ros.automobile import AutomobileNode

    base = {'synchronous': True}
    plain = AutomobileNode(transport='dds', parameter_overrides=base)
    idle = AutomobileNode(transport='dds', parameter_overrides=dict(base, foxglove=_free_port()))
    forced = AutomobileNode(transport='dds',
                            parameter_overrides=dict(base, foxglove=_free_port()))
    for sink in forced._live.topics.sinks.values():
        if isinstance(sink, ChannelSink):
            sink.open = True
    apps = {'without': plain, 'idle': idle, 'forced': forced}
    for app in apps.values():
        app.vehicles[''].logic.set_cruising_speed_within_top_kmh(30.0)
        app.step(50)
    times = {name: [] for name in apps}
    try:
        for _ in range(args.blocks):
            for name, app in apps.items():
                times[name].append(_block(app, args.steps))
    finally:
        for app in apps.values():
            app.close()
    idle_ratio = statistics.median(i / w for i, w in zip(times['idle'], times['without']))
    forced_ratio = statistics.median(f / w for f, w in zip(times['forced'], times['without']))
    print('Foxglove live view, automobile node (Car, 10 ms step, synchronous, in-process), '
          f'{args.blocks} interleaved blocks of {args.steps} steps')
    for name in apps:
        print(f'  {name:8s}: {1e6 * statistics.median(times[name]):7.1f} us per step (median)')
    print(f'  live view, no client       / without: {idle_ratio:.2f}x')
    print(f'  every channel forwarding   / without: {forced_ratio:.2f}x')
    return 0


if __name__ == '__main__':
    raise SystemExit(main())
