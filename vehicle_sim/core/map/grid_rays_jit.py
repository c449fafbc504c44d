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
GridRays' march compiled by numba (the ``fast`` extra): the same rays, the same arithmetic.

:func:`march` is core/map/grid_rays.py's ``GridRays._band``, ``_march``, ``_corner_hits`` and
``_window`` written one ray at a time: the same state per ray, the same operations in the same
order (IEEE doubles, no fused or reordered arithmetic), the same looks of jumps over the rays
still going and the same walk once few are left (how many are left decides when a ray walks,
and so which formula finds its hit). So a scan is the numpy march's to the bit; what numpy pays
per call (a few microseconds, several hundred calls a scan) is gone: on the SLAM-like map of
benchmarks/bench_occupancy_lidar.py a 1080-ray cast takes about 0.1 ms instead of 1.

Imported by GridRays on its first cast (never with the package: importing numba takes 0.3 s
or more), compiled then and kept in numba's on-disk cache (``cache=True``: ``__pycache__``
beside this file, or numba's user cache directory where that is not writable;
``NUMBA_CACHE_DIR`` moves it), so later processes load it in a fraction of a second.
"""

import math

import numba
import numpy as np

_JIT = dict(cache=True, nogil=True, error_model='numpy')


@numba.njit(**_JIT)
def _fmin(a, b):
    # np.fmin: the other where one is NaN
    if a != a:
        return b
    if b != b:
        return a
    return a if a <= b else b


@numba.njit(**_JIT)
def _fmax(a, b):
    # np.fmax: the other where one is NaN
    if a != a:
        return b
    if b != b:
        return a
    return a if a >= b else b


@numba.njit(**_JIT)
def _minimum(a, b):
    # np.minimum: NaN where one is NaN
    if a != a or b != b:
        return math.nan
    return a if a <= b else b


@numba.njit(**_JIT)
def _maximum(a, b):
    # np.maximum: NaN where one is NaN
    if a != a or b != b:
        return math.nan
    return a if a >= b else b


@numba.njit(**_JIT)
def _sign(a):
    # np.sign
    if a > 0.0:
        return 1.0
    if a < 0.0:
        return -1.0
    return a            # 0.0 (its sign kept) or NaN


@numba.njit(**_JIT)
def _clipped(squares, index):
    # squares.take(index, mode='clip') == 0 for a float index (astype(np.intp) truncates)
    cell = int(index)
    if cell < 0:
        cell = 0
    elif cell >= squares.size:
        cell = squares.size - 1
    return squares[cell] == 0


@numba.njit(**_JIT)
def _band(z, start_x, start_y, speed_z, speed_x, speed_y, tops, on_border):
    # GridRays._band for one ray: its fractions (low, high) between the ground and the walls'
    # top and inside the grid's rectangle, within [0, 1]
    enter_max, leave_min = -math.inf, math.inf
    for axis in range(3):
        if axis == 0:
            position, speed = z, speed_z
        elif axis == 1:
            position, speed = start_x, speed_x
        else:
            position, speed = start_y, speed_y
        inverse = 1.0 / speed
        near = -position * inverse
        far = (tops[axis] - position) * inverse
        enter, leave = _fmin(near, far), _fmax(near, far)
        if on_border and speed == 0.0:
            inside = 0.0 <= position and position <= tops[axis]
            enter = -math.inf if inside else math.inf
            leave = math.inf if inside else -math.inf
        # enter.max(axis=0) and leave.min(axis=0): NaN where one is NaN
        enter_max = _maximum(enter_max, enter)
        leave_min = _minimum(leave_min, leave)
    return _maximum(enter_max, 0.0), _minimum(leave_min, 1.0)


@numba.njit(**_JIT)
def _corner_hit(squares, stride, nudge, nudged_x, nudged_y, speed_x, speed_y, sign_x, sign_y,
                t, high):
    # GridRays._corner_hits for one ray whose jump ended where its exits tie
    position_x = nudged_x + speed_x * t
    position_y = nudged_y + speed_y * t
    ahead_x, ahead_y = math.floor(position_x), math.floor(position_y)
    behind_x = math.floor(position_x - sign_x * (2.0 * nudge))
    behind_y = math.floor(position_y - sign_y * (2.0 * nudge))
    beside = min(squares[int(behind_y * stride + ahead_x)],
                 squares[int(ahead_y * stride + behind_x)])
    return ahead_x != behind_x and ahead_y != behind_y and beside == 0 and t < high


@numba.njit(**_JIT)
def _walk_axis(squares, nudge, cells, cross, between, line, sign, start_other, speed_other,
               weight, other_weight, end):
    # One axis of GridRays._window for one ray: the fraction of the first of its next
    # ``cells`` borders along the axis where it enters a wall cell (inf: none), and the
    # fraction of the last border
    found = math.inf
    reach = cross + between * (cells - 1.0)
    back = line - (1.0 if sign < 0.0 else 0.0)
    for step in range(cells):
        fraction = cross + between * float(step)
        inside = _minimum(fraction, end)
        along = (back + sign * float(step)) * weight
        beside = start_other + speed_other * inside
        below = math.floor(beside - nudge)
        above = math.floor(beside + nudge)
        wall = _clipped(squares, below * other_weight + along)
        if not wall and above != below:
            wall = _clipped(squares, above * other_weight + along)
        if wall:
            found = fraction        # the fractions rise with the steps: the first is the least
            break
    return found, reach


@numba.njit(**_JIT)
def _walk(squares, stride, nudge, cells, speed_x, speed_y, start_x, start_y, sign_x, sign_y,
          inverse_x, inverse_y, now, end):
    # GridRays._window for one ray still going: (t, hit, done)
    position_x = start_x + speed_x * now
    position_y = start_y + speed_y * now
    cell_x = math.floor(position_x + sign_x * nudge)
    cell_y = math.floor(position_y + sign_y * nudge)
    first = squares[int(cell_y * stride + cell_x)] == 0
    line_x = cell_x + (1.0 if sign_x > 0.0 else 0.0)
    line_y = cell_y + (1.0 if sign_y > 0.0 else 0.0)
    moves_x, moves_y = math.isfinite(inverse_x), math.isfinite(inverse_y)
    cross_x = (line_x - start_x) * sign_x * inverse_x if moves_x else math.inf
    cross_y = (line_y - start_y) * sign_y * inverse_y if moves_y else math.inf
    between_x = inverse_x if moves_x else 0.0
    between_y = inverse_y if moves_y else 0.0
    found_x, reach_x = _walk_axis(squares, nudge, cells, cross_x, between_x, line_x, sign_x,
                                  start_y, speed_y, 1.0, stride, end)
    found_y, reach_y = _walk_axis(squares, nudge, cells, cross_y, between_y, line_y, sign_y,
                                  start_x, speed_x, stride, 1.0, end)
    limit = _minimum(_minimum(reach_x, reach_y), end)
    meet = _minimum(found_x, found_y)
    meets = first or (meet < math.inf and meet <= limit)
    if first:
        t = now
    elif meets:
        t = meet
    else:
        t = limit
    return t, meets, meets or limit >= end


@numba.njit(**_JIT)
def march(squares, stride, quadrant_rows, tops, origin, start_x, start_y, speed, vectors,
          result, jumps_per_look, window_rays, window_cells, nudge, cut, box):
    """
    Cast the rays over the quadrant squares; write each ray's fraction into ``result``.

    The arguments are GridRays' own: its padded squares (flat), their row stride and the rows
    of one quadrant, the band's tops, the rays' origin (3,), their start in grid cells, their
    speed (2, n) [cells per unit of fraction] and vectors (n, 3) [m], the result (n,) (1.0
    where nothing is met; left as it is), grid_rays.py's constants (read when called), and
    where GridRays.cast_cut wants the cut rays (n, 3) and their box (2, 3) (no rows: not
    asked for).
    """
    _march(squares, stride, quadrant_rows, tops, origin, start_x, start_y, speed, vectors,
           result, jumps_per_look, window_rays, window_cells, nudge)
    if cut.shape[0] == 0:
        return
    for axis in range(3):
        box[0, axis] = box[1, axis] = origin[axis]
    for ray in range(result.shape[0]):
        for axis in range(3):
            end = origin[axis] + vectors[ray, axis] * result[ray]
            cut[ray, axis] = end
            if end < box[0, axis]:
                box[0, axis] = end
            if end > box[1, axis]:
                box[1, axis] = end


@numba.njit(**_JIT)
def _march(squares, stride, quadrant_rows, tops, origin, start_x, start_y, speed, vectors,
           result, jumps_per_look, window_rays, window_cells, nudge):
    # GridRays._band, _march, _corner_hits and _window
    count = speed.shape[1]
    z = origin[2]
    on_border = False
    position = (z, start_x, start_y)
    for axis in range(3):
        if position[axis] == 0.0 or position[axis] == tops[axis]:
            on_border = True
    # the state of the rays still going (GridRays' _ROWS), the live ones first
    ids = np.empty(count, dtype=np.int64)
    t = np.empty(count)
    high = np.empty(count)
    n = 0
    for ray in range(count):
        low, end = _band(z, start_x, start_y, vectors[ray, 2], speed[0, ray], speed[1, ray],
                         tops, on_border)
        if low <= end:
            ids[n], t[n], high[n] = ray, low, end
            n += 1
    speed_x, speed_y = np.empty(n), np.empty(n)
    padded_x, padded_y = np.empty(n), np.empty(n)
    nudged_x, nudged_y = np.empty(n), np.empty(n)
    sign_x, sign_y = np.empty(n), np.empty(n)
    offset_x, offset_y = np.empty(n), np.empty(n)
    inverse_x, inverse_y = np.empty(n), np.empty(n)
    tie = np.empty(n)
    for i in range(n):
        vx, vy = speed[0, ids[i]], speed[1, ids[i]]
        back_x = 1.0 if vx < 0.0 else 0.0
        back_y = 1.0 if vy < 0.0 else 0.0
        speed_x[i], speed_y[i] = vx, vy
        sign_x[i], sign_y[i] = _sign(vx), _sign(vy)
        inverse_x[i], inverse_y[i] = 1.0 / abs(vx), 1.0 / abs(vy)
        padded_x[i] = start_x + 1.0
        padded_y[i] = (start_y + 1.0) + (2.0 * back_y + back_x) * quadrant_rows
        nudged_x[i] = sign_x[i] * nudge + padded_x[i]
        nudged_y[i] = sign_y[i] * nudge + padded_y[i]
        offset_x[i] = sign_x[i] * padded_x[i] + back_x
        offset_y[i] = sign_y[i] * padded_y[i] + back_y
        tie[i] = _maximum(inverse_x[i], inverse_y[i]) * (4.0 * nudge)
        if tie[i] == math.inf:
            tie[i] = 0.0
    k = np.empty(n, dtype=np.uint8)
    corner = np.empty(n, dtype=np.bool_)
    hit = np.empty(n, dtype=np.bool_)
    done = np.empty(n, dtype=np.bool_)
    while n:
        # a look: jumps_per_look jumps of every ray still going (a done one stands still)
        corner[:n] = False
        for _ in range(jumps_per_look):
            for i in range(n):
                cell_x = math.floor(speed_x[i] * t[i] + nudged_x[i])
                cell_y = math.floor(speed_y[i] * t[i] + nudged_y[i])
                k[i] = squares[int(cell_x + stride * cell_y)]
                x = ((cell_x * sign_x[i] + k[i]) - offset_x[i]) * inverse_x[i]
                y = ((cell_y * sign_y[i] + k[i]) - offset_y[i]) * inverse_y[i]
                ties = abs(x - y) <= tie[i]
                t[i] = _fmin(_fmax(t[i], _fmin(x, y)), high[i])
                if ties and k[i] > 0 and _corner_hit(
                        squares, stride, nudge, nudged_x[i], nudged_y[i], speed_x[i],
                        speed_y[i], sign_x[i], sign_y[i], t[i], high[i]):
                    high[i] = t[i]
                    corner[i] = True
        for i in range(n):
            hit[i] = k[i] == 0 or corner[i]
            done[i] = t[i] >= high[i] or hit[i]
        if n <= window_rays:
            for i in range(n):
                if not done[i]:
                    t[i], hit[i], done[i] = _walk(
                        squares, stride, nudge, window_cells, speed_x[i], speed_y[i],
                        padded_x[i], padded_y[i], sign_x[i], sign_y[i], inverse_x[i],
                        inverse_y[i], t[i], high[i])
        # the rays done give their fraction; the others move up, in order
        kept = 0
        for i in range(n):
            if done[i]:
                result[ids[i]] = t[i] + 0.0 if hit[i] else 1.0      # +0.0, as GridRays.cast
                continue
            if kept != i:
                ids[kept], t[kept], high[kept] = ids[i], t[i], high[i]
                speed_x[kept], speed_y[kept] = speed_x[i], speed_y[i]
                padded_x[kept], padded_y[kept] = padded_x[i], padded_y[i]
                nudged_x[kept], nudged_y[kept] = nudged_x[i], nudged_y[i]
                sign_x[kept], sign_y[kept] = sign_x[i], sign_y[i]
                offset_x[kept], offset_y[kept] = offset_x[i], offset_y[i]
                inverse_x[kept], inverse_y[kept] = inverse_x[i], inverse_y[i]
                tie[kept] = tie[i]
            kept += 1
        n = kept
