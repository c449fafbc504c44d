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
The lane graph: lanes with centrelines, boundaries, widths, speed limits and their neighbours.

A :class:`Lane` is one lanelet: a centreline polyline (its direction is the direction of
travel), a left and a right :class:`Boundary` (a polyline with a line type: solid, dashed,
curbstone, ...), the lane's width along it, a speed limit, its successors and its left and right
neighbours of the same direction (with whether a lane change onto them is allowed).
:class:`LaneGraph` holds the lanes (and ``rules``: the map's stop lines, signals, right of way,
conflicts and areas, core/map/lane_rules.py) and answers the two queries everything else needs:

- :meth:`LaneGraph.locate`: which lane a point is on, and where: the arc length ``s`` along
  the centreline, the lateral offset (+ = left of the centreline, REP 103), the heading error
  of a yaw against the lane's direction, the lane's width and speed limit there;
- :meth:`LaneGraph.pose_at`: the pose (x, y, yaw) at ``s`` and ``offset`` on a lane.

A point is on a lane when it lies between the lane's ends and within half the lane's width of
its centreline; where lanes overlap (intersections) the lane the vehicle's heading fits best
wins, and :class:`~vehicle_sim.core.map.lane_state.LaneTracker` keeps a vehicle on its lane
while it stays on it. Coordinates are world metres (x east, y north).
"""

import bisect
from dataclasses import dataclass
import math
from typing import Dict, Optional, Sequence, Tuple

import numpy as np

from vehicle_sim.core.geometry.angles import wrap_angle_rad
from vehicle_sim.core.map.lane_rules import LaneRules
from vehicle_sim.core.specs.errors import InvalidParameterError

# Line types of lane boundaries. The two-part types read as seen along the line: 'dashed_solid'
# is dashed on its left side, solid on its right side (Lanelet2's subtypes of line_thin).
LINE_TYPES = ('solid', 'dashed', 'solid_solid', 'dashed_solid', 'solid_dashed', 'dashed_dashed',
              'curbstone', 'road_border', 'wall', 'virtual', 'none')
# Lines that mark nothing to cross: no lane invasion is reported for them.
UNMARKED_TYPES = ('virtual', 'none')
# Lines that may not be crossed from either side (the stay_in_lane criterion's "solid lines");
# the mixed types count as solid here too, whichever side the vehicle came from.
SOLID_TYPES = ('solid', 'solid_solid', 'dashed_solid', 'solid_dashed', 'curbstone',
               'road_border', 'wall')

_ON_LINE_M = 1e-6
# LaneGraph.locate looks only at the segments near a point: those whose reach meets the point's
# cell of a grid this fine [m] (a city of 8 000 segments: some 40 in a cell).
LOCATE_CELL_M = 16.0
# What a segment's reach adds to half its widest width: the on-line tolerance and more, so
# that rounding cannot leave out a segment whose lane holds the point [m].
_REACH_SLACK_M = 1e-3
# Lane subtypes the traffic drives on (Lanelet2's lanelet subtypes; roads: 'road').
TRAFFIC_SUBTYPES = ('road', 'highway')


def line_crossable(line_type, from_left_side):
    """
    Return whether a lane change across a line of ``line_type`` is allowed.

    :param line_type: one of :data:`LINE_TYPES`.
    :param from_left_side: the vehicle is on the line's left (seen along the line).
    """
    if line_type in ('dashed', 'dashed_dashed', 'virtual', 'none'):
        return True
    if line_type == 'dashed_solid':
        return from_left_side
    if line_type == 'solid_dashed':
        return not from_left_side
    return False


def _points(data, what):
    points = np.asarray(data, dtype=float)
    if points.ndim != 2 or points.shape[1] < 2 or len(points) < 2:
        raise InvalidParameterError(f'{what}: needs at least 2 points [x, y]')
    points = points[:, :2]
    if not np.all(np.isfinite(points)):
        raise InvalidParameterError(f'{what}: every coordinate must be finite')
    keep = np.ones(len(points), dtype=bool)         # drop repeated points
    keep[1:] = np.hypot(*np.diff(points, axis=0).T) > 1e-9
    points = points[keep]
    if len(points) < 2:
        raise InvalidParameterError(f'{what}: its points must not all coincide')
    return points


@dataclass(frozen=True, eq=False)
class Boundary:
    """A lane boundary: an id (shared by the two lanes it separates), a polyline, a line type."""

    id: int
    points: np.ndarray
    line_type: str

    def __post_init__(self):
        if self.line_type not in LINE_TYPES:
            raise InvalidParameterError(f'boundary {self.id}: line type {self.line_type!r} is '
                                        f'not one of {", ".join(LINE_TYPES)}')
        object.__setattr__(self, 'points', _points(self.points, f'boundary {self.id}'))


def distances_to_polyline(points, polyline):
    """Return the distance of each point (M, 2) to a polyline (N, 2) [m] (numpy)."""
    a = polyline[:-1][None, :, :]
    d = np.diff(polyline, axis=0)[None, :, :]
    length2 = np.maximum((d * d).sum(axis=2), 1e-18)
    rel = points[:, None, :] - a
    t = np.clip((rel * d).sum(axis=2) / length2, 0.0, 1.0)
    gap = rel - t[:, :, None] * d
    return np.sqrt((gap * gap).sum(axis=2)).min(axis=1)


class Lane:
    """
    One lane: its centreline (direction of travel), boundaries, widths, limit and neighbours.

    :param lane_id: the lane's id (a lanelet's id).
    :param centerline: (N, 2) points [m], N >= 2.
    :param left: the left Boundary.
    :param right: the right Boundary.
    :param speed_limit_mps: the speed limit [m/s].
    :param successors: ids of the lanes that follow it.
    :param left_lane: id of the same-direction lane on its left; None = none.
    :param right_lane: id of the same-direction lane on its right; None = none.
    :param left_change: a lane change onto ``left_lane`` is allowed.
    :param right_change: a lane change onto ``right_lane`` is allowed.
    :param widths: the width at each centreline point [m]; None = measured between the
        boundaries. A width may be 0 at points (a taper, where the bounds meet at a merge), not
        everywhere.
    :param name: a readable name ('' = none).
    :param subtype: what the lane is for, as Lanelet2's lanelet subtypes say: 'road' (the
        default), 'highway', 'road_shoulder', 'bicycle_lane', 'exit', 'play_street', ...
        (:data:`TRAFFIC_SUBTYPES`: the ones traffic drives).
    """

    def __init__(self, lane_id, centerline, left, right, speed_limit_mps, successors=(),
                 left_lane=None, right_lane=None, left_change=False, right_change=False,
                 widths=None, name='', subtype='road'):
        self.id = int(lane_id)
        self.centerline = _points(centerline, f'lane {lane_id}: centerline')
        self.left = left
        self.right = right
        if not (isinstance(speed_limit_mps, (int, float)) and math.isfinite(speed_limit_mps)
                and speed_limit_mps > 0.0):
            raise InvalidParameterError(f'lane {lane_id}: speed limit {speed_limit_mps!r} must '
                                        f'be a finite number > 0 [m/s]')
        self.speed_limit_mps = float(speed_limit_mps)
        self.successors = tuple(int(s) for s in successors)
        self.left_lane = None if left_lane is None else int(left_lane)
        self.right_lane = None if right_lane is None else int(right_lane)
        self.left_change = bool(left_change) and self.left_lane is not None
        self.right_change = bool(right_change) and self.right_lane is not None
        self.name = name
        self.subtype = str(subtype)
        pts = self.centerline
        if widths is None:
            widths = (distances_to_polyline(pts, left.points)
                      + distances_to_polyline(pts, right.points))
        widths = np.broadcast_to(np.asarray(widths, dtype=float), (len(pts),))
        if not np.all(np.isfinite(widths)) or np.any(widths < 0.0):
            raise InvalidParameterError(f'lane {lane_id}: its width must be >= 0 and finite '
                                        f'everywhere')
        if not np.any(widths > 0.0):
            raise InvalidParameterError(f'lane {lane_id}: its width must be > 0 somewhere (its '
                                        f'bounds coincide)')
        seg = np.diff(pts, axis=0)
        lengths = np.hypot(seg[:, 0], seg[:, 1])
        # plain lists: the per-step walk reads single values, faster from lists than arrays
        self.xs = pts[:, 0].tolist()
        self.ys = pts[:, 1].tolist()
        self.ux = (seg[:, 0] / lengths).tolist()
        self.uy = (seg[:, 1] / lengths).tolist()
        self.seg_len = lengths.tolist()
        self.s0 = np.concatenate(([0.0], np.cumsum(lengths)[:-1])).tolist()
        self.widths = widths.tolist()
        self.length_m = float(lengths.sum())
        headings = np.arctan2(seg[:, 1], seg[:, 0])
        self.headings = headings.tolist()
        # the direction at each point: its segments' mean (the ends: their segment's), so that
        # the heading along the lane is continuous and within O(turn^2) of a smooth curve's
        turns = np.angle(np.exp(1j * np.diff(headings)))
        vertex = np.concatenate(([headings[0]], headings[:-1] + 0.5 * turns, [headings[-1]]))
        self.vertex_headings = vertex.tolist()
        self.turns = np.angle(np.exp(1j * np.diff(vertex))).tolist()

    @property
    def segment_count(self):
        return len(self.seg_len)

    def segment_at(self, s_m):
        """Return the index of the centreline segment that holds arc length ``s_m``."""
        k = bisect.bisect_right(self.s0, s_m) - 1
        return min(max(k, 0), len(self.seg_len) - 1)

    def width_at(self, k, t_m):
        """Return the width [m] at ``t_m`` along segment ``k``."""
        w0, w1 = self.widths[k], self.widths[k + 1]
        return w0 + (w1 - w0) * min(max(t_m / self.seg_len[k], 0.0), 1.0)

    def heading_at(self, k, t_m):
        """Return the lane's direction [rad] at ``t_m`` along segment ``k`` (interpolated)."""
        return self.vertex_headings[k] + self.turns[k] * min(max(t_m / self.seg_len[k], 0.0),
                                                             1.0)

    def centre_pose(self, s_m):
        """
        Return the centreline pose (x, y, yaw) at arc length ``s_m``, unchecked.

        The hot path of predictions that walk along lanes and keep ``s_m`` in [0, length]
        themselves; :meth:`LaneGraph.pose_at` checks its arguments and gives the same pose.
        """
        # segment_at and heading_at written out: the same arithmetic
        s0 = self.s0
        k = bisect.bisect_right(s0, s_m) - 1
        last = len(s0) - 1
        k = 0 if k < 0 else (last if k > last else k)
        t = s_m - s0[k]
        f = t / self.seg_len[k]
        f = 0.0 if f < 0.0 else (1.0 if f > 1.0 else f)
        yaw = self.vertex_headings[k] + self.turns[k] * f
        return (self.xs[k] + self.ux[k] * t, self.ys[k] + self.uy[k] * t,
                wrap_angle_rad(yaw))

    def walk(self, x, y, k):
        """
        Project a point on the centreline, walking from segment ``k`` to the nearest one.

        The walk goes one way only (forwards while the point lies beyond a segment's end,
        backwards while before its start), so it stops on the outside of a bend too.

        :return: (segment index, distance along it (unclamped) [m], signed offset [m]).
        """
        xs, ys, ux, uy, lengths = self.xs, self.ys, self.ux, self.uy, self.seg_len
        last = len(lengths) - 1
        step = 0
        while True:
            dx, dy = x - xs[k], y - ys[k]
            t = dx * ux[k] + dy * uy[k]
            if t > lengths[k] and k < last and step >= 0:
                k, step = k + 1, 1
            elif t < 0.0 and k > 0 and step <= 0:
                k, step = k - 1, -1
            else:
                return k, t, ux[k] * dy - uy[k] * dx

    def position(self, k, t_m, offset_m, yaw_rad=None):
        """Return the LanePosition of a walk's result (``yaw_rad`` None: heading error 0)."""
        t = min(max(t_m, 0.0), self.seg_len[k])
        error = 0.0 if yaw_rad is None else wrap_angle_rad(yaw_rad - self.heading_at(k, t))
        return LanePosition(self.id, self.s0[k] + t, offset_m, error, self.width_at(k, t),
                            self.speed_limit_mps)


