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
Predicted paths along a route of SUMO edges on a SUMO network's lane graph.

A SUMO vehicle's predicted path (its TrafficObject's ``path``) follows its lane and the lanes
after it at its current speed, as the builtin engine's (core/traffic/objects.py): at each lane's
end the successor is the one that leads (through the junction's internal lanes) onto the next
edge of the vehicle's route; without one, the first successor. Lane names are SUMO lane ids
(``<edge>_<index>``, internal lanes ``:<junction>_<link>_<index>``), as the lane graph of a
SUMO network has them (vehicle_sim/maps/sumo_net.py).
"""

from typing import Optional, Sequence, Tuple


def edge_of(lane_name: str) -> str:
    """Return the SUMO edge of a SUMO lane id ('A0A1_1' -> 'A0A1')."""
    return lane_name.rsplit('_', 1)[0]


def _leads_to(graph, lane_id, edge, depth=4):
    """Whether lane ``lane_id``, or the internal lanes after it, reach a lane of ``edge``."""
    lane = graph.lanes[lane_id]
    if not lane.name.startswith(':'):
        return edge_of(lane.name) == edge
    return depth > 0 and any(_leads_to(graph, nxt, edge, depth - 1) for nxt in lane.successors)


def route_path(graph, lane_id: int, s_m: float, speed_mps: float, count: int, step_s: float,
               next_edges: Sequence[str] = ()) -> Tuple[Tuple[float, float, float], ...]:
    """
    Return ``count`` poses (x, y, yaw) every ``step_s`` along the lanes from ``s_m`` on a lane.

    :param graph: the LaneGraph.
    :param lane_id: the lane the path starts on.
    :param s_m: where on it [m] (clamped to the lane).
    :param speed_mps: the constant speed [m/s] (>= 0).
    :param count: how many poses.
    :param step_s: the time between two poses [s].
    :param next_edges: the SUMO edges the route takes after the current one, in order.
    :return: the poses; fewer where the lanes end.
    """
    lanes = graph.lanes
    lane = lanes[lane_id]
    s = min(max(s_m, 0.0), lane.length_m)
    edges = list(next_edges)
    poses = []
    for _ in range(count):
        s += speed_mps * step_s
        while s > lane.length_m:
            nxt = _successor(graph, lane, edges)
            if nxt is None:
                return tuple(poses)              # the lanes end: the prediction too
            s -= lane.length_m
            lane = lanes[nxt]
            if not lane.name.startswith(':') and edges and edge_of(lane.name) == edges[0]:
                edges.pop(0)
        poses.append(lane.centre_pose(s))
    return tuple(poses)


def _successor(graph, lane, edges) -> Optional[int]:
    successors = lane.successors
    if not successors:
        return None
    if edges:
        for nxt in successors:
            if _leads_to(graph, nxt, edges[0]):
                return nxt
    return successors[0]
