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
Where two traffic vehicles' footprints can overlap on a lane map, sampled along the lanes.

A lane map's conflicts (``LaneRules.conflicts``) are where the lanes' *areas* overlap. A vehicle
is a rectangle centred on its lane's centreline along its heading, and in a tight turn its
corners swing out of its lane's area (a 4.5 m car on a 4 m radius cuts a corner by some 0.5 m;
near the end of a turn its front or rear sticks out along the tangent). :func:`footprint_overlaps`
finds the lane ranges where footprints of the largest traffic vehicle (inflated by a margin)
overlap: it samples each lane's centre poses every ``step_m`` (as the traffic manager places its
vehicles), hashes them on a grid, and tests the rectangles of nearby samples of different lanes
by separating axes (numpy, all pairs at once).
"""

import math
from typing import Dict, Iterable, Tuple

import numpy as np


def _rectangles(x, y, yaw, length, width):
    """Return the corners (P, 4, 2) of rectangles centred at (x, y) along ``yaw``."""
    c, s = np.cos(yaw), np.sin(yaw)
    u = 0.5 * np.asarray(length, dtype=float)
    v = 0.5 * np.asarray(width, dtype=float)
    return np.stack([np.stack([x + c * (su * u) - s * (sv * v), y + s * (su * u) + c * (sv * v)],
                              axis=-1)
                     for su, sv in ((1, 1), (-1, 1), (-1, -1), (1, -1))], axis=1)


def _overlap(a, b):
    """Return which pairs of rectangles (P, 4, 2) overlap (separating axis test)."""
    hit = np.ones(len(a), dtype=bool)
    for poly in (a, b):
        for k in (0, 1):
            edge = poly[:, k + 1] - poly[:, k]
            axis = np.stack([-edge[:, 1], edge[:, 0]], axis=1)[:, None, :]
            pa, pb = (a * axis).sum(axis=2), (b * axis).sum(axis=2)
            hit &= (pa.max(axis=1) > pb.min(axis=1)) & (pb.max(axis=1) > pa.min(axis=1))
    return hit


def _near_pairs(x, y, cell):
    """Return index arrays (a, b), a != b, of the points in the same or neighbouring cells."""
    ix, iy = np.floor(x / cell).astype(np.int64), np.floor(y / cell).astype(np.int64)
    by_cell: Dict[Tuple[int, int], list] = {}
    for index, key in enumerate(zip(ix.tolist(), iy.tolist())):
        by_cell.setdefault(key, []).append(index)
    firsts, seconds = [np.zeros(0, dtype=np.int64)], [np.zeros(0, dtype=np.int64)]
    for (cx, cy), members in by_cell.items():
        here = np.array(members)
        for k, (dx, dy) in enumerate(((0, 0), (1, -1), (1, 0), (1, 1), (0, 1))):
            others = by_cell.get((cx + dx, cy + dy))
            if not others:
                continue
            a, b = np.meshgrid(here, np.array(others), indexing='ij')
            a, b = a.ravel(), b.ravel()
            if k == 0:
                a, b = a[a < b], b[a < b]
            firsts.append(a)
            seconds.append(b)
    return np.concatenate(firsts), np.concatenate(seconds)


def overlapping(boxes):
    """
    Return the index pairs (i, j), i < j, of the rectangles that overlap.

    :param boxes: [(x, y, yaw, length, width)] [m, rad]: centre, heading and size.
    """
    if len(boxes) < 2:
        return []
    boxes = np.asarray(boxes, dtype=float)
    x, y = boxes[:, 0], boxes[:, 1]
    a, b = _near_pairs(x, y, float(np.hypot(boxes[:, 3], boxes[:, 4]).max()))
    rects = _rectangles(x, y, boxes[:, 2], boxes[:, 3], boxes[:, 4])
    hit = _overlap(rects[a], rects[b])
    return sorted((min(i, j), max(i, j)) for i, j in zip(a[hit].tolist(), b[hit].tolist()))


def footprint_overlaps(graph, ranges: Dict[int, Tuple[float, float]], length_m, width_m,
                       skip: Iterable[Tuple[int, int]] = (), step_m=0.5, margin_m=0.15):
    """
    Return {(lane a, lane b): ((lo, hi) on a, (lo, hi) on b)} where footprints can overlap.

    Each range is where the centre of a vehicle on that lane may have a footprint overlapping
    one on the other lane (the overlapping samples' range, widened by a step), a < b.

    :param graph: the LaneGraph.
    :param ranges: {lane id: (from, to) arc lengths to sample} [m].
    :param length_m: the footprint's length [m] (the longest vehicle).
    :param width_m: its width [m] (the widest vehicle).
    :param skip: lane pairs never tested (either order: a lane and the lane it follows, ...).
    :param step_m: sampling step along each lane [m].
    :param margin_m: the rectangles are this much larger on every side [m].
    """
    lanes, xs, ys, yaws, ss = [], [], [], [], []
    for lane_id, (lo, hi) in sorted(ranges.items()):
        length = graph.lanes[lane_id].length_m
        lo, hi = max(0.0, lo), min(length, hi)
        count = max(1, int(math.ceil((hi - lo) / step_m)))
        for s in np.linspace(lo, hi, count + 1):
            x, y, yaw = graph.pose_at(lane_id, float(s))
            lanes.append(lane_id)
            xs.append(x)
            ys.append(y)
            yaws.append(yaw)
            ss.append(float(s))
    if not lanes:
        return {}
    lane_of, s_of = np.array(lanes), np.array(ss)
    x, y = np.array(xs), np.array(ys)
    rects = _rectangles(x, y, np.array(yaws), length_m + 2.0 * margin_m,
                        width_m + 2.0 * margin_m)
    a, b = _near_pairs(x, y, math.hypot(length_m, width_m) + 2.0 * margin_m)
    keep = lane_of[a] != lane_of[b]
    a, b = a[keep], b[keep]
    skip = {frozenset(pair) for pair in skip}
    if skip and len(a):
        keep = np.array([frozenset((p, q)) not in skip
                         for p, q in zip(lane_of[a].tolist(), lane_of[b].tolist())], dtype=bool)
        a, b = a[keep], b[keep]
    hit = _overlap(rects[a], rects[b]) if len(a) else np.zeros(0, dtype=bool)
    out: Dict[Tuple[int, int], list] = {}
    for p, q in zip(a[hit].tolist(), b[hit].tolist()):
        if lane_of[p] > lane_of[q]:
            p, q = q, p
        key = (int(lane_of[p]), int(lane_of[q]))
        sp, sq = s_of[p], s_of[q]
        got = out.get(key)
        if got is None:
            out[key] = [sp, sp, sq, sq]
        else:
            got[0], got[1] = min(got[0], sp), max(got[1], sp)
            got[2], got[3] = min(got[2], sq), max(got[3], sq)
    return {key: ((lo_a - step_m, hi_a + step_m), (lo_b - step_m, hi_b + step_m))
            for key, (lo_a, hi_a, lo_b, hi_b) in sorted(out.items())}
