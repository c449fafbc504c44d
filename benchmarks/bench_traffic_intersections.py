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
Traffic at intersections (docs/traffic.md, Intersections): throughput, queues, overlaps, cost.

The city block of config/worlds/city_block.yaml (five unsignalled intersections: the traffic
yields at the conflicts, first come first served) and of city_block_signals.yaml (the same
intersections, each with a light per approach on the default fixed-time plan), with dense
traffic (``--vehicles``, 100 by default: about 35 per km of lane), run by the core
TrafficManager alone (no physics, 100 ms updates) for ``--minutes`` of simulated time. Printed
per intersection (named by its centre): the vehicles through it per hour (a vehicle leaving one
of its lanes onto a lane of no intersection), the queue on its approaches (vehicles standing
on the lanes that enter it: the mean over time of their sum, and the longest queue of one
approach), and for the whole run: the traffic-traffic overlaps (footprints tested every step:
0 expected), the mean speed and the cost of a manager step.

Run: ``.venv/bin/python benchmarks/bench_traffic_intersections.py [--minutes 10] [--quick]``.
"""

import argparse
import math
import time

import numpy as np

from vehicle_sim.config import load_world
from vehicle_sim.core.map.signal_params import SignalSpec
from vehicle_sim.core.map.signal_plan import SignalController
from vehicle_sim.core.traffic.footprints import overlapping
from vehicle_sim.core.traffic.manager import TrafficManager
from vehicle_sim.core.traffic.params import traffic_from_dict
from vehicle_sim.maps.lane_maps import with_lanes
from vehicle_sim.physics.traffic_bodies import model_dimensions

DT_S = 0.1
STANDING_MPS = 0.5            # a vehicle slower than this is in a queue
MODELS = ('ToyotaPrius', 'BmwX5', 'TeslaModel3', 'CitroenCZero', 'LincolnMKZ')


def city(world, vehicles, seed=1):
    """Return (TrafficManager, SignalController or None) of a city world with ``vehicles``."""
    spec = with_lanes(load_world(world))
    graph = spec.lanes
    signals = None
    if graph.rules.groups:
        settings = spec.signals or SignalSpec(source=f'{world}: signals')
        signals = SignalController(graph, settings.fixed_time_plan())
    traffic = traffic_from_dict({'vehicles': vehicles, 'seed': seed, 'models': list(MODELS),
                                 'spawn': {'spacing': 15.0}}, f'{world}: traffic')
    sizes = {m: model_dimensions(m)[:2] for m in MODELS}
    return TrafficManager(graph, traffic, sizes, signals=signals), signals


def intersections(graph):
    """Return {lane id: intersection index} of the lanes in conflict, and their centres."""
    parent = {}

    def root(lane):
        while parent.setdefault(lane, lane) != lane:
            lane = parent[lane]
        return lane
    for conflict in graph.rules.conflicts:
        parent[root(conflict.lane_id)] = root(conflict.other_id)
    groups = {}
    for lane in sorted(parent):
        groups.setdefault(root(lane), []).append(lane)
    of, centres = {}, []
    for index, lanes in enumerate(sorted(groups.values())):
        points = np.concatenate([graph.lanes[lane].centerline for lane in lanes])
        centres.append(tuple(points.mean(axis=0)))
        for lane in lanes:
            of[lane] = index
    return of, centres


def run(manager, signals, minutes):
    """Run ``minutes`` of simulated time; return the figures (see the module docstring)."""
    graph = manager.graph
    of, centres = intersections(graph)
    approaches = {}               # approach lane -> intersection
    for lane in graph.lanes.values():
        if lane.id not in of:
            for after in lane.successors:
                if after in of:
                    approaches[lane.id] = of[after]
    through = [0] * len(centres)
    queue_sum = [0.0] * len(centres)
    queue_max = [0] * len(centres)
    was = [v.lane for v in manager.vehicles]
    steps = int(round(minutes * 60.0 / DT_S))
    overlaps, stepping, speeds = 0, 0.0, []
    for _ in range(steps):
        start = time.perf_counter()
        manager.step(DT_S)
        stepping += time.perf_counter() - start
        if signals is not None:
            signals.update(manager.time_s)
        queues = {}
        boxes = []
        for v in manager.vehicles:
            if not v.active:
                was[v.index] = None
                continue
            if was[v.index] in of and v.lane not in of:
                through[of[was[v.index]]] += 1
            was[v.index] = v.lane
            if v.lane in approaches and v.speed_mps < STANDING_MPS:
                queues[v.lane] = queues.get(v.lane, 0) + 1
            boxes.append((*manager.pose(v), v.length_m, v.width_m))
            speeds.append(v.speed_mps)
        overlaps += len(overlapping(boxes))
        for lane, count in queues.items():
            index = approaches[lane]
            queue_sum[index] += count
            queue_max[index] = max(queue_max[index], count)
    hours = minutes / 60.0
    rows = [(centres[i], through[i] / hours, queue_sum[i] / steps, queue_max[i])
            for i in range(len(centres))]
    return rows, overlaps, float(np.mean(speeds)), stepping / steps


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[1])
    parser.add_argument('--minutes', type=float, default=10.0, help='simulated minutes')
    parser.add_argument('--vehicles', type=int, default=100, help='traffic vehicles')
    parser.add_argument('--quick', action='store_true', help='2 simulated minutes')
    args = parser.parse_args(argv)
    minutes = 2.0 if args.quick else args.minutes
    for world in ('city_block', 'city_block_signals'):
        manager, signals = city(world, args.vehicles)
        rows, overlaps, speed, step_s = run(manager, signals, minutes)
        print(f'{world}: {args.vehicles} vehicles, {minutes:g} simulated min: '
              f'{overlaps} traffic-traffic overlaps, mean speed {speed:.1f} m/s, '
              f'{1e3 * step_s:.2f} ms a manager step')
        for (x, y), per_hour, queue, longest in rows:
            print(f'  intersection at ({x:6.1f}, {y:6.1f}): {per_hour:5.0f} vehicles/h, '
                  f'queue {queue:4.1f} vehicles (mean, all approaches), longest '
                  f'{longest} on one approach')
        total = sum(row[1] for row in rows)
        print(f'  all {len(rows)}: {total:.0f} vehicles/h')
        if math.isnan(speed):
            raise SystemExit('no vehicle moved')


if __name__ == '__main__':
    main()
