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
Paths and routes of SUMO edges on a SUMO network's lane graph.

A SUMO vehicle's predicted path (its TrafficObject's ``path``, :func:`route_path`) follows its
lane and the lanes after it at its current speed, as the builtin engine's
(core/traffic/objects.py): at each lane's end the successor is the one that leads (through the
junction's internal lanes) onto the next edge of the vehicle's route; without one, the first
successor. The other way round, :func:`edges_along` gives the SUMO edges a path of points passes
(a scenario actor's waypoints: its route in SUMO). Lane names are SUMO lane ids
(``<edge>_<index>``, internal lanes ``:<junction>_<link>_<index>``), as the lane graph of a
SUMO network has them (vehicle_sim/maps/sumo_net.py).
"""

import math
from typing import Optional, Sequence, Tuple

# edges_along looks at a path's points this far apart [m] (less than a junction's width)
ALONG_STEP_M = 1.0
# ... and takes a lane for the path's only where the lane heads within this of the path [rad]
ALONG_TURN_RAD = 0.25 * math.pi


def edge_of(lane_name: str) -> str:
    """Return the SUMO edge of a SUMO lane id ('A0A1_1' -> 'A0A1')."""
    return lane_name.rsplit('_', 1)[0]


def edges_along(graph, points: Sequence[Tuple[float, float]],
                step_m: float = ALONG_STEP_M) -> Tuple[str, ...]:
    """
    Return the SUMO edges a path passes, in order (a scenario actor's route in SUMO).

    The polyline through ``points`` is looked at every ``step_m``: each point is located on
    the lanes with the polyline's heading there (``LaneGraph.locate``); a point on no lane, on
    a lane inside a junction (SUMO's router joins the edges on either side) or on one heading
    more than ALONG_TURN_RAD away from the path's heading (a road it crosses, or the other
    way) adds nothing; an edge met again right after itself is kept once.

    :param graph: the LaneGraph of a SUMO network (lane names are SUMO lane ids).
    :param points: [(x, y)] [m], two or more (one gives its own edge, heading unknown).
    :param step_m: the spacing of the points looked at [m] (> 0).
    """
    edges = []

    def add(x, y, yaw):
        position = graph.locate(x, y, yaw)
        if position is None or (yaw is not None
                                and abs(position.heading_error_rad) > ALONG_TURN_RAD):
            return
        name = graph.lanes[position.lane_id].name
        if name and not name.startswith(':'):
            edge = edge_of(name)
            if not edges or edges[-1] != edge:
                edges.append(edge)

    points = [(float(x), float(y)) for x, y in points]
    if len(points) == 1:
        add(*points[0], None)
    for (ax, ay), (bx, by) in zip(points, points[1:]):
        length = math.hypot(bx - ax, by - ay)
        if length == 0.0:
            continue
        yaw = math.atan2(by - ay, bx - ax)
        count = max(1, int(math.ceil(length / step_m)))
        for k in range(count + 1):
            f = k / count
            add(ax + (bx - ax) * f, ay + (by - ay) * f, yaw)
    return tuple(edges)


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
