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
Lane state per step per vehicle: target <= 20 us (issue "Roads to drive on").

A vehicle drives the shipped highway (config/worlds/highway.yaml: 3 + 3 lanes, 2.33 km) at
30 m/s with 10 ms steps, weaving between its three lanes (a lane change every 4 s), and each step
computes its lane state (core LaneTracker.update) and its lane invasions
(LaneInvasionDetector.update), as a node would for ``<ns>/lane_state`` and
``<ns>/lane_invasion``. The same drive runs on a map 50 times larger (50 highways side by side,
1500 lanes) to show that the per-step cost does not grow with the map, and on the highway with a
stop line every 100 m of each forward lane (the lane state's next stop line ahead found each
step: core/map/lane_state.py); the whole-map search
(``LaneGraph.locate``, what a step costs only after a teleport or when a vehicle leaves every
lane) is printed for context. Figures: best of 5 runs of the whole drive, per step.

Run: ``.venv/bin/python benchmarks/bench_lanes.py [--quick]``.
"""

import argparse
import math
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))

from vehicle_sim.config import load_world  # noqa: E402
from vehicle_sim.core.map.lane_invasion import LaneInvasionDetector  # noqa: E402
from vehicle_sim.core.map.lane_rules import LaneRules, StopLine  # noqa: E402
from vehicle_sim.core.map.lane_state import LaneTracker  # noqa: E402
from vehicle_sim.core.map.road_segments import (  # noqa: E402
    lane_graph_from_roads,
    roads_from_list,
)

TARGET_US = 20.0
SPEED_MPS = 30.0
DT_S = 0.01


def _drive(graph, steps):
    """Return the poses of a drive along the first forward lanes, weaving between lanes 0..2."""
    chain = [100001]
    while graph.lanes[chain[-1]].successors:
        chain.append(graph.lanes[chain[-1]].successors[0])
    poses, lane_index, s = [], 0, 0.0
    for step in range(steps):
        lane = graph.lanes[chain[lane_index]]
        if s > lane.length_m:
            s -= lane.length_m
            lane_index = (lane_index + 1) % len(chain)
            lane = graph.lanes[chain[lane_index]]
        x, y, yaw = graph.pose_at(lane.id, s, 0.0)
        # 0 .. 7.5 m right of lane 0's centre (lane 2's centre) and back every 8 s
        shift = 3.75 - 3.75 * math.cos(2.0 * math.pi * step * DT_S / 8.0)
        poses.append((x + math.sin(yaw) * shift, y - math.cos(yaw) * shift, yaw))
        s += SPEED_MPS * DT_S
    return poses


def per_step_us(graph, poses, repeat=5, with_invasion=True):
    """Return the best-of-``repeat`` cost of one step's lane state (and invasions) [us]."""
    best = float('inf')
    crossings = 0
    for _ in range(repeat):
        tracker = LaneTracker(graph)
        detector = LaneInvasionDetector(graph)
        update, invaded = tracker.update, detector.update
        start = time.perf_counter()
        if with_invasion:
            for index, (x, y, yaw) in enumerate(poses):
                update(x, y, yaw)
                crossings += len(invaded(x, y, index * DT_S))
        else:
            for x, y, yaw in poses:
                update(x, y, yaw)
        best = min(best, (time.perf_counter() - start) / len(poses))
    return best * 1e6, crossings // repeat


def locate_us(graph, poses, count=200):
    """Return the cost of a whole-map search (LaneGraph.locate) [us]."""
    sample = poses[::max(1, len(poses) // count)][:count]
    start = time.perf_counter()
    for x, y, yaw in sample:
        graph.locate(x, y, yaw)
    return (time.perf_counter() - start) / len(sample) * 1e6


def large_graph(copies):
    """Return ``copies`` highways side by side, 100 m apart (their lanes in one graph)."""
    world = load_world('highway')
    road = dict(lanes=3, backward_lanes=3, lane_width=3.75, speed_limit=33.3,
                centre_line='solid_solid',
                segments=[{'type': s.type, 'length': s.length_m} if s.type != 'arc' else
                          {'type': 'arc', 'radius': s.radius_m, 'angle': s.angle_deg}
                          for s in world.roads[0].segments])
    roads = [dict(road, name=f'h{i}', start={'x': 0.0, 'y': 100.0 * i, 'yaw': 0.0})
             for i in range(copies)]
    return lane_graph_from_roads(roads_from_list(roads, 'bench'), 'bench')


def with_stop_lines(world, every_m=100.0):
    """Return the highway's graph with a stop sign's line every ``every_m`` on forward lanes."""
    graph = lane_graph_from_roads(world.roads, world.source)
    lines = []
    for lane in graph.lanes.values():
        if lane.id % 100 >= 50:               # the backward lanes: none
            continue
        s = every_m / 2.0
        while s < lane.length_m:
            x, y, yaw = graph.pose_at(lane.id, s)
            nx, ny = -math.sin(yaw) * 1.5, math.cos(yaw) * 1.5
            lines.append(StopLine(len(lines) + 1, lane.id, s,
                                  [(x - nx, y - ny), (x + nx, y + ny)], 'stop_sign'))
            s += every_m
    graph.set_rules(LaneRules(stop_lines=tuple(lines)))
    return graph


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[1])
    parser.add_argument('--quick', action='store_true', help='fewer steps')
    args = parser.parse_args(argv)
    steps = 2000 if args.quick else 7000
    world = load_world('highway')
    highway = lane_graph_from_roads(world.roads, world.source)
    poses = _drive(highway, steps)
    big = large_graph(50)
    lined = with_stop_lines(world)
    print(f'load average {"/".join(f"{x:.1f}" for x in os.getloadavg())}; {steps} steps of '
          f'{DT_S * 1000:g} ms at {SPEED_MPS:g} m/s, weaving across 2 lane lines every 8 s')
    rows = []
    for name, graph in (('highway (30 lanes)', highway),
                        (f'50 highways ({len(big.lanes)} lanes)', big),
                        (f'highway, {len(lined.rules.stop_lines)} stop lines', lined)):
        both, crossings = per_step_us(graph, poses)
        state_only, _ = per_step_us(graph, poses, with_invasion=False)
        rows.append((name, both, state_only, locate_us(graph, poses), crossings))
    print(f'| map | lane state + invasion [us/step] | lane state only | whole-map search '
          f'[us] | crossings | target <= {TARGET_US:g} us |')
    print('|---|---|---|---|---|---|')
    for name, both, state_only, search, crossings in rows:
        verdict = 'met' if both <= TARGET_US else 'MISSED'
        print(f'| {name} | {both:.2f} | {state_only:.2f} | {search:.1f} | {crossings} | '
              f'{verdict} |')
    return rows


if __name__ == '__main__':
    main()
