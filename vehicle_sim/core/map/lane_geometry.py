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
What a lane map looks like: the road surface, the painted markings and the low barriers.

File-free and engine-free: triangle meshes (vertices and index triples, world metres) that a
renderer or a physics engine turns into shapes, and the barrier segments (curbstones, road
borders, walls) that become low collision geometry. The same for every kind of lane map.

- Surface: each lane is a strip between its centreline shifted by half its width to either
  side, at z = 0 (the ground plane) plus ``SURFACE_Z_M``.
- Markings: ``solid`` a stripe ``LINE_WIDTH_M`` wide along the line; ``dashed`` dashes of
  ``DASH_M`` with gaps of ``GAP_M`` (measured along each line from its start); the two-part
  types two stripes ``DOUBLE_GAP_M`` apart (left part on the line's left). Curbstones, road
  borders and walls are barriers, not paint; virtual and none lines are not drawn.
- Barriers: one segment per line piece, with the height of its type (``BARRIER_HEIGHT_M``).
"""

from dataclasses import dataclass
import math
from typing import Tuple

import numpy as np

from vehicle_sim.core.map.lane_graph import LaneGraph

SURFACE_Z_M = 0.002
MARKING_Z_M = 0.004
LINE_WIDTH_M = 0.15
DOUBLE_GAP_M = 0.12
DASH_M = 3.0
GAP_M = 6.0
BARRIER_HEIGHT_M = {'curbstone': 0.15, 'road_border': 0.15, 'wall': 1.0}
BARRIER_WIDTH_M = 0.2
# the parts of each painted type across the line: (kind, lateral shift [m], + = left)
_HALF = 0.5 * (LINE_WIDTH_M + DOUBLE_GAP_M)
PAINT = {
    'solid': (('solid', 0.0),),
    'dashed': (('dashed', 0.0),),
    'solid_solid': (('solid', _HALF), ('solid', -_HALF)),
    'dashed_dashed': (('dashed', _HALF), ('dashed', -_HALF)),
    'dashed_solid': (('dashed', _HALF), ('solid', -_HALF)),
    'solid_dashed': (('solid', _HALF), ('dashed', -_HALF)),
}


@dataclass(frozen=True)
class Mesh:
    """A triangle mesh: ``vertices`` (N, 3) float [m], ``triangles`` (M, 3) int indices."""

    vertices: np.ndarray
    triangles: np.ndarray


@dataclass(frozen=True)
class Barrier:
    """A straight piece of a barrier line: from (x0, y0) to (x1, y1) [m], its type and height."""

    x0_m: float
    y0_m: float
    x1_m: float
    y1_m: float
    line_type: str
    height_m: float


def _normals(points):
    """Return the unit left normal at each point of a polyline (its segments' mean)."""
    seg = np.diff(points, axis=0)
    seg /= np.hypot(seg[:, 0], seg[:, 1])[:, None]
    tangent = np.vstack((seg[:1], seg[:-1] + seg[1:], seg[-1:]))
    tangent /= np.maximum(np.hypot(tangent[:, 0], tangent[:, 1]), 1e-12)[:, None]
    return np.column_stack((-tangent[:, 1], tangent[:, 0]))


class _MeshBuilder:
    """Collects strips of quads into one mesh."""

    def __init__(self):
        self.vertices, self.triangles, self.count = [], [], 0

    def strip(self, left, right, z_m):
        """Add the quads between two polylines of equal length (left, right: (N, 2))."""
        base, count = self.count, len(left)
        z = np.full((count, 1), z_m)
        self.vertices.append(np.vstack((np.hstack((left, z)), np.hstack((right, z)))))
        self.count += 2 * count
        i = np.arange(count - 1)
        # per quad two triangles, counter-clockwise seen from above (normals up)
        l0, l1, r0, r1 = base + i, base + i + 1, base + count + i, base + count + i + 1
        self.triangles.append(np.column_stack((l0, r0, r1)))
        self.triangles.append(np.column_stack((l0, r1, l1)))

    def mesh(self):
        if not self.vertices:
            return Mesh(np.zeros((0, 3)), np.zeros((0, 3), dtype=np.int64))
        return Mesh(np.vstack(self.vertices), np.vstack(self.triangles).astype(np.int64))


def surface_mesh(graph: LaneGraph) -> Mesh:
    """Return the road surface: one strip per lane, its width wide, around its centreline."""
    builder = _MeshBuilder()
    for lane in graph.lanes.values():
        points = lane.centerline
        half = 0.5 * np.asarray(lane.widths)[:, None]
        normals = _normals(points)
        builder.strip(points + half * normals, points - half * normals, SURFACE_Z_M)
    return builder.mesh()


def _pieces(points, dashed):
    """Yield the (M, 2) polylines painted along a line: all of it, or its dashes."""
    if not dashed:
        yield points
        return
    seg = np.hypot(*np.diff(points, axis=0).T)
    s = np.concatenate(([0.0], np.cumsum(seg)))
    start = 0.0
    while start < s[-1]:
        end = min(start + DASH_M, s[-1])
        inner = s[(s > start) & (s < end)]
        at = np.concatenate(([start], inner, [end]))
        yield np.column_stack((np.interp(at, s, points[:, 0]), np.interp(at, s, points[:, 1])))
        start += DASH_M + GAP_M


def painted_pieces(graph: LaneGraph):
    """
    Yield what is painted along every boundary (each once): (boundary, kind, piece).

    ``kind`` is 'solid' or 'dashed' (one stripe of a boundary's type, :data:`PAINT`); ``piece``
    is an (M, 2) polyline [m] along the stripe's middle: the whole stripe, or one dash.
    """
    for boundary in graph.boundaries():
        for kind, shift in PAINT.get(boundary.line_type, ()):
            points = boundary.points + shift * _normals(boundary.points)
            for piece in _pieces(points, kind == 'dashed'):
                if len(piece) < 2 or math.hypot(*(piece[-1] - piece[0])) < 1e-6:
                    continue
                yield boundary, kind, piece


def marking_mesh(graph: LaneGraph) -> Mesh:
    """Return the painted lines: stripes and dashes of every boundary (each once)."""
    builder = _MeshBuilder()
    half = 0.5 * LINE_WIDTH_M
    for _, _, piece in painted_pieces(graph):
        normals = _normals(piece)
        builder.strip(piece + half * normals, piece - half * normals, MARKING_Z_M)
    return builder.mesh()


def barriers(graph: LaneGraph) -> Tuple[Barrier, ...]:
    """Return the barrier pieces (curbstones, road borders, walls) of every boundary, once."""
    found = []
    for boundary in graph.boundaries():
        height = BARRIER_HEIGHT_M.get(boundary.line_type)
        if height is None:
            continue
        pts = boundary.points.tolist()
        found.extend(Barrier(a[0], a[1], b[0], b[1], boundary.line_type, height)
                     for a, b in zip(pts[:-1], pts[1:]))
    return tuple(found)
