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
Rays against boxes turned about z and upright cylinders (core/geometry/ray_shapes.py) vs Bullet.

Bullet's ray test (rayTestBatch) is the reference, on random scenes of boxes of traffic sizes
and persons' cylinders, rays in every direction and up to 35 degrees up or down, from outside
every shape and from inside one (neither sees that one: the ray meets what lies beyond): the
same shape for every ray; on a box the same distance to within 1e-9 m and the same surface
normal; on a cylinder ours exactly on its surface, Bullet's within its convex cast's tolerance
(2 cm) of ours; except rays that graze an edge (Bullet's hit up to 1 mm off
the shape's face there: each such one is checked to lie within 1 mm of an edge, both answers
agreeing once the shapes grow by 1 mm).
"""

import numpy as np
import pybullet
import pytest

from vehicle_sim.core.geometry.ray_shapes import cast_shapes

RANGE_M = 30.0
EDGE_M = 1.0e-3          # how far Bullet's hit may lie off a shape's face where a ray grazes
CYLINDER_M = 0.02        # how far Bullet's hit on a cylinder may lie off it (its convex cast)


def _scene(seed):
    # Random boxes (centre x, y, z, yaw, half length, width, height) and cylinders (x, y, z,
    # radius, half height) in Bullet; return them, their body ids (boxes first) and the client.
    cid = pybullet.connect(pybullet.DIRECT)
    rng = np.random.default_rng(seed)
    boxes, cylinders, ids = [], [], []
    for _ in range(40):
        x, y = rng.uniform(-25.0, 25.0, 2)
        yaw = rng.uniform(-np.pi, np.pi)
        half = (rng.uniform(0.3, 6.0), rng.uniform(0.3, 1.5), rng.uniform(0.5, 1.8))
        z = half[2] + rng.uniform(0.0, 0.3)
        shape = pybullet.createCollisionShape(pybullet.GEOM_BOX, halfExtents=half,
                                              physicsClientId=cid)
        ids.append(pybullet.createMultiBody(
            0.0, shape, -1, [x, y, z], pybullet.getQuaternionFromEuler([0.0, 0.0, yaw]),
            physicsClientId=cid))
        boxes.append((x, y, z, yaw, *half))
    for _ in range(20):
        x, y = rng.uniform(-10.0, 10.0, 2)
        radius, half = rng.uniform(0.2, 0.5), rng.uniform(0.7, 1.0)
        shape = pybullet.createCollisionShape(pybullet.GEOM_CYLINDER, radius=radius,
                                              height=2.0 * half, physicsClientId=cid)
        ids.append(pybullet.createMultiBody(0.0, shape, -1, [x, y, half],
                                            physicsClientId=cid))
        cylinders.append((x, y, half, radius, half))
    pybullet.performCollisionDetection(physicsClientId=cid)
    return np.array(boxes), np.array(cylinders), np.array(ids), cid


def _rays(origin, count, seed):
    rng = np.random.default_rng(seed)
    azimuth = rng.uniform(-np.pi, np.pi, count)
    elevation = rng.uniform(-0.6, 0.6, count)
    return origin + RANGE_M * np.stack([np.cos(elevation) * np.cos(azimuth),
                                        np.cos(elevation) * np.sin(azimuth),
                                        np.sin(elevation)], axis=1)


def _bullet(cid, origin, ends):
    results = pybullet.rayTestBatch([list(origin)] * len(ends), ends.tolist(),
                                    physicsClientId=cid)
    bodies = np.array([r[0] for r in results])
    fractions = np.array([r[2] if r[0] >= 0 else 1.0 for r in results])
    normals = np.array([r[4] for r in results])
    return fractions, bodies, normals


def _grown(boxes, cylinders):
    boxes, cylinders = boxes.copy(), cylinders.copy()
    boxes[:, 4:] += EDGE_M
    cylinders[:, 3:] += EDGE_M
    return boxes, cylinders


@pytest.mark.parametrize('seed', [1, 2, 3])
def test_rays_against_boxes_and_cylinders_are_bullets(seed):
    boxes, cylinders, ids, cid = _scene(seed)
    try:
        origins = [np.array([0.3, -0.2, 0.9]),
                   boxes[0, :3] + np.array([0.1, -0.05, 0.2])]      # inside the first box
        cylinder_hits = 0
        for index, origin in enumerate(origins):
            ends = _rays(origin, 4000, seed * 10 + index)
            want, want_bodies, want_normals = _bullet(cid, origin, ends)
            fractions, shapes, normals = cast_shapes(origin, ends, boxes, cylinders)
            bodies = np.where(shapes >= 0, ids[np.maximum(shapes, 0)], -1)
            assert (want_bodies >= 0).sum() > 200                   # the rays meet shapes
            hit = want_bodies >= 0
            error = np.abs(fractions - want) * RANGE_M
            cosine = np.einsum('ij,ij->i', normals, want_normals)
            box = shapes < len(boxes)
            # boxes: Bullet's answer to 1e-9 m (its box ray test is exact)
            same = (bodies == want_bodies) & (error <= 1e-9) & (~hit | (cosine >= 1.0 - 1e-9))
            # cylinders: Bullet's convex cast stops within its tolerance (about 1 cm) of the
            # surface; ours is on it
            cylinder = (bodies == want_bodies) & hit & ~box
            assert np.all(error[cylinder] <= CYLINDER_M) and np.all(cosine[cylinder] > 0.99)
            cylinder_hits += cylinder.sum()
            rays = np.flatnonzero(cylinder)
            points = origin + (ends[rays] - origin) * fractions[rays, None]
            centres = cylinders[shapes[rays] - len(boxes)]
            side = np.hypot(points[:, 0] - centres[:, 0], points[:, 1] - centres[:, 1])
            cap = np.abs(points[:, 2] - centres[:, 2])
            assert np.all(np.minimum(np.abs(side - centres[:, 3]),
                                     np.abs(cap - centres[:, 4])) <= 1e-9)
            edge = ~same & ~cylinder
            assert edge.sum() <= 0.002 * len(ends), edge.sum()
            # each that differs grazes an edge: with the shapes 1 mm larger both agree
            wide, _, _ = cast_shapes(origin, ends[edge], *_grown(boxes, cylinders))
            assert np.all(np.abs(np.minimum(wide, fractions[edge]) - np.minimum(
                wide, want[edge])) * RANGE_M <= 2.0 * EDGE_M)
        assert cylinder_hits > 20
    finally:
        pybullet.disconnect(physicsClientId=cid)


def test_rays_along_faces_and_straight_down():
    # axis-aligned rays (zero components: the slabs' parallel case) and a vertical ray onto a
    # cylinder's top and into a box's top
    boxes = np.array([[10.0, 0.0, 1.0, 0.0, 2.0, 1.0, 0.8]])
    cylinders = np.array([[0.0, 10.0, 0.9, 0.25, 0.9]])
    origin = np.zeros(3) + [0.0, 0.0, 1.0]
    ends = np.array([[30.0, 0.0, 1.0], [0.0, 30.0, 1.0], [-30.0, 0.0, 1.0]])
    fractions, shapes, normals = cast_shapes(origin, ends, boxes, cylinders)
    np.testing.assert_allclose(fractions[:2] * 30.0, [8.0, 9.75])
    assert shapes.tolist() == [0, 1, -1]
    np.testing.assert_allclose(normals[:2], [[-1.0, 0.0, 0.0], [0.0, -1.0, 0.0]])
    for y, found in ((1.0, 0), (1.0001, -1)):         # along the box's side face, and past it
        fractions, shapes, _ = cast_shapes([0.0, y, 1.0], [[30.0, y, 1.0]], boxes)
        assert shapes.tolist() == [found]
    down = np.array([[10.0, 0.0, 5.0], [0.0, 10.0, 5.0]])
    fractions, shapes, normals = cast_shapes(down[0], down[:1] - [0.0, 0.0, 5.0], boxes)
    np.testing.assert_allclose(fractions * 5.0, [3.2])
    np.testing.assert_allclose(normals, [[0.0, 0.0, 1.0]])
    fractions, shapes, normals = cast_shapes(down[1], down[1:] - [0.0, 0.0, 5.0],
                                             None, cylinders)
    np.testing.assert_allclose(fractions * 5.0, [3.2])
    assert shapes.tolist() == [0]
    np.testing.assert_allclose(normals, [[0.0, 0.0, 1.0]])
