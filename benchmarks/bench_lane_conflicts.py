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
The conflicts of a lane map from its geometry: time for a few thousand lanes (issue 30).

Grids of N x N roads (two lanes each way, 100 m blocks, an intersection with its turn lanes at
every crossing) are built from ``roads:`` and ``lane_conflicts`` (core/map/lane_conflicts.py)
runs on their LaneGraph; printed: lanes, conflicts, the graph's build time without the rules
and the conflicts' time, best of 3. The shipped city_block (100 lanes) for context.

Run: ``.venv/bin/python benchmarks/bench_lane_conflicts.py [--quick]``.
"""

import argparse
import math
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))

from vehicle_sim.config import load_world  # noqa: E402
from vehicle_sim.core.map.lane_conflicts import lane_conflicts  # noqa: E402
from vehicle_sim.core.map.lane_graph import LaneGraph  # noqa: E402
from vehicle_sim.core.map.road_segments import (  # noqa: E402
    lane_graph_from_roads,
    roads_from_list,
)

BLOCK_M = 100.0
LANES = 2


def grid(n):
    """Return the roads of an n x n grid of two-lane roads crossing every BLOCK_M."""
    width = 2 * LANES * 3.5
    segments = []
    for _ in range(n):
        segments += [{'type': 'straight', 'length': BLOCK_M - width},
                     {'type': 'intersection', 'length': width}]
    segments.append({'type': 'straight', 'length': BLOCK_M - width})
    roads = []
    for i in range(n):
        at = (i + 1) * BLOCK_M - width / 2
        roads.append({'name': f'ew{i}', 'start': {'x': 0.0, 'y': at, 'yaw': 0.0},
                      'lanes': LANES, 'segments': segments})
        roads.append({'name': f'ns{i}', 'start': {'x': at, 'y': 0.0, 'yaw': math.pi / 2},
                      'lanes': LANES, 'segments': segments})
    return roads_from_list(roads, 'grid')


def best_of(runs, action):
    best, result = math.inf, None
    for _ in range(runs):
        start = time.perf_counter()
        result = action()
        best = min(best, time.perf_counter() - start)
    return best, result


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[1])
    parser.add_argument('--quick', action='store_true', help='smaller grids')
    args = parser.parse_args(argv)
    sizes = (4, 8) if args.quick else (4, 8, 12, 16)
    print(f'load average {"/".join(f"{x:.1f}" for x in os.getloadavg())}')
    print('| map | lanes | conflicts | lanes only [s] | conflicts [s] |')
    print('|---|---|---|---|---|')
    maps = [('city_block', lane_graph_from_roads(load_world('city_block').roads))]
    maps += [(f'grid {n} x {n}', lane_graph_from_roads(grid(n))) for n in sizes]
    for name, graph in maps:
        lanes = list(graph.lanes.values())
        build_s, _ = best_of(3, lambda: LaneGraph(lanes))
        conflicts_s, conflicts = best_of(3, lambda: lane_conflicts(graph))
        print(f'| {name} | {len(lanes)} | {len(conflicts)} | {build_s:.2f} | {conflicts_s:.2f} |')


if __name__ == '__main__':
    main()
