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
The conflicts of a LaneGraph, from its lanes' geometry: :func:`lane_conflicts`.

A lane's area is its centreline swept by its width: a chain of quadrilaterals, one per piece of
centreline (at most :data:`PIECE_M` long), between the cross-sections at the piece's ends
(perpendicular to the lane's direction there, so that consecutive pieces share an edge). Two
lanes conflict where their areas overlap, except:

- one follows the other (a successor or predecessor): they meet end to start;
- they are neighbours of one direction (``left_lane``/``right_lane``): vehicles change lanes
  between them, the lane change's business;
- they leave one lane (a fork: a common predecessor): the vehicles at their shared start are in
  one queue, on the lane they leave, ordered along it; where the branches part, each follows its
  own. (Branches of a fork that cross again further on are not found: no map here draws one.)

Lanes that share a boundary (the two directions of a road, neighbours) touch but do not
overlap: the overlap is looked for with both areas shrunk by :data:`MARGIN_M` on each side, so
that a shared boundary or two polylines of one curve a few millimetres apart do not count. Where
they do overlap, the Conflict's arc-length ranges are those of the full areas: on each lane, the
first and last arc length of its area that lies in the other's (two lanes crossing at a right
angle: the other lane's width, centred on the crossing point). The kind is 'merging' when the
two lanes have a successor in common, else 'crossing'.

The search is quick for a few thousand lanes: the pieces' bounding boxes are swept along x
(sorted, then matched in y), the remaining pairs of pieces are tested at once with the
separating axis theorem, and the pieces of the conflicting lanes that overlap are clipped
(Sutherland-Hodgman, all at once) for the ranges.
"""

from typing import Tuple

import numpy as np

from vehicle_sim.core.map.lane_rules import Conflict

PIECE_M = 4.0                   # longest piece of a lane's area [m]
MARGIN_M = 0.1                  # areas shrunk by this on each side to find overlaps [m]
_EPS = 1e-9


def _lane_pieces(lane):
    """
    Return the cross-sections at the ends of a lane's K pieces.

    :return: centres (K + 1, 2), unit normals (K + 1, 2), half widths (K + 1,) and arc
        lengths (K + 1,).
    """
    seg_len = np.asarray(lane.seg_len)
    pieces = np.maximum(1, np.ceil(seg_len / PIECE_M).astype(int))
    k = np.repeat(np.arange(len(seg_len)), pieces)
    f = (np.arange(len(k)) - np.repeat(np.cumsum(pieces) - pieces, pieces)) / pieces[k]
    xs, ys, widths = np.asarray(lane.xs), np.asarray(lane.ys), np.asarray(lane.widths)
    s = np.append(np.asarray(lane.s0)[k] + f * seg_len[k], lane.length_m)
    centre = np.column_stack((np.append(xs[k] + f * (xs[k + 1] - xs[k]), xs[-1]),
                              np.append(ys[k] + f * (ys[k + 1] - ys[k]), ys[-1])))
    heading = np.asarray(lane.headings)[k]
    at_vertex = f == 0.0                    # the cross-section at a vertex: the mean direction
    heading[at_vertex] = np.asarray(lane.vertex_headings)[k[at_vertex]]
    heading = np.append(heading, lane.vertex_headings[-1])
    half = 0.5 * np.append(widths[k] + f * (widths[k + 1] - widths[k]), widths[-1])
    return centre, np.column_stack((-np.sin(heading), np.cos(heading))), half, s


def _quads(centre, normal, half, pieces):
    """Return the quads (K, 4, 2) between the cross-sections ``pieces``, ``pieces + 1``."""
    left, right = centre + normal * half[:, None], centre - normal * half[:, None]
    quads = np.stack((right[pieces], right[pieces + 1], left[pieces + 1], left[pieces]), axis=1)
    x, y = quads[:, :, 0], quads[:, :, 1]
    area = (x * np.roll(y, -1, axis=1) - y * np.roll(x, -1, axis=1)).sum(axis=1)
    return np.where((area < 0.0)[:, None, None], quads[:, ::-1], quads)


def _candidate_pairs(boxes, lane_of, cell_m):
    """Return index pairs (i, j), i < j, of pieces of different lanes whose boxes overlap."""
    low = np.floor(boxes[:, :2] / cell_m).astype(np.int64)
    high = np.floor(boxes[:, 2:] / cell_m).astype(np.int64)
    span = high - low + 1
    counts = span[:, 0] * span[:, 1]
    piece = np.repeat(np.arange(len(boxes)), counts)
    index = np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts, counts)
    cx = low[piece, 0] + index % span[piece, 0]
    cy = low[piece, 1] + index // span[piece, 0]
    cell = (cx - cx.min()) * (cy.max() - cy.min() + 1) + (cy - cy.min())
    order = np.lexsort((piece, cell))
    cell, piece = cell[order], piece[order]
    group_end = np.searchsorted(cell, cell, side='right')
    counts = group_end - np.arange(len(cell)) - 1
    first = np.repeat(np.arange(len(cell)), counts)
    offsets = np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts, counts)
    a, b = piece[first], piece[first + 1 + offsets]
    keep = (lane_of[a] != lane_of[b]) & (boxes[a, 0] <= boxes[b, 2]) & \
        (boxes[b, 0] <= boxes[a, 2]) & (boxes[a, 1] <= boxes[b, 3]) & (boxes[b, 1] <= boxes[a, 3])
    a, b = np.minimum(a[keep], b[keep]), np.maximum(a[keep], b[keep])
    unique = np.unique(a * len(boxes) + b)
    return unique // len(boxes), unique % len(boxes)


def _overlapping(qa, qb):
    """Return which pairs of convex quads (P, 4, 2) overlap with positive depth (SAT)."""
    result = np.ones(len(qa), dtype=bool)
    for quads in (qa, qb):
        for k in range(4):
            edge = quads[:, (k + 1) % 4] - quads[:, k]
            axis = np.column_stack((-edge[:, 1], edge[:, 0]))
            pa = np.einsum('pkc,pc->pk', qa, axis)
            pb = np.einsum('pkc,pc->pk', qb, axis)
            scale = np.hypot(axis[:, 0], axis[:, 1])
            depth = np.minimum(pa.max(1) - pb.min(1), pb.max(1) - pa.min(1))
            # a degenerate edge (zero width) separates nothing
            result &= (depth > _EPS * np.maximum(scale, 1.0)) | (scale < _EPS)
    return result


def _clip(subject, clipper):
    """
    Clip convex quads by convex quads (Sutherland-Hodgman), all pairs at once.

    :param subject: (P, 4, 2) quads.
    :param clipper: (P, 4, 2) quads, counter-clockwise.
    :return: points (P, 8, 2) of each overlap and which of them are valid (P, 8).
    """
    count = len(subject)
    points = np.concatenate((subject, np.zeros((count, 4, 2))), axis=1)
    valid = np.zeros((count, 8), dtype=bool)
    valid[:, :4] = True
    rows = np.arange(count)[:, None]
    for k in range(4):
        a, b = clipper[:, k], clipper[:, (k + 1) % 4]
        edge = b - a
        side = edge[:, None, 0] * (points[:, :, 1] - a[:, None, 1]) - \
            edge[:, None, 1] * (points[:, :, 0] - a[:, None, 0])
        # the next valid point of each valid point (the polygon's points are packed in front)
        n = valid.sum(axis=1)
        nxt = (np.arange(8)[None, :] + 1) % np.maximum(n, 1)[:, None]
        q, sq = points[rows, nxt], side[rows, nxt]
        inside = valid & (side >= 0.0)
        crossing = valid & ((side >= 0.0) != (sq >= 0.0))
        f = np.where(crossing, side / np.where(crossing, side - sq, 1.0), 0.0)
        cut = points + f[:, :, None] * (q - points)
        both = np.stack((points, cut), axis=2).reshape(count, 16, 2)
        keep = np.stack((inside, crossing), axis=2).reshape(count, 16)
        order = np.argsort(~keep, axis=1, kind='stable')[:, :8]
        points, valid = both[rows, order], keep[rows, order]
    return points, valid


def _s_on(points, valid, centres, s_pieces):
    """Return (min, max) arc length of each overlap's points on its pieces' axes."""
    c0, c1 = centres[:, 0], centres[:, 1]
    d = c1 - c0
    length2 = np.maximum((d * d).sum(axis=1), _EPS)
    f = ((points - c0[:, None]) * d[:, None]).sum(axis=2) / length2[:, None]
    s = s_pieces[:, :1] + np.clip(f, 0.0, 1.0) * (s_pieces[:, 1:] - s_pieces[:, :1])
    return np.where(valid, s, np.inf).min(axis=1), np.where(valid, s, -np.inf).max(axis=1)


def _excluded(graph):
    """Return the lane pairs that never conflict: chained, neighbours, forks."""
    pairs = set()
    for lane in graph.lanes.values():
        for other in lane.successors + (lane.left_lane, lane.right_lane):
            if other is not None:
                pairs.add((lane.id, other))
        branches = lane.successors
        for i, one in enumerate(branches):
            pairs.update((one, other) for other in branches[i + 1:])
    return pairs


def lane_conflicts(graph) -> Tuple[Conflict, ...]:
    """
    Return the Conflicts of a LaneGraph's lanes (each pair once, ordered by lane ids).

    :param graph: the LaneGraph.
    """
    lanes = sorted(graph.lanes.values(), key=lambda lane: lane.id)
    sections = [_lane_pieces(lane) for lane in lanes]
    centre = np.concatenate([section[0] for section in sections])
    normal = np.concatenate([section[1] for section in sections])
    half = np.concatenate([section[2] for section in sections])
    s = np.concatenate([section[3] for section in sections])
    counts = np.array([len(section[3]) for section in sections])
    # piece k of the map runs from cross-section pieces[k] to pieces[k] + 1, within one lane
    last = np.cumsum(counts) - 1
    keep = np.ones(len(s), dtype=bool)
    keep[last] = False
    pieces = np.flatnonzero(keep)
    lane_of = np.repeat(np.arange(len(lanes)), counts - 1)
    full = _quads(centre, normal, half, pieces)
    shrunk = _quads(centre, normal, np.maximum(half - MARGIN_M, 0.0), pieces)
    s_pieces = np.column_stack((s[pieces], s[pieces + 1]))
    centres = np.stack((centre[pieces], centre[pieces + 1]), axis=1)
    boxes = np.column_stack((full[:, :, 0].min(1), full[:, :, 1].min(1),
                             full[:, :, 0].max(1), full[:, :, 1].max(1)))
    a, b = _candidate_pairs(boxes, lane_of, 2.0 * PIECE_M)
    index_of = {lane.id: index for index, lane in enumerate(lanes)}
    count = len(lanes)
    excluded = np.array(sorted(min(index_of[x], index_of[y]) * count
                               + max(index_of[x], index_of[y]) for x, y in _excluded(graph)),
                        dtype=np.int64)
    a, b = np.where(lane_of[a] < lane_of[b], a, b), np.where(lane_of[a] < lane_of[b], b, a)
    pair = lane_of[a].astype(np.int64) * count + lane_of[b]
    keep = ~np.isin(pair, excluded)
    a, b, pair = a[keep], b[keep], pair[keep]
    touching = _overlapping(full[a], full[b])
    a, b, pair = a[touching], b[touching], pair[touching]
    deep = _overlapping(shrunk[a], shrunk[b])
    keep = np.isin(pair, pair[deep])                    # every piece of a conflicting pair
    a, b, pair = a[keep], b[keep], pair[keep]
    points, valid = _clip(full[a], full[b])
    enough = valid.sum(axis=1) >= 3
    a, b, pair, points, valid = a[enough], b[enough], pair[enough], points[enough], \
        valid[enough]
    lo_a, hi_a = _s_on(points, valid, centres[a], s_pieces[a])
    lo_b, hi_b = _s_on(points, valid, centres[b], s_pieces[b])
    pairs, slot = np.unique(pair, return_inverse=True)
    spans = np.tile([np.inf, -np.inf, np.inf, -np.inf], (len(pairs), 1))
    np.minimum.at(spans[:, 0], slot, lo_a)
    np.maximum.at(spans[:, 1], slot, hi_a)
    np.minimum.at(spans[:, 2], slot, lo_b)
    np.maximum.at(spans[:, 3], slot, hi_b)
    conflicts = []
    for key, span in zip(pairs.tolist(), spans.tolist()):
        one, other = lanes[key // count], lanes[key % count]
        kind = 'merging' if set(one.successors) & set(other.successors) else 'crossing'
        conflicts.append(Conflict(one.id, other.id, (span[0], span[1]), (span[2], span[3]),
                                  kind))
    return tuple(conflicts)
