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
Ray casting for the lidar and the distance sensor (PyBullet rayTestBatch).

Rays use a collision mask that skips the sensor's own vehicle (World.ray_mask_excluding), so a
sensor mounted inside or behind the body sees past it. In a world with map walls
(``World.ray_split_m`` set by physics/map_layer.py) each ray is cast up to that distance first
and on from there only where it hit nothing: Bullet walks a static mesh's tree along the whole
ray, so long rays in a dense map cost about 2 us more each (benchmarks/bench_maps.py); the hits
are the same (on curved convex shapes within Bullet's ray-cast precision, about 1 mm).
"""

import numpy as np
import pybullet

# Rays per rayTestBatch call: PyBullet refuses more than 16384 and silently answers only 16383
# of exactly 16384 (pybullet 3.2.7), so batches stay below that.
MAX_BATCH = 16383


def cast_rays(world, origin, ends, mask):
    """
    Cast rays from one origin and return the hit fraction of each.

    :param world: the World.
    :param origin: (3,) start of every ray in the world [m].
    :param ends: (n, 3) ends of the rays in the world [m].
    :param mask: collision filter mask of the rays.
    :return: (n,) fractions of the ray length at the first hit; 1.0 where nothing was hit
        (PyBullet reports misses with object id -1 and fraction 1).
    """
    world.update_collision_state()
    origin = np.asarray(origin, dtype=float)
    ends = np.asarray(ends, dtype=float)
    split_m = world.ray_split_m
    if split_m is None or len(ends) < 2:
        return _fractions(world, [origin.tolist()] * len(ends), ends, mask)
    # Near, then far: Bullet walks a static mesh's tree along the whole ray, not only up to its
    # first hit, so in a world with map walls each ray is cast up to split_m first, and only
    # the rays that hit nothing there go on from that point to their end.
    vectors = ends - origin
    scale = np.minimum(split_m / np.maximum(np.linalg.norm(vectors, axis=1), 1e-12), 1.0)
    middles = origin + vectors * scale[:, None]
    fractions = _fractions(world, [origin.tolist()] * len(ends), middles, mask) * scale
    far = (fractions >= scale) & (scale < 1.0)
    if far.any():
        rest = _fractions(world, middles[far].tolist(), ends[far], mask)
        fractions[far] = np.where(rest < 1.0, scale[far] + rest * (1.0 - scale[far]), 1.0)
    return fractions


def _fractions(world, starts, ends, mask):
    # rayTestBatch in chunks: the hit fraction of each ray, 1.0 for a miss.
    count = len(ends)
    fractions = np.ones(count)
    cid = world.client_id
    for first in range(0, count, MAX_BATCH):
        chunk = ends[first:first + MAX_BATCH].tolist()
        results = pybullet.rayTestBatch(starts[first:first + MAX_BATCH], chunk,
                                        collisionFilterMask=mask, physicsClientId=cid)
        fractions[first:first + len(chunk)] = [r[2] if r[0] >= 0 else 1.0 for r in results]
    return fractions
