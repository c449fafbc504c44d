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
Lane invasion: one event each time a vehicle's reference point crosses a lane marking.

Like CARLA's lane-invasion sensor, an event names the marking's line type (solid, dashed,
curbstone, ...). Each step the motion of the point from its previous position is tested against
the boundary segments in the grid cells it passes (a uniform grid built once per map), so a
step costs a few segment tests. Markings of type virtual or none mark nothing and give no event.

Counting rule (so that one crossing is one event): the motion counts from just after its start
to its end inclusive, and a boundary segment from its start inclusive to its end exclusive. A
point that lands exactly on a line has crossed it; moving off it again is not a second crossing;
a crossing at the vertex two segments share counts once. A boundary crossed twice in one step
(a hairpin) gives one event.
"""

from dataclasses import dataclass
import math
from typing import Dict, List, Tuple

from vehicle_sim.core.map.lane_graph import LaneGraph, UNMARKED_TYPES


@dataclass(frozen=True)
class LaneInvasion:
    """
    A crossing of one lane marking.

    :param time_s: simulated time of the step that crossed [s].
    :param boundary_id: the boundary's id (a Lanelet2 line string's id).
    :param line_type: its line type (lane_graph.LINE_TYPES).
    :param x_m: where it was crossed, world x [m].
    :param y_m: world y [m].
    """

    time_s: float
    boundary_id: int
    line_type: str
    x_m: float
    y_m: float


class LaneInvasionDetector:
    """
    The lane invasions of one vehicle, from its reference point step by step.

    :param graph: the LaneGraph whose boundaries are the markings.
    :param cell_m: grid cell size [m].
    :param ignore: line types that give no event.
    """

    def __init__(self, graph: LaneGraph, cell_m=10.0, ignore=UNMARKED_TYPES):
        self.cell_m = float(cell_m)
        self._segments: List[Tuple[float, float, float, float, int, str]] = []
        self._grid: Dict[Tuple[int, int], List[int]] = {}
        for boundary in graph.boundaries():
            if boundary.line_type in ignore:
                continue
            pts = boundary.points.tolist()
            for (ax, ay), (bx, by) in zip(pts[:-1], pts[1:]):
                self._add(ax, ay, bx, by, boundary.id, boundary.line_type)
        self._last = None

    def _add(self, ax, ay, bx, by, boundary_id, line_type):
        index = len(self._segments)
        self._segments.append((ax, ay, bx - ax, by - ay, boundary_id, line_type))
        length = math.hypot(bx - ax, by - ay)
        pieces = max(1, math.ceil(length / (0.5 * self.cell_m)))
        cells = set()
        size = self.cell_m
        for n in range(pieces):           # the cells each piece's bounding box overlaps
            x0, y0 = ax + n / pieces * (bx - ax), ay + n / pieces * (by - ay)
            x1, y1 = ax + (n + 1) / pieces * (bx - ax), ay + (n + 1) / pieces * (by - ay)
            for cx in range(math.floor(min(x0, x1) / size), math.floor(max(x0, x1) / size) + 1):
                for cy in range(math.floor(min(y0, y1) / size),
                                math.floor(max(y0, y1) / size) + 1):
                    cells.add((cx, cy))
        for cell in cells:
            self._grid.setdefault(cell, []).append(index)

    def reset(self):
        """Forget the previous position (after a teleport: a jump is not a crossing)."""
        self._last = None

    def update(self, x_m, y_m, time_s) -> Tuple[LaneInvasion, ...]:
        """Return the markings crossed since the previous update (usually none)."""
        last = self._last
        self._last = (x_m, y_m)
        if last is None or (last[0] == x_m and last[1] == y_m):
            return ()
        px, py = last
        rx, ry = x_m - px, y_m - py
        size = self.cell_m
        candidates = set()
        for cx in range(math.floor(min(px, x_m) / size), math.floor(max(px, x_m) / size) + 1):
            for cy in range(math.floor(min(py, y_m) / size),
                            math.floor(max(py, y_m) / size) + 1):
                candidates.update(self._grid.get((cx, cy), ()))
        events = {}
        for index in candidates:
            ax, ay, sx, sy, boundary_id, line_type = self._segments[index]
            denom = rx * sy - ry * sx
            if denom == 0.0 or boundary_id in events:
                continue
            qx, qy = ax - px, ay - py
            t = (qx * sy - qy * sx) / denom       # along the motion
            u = (qx * ry - qy * rx) / denom       # along the boundary segment
            if 0.0 < t <= 1.0 and 0.0 <= u < 1.0:
                events[boundary_id] = LaneInvasion(time_s, boundary_id, line_type,
                                                   px + t * rx, py + t * ry)
        return tuple(events.values())
