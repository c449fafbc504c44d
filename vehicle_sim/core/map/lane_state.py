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

The state also names the next stop line ahead (the lane map's rules, core/map/lane_rules.py):
the first on the lane beyond the vehicle, else on the lanes that follow it (the first
successor at a fork: the tracker does not know the vehicle's route), within
:data:`STOP_LINE_HORIZON_M` along the lanes; with its traffic light group and that group's state
when a signal controller is given (core/map/signal_plan.py). What lies beyond each lane's end is
looked up once per lane, so a step costs a look at the lines of the current lane.
"""

from dataclasses import dataclass
import math

from vehicle_sim.core.geometry.angles import wrap_angle_rad
from vehicle_sim.core.map.lane_graph import LaneGraph

_HALF_TURN = 0.5 * math.pi
# How far ahead along the lanes the next stop line is looked for [m].
STOP_LINE_HORIZON_M = 200.0
# A vehicle leaving a lane's end onto a successor that starts at an angle to it (a kink where
# two lanes join, as a SUMO network's junction lanes meet the lanes they lead to) crosses a
# wedge beyond the one lane's end and before the other's start, on the outside of the kink:
# up to this far before the successor's start it is on the successor, at s = 0 [m].
JOIN_M = 0.5
_UNKNOWN = object()


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
    :param stop_line_ahead: a stop line lies ahead within :data:`STOP_LINE_HORIZON_M` along the
        lanes; False: the stop line values below are 0 and ''.
    :param stop_line_id: the next stop line's id.
    :param stop_line_kind: its kind: 'traffic_light', 'stop_sign', 'yield' or 'road_marking'.
    :param stop_line_distance_m: from the vehicle's reference point (``s_m``) to the line,
        along the lanes [m] (0: on it).
    :param traffic_light_group_id: the group of a traffic light stop line; 0 for other kinds.
    :param signal_state: that group's state now ('red', 'yellow', 'green', 'off'); '' for other
        kinds, or when no signal controller runs.
    """

    on_lane: bool
    lane_id: int
    s_m: float
    offset_m: float
    heading_error_rad: float
    width_m: float
    speed_limit_mps: float
    stop_line_ahead: bool = False
    stop_line_id: int = 0
    stop_line_kind: str = ''
    stop_line_distance_m: float = 0.0
    traffic_light_group_id: int = 0
    signal_state: str = ''


OFF_LANE = LaneState(False, 0, 0.0, 0.0, 0.0, 0.0, 0.0)


class LaneTracker:
    """
    The lane state of one vehicle, updated each step from its pose.

    :param graph: the LaneGraph (its ``rules``: the stop lines and groups).
    :param signals: the world's SignalController (``state(group_id)``), or None: traffic light
        stop lines then have no ``signal_state``.
    :param horizon_m: how far ahead the next stop line is looked for [m].
    """

    def __init__(self, graph: LaneGraph, signals=None, horizon_m: float = STOP_LINE_HORIZON_M):
        self.graph = graph
        self.signals = signals
        self.horizon_m = horizon_m
        self._lane = None
        self._k = 0
        self._rules = None
        self._beyond = {}       # lane id -> (StopLine, distance from the lane's end) or None
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
                return self._commit(lane, k, *fit[1:])
            best = None             # where lanes fork, the one the vehicle fits best
            for other, near_s in self._nearby(lane, k, t, offset):
                k, t, offset = other.walk(x_m, y_m, other.segment_at(near_s))
                if near_s == 0.0 and k == 0 and -JOIN_M <= t < 0.0 and \
                        other.id in lane.successors:        # in the wedge of a kink
                    t = 0.0
                fit = self._fit(other, k, t, offset, yaw_rad, turn_limit=_HALF_TURN)
                if fit is not None and (best is None or fit[0] < best[0][0]):
                    best = (fit, other, k)
            if best is not None:
                fit, other, k = best
                return self._commit(other, k, *fit[1:])
        found = self.graph.locate(x_m, y_m, yaw_rad)
        if found is None:
            self._lane = None
            self.state = OFF_LANE
            return OFF_LANE
        lane = self.graph.lanes[found.lane_id]
        return self._commit(lane, lane.segment_at(found.s_m), found.s_m, found.offset_m,
                            found.heading_error_rad, found.width_m)

    def _commit(self, lane, k, s_m, offset_m, error_rad, width_m):
        self._lane, self._k = lane, k
        ahead = self._stop_line_ahead(lane, s_m) if self.graph.rules.stop_lines else None
        if ahead is None:
            state = LaneState(True, lane.id, s_m, offset_m, error_rad, width_m,
                              lane.speed_limit_mps)
        else:
            line, distance = ahead
            group_id = line.group_id if line.kind == 'traffic_light' else None
            signals = self.signals
            state = LaneState(
                True, lane.id, s_m, offset_m, error_rad, width_m, lane.speed_limit_mps, True,
                line.id, line.kind, distance, 0 if group_id is None else group_id,
                '' if group_id is None or signals is None else signals.state(group_id))
        self.state = state
        return state

    def _stop_line_ahead(self, lane, s_m):
        """Return (StopLine, distance along the lanes) of the next line ahead, or None."""
        rules = self.graph.rules
        if rules is not self._rules:            # the map's rules changed: forget the lookups
            self._rules, self._beyond = rules, {}
        horizon = self.horizon_m
        for line in rules.stop_lines_on(lane.id):
            if line.s_m >= s_m:
                distance = line.s_m - s_m
                return (line, distance) if distance <= horizon else None
        beyond = self._beyond.get(lane.id, _UNKNOWN)
        if beyond is _UNKNOWN:
            # the first line from the lane's end on, within the horizon from there: the first
            # from anywhere on the lane (a nearer one would be on the lane or first after it)
            beyond = self._beyond[lane.id] = rules.next_stop_line(
                self.graph, lane.id, lane.length_m, horizon)
        if beyond is None:
            return None
        line, distance = beyond
        distance += lane.length_m - s_m
        return (line, distance) if distance <= horizon else None

    @staticmethod
    def _fit(lane, k, t, offset, yaw_rad, turn_limit=None):
        """Return (how badly it fits, s, offset, heading error, width) on ``lane``, or None."""
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
        # a taper's end has width 0
        return (abs(offset) / max(width, 1e-6) + abs(error), lane.s0[k] + tc, offset, error,
                width)

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
