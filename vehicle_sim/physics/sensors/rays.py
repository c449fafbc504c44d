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
sensor mounted inside or behind the body sees past it.
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
    start = [float(v) for v in origin]
    ends = np.asarray(ends, dtype=float)
    count = len(ends)
    fractions = np.ones(count)
    cid = world.client_id
    for first in range(0, count, MAX_BATCH):
        chunk = ends[first:first + MAX_BATCH].tolist()
        results = pybullet.rayTestBatch([start] * len(chunk), chunk, collisionFilterMask=mask,
                                        physicsClientId=cid)
        fractions[first:first + len(chunk)] = [r[2] if r[0] >= 0 else 1.0 for r in results]
    return fractions
