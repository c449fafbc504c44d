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
The conflict zones the traffic asks for, and the overlaps at forks (core/traffic/rules.py).

A :class:`Zone` is one side of a conflict: the range of a lane where a vehicle on it would meet
a vehicle on the other side. The zones come from the map's conflicts (``LaneRules.conflicts``:
lane areas that cross or merge) and from the footprints of the largest vehicle swept along the
junction lanes (footprints.py: a car's rectangle swings outside its lane's area in a tight
turn); one zone pair per pair of lanes, the union of both. Where the branches of a fork overlap
near their start, ``forks`` gives how far (vehicles there follow the other branches' vehicles
instead of asking for a zone).
"""

from dataclasses import dataclass
from typing import Callable, Dict, List, Tuple

import numpy as np

from vehicle_sim.core.map.lane_graph import distances_to_polyline
from vehicle_sim.core.traffic.footprints import footprint_overlaps

FORK_SAMPLE_M = 0.5         # sampling step of the fork overlaps
SWEPT_LEAVING_M = 10.0      # footprints are sampled this far onto the lanes leaving a junction
FORK_REACH_M = 30.0         # fork overlaps are measured over at most this of each branch


class Zone:
    """One side of a conflict: its lane's range, the pair it belongs to and its precedence."""

    __slots__ = ('key', 'other', 'lane', 's0', 's1', 'yields')

    def __init__(self, key, other, lane, s0, s1, yields):
        self.key, self.other, self.lane, self.s0, self.s1 = key, other, lane, s0, s1
        self.yields = yields


@dataclass
class ConflictZones:
    """
    The zones of a lane graph.

    :param zones: {lane id: its Zones by increasing s}.
    :param other: {zone key: the Zone} (a zone's ``other`` key names the other side).
    :param forks: {lane id: arc length from its start within which it overlaps a sibling} [m].
    :param siblings: {lane id: the other lanes leaving the lane it leaves}.
    """

    zones: Dict[int, Tuple[Zone, ...]]
    other: Dict[tuple, Zone]
    forks: Dict[int, float]
    siblings: Dict[int, Tuple[int, ...]]


def conflict_zones(graph, length_m, width_m, yields: Callable[[int, int], bool]) -> ConflictZones:
    """
    Return the ConflictZones of a LaneGraph (its rules' conflicts and the swept footprints).

    :param length_m: the longest traffic vehicle [m].
    :param width_m: the widest traffic vehicle [m].
    :param yields: ``yields(lane, other)``: the lane's side gives way (core/map/priority.py).
    """
    rules = graph.rules
    forks = fork_lengths(graph, width_m + 0.5)
    siblings = {}
    for lane in graph.lanes.values():
        if len(lane.successors) > 1:
            for one in lane.successors:
                siblings[one] = tuple(s for s in lane.successors if s != one)
    pairs = [(c.lane_id, c.other_id, c.s_m, c.other_s_m) for c in rules.conflicts]
    pairs += _swept(graph, pairs, forks, siblings, length_m, width_m)
    merged: Dict[Tuple[int, int], list] = {}    # one zone pair per lane pair: the union
    for a, b, on_a, on_b in pairs:
        if a > b:
            a, b, on_a, on_b = b, a, on_b, on_a
        got = merged.get((a, b))
        if got is None:
            merged[(a, b)] = [min(on_a), max(on_a), min(on_b), max(on_b)]
        else:
            got[0], got[1] = min(got[0], min(on_a)), max(got[1], max(on_a))
            got[2], got[3] = min(got[2], min(on_b)), max(got[3], max(on_b))
    found: Dict[int, List[Zone]] = {}
    for pair, ((a, b), (a0, a1, b0, b1)) in enumerate(sorted(merged.items())):
        on_a, on_b = (a0, a1), (b0, b1)
        found.setdefault(a, []).append(Zone(
            (pair, 0), (pair, 1), a, min(on_a), max(on_a), yields(a, b)))
        found.setdefault(b, []).append(Zone(
            (pair, 1), (pair, 0), b, min(on_b), max(on_b), yields(b, a)))
    zones = {lane: tuple(sorted(z, key=lambda zone: (zone.s0, zone.key)))
             for lane, z in found.items()}
    return ConflictZones(zones, {zone.key: zone for z in zones.values() for zone in z}, forks,
                         siblings)


def fork_lengths(graph, width_m) -> Dict[int, float]:
    """
    Return {lane id: arc length from its start within which it overlaps a sibling} [m].

    Siblings are lanes that leave the same lane; a branch overlaps another while their
    centrelines are closer than ``width_m`` (the widest vehicle plus a margin). Lanes without
    a sibling are not in the result.
    """
    lanes, out = graph.lanes, {}
    for lane in lanes.values():
        branches = lane.successors
        if len(branches) < 2:
            continue
        for one in branches:
            this = lanes[one]
            reach = min(this.length_m, FORK_REACH_M)
            places = np.arange(0.0, reach + 1e-9, FORK_SAMPLE_M)
            along = np.append(this.s0, this.length_m)
            points = np.c_[np.interp(places, along, this.xs), np.interp(places, along, this.ys)]
            near = np.zeros(len(places), dtype=bool)
            for other in branches:
                if other != one:
                    near |= distances_to_polyline(points, lanes[other].centerline) < width_m
            length = float(places[near].max()) + FORK_SAMPLE_M if near.any() else 0.0
            if length > 0.0:
                out[one] = max(out.get(one, 0.0), min(length, this.length_m))
    return out


def _swept(graph, pairs, forks, siblings, length_m, width_m):
    """
    Return the conflicts of footprints beyond the lanes' areas (footprints.py).

    Sampled on the lanes of the conflicts and the forks' branches, and the first
    ``SWEPT_LEAVING_M`` of the lanes they lead to; a lane and the lane it follows, and
    neighbours, are not tested. Branches of a fork that overlap lengthen its overlap
    (``forks``, updated) instead.
    """
    lanes = graph.lanes
    inside = {a for a, b, _, _ in pairs} | {b for a, b, _, _ in pairs} | set(forks)
    if not inside or length_m <= 0.0:
        return []
    ranges = {lane: (0.0, lanes[lane].length_m) for lane in inside}
    for lane in inside:
        for after in lanes[lane].successors:
            ranges.setdefault(after, (0.0, SWEPT_LEAVING_M))
    skip = set()
    for lane in ranges:
        for other in lanes[lane].successors + (lanes[lane].left_lane,
                                               lanes[lane].right_lane):
            if other is not None:
                skip.add((lane, other))
    extra = []
    for (a, b), (on_a, on_b) in footprint_overlaps(graph, ranges, length_m, width_m,
                                                   skip).items():
        if b in siblings.get(a, ()):
            forks[a] = max(forks.get(a, 0.0), on_a[1])
            forks[b] = max(forks.get(b, 0.0), on_b[1])
        else:
            extra.append((a, b, on_a, on_b))
    return extra
