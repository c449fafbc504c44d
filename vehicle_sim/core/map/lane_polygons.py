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
The lanes that pass through a polygon (a crosswalk's lanes): :func:`lanes_through`.

A lane passes through a polygon when a point of its centreline, sampled every
:data:`SAMPLE_M`, lies inside it (its end points left out: a lane that only touches the polygon
with an end does not pass through it). Lanes that overlap each other: core/map/lane_conflicts.py.
"""

import math

import numpy as np

SAMPLE_M = 0.5


def _samples(lane):
    count = max(2, int(math.ceil(lane.length_m / SAMPLE_M)) + 1)
    return np.linspace(0.0, lane.length_m, count)


def _contains(polygon, points):
    """Return which points (M, 2) lie inside a polygon (N, 2) (even-odd rule)."""
    x, y = points[:, 0][:, None], points[:, 1][:, None]
    x0, y0 = polygon[:, 0][None, :], polygon[:, 1][None, :]
    x1, y1 = np.roll(polygon[:, 0], -1)[None, :], np.roll(polygon[:, 1], -1)[None, :]
    crosses = (y0 > y) != (y1 > y)
    with np.errstate(divide='ignore', invalid='ignore'):
        at_x = x0 + (y - y0) * (x1 - x0) / (y1 - y0)
    return np.logical_xor.reduce(crosses & (x < at_x), axis=1)


def lanes_through(graph, polygon):
    """Return the ids of the lanes whose centreline passes through a polygon (N, 2) [m], sorted."""
    polygon = np.asarray(polygon, dtype=float)[:, :2]
    low, high = polygon.min(axis=0), polygon.max(axis=0)
    found = []
    for lane in graph.lanes.values():
        xs, ys = np.asarray(lane.xs), np.asarray(lane.ys)
        if xs.max() < low[0] or xs.min() > high[0] or ys.max() < low[1] or ys.min() > high[1]:
            continue
        points = np.array([lane.centre_pose(s)[:2] for s in _samples(lane)[1:-1]])
        if len(points) and _contains(polygon, points).any():
            found.append(lane.id)
    return tuple(sorted(found))
