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
Rays against an occupancy map's walls, cast over the grid itself: exact and cheap on any map.

An occupancy map's walls are columns standing on the ground, one per wall cell, ``height_m``
high (the same solid the physics builds from boxes). :class:`GridRays` finds where a batch of
3-D rays from one origin first meets them: the distance at which each ray enters its first wall
cell while between the ground and the walls' top (a ray from above meets a top face; one that
starts inside a wall meets it at 0). It is the same answer as
:func:`~vehicle_sim.core.map.occupancy.ray_march`, vectorised over the rays.

Each ray skips empty space in squares: :func:`quadrant_squares` (computed once when the map is
loaded) gives each cell the largest square of free cells reaching from it towards each quadrant
(up and right, up and left, ...); a ray in a cell whose square towards the ray's quadrant is k
cells wide cannot meet a wall before it leaves that square, so it jumps to where it does, then
looks again; at k = 0 it has entered a wall cell. Far from walls a ray crosses a room in one or
two jumps, and walls behind it or beside it do not shorten its jumps; among ragged walls the
squares shrink to a cell or two, so the last few rays left walk the next cells one by one, in one
go (:meth:`GridRays._window`). The rays jump three times between looks at which are done (a
done ray stands still). On a SLAM-like map a 1080-ray scan takes about 1 ms of numpy
(benchmarks/bench_occupancy_lidar.py), nearly all of it numpy's fixed cost per call; the same
march compiled by numba (grid_rays_jit.py, the ``fast`` extra: ``march``, the map key
``ray_march``) gives the same fractions to the bit in about 0.1 ms. A ray leaves the grid
once (it is convex) and nothing outside it is a wall. Why not Bullet: a ray cast against a
map's static meshes walks the meshes' trees along its whole length, past its first hit, and a
SLAM map's ragged walls hold a hundred thousand faces: 8 times the cost of the same lidar in an
empty world there (meshes of the walls' boundary alone, 7 times;
benchmarks/bench_grid_ray_options.py).
"""

import importlib.util
import math
from typing import Optional
import warnings

import numpy as np

from vehicle_sim.core.specs.errors import InvalidParameterError

# The squares are stored in a byte: at most this many cells wide (a ray through a larger empty
# area takes a few more jumps).
MAX_SQUARE_CELLS = 255
# The loop's emptiness tests: np.count_nonzero is a plain C call, ndarray.any() goes through
# numpy's Python wrapper (a few microseconds each, dozens of times a scan).
count_nonzero = np.count_nonzero
# Where a ray stands exactly on a cell border, its cell is looked up this far [cells] along it.
_NUDGE_CELLS = 1e-6
# Jumps between looks at which rays are done (a done ray stands still meanwhile).
_JUMPS_PER_LOOK = 3
# Where this few rays are left, each look is followed by a walk over their next cells.
_WINDOW_RAYS = 64
# Cell borders a walk crosses along each axis.
_WINDOW_CELLS = 64
# The rows of the rays' state (GridRays._march): per ray its speed along x and y [cells per unit
# of fraction], start [cells] (padded, its quadrant's rows up), start nudged ahead, sign,
# offset (back + sign * start), inverse (1 / |speed|), tie tolerance, t (its fraction now),
# high (its band's end) and index among the rays cast.
_ROWS = ('speed_x', 'speed_y', 'start_x', 'start_y', 'nudged_x', 'nudged_y', 'sign_x', 'sign_y',
         'offset_x', 'offset_y', 'inverse_x', 'inverse_y', 'tie', 't', 'high', 'id')
_SPEED, _START, _NUDGED, _SIGN = slice(0, 2), slice(2, 4), slice(4, 6), slice(6, 8)
_OFFSET, _INVERSE, _TIE, _T, _HIGH, _ID = slice(8, 10), slice(10, 12), 12, 13, 14, 15
# Which march casts (the map key ``ray_march``, core/map/kinds.py): ``compiled`` is this march
# compiled by numba (grid_rays_jit.py, the ``fast`` extra), ``numpy`` the one below, ``auto``
# the compiled one where numba imports, else numpy.
RAY_MARCHES = ('auto', 'numpy', 'compiled')
FAST_EXTRA_HINT = "pip install 'vehicle_sim[fast]' (or pip install numba)"
# grid_rays_jit's march once imported, or the ImportError it raised (imported once a process).
_COMPILED = {}
# What the compiled march gets for the cut rays and their box when they are not asked for.
_NO_CUT, _NO_BOX = np.empty((0, 3)), np.empty((0, 3))


def compiled_march_installed() -> bool:
    """Return whether numba is installed (found, not imported: that takes 0.3 s or more)."""
    return importlib.util.find_spec('numba') is not None


def compiled_march():
    """
    Return grid_rays_jit's compiled march, importing numba the first time.

    :raises ImportError: naming the ``fast`` extra, where numba is missing or does not import.
    """
    if not _COMPILED:
        try:
            from vehicle_sim.core.map.grid_rays_jit import march
            _COMPILED['march'] = march
        except ImportError as error:
            _COMPILED['error'] = ImportError(
                f'the compiled ray march needs numba, which does not import ({error}): '
                f'{FAST_EXTRA_HINT}')
    if 'error' in _COMPILED:
        raise _COMPILED['error']
    return _COMPILED['march']


def free_squares(walls: np.ndarray, out: Optional[np.ndarray] = None) -> np.ndarray:
    """
    Return each cell's largest free square reaching up and right from it, capped at 255.

    Cell (r, c) gets the largest j such that the cells ``walls[r:r + j, c:c + j]`` are all
    free (0 on a wall cell; cells beyond the grid's top and right edges count as free). One
    pass from the top row down (the largest-square recurrence
    ``f(r, c) = 1 + min(f(r + 1, c), f(r, c + 1), f(r + 1, c + 1))``, each row vectorised
    as a running minimum): about 0.05 s for a 3000 x 2250 grid.

    :param walls: bool (height, width) wall mask (row 0 = the bottom row).
    :param out: where to write them (a view will do), else a new array.
    :return: uint8 (height, width).
    """
    height, width = walls.shape
    cap = np.int16(MAX_SQUARE_CELLS)
    columns = np.arange(width, dtype=np.int16)
    squares = np.empty(walls.shape, dtype=np.uint8) if out is None else out
    above = np.full(width + 1, cap, dtype=np.int16)
    line = np.empty(width, dtype=np.int16)
    for row in range(height - 1, -1, -1):
        # 1 + the squares above and above-right; 0 on a wall
        np.minimum(above[:-1], above[1:], out=line)
        line += 1
        line[walls[row]] = 0
        # along the row, from the right: f(c) = min over j >= c of line(j) + (j - c)
        line += columns
        back = line[::-1]
        np.minimum.accumulate(back, out=back)
        line -= columns
        np.minimum(line, cap, out=line)
        above[:-1] = line
        squares[row] = line
    return squares


def quadrant_squares(walls: np.ndarray, out: Optional[np.ndarray] = None) -> np.ndarray:
    """
    Return :func:`free_squares` towards each quadrant: uint8 (4, height, width).

    Quadrant q = 2 * (down) + (left): 0 reaches up and right from a cell, 1 up and left,
    2 down and right, 3 down and left.

    :param out: where to write them (a view will do), else a new array.
    """
    squares = np.empty((4,) + walls.shape, dtype=np.uint8) if out is None else out
    for quadrant in range(4):
        flip = (slice(None, None, -1 if quadrant & 2 else 1),
                slice(None, None, -1 if quadrant & 1 else 1))
        free_squares(walls[flip], out=squares[quadrant][flip])
    return squares


class GridRays:
    """
    An occupancy map's walls for ray casting, in the frame the rays come in (the world's).

    :param walls: bool (height, width) wall mask (row 0 = the bottom row).
    :param resolution_m: cell size [m].
    :param corner: (x [m], y [m], yaw [rad]) of cell (0, 0)'s lower-left corner in the rays'
        frame (the grid's origin composed with the map's placement).
    :param height_m: the walls' height above z = 0 [m].
    :param march: which march casts, one of :data:`RAY_MARCHES` (``auto``: the compiled one
        where numba imports); numba is imported on the first cast, not here.
    """

    def __init__(self, walls: np.ndarray, resolution_m: float, corner, height_m: float,
                 march: str = 'auto'):
        if march not in RAY_MARCHES:
            raise InvalidParameterError(
                f"ray march {march!r}: must be one of {', '.join(RAY_MARCHES)}")
        self.march = march
        self._compiled = None if march == 'numpy' else ...     # ...: not looked up yet
        self.height_m = float(height_m)
        self._shape = walls.shape
        padded = np.full((4, walls.shape[0] + 2, walls.shape[1] + 2), MAX_SQUARE_CELLS,
                         dtype=np.uint8)
        quadrant_squares(walls, out=padded[:, 1:-1, 1:-1])
        self._squares = padded.ravel()
        self._stride = padded.shape[2]
        self._quadrant_rows = padded.shape[1]
        x, y, yaw = corner
        self._corner = (float(x), float(y))
        # frame -> grid: cells per metre along the grid's axes
        scale = 1.0 / resolution_m
        self._axes = np.array([[math.cos(yaw), math.sin(yaw)],
                               [-math.sin(yaw), math.cos(yaw)]]) * scale
        # the band's three slabs: z [m], then x and y [cells]: [0, top]
        self._tops = np.array([self.height_m, float(walls.shape[1]), float(walls.shape[0])])

    @property
    def nbytes(self) -> int:
        """Memory held [bytes]: the squares, four bytes a cell (with a border)."""
        return self._squares.nbytes

    @property
    def compiled(self) -> bool:
        """
        Whether the casts run the compiled march (numba imported the first time it is asked).

        :raises ImportError: naming the ``fast`` extra, for ``march='compiled'`` where numba
            does not import.
        """
        if self._compiled is ...:
            try:
                self._compiled = compiled_march()
            except ImportError as error:
                if self.march == 'compiled':
                    raise
                if compiled_march_installed():      # installed but broken: say so
                    warnings.warn(f'ray_march auto: {error}; the numpy march casts',
                                  RuntimeWarning, stacklevel=2)
                self._compiled = None
        return self._compiled is not None

    def cast(self, origin, ends) -> np.ndarray:
        """
        Return each ray's fraction of its length where it first meets a wall; 1.0 for none.

        :param origin: (3,) start of every ray [m].
        :param ends: (n, 3) ends of the rays [m].
        """
        return self._cast(origin, ends, None)

    def cast_cut(self, origin, ends):
        """
        Return :meth:`cast`'s fractions, the rays cut there and a box that holds them.

        :param origin: (3,) start of every ray [m].
        :param ends: (n, 3) ends of the rays [m].
        :return: (fractions (n,), cut (n, 3) [m]: ``origin + (ends - origin) * fraction``, each
            ray up to the wall it meets, box ((3,) lowest, (3,) highest corner) [m] of the
            origin and the cut ends). The compiled march works them out as it goes: numpy's
            reductions over an (n, 3) array cost tens of microseconds.
        """
        cut = np.empty((len(ends), 3))
        box = np.empty((2, 3))
        return self._cast(origin, ends, (cut, box)), cut, box

    def _cast(self, origin, ends, outputs):
        origin = np.asarray(origin, dtype=float)
        vectors = np.asarray(ends, dtype=float) - origin
        count = len(vectors)
        result = np.ones(count)
        grid_start = self._axes @ (origin[:2] - self._corner)
        if self._compiled is not None and self.compiled and count:
            # the same march, one ray at a time (grid_rays_jit.py)
            speed = np.empty((2, count))
            np.matmul(self._axes, vectors[:, :2].T, out=speed)
            cut, box = (_NO_CUT, _NO_BOX) if outputs is None else outputs
            self._compiled(self._squares, float(self._stride), float(self._quadrant_rows),
                           self._tops, origin, grid_start[0], grid_start[1], speed, vectors,
                           result, _JUMPS_PER_LOOK, _WINDOW_RAYS, _WINDOW_CELLS, _NUDGE_CELLS,
                           cut, box)
            return result
        if count:
            self._numpy_march(origin, vectors, grid_start, result)
        if outputs is not None:
            cut, box = outputs
            np.multiply(vectors, result[:, None], out=cut)
            np.add(origin, cut, out=cut)
            box[:] = origin
            if count:
                np.minimum(box[0], cut.min(axis=0), out=box[0])
                np.maximum(box[1], cut.max(axis=0), out=box[1])
        return result

    def _numpy_march(self, origin, vectors, grid_start, result):
        # The band, then the march (below), in numpy; writes the fractions into result.
        count = len(vectors)
        # Per ray, a column of the rays' state (the rows named in _ROWS); in grid cells.
        rays = np.empty((len(_ROWS), count))
        speed, start, t, high = rays[_SPEED], rays[_START], rays[_T], rays[_HIGH]
        np.matmul(self._axes, vectors[:, :2].T, out=speed)     # cells per unit of fraction
        start[:] = grid_start[:, None]
        with np.errstate(divide='ignore', invalid='ignore'):
            self._band(origin[2], vectors[:, 2], start[:, 0], speed, t, high)
            live = t <= high
            if not live.all():
                if not live.any():
                    return
                rays = rays.compress(live, axis=1)
            rays[_ID] = np.flatnonzero(live)
            self._march(result, rays)
        # a hit at the ray's start reads +0.0 (which zero numpy's max gives depends on its loop)
        result += 0.0

    def normals(self, origin, ends, fractions) -> np.ndarray:
        """
        Return the unit normal of the wall face each ray met, in the rays' frame: (n, 3).

        :param origin: (3,) start of every ray [m].
        :param ends: (n, 3) ends of the rays [m].
        :param fractions: (n,) what :meth:`cast` gave them; a ray that met nothing (1.0) gets
            a normal against it, as one that starts inside a wall (0.0).

        A hit on the walls' top (its point at their height, going down) faces up; else the
        hit lies on a cell border along x or along y (the one nearer a whole number of cells)
        and faces against the ray along that axis of the grid.
        """
        origin = np.asarray(origin, dtype=float)
        vectors = np.asarray(ends, dtype=float) - origin
        fractions = np.asarray(fractions, dtype=float)
        cells = (self._axes @ (origin[:2] - self._corner))[:, None] \
            + (self._axes @ vectors[:, :2].T) * fractions
        speed = self._axes @ vectors[:, :2].T
        off = np.abs(cells - np.round(cells))            # from the nearest border, per axis
        along_x = off[0] <= off[1]
        # the face's normal along the grid's x or y axis, against the ray, in the rays' frame
        unit = self._axes / np.linalg.norm(self._axes[0])      # rows: the grid's axes
        sign = -np.sign(np.where(along_x, speed[0], speed[1]))
        flat = np.where(along_x[:, None], unit[0][None, :], unit[1][None, :]) * sign[:, None]
        normals = np.zeros((len(vectors), 3))
        normals[:, :2] = flat
        z = origin[2] + vectors[:, 2] * fractions
        top = (np.abs(z - self.height_m) <= 1e-9 * max(1.0, self.height_m)) \
            & (vectors[:, 2] < 0.0)
        normals[top] = (0.0, 0.0, 1.0)
        against = (fractions <= 0.0) | (fractions >= 1.0) | ~np.any(normals, axis=1)
        if np.any(against):
            length = np.linalg.norm(vectors[against], axis=1)[:, None]
            normals[against] = -vectors[against] / np.where(length > 0.0, length, 1.0)
        return normals

    def _march(self, result, rays):
        # The jumps from square to square (see the module text), in padded cells, the
        # quadrants' squares stacked above each other (a ray's rows are shifted up by its
        # quadrant's): x = start + t * speed; the cell is looked up a nudge ahead; the ray
        # leaves the square of k cells from cell c along an axis where
        # sign * x = sign * c + k - back (back = 1 running down), at
        # t = (sign * c + k - back - sign * start) * inverse.
        speed, start, sign, inverse = rays[_SPEED], rays[_START], rays[_SIGN], rays[_INVERSE]
        back = speed < 0.0
        np.sign(speed, out=sign)
        np.abs(speed, out=inverse)
        np.divide(1.0, inverse, out=inverse)
        start += 1.0
        start[1] += (2.0 * back[1] + back[0]) * self._quadrant_rows
        np.multiply(sign, _NUDGE_CELLS, out=rays[_NUDGED])
        rays[_NUDGED] += start
        np.multiply(sign, start, out=rays[_OFFSET])
        rays[_OFFSET] += back
        # a jump whose exits along both axes are this close [fraction] may end on a corner
        # (none for a ray along an axis)
        tie = np.maximum(inverse[0], inverse[1], out=rays[_TIE])
        tie *= 4.0 * _NUDGE_CELLS
        tie[tie == np.inf] = 0.0
        squares, weights = self._squares, np.array([1.0, float(self._stride)])
        while True:
            speed, nudged, sign, offset, inverse = (
                rays[_SPEED], rays[_NUDGED], rays[_SIGN], rays[_OFFSET], rays[_INVERSE])
            t, high, tie = rays[_T], rays[_HIGH], rays[_TIE]
            corner = None
            for _ in range(_JUMPS_PER_LOOK):
                cells = speed * t
                cells += nudged
                np.floor(cells, out=cells)
                k = squares[(weights @ cells).astype(np.intp)]
                # the fraction where the ray leaves the square along each axis, the nearer
                cells *= sign
                cells += k
                cells -= offset
                cells *= inverse
                x, y = cells
                ties = np.abs(x - y) <= tie
                # a ray on a wall cell (k = 0) stands still, one past its band stops at its end
                np.fmin(x, y, out=x)
                np.fmax(t, x, out=t)
                np.fmin(t, high, out=t)
                if count_nonzero(ties):
                    stopped = self._corner_hits(np.flatnonzero(ties & (k > 0)), rays)
                    if count_nonzero(stopped):
                        high[stopped] = t[stopped]
                        corner = stopped if corner is None else corner | stopped
            hit = k == 0
            if corner is not None:
                hit |= corner
            done = t >= high
            done |= hit
            if len(t) <= _WINDOW_RAYS:
                self._window(rays, hit, done)
            if count_nonzero(done):
                # (a ray still going gets its fraction when it is done)
                result[rays[_ID].astype(np.intp)] = np.where(hit, t, 1.0)
                keep = ~done
                if not count_nonzero(keep):
                    return result
                rays = rays.compress(keep, axis=1)

    def _window(self, rays, hit, done):
        # The rays still going walk the next _WINDOW_CELLS cell borders along each axis, cell
        # by cell (where few rays are left, most of them run past ragged walls, a cell or two
        # a jump): at each border the cell entered is looked up a nudge to both sides along
        # the other axis (both cells beside a corner the ray passes). Sets the rays' t (the
        # first wall cell entered, else the window's end) and their hit and done in place.
        going = np.flatnonzero(~done)
        if len(going) == 0:
            return
        now, end = rays[_T, going], rays[_HIGH, going]
        speed, sign, start = rays[_SPEED, going], rays[_SIGN, going], rays[_START, going]
        inverse, squares, stride = rays[_INVERSE, going], self._squares, float(self._stride)
        position = start + speed * now
        # the cell the ray is in now (its last jump's end) may be a wall
        cell = np.floor(position + sign * _NUDGE_CELLS)
        first = squares[(cell[1] * stride + cell[0]).astype(np.intp)] == 0
        # the borders ahead along each axis: the fractions where the ray crosses them
        line = cell + (sign > 0.0)
        moves = np.isfinite(inverse)
        cross = np.where(moves, (line - start) * sign * inverse, np.inf)
        between = np.where(moves, inverse, 0.0)
        steps = np.arange(_WINDOW_CELLS, dtype=float)
        found, reach = [], []
        for axis, other, weight, other_weight in ((0, 1, 1.0, stride), (1, 0, stride, 1.0)):
            fractions = cross[axis][:, None] + between[axis][:, None] * steps
            reach.append(fractions[:, -1])
            inside = np.minimum(fractions, end[:, None])         # where the cells are looked up
            along = (line[axis] - (sign[axis] < 0.0))[:, None] + sign[axis][:, None] * steps
            along *= weight
            beside = start[other][:, None] + speed[other][:, None] * inside
            below = np.floor(beside - _NUDGE_CELLS)
            above = np.floor(beside + _NUDGE_CELLS, out=beside)
            # the cells a nudge to both sides differ only where a border is crossed on a corner;
            # the walk's last borders may lie past the grid (on a map a few cells tall, past the
            # table's end): those cells are looked up clipped to the table, their answers past
            # the ray's end unused
            wall = None
            for near in (below, above) if count_nonzero(above != below) else (below,):
                near *= other_weight
                near += along
                meets = squares.take(near.astype(np.intp), mode='clip') == 0
                wall = meets if wall is None else wall | meets
            found.append(np.where(wall, fractions, np.inf).min(axis=1))
        limit = np.minimum(np.minimum(reach[0], reach[1]), end)
        meet = np.minimum(found[0], found[1])
        meets = first | (meet < np.inf) & (meet <= limit)
        rays[_T, going] = np.where(first, now, np.where(meets, meet, limit))
        hit[going] = meets
        done[going] = meets | (limit >= end)

    def _corner_hits(self, which, rays):
        # Rays whose jump ended on a cell corner touch the two cells beside the one ahead
        # too: a ray between two wall cells that share a corner meets them there.
        t, high = rays[_T, which], rays[_HIGH, which]
        hit = np.zeros(rays.shape[1], dtype=bool)
        position = rays[_NUDGED, which] + rays[_SPEED, which] * t       # nudged ahead
        nudge = rays[_SIGN, which] * (2.0 * _NUDGE_CELLS)
        ahead, behind = np.floor(position), np.floor(position - nudge)
        squares, stride = self._squares, self._stride
        beside = np.minimum(squares[(behind[1] * stride + ahead[0]).astype(np.intp)],
                            squares[(ahead[1] * stride + behind[0]).astype(np.intp)])
        hit[which] = ((ahead[0] != behind[0]) & (ahead[1] != behind[1]) & (beside == 0)
                      & (t < high))
        return hit

    def _band(self, z, speed_z, start, speed, low, high):
        # The fractions [low, high] of each ray that lie between the ground and the walls' top
        # and inside the grid's rectangle (outside it nothing is a wall), within [0, 1]:
        # along z [m], x and y [cells]; written into low and high.
        position = np.array([z, start[0], start[1]])
        speeds = np.concatenate([speed_z[None, :], speed])
        inverse = 1.0 / speeds
        near = -position[:, None] * inverse
        far = (self._tops - position)[:, None] * inverse
        enter, leave = np.fmin(near, far), np.fmax(near, far)
        # a ray that does not move along an axis: inside the slab (-inf, inf) else empty,
        # which the above gives but for a start on the slab's border (0 * inf)
        if ((position == 0.0) | (position == self._tops)).any():
            still = speeds == 0.0
            inside = ((0.0 <= position) & (position <= self._tops))[:, None]
            enter = np.where(still, np.where(inside, -np.inf, np.inf), enter)
            leave = np.where(still, np.where(inside, np.inf, -np.inf), leave)
        np.maximum(enter.max(axis=0), 0.0, out=low)
        np.minimum(leave.min(axis=0), 1.0, out=high)
