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
How far a vehicle travelled along the lanes between two lane positions.

:func:`lane_distance` is the signed distance along the lane graph from (lane a, s_a) to (lane
b, s_b): along one lane the change of s; onto a successor the rest of the first lane plus s on
the next (lanes in between counted whole); back onto a predecessor the same, negative; across
to a same-direction neighbour (a lane change) the change of s with s_a carried over at the same
fraction of the lane's length (as LaneTracker moves a vehicle to a neighbour). Positions with no
such link within a few lanes are unrelated (a jump): the distance is None.
"""

from typing import Optional

from vehicle_sim.core.map.lane_graph import LaneGraph

# Lanes searched along successors (and predecessors) for the second position: enough for one
# step that skips a short connector lane at an intersection.
MAX_LANES = 3


def _starts(graph, lane_id, s_m):
    # (lane id, s there) of a position and of the same place on its neighbours
    lane = graph.lanes[lane_id]
    yield lane_id, s_m
    for side in (lane.left_lane, lane.right_lane):
        if side is not None:
            yield side, s_m / lane.length_m * graph.lanes[side].length_m


def lane_distance(graph: LaneGraph, from_lane: int, from_s_m: float, to_lane: int,
                  to_s_m: float, max_lanes: int = MAX_LANES) -> Optional[float]:
    """
    Return the signed distance [m] along the lanes between two lane positions, or None.

    :param graph: the LaneGraph of both lanes.
    :param from_lane: the first position's lane id; ``from_s_m`` its arc length [m].
    :param to_lane: the second position's lane id; ``to_s_m`` its arc length [m].
    :param max_lanes: how many successors (predecessors) deep to search.
    :return: + forward (the lanes' direction), - backward; None when the positions are not
        linked within ``max_lanes`` lanes (the shortest link wins where there are several).
    """
    lanes = graph.lanes
    found = []
    for start, s_m in _starts(graph, from_lane, from_s_m):
        if start == to_lane:
            found.append(to_s_m - s_m)
            continue
        ahead = [(start, lanes[start].length_m - s_m)]     # (lane, distance to its end)
        behind = [(start, -s_m)]                           # (lane, distance to its start)
        for _ in range(max_lanes):
            next_ahead, next_behind = [], []
            for lane_id, gap in ahead:
                for successor in lanes[lane_id].successors:
                    if successor == to_lane:
                        found.append(gap + to_s_m)
                    next_ahead.append((successor, gap + lanes[successor].length_m))
            for lane_id, gap in behind:
                for predecessor in graph.predecessors[lane_id]:
                    if predecessor == to_lane:
                        found.append(gap - (lanes[predecessor].length_m - to_s_m))
                    next_behind.append((predecessor, gap - lanes[predecessor].length_m))
            if found:
                break
            ahead, behind = next_ahead, next_behind
    if not found:
        return None
    return min(found, key=abs)
