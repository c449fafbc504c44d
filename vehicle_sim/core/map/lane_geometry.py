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
  side, at z = 0 (the ground plane) plus ``SURFACE_Z_M``; the rules' areas of a road kind
  (:data:`ROAD_AREA_KINDS`: a junction's polygon, as a SUMO network has them) are road surface
  too, flat at the same height.
- Markings: ``solid`` a stripe ``LINE_WIDTH_M`` wide along the line; ``dashed`` dashes of
  ``DASH_M`` with gaps of ``GAP_M`` (measured along each line from its start); the two-part
  types two stripes ``DOUBLE_GAP_M`` apart (left part on the line's left). Curbstones, road
  borders and walls are barriers, not paint; virtual and none lines are not drawn.
- Barriers: one segment per line piece, with the height of its type (``BARRIER_HEIGHT_M``).
- The rules' paint (``graph.rules``, core/map/lane_rules.py): a stop line is a white bar
  ``STOP_LINE_WIDTH_M`` wide along its points; a crosswalk is zebra stripes (``ZEBRA_STRIPE_M``
  wide, ``ZEBRA_GAP_M`` apart, along the polygon's short side, clipped to it); every other
  MapArea (walkway, parking, keepout, building, a regulatory element's area) is its polygon,
  flat, in its kind's colour (:data:`AREA_COLORS`, :data:`OTHER_AREA_COLOR` for the rest), at
  ``AREA_Z_M`` (above the road surface, below the paint).
"""

from dataclasses import dataclass
import math
from typing import Dict, List, Tuple

import numpy as np

from vehicle_sim.core.map.lane_graph import LaneGraph

SURFACE_Z_M = 0.002
AREA_Z_M = 0.003
MARKING_Z_M = 0.004
LINE_WIDTH_M = 0.15
DOUBLE_GAP_M = 0.12
DASH_M = 3.0
GAP_M = 6.0
BARRIER_HEIGHT_M = {'curbstone': 0.15, 'road_border': 0.15, 'wall': 1.0}
BARRIER_WIDTH_M = 0.2
STOP_LINE_WIDTH_M = 0.4
ZEBRA_STRIPE_M = 0.5
ZEBRA_GAP_M = 0.5
# The colours (RGBA) of the areas drawn flat, by MapArea kind; any other kind (a regulatory
# element's area: detection_area, no_stopping_area, bus_stop_area, ...) is OTHER_AREA_COLOR.
# Crosswalks are zebra stripes in the paint's white (PAINT_COLOR), not a fill.
AREA_COLORS = {
    'walkway': (0.62, 0.62, 0.60, 1.0),      # pavement
    'parking': (0.22, 0.30, 0.45, 1.0),      # blue-tinted asphalt
    'keepout': (0.65, 0.20, 0.15, 1.0),      # red
    'building': (0.55, 0.45, 0.38, 1.0),     # brick
}
OTHER_AREA_COLOR = (0.55, 0.35, 0.65, 1.0)   # violet
# Area kinds drawn as road surface (part of the surface mesh), not as areas.
ROAD_AREA_KINDS = ('junction',)
PAINT_COLOR = (0.95, 0.95, 0.95, 1.0)        # white road paint
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

    def polygon(self, points, z_m):
        """Add a flat simple polygon ((N, 2), either winding), triangulated by ear clipping."""
        triangles = polygon_triangles(points)
        if not len(triangles):
            return
        self.vertices.append(np.column_stack((points, np.full(len(points), z_m))))
        self.triangles.append(triangles + self.count)
        self.count += len(points)

    def mesh(self):
        if not self.vertices:
            return Mesh(np.zeros((0, 3)), np.zeros((0, 3), dtype=np.int64))
        return Mesh(np.vstack(self.vertices), np.vstack(self.triangles).astype(np.int64))


def join_meshes(*meshes: Mesh) -> Mesh:
    """Return one mesh of several (their vertices in order, the indices shifted)."""
    offsets = np.cumsum([0] + [len(mesh.vertices) for mesh in meshes[:-1]])
    return Mesh(np.vstack([mesh.vertices.reshape(-1, 3) for mesh in meshes]),
                np.vstack([mesh.triangles.reshape(-1, 3) + offset
                           for mesh, offset in zip(meshes, offsets)]).astype(np.int64))


def surface_mesh(graph: LaneGraph) -> Mesh:
    """
    Return the road surface: one strip per lane, its width wide, around its centreline.

    The rules' areas of :data:`ROAD_AREA_KINDS` (junctions) are part of it, flat.
    """
    builder = _MeshBuilder()
    for lane in graph.lanes.values():
        points = lane.centerline
        half = 0.5 * np.asarray(lane.widths)[:, None]
        normals = _normals(points)
        builder.strip(points + half * normals, points - half * normals, SURFACE_Z_M)
    for area in graph.rules.areas:
        if area.kind in ROAD_AREA_KINDS:
            builder.polygon(area.polygon, SURFACE_Z_M)
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


# ------------------------------------------------------------------------------ the rules' paint

def _cross(o, a, b):
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])


def _cross_many(o, a, points):
    # _cross(o, a, p) for every row p of points (M, 2).
    return (a[0] - o[0]) * (points[:, 1] - o[1]) - (a[1] - o[1]) * (points[:, 0] - o[0])


def polygon_triangles(points) -> np.ndarray:
    """
    Return the triangles (M, 3) of a simple polygon (N, 2) by ear clipping, counter-clockwise.

    Collinear and repeated points are allowed; a degenerate polygon (no area) gives none.
    """
    points = np.asarray(points, dtype=float)
    n = len(points)
    area = 0.5 * float(np.sum(points[:, 0] * np.roll(points[:, 1], -1)
                              - np.roll(points[:, 0], -1) * points[:, 1])) if n >= 3 else 0.0
    if abs(area) < 1e-9:
        return np.zeros((0, 3), dtype=np.int64)
    order = list(range(n)) if area > 0 else list(range(n - 1, -1, -1))
    found = _first_try_ears(points.tolist(), order) if n <= _FIRST_TRY_MAX else None
    if found is None:
        found = _clip_ears(points, order)
    return np.array(found, dtype=np.int64).reshape(-1, 3)


# Polygons of up to this many corners try _first_try_ears first (a crosswalk's stripes, a
# junction's corners): a loop in plain floats, without the general loop's numpy per ear.
_FIRST_TRY_MAX = 12


def _first_try_ears(points, order):
    """
    Return :func:`_clip_ears`' triangles where every ear is found at its first try, else None.

    That is where each corner the clipping visits, (last, order[j], order[j + 1]), turns left by
    more than the collinear tolerance and holds none of the corners still to clip (a convex
    polygon without collinear corners): the clipping then takes the fan of ``order[-1]``, and
    its last triangle as the general loop writes it. The same tests, in the same arithmetic, as
    :func:`_clip_ears`: the same triangles where it answers.
    """
    corners = [points[k] for k in order]
    n = len(order)
    last = corners[-1]
    found = []
    for j in range(n - 3):
        pb, pc = corners[j], corners[j + 1]
        if not _cross(last, pb, pc) > 1e-12:
            return None
        for q in corners[j + 2:n - 1]:
            if (_cross(last, pb, q) >= 0.0 and _cross(pb, pc, q) >= 0.0
                    and _cross(pc, last, q) >= 0.0):
                return None
        found.append((order[-1], order[j], order[j + 1]))
    if _cross(corners[n - 3], corners[n - 2], last) > 1e-12:
        found.append((order[n - 3], order[n - 2], order[-1]))
    return found


def _clip_ears(points, order):
    """Return the ears of the polygon ``points[order]`` (counter-clockwise), clipped in turn."""
    order = list(order)
    found: List[Tuple[int, int, int]] = []
    i, misses = 0, 0
    while len(order) > 3 and misses < len(order):   # a full round without an ear: stop
        count = len(order)
        i %= count
        a, b, c = order[i - 1], order[i], order[(i + 1) % count]
        pa, pb, pc = points[a], points[b], points[c]
        turn = _cross(pa, pb, pc)
        if abs(turn) <= 1e-12:                  # collinear: the middle point adds nothing
            order.pop(i)
            misses = 0
            continue
        if turn > 0.0:                          # a convex corner: an ear if nothing is in it
            rest = np.array(order)
            rest = rest[(rest != a) & (rest != b) & (rest != c)]
            q = points[rest]
            inside = ((_cross_many(pa, pb, q) >= 0.0) & (_cross_many(pb, pc, q) >= 0.0)
                      & (_cross_many(pc, pa, q) >= 0.0))
            if not inside.any():
                found.append((a, b, c))
                order.pop(i)
                i, misses = max(i - 1, 0), 0
                continue
        i += 1
        misses += 1
    if len(order) == 3 and _cross(*(points[k] for k in order)) > 1e-12:
        found.append(tuple(order))
    return found


def polygon_mesh(polygon, z_m=0.0) -> Mesh:
    """Return a flat simple polygon (N, 2) at height ``z_m`` as a Mesh (ear-clipped)."""
    builder = _MeshBuilder()
    builder.polygon(np.asarray(polygon, dtype=float), z_m)
    return builder.mesh()


def _clip(polygon, normal, limit):
    """Return the part of a polygon where point . normal <= limit (Sutherland-Hodgman)."""
    out = []
    for i, current in enumerate(polygon):
        previous = polygon[i - 1]
        inside_now = float(np.dot(current, normal)) <= limit
        inside_before = float(np.dot(previous, normal)) <= limit
        if inside_now != inside_before:
            d0 = float(np.dot(previous, normal)) - limit
            d1 = float(np.dot(current, normal)) - limit
            out.append(previous + (current - previous) * (d0 / (d0 - d1)))
        if inside_now:
            out.append(current)
    return out


def _long_axis(polygon):
    """Return the unit direction of a polygon's longer side (its minimum-area rectangle's)."""
    best = None
    for a, b in zip(polygon, np.roll(polygon, -1, axis=0)):
        edge = b - a
        length = math.hypot(*edge)
        if length < 1e-9:
            continue
        u = edge / length
        v = np.array((-u[1], u[0]))
        along, across = polygon @ u, polygon @ v
        extent_u, extent_v = np.ptp(along), np.ptp(across)
        area = extent_u * extent_v
        if best is None or area < best[0] - 1e-9:
            best = (area, u if extent_u >= extent_v else v)
    return best[1]


def zebra_stripes(polygon) -> List[np.ndarray]:
    """
    Return a crosswalk's zebra stripes: polygons (N, 2) [m] within ``polygon``.

    The stripes run along the polygon's short side (the road's direction), ``ZEBRA_STRIPE_M``
    wide and ``ZEBRA_GAP_M`` apart along its long side (the way across), centred on it.
    """
    polygon = np.asarray(polygon, dtype=float)
    across = _long_axis(polygon)
    t = polygon @ across
    first, last = float(t.min()), float(t.max())
    pitch = ZEBRA_STRIPE_M + ZEBRA_GAP_M
    count = max(1, int((last - first + ZEBRA_GAP_M) // pitch))
    start = first + 0.5 * ((last - first) - (count * pitch - ZEBRA_GAP_M))
    stripes = []
    for k in range(count):
        low = start + k * pitch
        part = _clip(list(polygon), across, low + ZEBRA_STRIPE_M)
        part = _clip(part, -across, -low) if part else []
        if len(part) >= 3:
            stripes.append(np.array(part))
    return stripes


def stop_line_mesh(graph: LaneGraph) -> Mesh:
    """Return the stop lines: a white bar ``STOP_LINE_WIDTH_M`` wide along each line's points."""
    builder = _MeshBuilder()
    half = 0.5 * STOP_LINE_WIDTH_M
    for line in graph.rules.stop_lines:
        normals = _normals(line.points)
        builder.strip(line.points + half * normals, line.points - half * normals, MARKING_Z_M)
    return builder.mesh()


def crosswalk_mesh(graph: LaneGraph) -> Mesh:
    """Return the zebra stripes of every crosswalk of the rules."""
    builder = _MeshBuilder()
    for area in graph.rules.areas:
        if area.kind == 'crosswalk':
            for stripe in zebra_stripes(area.polygon):
                builder.polygon(stripe, MARKING_Z_M)
    return builder.mesh()


def area_color(kind: str):
    """Return the RGBA an area of ``kind`` is drawn in (crosswalks: the paint's white)."""
    if kind == 'crosswalk':
        return PAINT_COLOR
    return AREA_COLORS.get(kind, OTHER_AREA_COLOR)


def drawn_as_area(kind: str) -> bool:
    """Return whether an area of ``kind`` is drawn flat in its colour (crosswalks: stripes)."""
    return kind != 'crosswalk' and kind not in ROAD_AREA_KINDS


def area_meshes(graph: LaneGraph) -> Dict[str, Mesh]:
    """Return {kind: the flat polygons of its areas} of the areas :func:`drawn_as_area`."""
    builders: Dict[str, _MeshBuilder] = {}
    for area in graph.rules.areas:
        if drawn_as_area(area.kind):
            builders.setdefault(area.kind, _MeshBuilder()).polygon(area.polygon, AREA_Z_M)
    meshes = {kind: builder.mesh() for kind, builder in builders.items()}
    return {kind: mesh for kind, mesh in meshes.items() if len(mesh.triangles)}
