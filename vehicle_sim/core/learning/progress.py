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
How far a vehicle got: along a path, toward a goal, or along its own heading.

Each measure is a small object with ``start(x, y, yaw)`` (at a reset) and ``advance(x, y,
yaw)`` (after a step), which returns the progress of that step [m]; positive is forward.

- :class:`PathProgress`: the arc length of the vehicle's projection on a polyline (the nearest
  point of the path); the step's progress is the change of that arc length. Its lateral
  distance from the path is kept as ``lateral_m``.
- :class:`GoalProgress`: the decrease of the straight-line distance to a goal point.
- :class:`HeadingProgress`: the displacement projected on the heading at the step's start
  (distance driven forward; reversing counts negative).
- :class:`LaneProgress`: the distance along the lanes of a lane map (core/map/lane_travel.py),
  from lane states (core/map/lane_state.py) rather than poses: ``start(state)`` and
  ``advance(state)``.
"""

import math

import numpy as np

from vehicle_sim.core.map.lane_travel import lane_distance
from vehicle_sim.core.specs.errors import InvalidParameterError


class PathProgress:
    """
    Progress along a polyline [[x, y], ...] (at least two distinct points) [m].

    :param points: the path's vertices in order [m].
    :raises InvalidParameterError: for fewer than two points, a non-finite value or a path of
        zero length.
    """

    def __init__(self, points):
        array = np.asarray(points, dtype=float)
        if array.ndim != 2 or array.shape[1] != 2 or len(array) < 2:
            raise InvalidParameterError(f'path: give at least two [x, y] points, got '
                                        f'{array.shape[0] if array.ndim else 0} of shape '
                                        f'{array.shape[1:] if array.ndim == 2 else array.shape}')
        if not np.all(np.isfinite(array)):
            raise InvalidParameterError('path: every coordinate must be finite')
        self.points = array
        self._starts = array[:-1]
        self._deltas = array[1:] - array[:-1]
        lengths = np.hypot(self._deltas[:, 0], self._deltas[:, 1])
        if not lengths.sum() > 0.0:
            raise InvalidParameterError('path: its points are all the same; it has no length')
        self._squared = np.maximum(lengths * lengths, 1e-300)
        self._offsets = np.concatenate(([0.0], np.cumsum(lengths)[:-1]))
        self._lengths = lengths
        self.length_m = float(lengths.sum())
        self.arc_m = 0.0
        self.lateral_m = 0.0

    def project(self, x_m, y_m):
        """
        Return (arc length [m], lateral distance [m]) of the nearest point of the path.

        Ties between segments go to the first one (the path's order).
        """
        rel = np.array((x_m, y_m)) - self._starts
        t = np.clip((rel * self._deltas).sum(axis=1) / self._squared, 0.0, 1.0)
        nearest = self._starts + self._deltas * t[:, None]
        gap = np.array((x_m, y_m)) - nearest
        distances = np.hypot(gap[:, 0], gap[:, 1])
        index = int(np.argmin(distances))
        return (float(self._offsets[index] + t[index] * self._lengths[index]),
                float(distances[index]))

    def start(self, x_m, y_m, yaw_rad=0.0):
        self.arc_m, self.lateral_m = self.project(x_m, y_m)

    def advance(self, x_m, y_m, yaw_rad=0.0):
        arc_m, self.lateral_m = self.project(x_m, y_m)
        progress, self.arc_m = arc_m - self.arc_m, arc_m
        return progress

    @property
    def done(self):
        """True once the projection is at the path's end."""
        return self.arc_m >= self.length_m - 1e-9


class GoalProgress:
    """
    Progress toward a goal point: how much closer a step brought the vehicle [m].

    :param goal: (x, y) of the goal [m].
    :param radius_m: the goal region's radius [m]: ``reached`` inside it.
    """

    def __init__(self, goal, radius_m):
        gx, gy = (float(v) for v in goal)
        if not (math.isfinite(gx) and math.isfinite(gy)):
            raise InvalidParameterError(f'goal = {goal!r}: must be two finite numbers')
        if not radius_m > 0.0:
            raise InvalidParameterError(f'goal radius = {radius_m!r}: must be > 0 m')
        self.goal = (gx, gy)
        self.radius_m = float(radius_m)
        self.distance_m = math.inf

    def _distance(self, x_m, y_m):
        return math.hypot(x_m - self.goal[0], y_m - self.goal[1])

    def start(self, x_m, y_m, yaw_rad=0.0):
        self.distance_m = self._distance(x_m, y_m)

    def advance(self, x_m, y_m, yaw_rad=0.0):
        distance = self._distance(x_m, y_m)
        progress, self.distance_m = self.distance_m - distance, distance
        return progress

    @property
    def done(self):
        """True while the vehicle is inside the goal region."""
        return self.distance_m <= self.radius_m


class HeadingProgress:
    """Progress as the displacement along the heading at the step's start [m]."""

    def __init__(self):
        self._last = (0.0, 0.0, 0.0)

    def start(self, x_m, y_m, yaw_rad):
        self._last = (x_m, y_m, yaw_rad)

    def advance(self, x_m, y_m, yaw_rad):
        x0, y0, yaw0 = self._last
        self._last = (x_m, y_m, yaw_rad)
        return (x_m - x0) * math.cos(yaw0) + (y_m - y0) * math.sin(yaw0)

    done = False


class LaneProgress:
    """
    Progress along the lanes of a map [m]: the change of s along the route, following successors.

    Fed with the vehicle's LaneState after each step (a LaneTracker's). A step that ends off
    every lane makes no progress; the last position on a lane is kept, so that coming back onto
    the lane (the same one, a successor, a predecessor or a neighbour) counts the distance
    along the lanes since then. A step onto a lane not linked to that position (a jump across
    the road, onto the opposite direction) makes no progress and starts counting afresh there.

    :param graph: the LaneGraph.
    """

    def __init__(self, graph):
        self.graph = graph
        self._last = None           # (lane id, s [m]) of the last state on a lane

    def start(self, state):
        self._last = (state.lane_id, state.s_m) if state.on_lane else None

    def advance(self, state):
        if not state.on_lane:
            return 0.0
        last, self._last = self._last, (state.lane_id, state.s_m)
        if last is None:
            return 0.0
        distance = lane_distance(self.graph, last[0], last[1], state.lane_id, state.s_m)
        return 0.0 if distance is None else distance

    done = False
