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
Footprints on the ground plane and the distances between them (pure 2-D geometry).

- :class:`Outline`: a vehicle's footprint rectangle in its base_link frame, from its parameters
  (:func:`car_outline`, :func:`robot_outline`); :meth:`Outline.corners` places it at a pose.
- :class:`Footprint`: a named convex polygon or circle in the world: an obstacle's
  (:func:`obstacle_footprint`), or any wall polygon a map provides.
- :func:`clearance`: the distance between a vehicle's corners and a footprint, with the two
  closest points; :func:`band_polygon`: the region within a distance of a polyline.

Polygons are tuples of (x, y) [m], counter-clockwise.
"""

from dataclasses import dataclass
import math
from typing import Optional, Sequence, Tuple

from vehicle_sim.core.geometry.angles import wrap_angle_rad
from vehicle_sim.core.geometry.frames import rotation_matrix

Point = Tuple[float, float]
Polygon = Tuple[Point, ...]
# A tilted cylinder's rims are sampled at this many points: the polygon lies inside the true
# outline by at most r (1 - cos(pi / n)), 0.5 % of the radius.
RIM_POINTS = 32


# ------------------------------------------------------------------------- points, segments
def distance_to_segment(px, py, ax, ay, bx, by):
    """Return the distance [m] from point p to the segment a-b."""
    return math.dist((px, py), closest_on_segment(px, py, ax, ay, bx, by))


def closest_on_segment(px, py, ax, ay, bx, by) -> Point:
    """Return the point of the segment a-b closest to p."""
    dx, dy = bx - ax, by - ay
    length2 = dx * dx + dy * dy
    t = 0.0 if length2 == 0.0 else max(0.0, min(1.0, ((px - ax) * dx + (py - ay) * dy)
                                                / length2))
    return (ax + t * dx, ay + t * dy)


def distance_to_polyline(px, py, points: Sequence[Point]):
    """Return the distance [m] from a point to a polyline (the lateral deviation from a path)."""
    return min(distance_to_segment(px, py, *a, *b) for a, b in zip(points, points[1:]))


def _edges(polygon):
    return zip(polygon, polygon[1:] + polygon[:1])


def _cross(o, a, b):
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])


def convex_hull(points: Sequence[Point]) -> Polygon:
    """Return the convex hull of points, counter-clockwise (Andrew's monotone chain)."""
    unique = sorted(set((float(x), float(y)) for x, y in points))
    if len(unique) < 3:
        return tuple(unique)
    lower, upper = [], []
    for point in unique:
        while len(lower) >= 2 and _cross(lower[-2], lower[-1], point) <= 0.0:
            lower.pop()
        lower.append(point)
    for point in reversed(unique):
        while len(upper) >= 2 and _cross(upper[-2], upper[-1], point) <= 0.0:
            upper.pop()
        upper.append(point)
    return tuple(lower[:-1] + upper[:-1])


def inside_convex(point: Point, polygon: Polygon):
    """Return whether a point lies in (or on) a counter-clockwise convex polygon."""
    return all(_cross(a, b, point) >= 0.0 for a, b in _edges(polygon))


def _separated(a: Polygon, b: Polygon):
    """Return whether an edge normal of a or b separates the convex polygons (SAT)."""
    for polygon in (a, b):
        for (x0, y0), (x1, y1) in _edges(polygon):
            nx, ny = y1 - y0, x0 - x1
            a_proj = [nx * x + ny * y for x, y in a]
            b_proj = [nx * x + ny * y for x, y in b]
            if max(a_proj) < min(b_proj) or max(b_proj) < min(a_proj):
                return True
    return False


# ------------------------------------------------------------------------------ footprints
@dataclass(frozen=True)
class Footprint:
    """
    A named shape on the ground: a convex polygon, or a circle when ``radius_m`` is set.

    :param name: what it is (an obstacle's name; the "closest" of a clearance).
    :param vertices: the polygon, counter-clockwise [m] (empty for a circle).
    :param center_m: the circle's centre [x, y] [m].
    :param radius_m: the circle's radius [m]; None for a polygon.
    """

    name: str
    vertices: Polygon = ()
    center_m: Optional[Point] = None
    radius_m: Optional[float] = None

    @property
    def is_circle(self):
        return self.radius_m is not None


def polygon_footprint(name, vertices: Sequence[Point]) -> Footprint:
    """Return the footprint of a convex polygon (any vertex order; its hull is kept)."""
    return Footprint(name, vertices=convex_hull(vertices))


def circle_footprint(name, center_m: Point, radius_m) -> Footprint:
    """Return the footprint of a circle [m]."""
    return Footprint(name, center_m=(float(center_m[0]), float(center_m[1])),
                     radius_m=float(radius_m))


def _hull(spec, centre, rotation, local) -> Footprint:
    points = [(centre[0] + sum(rotation[0][k] * p[k] for k in range(3)),
               centre[1] + sum(rotation[1][k] * p[k] for k in range(3))) for p in local]
    return polygon_footprint(spec.name, points)


def box_footprint(spec, centre, rotation) -> Footprint:
    """Return a box's footprint: the hull of its eight corners."""
    sx, sy, sz = (s / 2.0 for s in spec.size_m)
    return _hull(spec, centre, rotation,
                 [(x, y, z) for x in (-sx, sx) for y in (-sy, sy) for z in (-sz, sz)])


def cylinder_footprint(spec, centre, rotation) -> Footprint:
    """Return a cylinder's footprint: a circle upright, else the hull of its two rims."""
    if abs(abs(rotation[2][2]) - 1.0) < 1e-12:          # axis vertical
        return circle_footprint(spec.name, centre, spec.radius_m)
    half = spec.height_m / 2.0
    return _hull(spec, centre, rotation,
                 [(spec.radius_m * math.cos(a), spec.radius_m * math.sin(a), z)
                  for a in (2.0 * math.pi * k / RIM_POINTS for k in range(RIM_POINTS))
                  for z in (-half, half)])


def sphere_footprint(spec, centre, rotation) -> Footprint:
    """Return a sphere's footprint: a circle."""
    return circle_footprint(spec.name, centre, spec.radius_m)


# obstacle shape (core/world/params.py OBSTACLE_SHAPES) -> footprint(spec, centre (x, y),
# rotation matrix) -> its Footprint on the ground.
OBSTACLE_FOOTPRINTS = {
    'box': box_footprint,
    'cylinder': cylinder_footprint,
    'sphere': sphere_footprint,
}


def obstacle_footprint(spec, position_m=None, quaternion=None) -> Footprint:
    """
    Return an obstacle's shape projected on the ground (its shape's row of OBSTACLE_FOOTPRINTS).

    A box gives the hull of its eight corners, a sphere and an upright cylinder a circle, a
    tilted cylinder the hull of its two rims (RIM_POINTS each).

    :param spec: core.world_params.ObstacleSpec.
    :param position_m: its centre now [x, y, z]; None = the spec's position.
    :param quaternion: its orientation now (x, y, z, w); None = the spec's roll, pitch, yaw.
    """
    position = spec.position_m if position_m is None else position_m
    rotation = rotation_matrix(spec.pose.quaternion if quaternion is None else quaternion)
    centre = (float(position[0]), float(position[1]))
    return OBSTACLE_FOOTPRINTS[spec.shape](spec, centre, rotation)


# -------------------------------------------------------------------------------- vehicles
@dataclass(frozen=True)
class Outline:
    """A vehicle's footprint rectangle in its base_link frame (x forward, y left) [m]."""

    x_min_m: float
    x_max_m: float
    y_min_m: float
    y_max_m: float

    @property
    def length_m(self):
        return self.x_max_m - self.x_min_m

    @property
    def width_m(self):
        return self.y_max_m - self.y_min_m

    def corners(self, x_m, y_m, yaw_rad) -> Polygon:
        """Return the rectangle with base_link at (x, y) heading ``yaw_rad``, counter-clockwise."""
        c, s = math.cos(yaw_rad), math.sin(yaw_rad)
        local = ((self.x_min_m, self.y_min_m), (self.x_max_m, self.y_min_m),
                 (self.x_max_m, self.y_max_m), (self.x_min_m, self.y_max_m))
        return tuple((x_m + c * u - s * v, y_m + s * u + c * v) for u, v in local)


def _bounding(rectangles):
    """Return the Outline around (x_min, x_max, y_min, y_max) tuples."""
    x0, x1, y0, y1 = zip(*rectangles)
    return Outline(min(x0), max(x1), min(y0), max(y1))


def car_outline(params) -> Outline:
    """
    Return a car's footprint: the rectangle around its collision boxes and tyres.

    Boxes are seen from above (a pitched box reaches l cos(pitch) + h sin(pitch) along x);
    tyres are their radius along x and their width across, at the axles' ends.

    :param params: core.params.CarParams (base_link at the rear-axle centre).
    """
    parts = []
    for box in params.collision_boxes:
        length, width, height = box.size_m
        c, s = abs(math.cos(box.pitch_rad)), abs(math.sin(box.pitch_rad))
        half_x = (length * c + height * s) / 2.0
        x, y, _ = box.position_m
        parts.append((x - half_x, x + half_x, y - width / 2.0, y + width / 2.0))
    for x, track, radius, width in ((params.wheelbase_m, params.track_front_m,
                                     params.front_tire_radius_m, params.front_tire_width_m),
                                    (0.0, params.track_rear_m, params.rear_tire_radius_m,
                                     params.rear_tire_width_m)):
        half_y = track / 2.0 + width / 2.0
        parts.append((x - radius, x + radius, -half_y, half_y))
    return _bounding(parts)


def robot_outline(params) -> Outline:
    """
    Return a robot's footprint: the rectangle around its body box, wheels and caster.

    :param params: core.robot_params.RobotParams (base_link below the centre of the axle(s)).
    """
    length, width, _ = params.body_size_m
    x = params.body_offset_m
    parts = [(x - length / 2.0, x + length / 2.0, -width / 2.0, width / 2.0)]
    half_y = params.wheel_tread_m / 2.0 + params.wheel_width_m / 2.0
    r = params.wheel_radius_m
    for axle_x in {params.wheel_base_m / 2.0, -params.wheel_base_m / 2.0}:
        parts.append((axle_x - r, axle_x + r, -half_y, half_y))
    if params.drive == 'caster':
        c, rc = params.caster_offset_m, params.caster_radius_m
        parts.append((c - rc, c + rc, -rc, rc))
    return _bounding(parts)


# ------------------------------------------------------------------------------- distances
def _polygon_to_point(polygon: Polygon, point: Point):
    """Return (distance, closest point of the polygon's boundary) from a point outside it."""
    best = None
    for a, b in _edges(polygon):
        q = closest_on_segment(*point, *a, *b)
        d = math.dist(point, q)
        if best is None or d < best[0]:
            best = (d, q)
    return best


def clearance(vehicle: Polygon, footprint: Footprint):
    """
    Return the distance between a vehicle's (convex) corners and a footprint.

    :param vehicle: counter-clockwise convex polygon, e.g. :meth:`Outline.corners`.
    :return: (distance [m], point on the vehicle, point on the footprint); 0 and None, None
        where they overlap.
    """
    if footprint.is_circle:
        centre, radius = footprint.center_m, footprint.radius_m
        if inside_convex(centre, vehicle):
            return 0.0, None, None
        d, on_vehicle = _polygon_to_point(vehicle, centre)
        if d <= radius:
            return 0.0, None, None
        t = radius / d
        on_circle = (centre[0] + (on_vehicle[0] - centre[0]) * t,
                     centre[1] + (on_vehicle[1] - centre[1]) * t)
        return d - radius, on_vehicle, on_circle
    other = footprint.vertices
    if not _separated(vehicle, other):
        return 0.0, None, None
    # disjoint convex polygons: the closest pair is a vertex of one and an edge of the other
    best = None
    for point in vehicle:
        d, q = _polygon_to_point(other, point)
        if best is None or d < best[0]:
            best = (d, point, q)
    for point in other:
        d, q = _polygon_to_point(vehicle, point)
        if d < best[0]:
            best = (d, q, point)
    return best


# ------------------------------------------------------------------------------------ bands
def band_polygon(points: Sequence[Point], half_width_m, arc_points=8) -> Polygon:
    """
    Return the outline of the region within ``half_width_m`` of a polyline (a path's band).

    Round at the ends and on the outside of bends (arcs of ``arc_points`` segments), the
    offset lines' intersection on the inside; exact while each segment is longer than the
    band is wide at its bends.

    :param points: the polyline [m] (at least 2 distinct points).
    :return: the outline (not closed: the last vertex is not repeated).
    """
    path = [tuple(map(float, points[0]))]
    for point in points[1:]:
        if math.dist(point, path[-1]) > 0.0:
            path.append(tuple(map(float, point)))
    if len(path) < 2:
        raise ValueError('a band needs a polyline of at least 2 distinct points')
    r = float(half_width_m)
    headings = [math.atan2(b[1] - a[1], b[0] - a[0]) for a, b in zip(path, path[1:])]

    def arc(centre, start, end):
        return [(centre[0] + r * math.cos(start + (end - start) * k / arc_points),
                 centre[1] + r * math.sin(start + (end - start) * k / arc_points))
                for k in range(arc_points + 1)]

    def side(nodes, angles, sign):
        # one side walked along nodes: sign +1 = left of the heading
        out = []
        for i, node in enumerate(nodes[1:-1], 1):
            before, after = angles[i - 1], angles[i]
            turn = wrap_angle_rad(after - before)
            if turn * sign < 0.0:       # outside of the bend: an arc
                out += arc(node, before + sign * math.pi / 2, before + sign * math.pi / 2
                           + turn)
            else:                       # inside: where the two offset lines meet
                bisector = before + turn / 2.0 + sign * math.pi / 2
                reach = r / math.cos(turn / 2.0)
                out.append((node[0] + reach * math.cos(bisector),
                            node[1] + reach * math.sin(bisector)))
        return out

    start, end = path[0], path[-1]
    reverse = [h + math.pi for h in reversed(headings)]
    # clockwise: the left side forwards, round the end, the right side back, round the start
    polygon = side(path, headings, 1.0) \
        + arc(end, headings[-1] + math.pi / 2, headings[-1] - math.pi / 2) \
        + side(path[::-1], reverse, 1.0) \
        + arc(start, headings[0] - math.pi / 2, headings[0] - 3 * math.pi / 2)
    return tuple(polygon)