@dataclass(frozen=True)
class LanePosition:
    """
    Where a point is on a lane.

    :param lane_id: the lane (lanelet) id.
    :param s_m: arc length along the centreline from its start [m].
    :param offset_m: lateral offset from the centreline, + = left [m].
    :param heading_error_rad: yaw minus the lane's direction there, in (-pi, pi] [rad].
    :param width_m: the lane's width there [m].
    :param speed_limit_mps: the lane's speed limit [m/s].
    """

    lane_id: int
    s_m: float
    offset_m: float
    heading_error_rad: float
    width_m: float
    speed_limit_mps: float


class LaneGraph:
    """
    The lanes of a map, checked for consistency, and the queries on them.

    :param lanes: the Lane objects (ids unique; successors and neighbours name lanes of it).
    :param source: what the lanes come from (a file, 'roads'), quoted in errors.
    :raises InvalidParameterError: an id used twice, a reference to a missing lane, no lane.
    """

    def __init__(self, lanes: Sequence[Lane], source='lane map'):
        self.source = source
        if not lanes:
            raise InvalidParameterError(f'{source}: has no lanes')
        self.lanes: Dict[int, Lane] = {}
        for lane in lanes:
            if lane.id in self.lanes:
                raise InvalidParameterError(f'{source}: lane id {lane.id} is used twice')
            self.lanes[lane.id] = lane
        self.predecessors: Dict[int, Tuple[int, ...]] = {i: () for i in self.lanes}
        for lane in lanes:
            for ref, what in [(s, 'successor') for s in lane.successors] + [
                    (lane.left_lane, 'left lane'), (lane.right_lane, 'right lane')]:
                if ref is not None and ref not in self.lanes:
                    raise InvalidParameterError(f'{source}: lane {lane.id}: {what} {ref} is '
                                                f'not in the map')
            for successor in lane.successors:
                self.predecessors[successor] += (lane.id,)
        self._index_segments()
        self._names = None
        self.rules = LaneRules()

    def set_rules(self, rules: LaneRules):
        """Attach the map's rules (core/map/lane_rules.py), checked against the lanes."""
        rules.check(self, self.source)
        self.rules = rules

    def _index_segments(self):
        lanes = list(self.lanes.values())
        self._lane_of_segment = np.concatenate(
            [np.full(lane.segment_count, i) for i, lane in enumerate(lanes)])
        self._lane_list = lanes
        self._seg = np.concatenate([np.arange(lane.segment_count) for lane in lanes])
        cat = np.concatenate
        self._ax = cat([lane.xs[:-1] for lane in lanes])
        self._ay = cat([lane.ys[:-1] for lane in lanes])
        self._ux = cat([lane.ux for lane in lanes])
        self._uy = cat([lane.uy for lane in lanes])
        self._len = cat([lane.seg_len for lane in lanes])
        self._w0 = cat([lane.widths[:-1] for lane in lanes])
        self._w1 = cat([lane.widths[1:] for lane in lanes])
        self._heading = cat([lane.headings for lane in lanes])
        self._first = self._seg == 0
        self._last = self._seg == cat([np.full(lane.segment_count, lane.segment_count - 1)
                                       for lane in lanes])
        # The grid of LOCATE_CELL_M cells: cell -> the segments whose reach (the points within
        # half their widest width of them, and the tolerance) meets it, ascending.
        reach = 0.5 * np.maximum(self._w0, self._w1) + _REACH_SLACK_M
        bx, by = self._ax + self._ux * self._len, self._ay + self._uy * self._len
        low_i = np.floor((np.minimum(self._ax, bx) - reach) / LOCATE_CELL_M)
        high_i = np.floor((np.maximum(self._ax, bx) + reach) / LOCATE_CELL_M)
        low_j = np.floor((np.minimum(self._ay, by) - reach) / LOCATE_CELL_M)
        high_j = np.floor((np.maximum(self._ay, by) + reach) / LOCATE_CELL_M)
        cells: Dict[Tuple[int, int], list] = {}
        boxes = np.column_stack((low_i, high_i, low_j, high_j))
        if np.all(np.isfinite(boxes)):
            for index, (i0, i1, j0, j1) in enumerate(boxes.astype(np.int64).tolist()):
                for i in range(i0, i1 + 1):
                    for j in range(j0, j1 + 1):
                        cells.setdefault((i, j), []).append(index)
            self._cells = {key: np.array(found, dtype=np.int64) for key, found in cells.items()}
        else:
            self._cells = None          # (a lane with a non-finite point: every segment looked at)
        self._cell_arrays = {}

    def lane(self, lane_id) -> Lane:
        """Return a lane by id; InvalidParameterError naming the id when there is none."""
        lane = self.lanes.get(lane_id) if isinstance(lane_id, int) and \
            not isinstance(lane_id, bool) else None
        if lane is None:
            raise InvalidParameterError(f'{self.source}: lane {lane_id!r} is not in the map')
        return lane

    def lane_named(self, name) -> Lane:
        """
        Return the lane of a name (``Lane.name``: a SUMO lane id, a lanelet's id as text).

        :raises InvalidParameterError: no lane or more than one has that name (a two-way
            lanelet's two lanes share theirs: give the id).
        """
        if self._names is None:
            names: Dict[str, list] = {}
            for lane in self.lanes.values():
                names.setdefault(lane.name, []).append(lane.id)
            self._names = names
        found = self._names.get(name, []) if isinstance(name, str) else []
        if len(found) != 1:
            what = 'is not in the map' if not found else \
                f'names {len(found)} lanes ({", ".join(map(str, found))}): give the id'
            raise InvalidParameterError(f'{self.source}: lane named {name!r} {what}')
        return self.lanes[found[0]]

    def boundaries(self):
        """Return every boundary once (shared ones by id), in lane order."""
        seen = {}
        for lane in self.lanes.values():
            for boundary in (lane.left, lane.right):
                seen.setdefault(boundary.id, boundary)
        return tuple(seen.values())

    def locate(self, x_m, y_m, yaw_rad=None) -> Optional[LanePosition]:
        """
        Return where a point is on the lanes, or None when it is on none.

        Among the lanes the point is on, the one whose direction is nearest ``yaw_rad`` (when
        given) wins, then the one whose centreline is nearest relative to its width.
        """
        found = self._segments_near(x_m, y_m)
        if found is None:
            return None
        index, ax, ay, ux, uy, length, w0, w1, heading, first, last = found
        dx = x_m - ax
        dy = y_m - ay
        t = dx * ux + dy * uy
        tc = np.clip(t, 0.0, length)
        gx, gy = dx - tc * ux, dy - tc * uy
        dist = np.sqrt(gx * gx + gy * gy)
        half = 0.5 * (w0 + (w1 - w0) * (tc / length))
        inside = (dist <= half + _ON_LINE_M) & ~(first & (t < -_ON_LINE_M)) \
            & ~(last & (t > length + _ON_LINE_M))
        candidates = np.flatnonzero(inside)
        if not len(candidates):
            return None
        # a taper's zero-width end: a point on it scores 0 (on the centreline), not 0 / 0
        score = dist[candidates] / np.maximum(half[candidates], _ON_LINE_M)
        if yaw_rad is not None:
            turn = np.abs(np.angle(np.exp(1j * (yaw_rad - heading[candidates]))))
            score = score + 4.0 * turn / math.pi
        best = index[candidates[int(np.argmin(score))]]
        lane = self._lane_list[int(self._lane_of_segment[best])]
        k = int(self._seg[best])
        k, t_k, offset = lane.walk(x_m, y_m, k)
        return lane.position(k, t_k, offset, yaw_rad)

    def _segments_near(self, x_m, y_m):
        """
        Return the segments that may hold a point, as arrays (their indices first), or None.

        The segments of the point's grid cell (all of them for a map with a point that is not
        finite; None for such a point); each array in ascending segment order, as over the
        whole map, so the same segment wins a tie. A cell's arrays are cut out once, when first
        asked for.
        """
        if not (math.isfinite(x_m) and math.isfinite(y_m)):
            return None                 # on no lane (over the whole map too)
        if self._cells is None:
            key = None
        else:
            key = (math.floor(x_m / LOCATE_CELL_M), math.floor(y_m / LOCATE_CELL_M))
            if key not in self._cells:
                return None
        found = self._cell_arrays.get(key)
        if found is None:
            index = (np.arange(len(self._ax)) if key is None else self._cells[key])
            found = self._cell_arrays[key] = (index,) + tuple(
                values[index] for values in (self._ax, self._ay, self._ux, self._uy, self._len,
                                             self._w0, self._w1, self._heading, self._first,
                                             self._last))
        return found

    def locate_on(self, lane_id, x_m, y_m, yaw_rad=None, near_s_m=None):
        """
        Return where a point is relative to one lane's centreline, on it or not.

        :param near_s_m: start the search at this arc length (None = the lane's start).
        :return: (LanePosition, on the lane: bool).
        """
        lane = self.lane(lane_id)
        k = 0 if near_s_m is None else lane.segment_at(near_s_m)
        k, t, offset = lane.walk(x_m, y_m, k)
        return lane.position(k, t, offset, yaw_rad), self._within(lane, k, t, offset)

    @staticmethod
    def _within(lane, k, t, offset):
        if (k == 0 and t < -_ON_LINE_M) or \
                (k == lane.segment_count - 1 and t > lane.seg_len[k] + _ON_LINE_M):
            return False
        return abs(offset) <= 0.5 * lane.width_at(k, t) + _ON_LINE_M

    def pose_at(self, lane_id, s_m, offset_m=0.0):
        """
        Return the pose (x, y, yaw) at arc length ``s_m`` and lateral ``offset_m`` on a lane.

        :raises InvalidParameterError: unknown lane, ``s_m`` outside [0, length], or an offset
            beyond half the lane's width there (off the lane).
        """
        lane = self.lane(lane_id)
        if not (math.isfinite(s_m) and 0.0 <= s_m <= lane.length_m):
            raise InvalidParameterError(f'{self.source}: lane {lane_id}: s = {s_m!r} m is not '
                                        f'on it (0 .. {lane.length_m:.3f} m)')
        k = lane.segment_at(s_m)
        t = s_m - lane.s0[k]
        half = 0.5 * lane.width_at(k, t)
        if not (math.isfinite(offset_m) and abs(offset_m) <= half):
            raise InvalidParameterError(f'{self.source}: lane {lane_id}: offset = {offset_m!r} '
                                        f'm is off the lane (|offset| <= {half:.3f} m there)')
        ux, uy = lane.ux[k], lane.uy[k]
        return (lane.xs[k] + ux * t - uy * offset_m, lane.ys[k] + uy * t + ux * offset_m,
                wrap_angle_rad(lane.heading_at(k, t)))
