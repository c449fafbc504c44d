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
Per-vehicle lane state: which lane a vehicle is on, where along it, and how far off its centre.

:class:`LaneTracker` follows one vehicle from step to step. It keeps the vehicle on its lane while
the vehicle stays on it (so that overlapping lanes at an intersection do not flicker), moves it
to a successor past the lane's end, a predecessor before its start, or a neighbour across a
boundary, and only searches the whole map when none of those holds it. A step that stays on its
lane costs one projection on a segment or two of the centreline (docs/lanes.md has the figure).
"""

from dataclasses import dataclass
import math

from vehicle_sim.core.geometry.angles import wrap_angle_rad
from vehicle_sim.core.map.lane_graph import LaneGraph

_HALF_TURN = 0.5 * math.pi


@dataclass(frozen=True)
class LaneState:
    """
    A vehicle's lane state after a step (the ``<ns>/lane_state`` message's values).

    :param on_lane: the vehicle's reference point is on a lane; False: every other value 0.
    :param lane_id: the lane (lanelet) id; 0 when off every lane.
    :param s_m: arc length along the lane's centreline [m].
    :param offset_m: lateral offset from the centreline, + = left [m].
    :param heading_error_rad: vehicle yaw minus the lane's direction, in (-pi, pi] [rad].
    :param width_m: the lane's width there [m].
    :param speed_limit_mps: the lane's speed limit [m/s].
    """

    on_lane: bool
    lane_id: int
    s_m: float
    offset_m: float
    heading_error_rad: float
    width_m: float
    speed_limit_mps: float


OFF_LANE = LaneState(False, 0, 0.0, 0.0, 0.0, 0.0, 0.0)


class LaneTracker:
    """
    The lane state of one vehicle, updated each step from its pose.

    :param graph: the LaneGraph.
    """

    def __init__(self, graph: LaneGraph):
        self.graph = graph
        self._lane = None
        self._k = 0
        self.state = OFF_LANE

    def reset(self):
        """Forget the current lane (after a teleport: the next update searches the map)."""
        self._lane = None
        self._k = 0
        self.state = OFF_LANE

    def update(self, x_m, y_m, yaw_rad) -> LaneState:
        """Return (and keep in ``state``) the lane state at a pose (world x, y [m], yaw [rad])."""
        lane = self._lane
        if lane is not None:
            k, t, offset = lane.walk(x_m, y_m, self._k)
            fit = self._fit(lane, k, t, offset, yaw_rad)
            if fit is not None:
                return self._commit(lane, k, fit[1])
            best = None             # where lanes fork, the one the vehicle fits best
            for other, near_s in self._nearby(lane, k, t, offset):
                k, t, offset = other.walk(x_m, y_m, other.segment_at(near_s))
                fit = self._fit(other, k, t, offset, yaw_rad, turn_limit=_HALF_TURN)
                if fit is not None and (best is None or fit[0] < best[0]):
                    best = (fit[0], other, k, fit[1])
            if best is not None:
                return self._commit(best[1], best[2], best[3])
        found = self.graph.locate(x_m, y_m, yaw_rad)
        if found is None:
            self._lane = None
            self.state = OFF_LANE
            return OFF_LANE
        lane = self.graph.lanes[found.lane_id]
        self._lane = lane
        self._k = lane.segment_at(found.s_m)
        self.state = LaneState(True, found.lane_id, found.s_m, found.offset_m,
                               found.heading_error_rad, found.width_m, found.speed_limit_mps)
        return self.state

    def _commit(self, lane, k, state):
        self._lane, self._k, self.state = lane, k, state
        return state

    @staticmethod
    def _fit(lane, k, t, offset, yaw_rad, turn_limit=None):
        """Return (how badly it fits, LaneState) when the pose is on ``lane``, else None."""
        lengths = lane.seg_len
        if (k == 0 and t < -1e-6) or (k == len(lengths) - 1 and t > lengths[k] + 1e-6):
            return None
        tc = t if t <= lengths[k] else lengths[k]
        if tc < 0.0:
            tc = 0.0
        w0 = lane.widths[k]
        width = w0 + (lane.widths[k + 1] - w0) * (tc / lengths[k])
        if abs(offset) > 0.5 * width + 1e-6:
            return None
        heading = lane.vertex_headings[k] + lane.turns[k] * (tc / lengths[k])
        error = wrap_angle_rad(yaw_rad - heading)
        if turn_limit is not None and abs(error) > turn_limit:
            return None
        return (abs(offset) / max(width, 1e-6) + abs(error),     # a taper's end: width 0
                LaneState(True, lane.id, lane.s0[k] + tc, offset, error, width,
                          lane.speed_limit_mps))

    def _nearby(self, lane, k, t, offset):
        """Yield (lane, arc length to search from) for a vehicle leaving ``lane``."""
        lanes = self.graph.lanes
        if k == lane.segment_count - 1 and t > lane.seg_len[k]:
            for successor in lane.successors:
                yield lanes[successor], 0.0
        elif k == 0 and t < 0.0:
            for predecessor in self.graph.predecessors[lane.id]:
                yield lanes[predecessor], lanes[predecessor].length_m
        else:
            fraction = (lane.s0[k] + max(t, 0.0)) / lane.length_m
            side = lane.left_lane if offset > 0.0 else lane.right_lane
            if side is not None:
                yield lanes[side], fraction * lanes[side].length_m
