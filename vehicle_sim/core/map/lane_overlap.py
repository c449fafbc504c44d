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
Where lanes overlap a lane or a polygon: a conflict's arc-length range, a crosswalk's lanes.

Both sample a lane's centreline every :data:`SAMPLE_M` (and at its ends):

- :func:`overlap_range`: the part of one lane where a vehicle on its centreline, as wide as the
  lane, touches the other lane's area: the centreline point lies within half of both widths of
  the other lane's centreline, between the other lane's ends;
- :func:`lanes_through`: the lanes whose centreline passes through a polygon (a lane that
  only touches it with an end does not).
"""

import math

import numpy as np

SAMPLE_M = 0.5


def _samples(lane):
    count = max(2, int(math.ceil(lane.length_m / SAMPLE_M)) + 1)
    return np.linspace(0.0, lane.length_m, count)


def overlap_range(graph, lane_id, other_id):
    """
    Return (first, last) arc length [m] on lane ``lane_id`` where it overlaps ``other_id``.

    :return: the range, or None where the lanes' areas do not overlap.
    """
    lane, other = graph.lanes[lane_id], graph.lanes[other_id]
    last = other.segment_count - 1
    inside = []
    k = 0
    for s_m in _samples(lane):
        x, y, _ = lane.centre_pose(s_m)
        k, t, offset = other.walk(x, y, k)
        if (k == 0 and t < 0.0) or (k == last and t > other.seg_len[k]):
            continue
        j = lane.segment_at(s_m)
        reach = 0.5 * other.width_at(k, t) + 0.5 * lane.width_at(j, s_m - lane.s0[j])
        if abs(offset) <= reach:
            inside.append(float(s_m))
    return (inside[0], inside[-1]) if inside else None


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
