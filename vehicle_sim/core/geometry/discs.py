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
Discs on the ground plane moved apart where they overlap (pure 2-D geometry).

:func:`separate_discs`: SUMO's pedestrian model puts two persons closer than their width now
and then (physics/sumo_pool.py); their upright cylinders are moved apart, each pair by the
least that ends its overlap, shared evenly, until no two overlap, now or (going on straight at
their velocities) until SUMO's next step.
"""

import math
from typing import List, Optional, Sequence, Tuple

Point = Tuple[float, float]

# Two discs closer than the sum of their radii by no more than this [m] touch (they do not
# overlap); a pair that overlaps is moved apart to exactly the sum.
TOUCH_M = 1.0e-4
MAX_PASSES = 200                 # passes over every pair before giving up (a long queue's)
# a cell's pairs: within it, and with the cells after it (each neighbouring pair of cells once)
NEIGHBOURS = ((0, 0), (1, -1), (1, 0), (1, 1), (0, 1))

__all__ = ['separate_discs', 'TOUCH_M']


def separate_discs(centres: Sequence[Point], radii: Sequence[float],
                   velocities: Optional[Sequence[Point]] = None, horizon_s=0.0,
                   max_passes=MAX_PASSES) -> List[Point]:
    """
    Return the centres moved so that no two discs overlap (by more than ``TOUCH_M``).

    Each overlapping pair is pushed apart along the line between its centres (two on the same
    point: along x), each disc by half the overlap; a pass goes over every pair near enough
    to overlap (a grid of cells as wide as the widest disc: each cell's pairs and those with
    the cells next to it, the cells in the order of their first disc), and the passes
    repeat until one moves nothing: in a queue of discs, each closer to the next than their
    width, the push goes down the queue, which gets longer by the sum of the overlaps. The
    same input gives the same output. After ``max_passes`` passes the centres are returned as
    they are then (overlaps left, each smaller than before).

    With ``velocities``, the discs go on straight at them for ``horizon_s``: a pair is pushed
    apart at its closest approach in that time, along the line between the two centres then,
    so that no two overlap at any time from the centres returned to ``horizon_s`` later.

    :param centres: the discs' centres (x, y) [m].
    :param radii: their radii [m], one per centre.
    :param velocities: their velocities (x, y) [m/s], one per centre (None: standing).
    :param horizon_s: how long they go on at them [s].
    :returns: the new centres, in the same order; a disc that overlaps none keeps its own.
    """
    if len(radii) != len(centres) or (velocities is not None
                                      and len(velocities) != len(centres)):
        raise ValueError(f'separate_discs: {len(centres)} centres but {len(radii)} radii'
                         + ('' if velocities is None else f' and {len(velocities)} velocities'))
    if not horizon_s >= 0.0:
        raise ValueError(f'separate_discs: horizon_s {horizon_s!r}: must be 0 or more')
    points = [[float(x), float(y)] for x, y in centres]
    if len(points) < 2 or max(radii) <= 0.0:
        return [tuple(p) for p in points]
    if velocities is None or horizon_s == 0.0:
        velocities, horizon_s = [(0.0, 0.0)] * len(points), 0.0
    # the cells are as wide as the widest disc and as far as any goes in the horizon
    cell = 2.0 * max(radii) + horizon_s * 2.0 * max(math.hypot(*v) for v in velocities)
    floor, hypot = math.floor, math.hypot
    for _ in range(max_passes):
        grid = {}
        for i, (x, y) in enumerate(points):
            grid.setdefault((floor(x / cell), floor(y / cell)), []).append(i)
        moved = False
        for (gx, gy), members in grid.items():       # a cell with itself and 4 neighbours
            for k, i in enumerate(members):
                for cx, cy in NEIGHBOURS:
                    others = members[k + 1:] if cx == cy == 0 else grid.get((gx + cx, gy + cy))
                    for j in others or ():
                        p, q = points[i], points[j]
                        dx, dy = q[0] - p[0], q[1] - p[1]
                        wx = velocities[j][0] - velocities[i][0]
                        wy = velocities[j][1] - velocities[i][1]
                        closing = -(dx * wx + dy * wy)
                        if closing > 0.0:          # their closest approach in the horizon
                            t = min(horizon_s, closing / (wx * wx + wy * wy))
                            dx, dy = dx + wx * t, dy + wy * t
                        need = radii[i] + radii[j]
                        if abs(dx) >= need or abs(dy) >= need:
                            continue
                        d = hypot(dx, dy)
                        if d >= need - TOUCH_M:
                            continue
                        ux, uy = (dx / d, dy / d) if d > 0.0 else (1.0, 0.0)
                        push = 0.5 * (need - d)
                        p[0] -= push * ux
                        p[1] -= push * uy
                        q[0] += push * ux
                        q[1] += push * uy
                        moved = True
        if not moved:
            break
    return [tuple(p) for p in points]
