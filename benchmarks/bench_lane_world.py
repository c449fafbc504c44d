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
A world with lanes against the same world without: the automobile node's in-process step.

The shipped highway (config/worlds/highway.yaml: roads:, 30 lanes, drawn surface and markings)
runs in an in-process automobile node, synchronous, its car cruising at 60 km/h along the
middle lane (put back at its start before each round, so that it stays on the first straight);
the same world without ``roads:`` is the baseline, measured in the same run
(alternating, best of the rounds). The node computes the car's lane state and lane invasions
each publish period (``<ns>/lane_state``, ``<ns>/lane_invasion``; no subscriber, so no message
is built: the cost of the tracking itself). Also printed: the time to build each world.
Target (issue "Roads to drive on"): lane state per step per vehicle <= 20 us, here measured
as the whole node step with lanes minus without (the drawn road adds nothing to the step: it
has no collision shape). A world without lanes is not touched by any of it.

Run: ``.venv/bin/python benchmarks/bench_lane_world.py [--quick]``.
"""

import argparse
import os
import sys
import tempfile
import time

import yaml

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, ROOT)

HIGHWAY = os.path.join(ROOT, 'config', 'worlds', 'highway.yaml')
TARGET_US = 20.0


def _node(world):
    from vehicle_sim.ros.automobile_node import AutomobileNode
    start = time.perf_counter()
    node = AutomobileNode(transport='dds', parameter_overrides={
        'world': world, 'synchronous': True})
    built_s = time.perf_counter() - start
    node._vehicles[0].logic.set_cruising_speed_kmh(60.0)
    node.step(200)                       # up to speed
    return node, built_s


def _per_step_us(node, steps):
    node.reset_vehicle('')
    node._vehicles[0].logic.set_cruising_speed_kmh(60.0)
    node.step(100)
    start = time.perf_counter()
    node.step(steps)
    return (time.perf_counter() - start) / steps * 1e6


def figures(quick=False):
    """Return {'lanes_us', 'plain_us', 'ratio', 'build_lanes_s', 'build_plain_s'}."""
    with open(HIGHWAY, encoding='utf-8') as stream:
        data = yaml.safe_load(stream)
    data.pop('roads')
    handle, plain = tempfile.mkstemp(suffix='.yaml')
    with os.fdopen(handle, 'w', encoding='utf-8') as stream:
        yaml.safe_dump(data, stream)
    lanes_node, lanes_s = _node(HIGHWAY)
    plain_node, plain_s = _node(plain)
    try:
        steps, rounds = (500, 3) if quick else (2000, 5)
        with_lanes, without = [], []
        for _ in range(rounds):
            with_lanes.append(_per_step_us(lanes_node, steps))
            without.append(_per_step_us(plain_node, steps))
    finally:
        lanes_node.close()
        plain_node.close()
        os.unlink(plain)
    best_lanes, best_plain = min(with_lanes), min(without)
    return {'lanes_us': best_lanes, 'plain_us': best_plain, 'ratio': best_lanes / best_plain,
            'extra_us': best_lanes - best_plain,
            'build_lanes_s': lanes_s, 'build_plain_s': plain_s}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--quick', action='store_true', help='fewer steps')
    found = figures(parser.parse_args().quick)
    print(f'highway node step with lanes:    {found["lanes_us"]:8.1f} us '
          f'(world built in {found["build_lanes_s"]:.2f} s)')
    print(f'same world without roads:        {found["plain_us"]:8.1f} us '
          f'(world built in {found["build_plain_s"]:.2f} s)')
    verdict = 'ok' if found['extra_us'] <= TARGET_US else 'OVER'
    print(f'lanes cost per step per car: {found["extra_us"]:.1f} us (target <= {TARGET_US:g} '
          f'us) {verdict}; ratio {found["ratio"]:.3f}x')


if __name__ == '__main__':
    main()
