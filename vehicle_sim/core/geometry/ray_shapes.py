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
Rays from one origin against boxes turned about z and upright cylinders (numpy, no physics).

:func:`cast_shapes`: the first hit of each ray among the shapes, its shape and the unit normal
of the surface there: what Bullet's ray test gives for the traffic's bodies (placed boxes and
persons' cylinders, physics/sumo_traffic.py), without the bodies standing in Bullet's tree
(a ray walks the tree past every box near it). A box is the slab test in its own frame; a
cylinder the circle in the ground plane and the slab of its height. A ray that starts inside a
shape does not see it (as Bullet's: it meets what lies beyond).
"""

import numpy as np

__all__ = ['cast_shapes']


def cast_shapes(origin, ends, boxes=None, cylinders=None):
    """
    Return the first hit of each ray among boxes and cylinders.

    :param origin: (3,) start of every ray [m].
    :param ends: (n, 3) ends of the rays [m].
    :param boxes: (m, 7) boxes: centre x, y, z, yaw [rad], half length (along the yaw), half
        width, half height [m]; None or empty: none.
    :param cylinders: (k, 5) upright cylinders: centre x, y, z, radius, half height [m].
    :return: (fractions (n,) of the ray at its first hit, 1.0 for none; shapes (n,) int: the
        index of the hit shape, boxes first then cylinders (m + j), -1 for none; normals (n, 3):
        unit normal of the surface hit, zeros for none).
    """
    origin = np.asarray(origin, dtype=float)
    ray = np.asarray(ends, dtype=float) - origin
    count = len(ray)
    found = []
    if boxes is not None and len(boxes):
        found.append(_boxes(origin, ray, np.asarray(boxes, dtype=float)))
    if cylinders is not None and len(cylinders):
        found.append(_cylinders(origin, ray, np.asarray(cylinders, dtype=float)))
    fractions = np.ones(count)
    shapes = np.full(count, -1, dtype=np.int64)
    normals = np.zeros((count, 3))
    offset = 0
    for entry, normal, size in found:
        best = np.argmin(entry, axis=1) if size else np.zeros(count, dtype=np.intp)
        t = entry[np.arange(count), best]
        closer = t < fractions
        fractions[closer] = t[closer]
        shapes[closer] = best[closer] + offset
        normals[closer] = normal(np.flatnonzero(closer), best[closer], t[closer])
        offset += size
    return fractions, shapes, normals


def _slab(start, direction, half):
    # Entry and exit fractions of rays into the slabs |start + t direction| <= half, per ray
    # and shape ((n, m) each): a ray along the slab is in it for every t or for none.
    with np.errstate(divide='ignore', invalid='ignore'):
        low = (-half - start) / direction
        high = (half - start) / direction
    parallel = direction == 0.0
    inside = np.abs(start) <= half
    near = np.where(parallel, np.where(inside, -np.inf, np.inf), np.minimum(low, high))
    far = np.where(parallel, np.where(inside, np.inf, -np.inf), np.maximum(low, high))
    return near, far


def _entry(near, far):
    # The fraction where a ray enters a shape from its slabs' entry and exit, inf for none
    # (missed, behind the origin, past the end, or from inside).
    hit = (near <= far) & (near >= 0.0) & (near <= 1.0)
    return np.where(hit, near, np.inf)


def _boxes(origin, ray, boxes):
    # Each ray in each box's frame: its start and direction turned by -yaw about the centre.
    c, s = np.cos(boxes[:, 3]), np.sin(boxes[:, 3])
    rx, ry = origin[0] - boxes[:, 0], origin[1] - boxes[:, 1]
    start = np.stack([c * rx + s * ry, -s * rx + c * ry, origin[2] - boxes[:, 2]])  # (3, m)
    dx, dy = ray[:, 0:1], ray[:, 1:2]
    direction = np.stack([dx * c + dy * s, -dx * s + dy * c,
                          np.broadcast_to(ray[:, 2:3], (len(ray), len(boxes)))])  # (3, n, m)
    nears, fars = zip(*(_slab(start[axis], direction[axis], boxes[:, 4 + axis])
                        for axis in range(3)))
    near = np.max(nears, axis=0)
    entry = _entry(near, np.min(fars, axis=0))
    axis_in = np.argmax(nears, axis=0)             # the face it entered by

    def normal(rays, which, t):
        axis = axis_in[rays, which]
        sign = -np.sign(direction[axis, rays, which])
        sign[sign == 0.0] = 1.0
        cw, sw = c[which], s[which]
        local_x = np.where(axis == 0, sign, 0.0)
        local_y = np.where(axis == 1, sign, 0.0)
        return np.stack([cw * local_x - sw * local_y, sw * local_x + cw * local_y,
                         np.where(axis == 2, sign, 0.0)], axis=1)

    return entry, normal, len(boxes)


def _cylinders(origin, ray, cylinders):
    # The circle in the ground plane (a quadratic in t) and the slab of the height.
    px = origin[0] - cylinders[:, 0]                                 # (k,)
    py = origin[1] - cylinders[:, 1]
    radius = cylinders[:, 3]
    dx, dy = ray[:, 0:1], ray[:, 1:2]                                # (n, 1)
    a = dx * dx + dy * dy                                            # (n, 1)
    b = dx * px + dy * py                                            # (n, k): half of b
    c = px * px + py * py - radius * radius                          # (k,)
    disc = b * b - a * c
    with np.errstate(divide='ignore', invalid='ignore'):
        root = np.sqrt(np.maximum(disc, 0.0))
        side_near = np.where(disc >= 0.0, (-b - root) / a, np.inf)
        side_far = np.where(disc >= 0.0, (-b + root) / a, -np.inf)
    vertical = (a == 0.0) & np.ones_like(b, dtype=bool)
    side_near = np.where(vertical, np.where(c <= 0.0, -np.inf, np.inf), side_near)
    side_far = np.where(vertical, np.where(c <= 0.0, np.inf, -np.inf), side_far)
    z_near, z_far = _slab(origin[2] - cylinders[:, 2], ray[:, 2:3], cylinders[:, 4])
    near = np.maximum(side_near, z_near)
    entry = _entry(near, np.minimum(side_far, z_far))
    by_side = side_near >= z_near

    def normal(rays, which, t):
        side = by_side[rays, which]
        x = px[which] + t * ray[rays, 0]
        y = py[which] + t * ray[rays, 1]
        length = np.hypot(x, y)
        length[length == 0.0] = 1.0
        sign = -np.sign(ray[rays, 2])
        sign[sign == 0.0] = 1.0
        return np.stack([np.where(side, x / length, 0.0), np.where(side, y / length, 0.0),
                         np.where(side, 0.0, sign)], axis=1)

    return entry, normal, len(cylinders)
