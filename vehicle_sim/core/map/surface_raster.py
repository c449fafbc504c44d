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
What is drawn on the ground where: a raster of labels over a lane map's flat meshes.

The lane layer draws the road surface, its markings, crosswalks and areas as visual meshes just
above the ground (physics/lane_layer.py): rays pass them and hit the ground plane. A labelled
lidar reads what is drawn where a ray met the ground from this raster: each cell holds the label
of the last mesh given that covers it (the road first, then the areas, the paint, the crosswalks,
as they are drawn one above the other), 0 where nothing is drawn.

Cells are ``CELL_M`` square (coarser where a map is so large that the raster would pass
``MAX_CELLS``: the cell grows until it fits). A triangle covers the cells whose centres lie
within half a cell of it, so a painted line narrower than a cell still marks the cells it
crosses. Triangles far larger than a cell are cut in two until their boxes are small, then
tested in batches against the centres of the cells of their boxes (numpy); built on the first
lookup, so a world that never asks pays nothing (a few tenths of a second for a town's roads).
"""

import math
from typing import Optional, Sequence, Tuple

import numpy as np

CELL_M = 0.1
MAX_CELLS = 1 << 25          # 32 M cells: 32 MB of labels at most
_MAX_BOX_CELLS = 1024        # a triangle's box of cells is cut smaller than this
_BATCH_CELLS = 1 << 22       # cell centres tested at once


class SurfaceRaster:
    """
    The labels of flat meshes on the ground, looked up by (x, y).

    :param layers: (label id, vertices (n, 3) [m], triangles (m, 3)) from the bottom layer up;
        z is ignored.
    """

    def __init__(self, layers: Sequence[Tuple[int, np.ndarray, np.ndarray]]):
        self._layers = [(int(label), np.asarray(vertices, dtype=float)[:, :2],
                         np.asarray(triangles, dtype=np.int64))
                        for label, vertices, triangles in layers if len(triangles)]
        self._cells: Optional[np.ndarray] = None
        self.cell_m = CELL_M
        self._corner = (0.0, 0.0)

    def labels_at(self, x_m, y_m) -> np.ndarray:
        """Return the label (uint8) drawn at each point (x, y) [m]; 0 where nothing is."""
        cells = self._raster()
        x = np.floor((np.asarray(x_m, dtype=float) - self._corner[0]) / self.cell_m)
        y = np.floor((np.asarray(y_m, dtype=float) - self._corner[1]) / self.cell_m)
        inside = (x >= 0) & (y >= 0) & (x < cells.shape[1]) & (y < cells.shape[0])
        found = np.zeros(x.shape, dtype=np.uint8)
        found[inside] = cells[y[inside].astype(np.intp), x[inside].astype(np.intp)]
        return found

    def _raster(self) -> np.ndarray:
        if self._cells is not None:
            return self._cells
        if not self._layers:
            self._cells = np.zeros((0, 0), dtype=np.uint8)
            return self._cells
        points = np.concatenate([vertices for _, vertices, _ in self._layers])
        low, high = points.min(axis=0), points.max(axis=0)
        span = high - low
        cell = CELL_M
        while (math.ceil(span[0] / cell) + 2) * (math.ceil(span[1] / cell) + 2) > MAX_CELLS:
            cell *= 1.5
        self.cell_m = cell
        self._corner = (float(low[0] - cell), float(low[1] - cell))
        shape = (math.ceil(span[1] / cell) + 3, math.ceil(span[0] / cell) + 3)
        cells = np.zeros(shape, dtype=np.uint8)
        for label, vertices, triangles in self._layers:
            corners = (vertices[triangles] - self._corner) / cell     # (m, 3, 2) in cells
            _fill(cells, corners, label)
        self._cells = cells
        return cells


def _fill(cells, corners, value):
    # Set the cells whose centres lie within half a cell of a triangle (corners in cells).
    corners = _small(_counter_clockwise(corners))
    low = np.floor(corners.min(axis=1) - 0.5).astype(np.int64)
    high = np.floor(corners.max(axis=1) + 0.5).astype(np.int64)
    np.clip(low, 0, np.array(cells.shape[::-1]) - 1, out=low)
    np.clip(high, 0, np.array(cells.shape[::-1]) - 1, out=high)
    width = high[:, 0] - low[:, 0] + 1
    counts = width * (high[:, 1] - low[:, 1] + 1)
    # the edges' unit normals pointing in, and their offsets: inside where n.p + d >= -0.5
    start, end = corners, np.roll(corners, -1, axis=1)
    edge = end - start
    length = np.hypot(edge[..., 0], edge[..., 1])
    normal = np.stack([-edge[..., 1], edge[..., 0]], axis=-1) / length[..., None]
    offset = -(normal * start).sum(axis=-1)
    first = 0
    ends = np.cumsum(counts)
    while first < len(counts):
        last = max(first + 1, int(np.searchsorted(ends, ends[first] - counts[first]
                                                  + _BATCH_CELLS, side='right')))
        which = np.arange(first, last)
        sizes = counts[which]
        owner = np.repeat(which, sizes)
        local = np.arange(sizes.sum()) - np.repeat(np.cumsum(sizes) - sizes, sizes)
        column = low[owner, 0] + local % width[owner]
        row = low[owner, 1] + local // width[owner]
        centre_x, centre_y = column + 0.5, row + 0.5
        inside = np.ones(len(owner), dtype=bool)
        for k in range(3):
            inside &= (normal[owner, k, 0] * centre_x + normal[owner, k, 1] * centre_y
                       + offset[owner, k]) >= -0.5
        cells[row[inside], column[inside]] = value
        first = last


def _counter_clockwise(corners):
    # Triangles with their corners counter-clockwise; degenerate ones dropped.
    a, b, c = corners[:, 0], corners[:, 1], corners[:, 2]
    area = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
    corners = corners[area != 0.0].copy()
    flip = area[area != 0.0] < 0.0
    corners[flip] = corners[flip][:, ::-1]
    return corners


def _small(corners):
    # Cut triangles whose boxes span more than _MAX_BOX_CELLS cells in two at the middle of
    # their longest edge (a long thin strip halves its length and keeps its width).
    done = []
    while len(corners):
        span = corners.max(axis=1) - corners.min(axis=1) + 2.0
        big = span[:, 0] * span[:, 1] > _MAX_BOX_CELLS
        done.append(corners[~big])
        corners = corners[big]
        if not len(corners):
            break
        # rotate each triangle so that its longest edge runs from corner 0 to corner 1
        edges = np.roll(corners, -1, axis=1) - corners
        longest = np.hypot(edges[..., 0], edges[..., 1]).argmax(axis=1)
        order = (longest[:, None] + np.arange(3)[None, :]) % 3
        corners = np.take_along_axis(corners, order[..., None], axis=1)
        a, b, c = corners[:, 0], corners[:, 1], corners[:, 2]
        middle = 0.5 * (a + b)
        corners = np.concatenate([np.stack((a, middle, c), axis=1),
                                  np.stack((middle, b, c), axis=1)])
    return np.concatenate(done) if done else corners
