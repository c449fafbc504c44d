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
sensor mounted inside or behind the body sees past it; the vehicle stands aside while they are
cast (World.rays_past_own: Bullet tests a ray against its shapes before the mask drops the
hit). In a world with an occupancy map (``World.ray_grids``, added by physics/map_layer.py) the
walls are found over the map's grid (core/map/grid_rays.py), and Bullet's rays, cast with the
walls' meshes they reach moved out of their way (World.rays_past_grids), stop where the walls
are: Bullet walks a static mesh's tree along the whole ray, past its first hit, so a large
map's meshes made each ray cost several times more (benchmarks/bench_occupancy_lidar.py).
:func:`cast_rays_hits` also gives what each ray hit (a labelled lidar's bodies and surface
normals).
"""

from itertools import chain
from operator import itemgetter

import numpy as np
import pybullet

# Rays per rayTestBatch call: PyBullet refuses more than 16384 and silently answers only 16383
# of exactly 16384 (pybullet 3.2.7), so batches stay below that.
MAX_BATCH = 16383
# the fields of a rayTestBatch result: (body, link, fraction, position, normal)
_BODY, _LINK, _FRACTION, _NORMAL = itemgetter(0), itemgetter(1), itemgetter(2), itemgetter(4)


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
    origin = np.asarray(origin, dtype=float)
    ends = np.asarray(ends, dtype=float)
    if len(ends) == 0:
        return np.ones(0)
    # the bodies placed now and then (traffic) put where they are where the rays go
    low, high = np.minimum(ends.min(axis=0), origin), np.maximum(ends.max(axis=0), origin)
    world.update_collision_state((low[0], low[1], high[0], high[1]))
    starts = [origin.tolist()] * len(ends)
    if not world.ray_grids:
        with world.rays_past_own(mask):
            return _fractions(world, starts, ends, mask)
    # The walls over their grid, then Bullet's rays up to them, the walls' meshes they reach
    # away.
    walls, _, near, reach = _cut_at_walls(world, origin, ends)
    with world.rays_past_grids(reach), world.rays_past_own(mask):
        fractions = _fractions(world, starts, near, mask)
    fractions *= walls          # a miss (1.0) gives the wall's own fraction, exactly
    return fractions


def _cut_at_walls(world, origin, ends):
    # The fraction of each ray where it meets a ray grid's wall, which grid's (None: the one
    # grid's), the rays cut there, and the box ((x, y, z) lowest, (x, y, z) highest) [m] that
    # holds them (GridRays.cast_cut).
    grids = world.ray_grids
    if len(grids) == 1:
        walls, near, box = grids[0].cast_cut(origin, ends)
        return walls, None, near, box.tolist()
    every = np.stack([grid.cast(origin, ends) for grid in grids])
    which = every.argmin(axis=0)
    walls = every[which, np.arange(len(ends))]
    near = origin + (ends - origin) * walls[:, None]
    box = [np.minimum(near.min(axis=0), origin).tolist(),
           np.maximum(near.max(axis=0), origin).tolist()]
    return walls, which, near, box


def cast_rays_hits(world, origin, ends, mask):
    """
    Cast rays from one origin; return what each hit: fractions, bodies, links and normals.

    As :func:`cast_rays`, and per ray the body id (-1: none) and link index of its hit and the
    unit normal of the surface there, world frame (rayTestBatch's). A ray that meets a ray
    grid's wall (an occupancy map's) hits the grid's first body (``World.ray_grid_bodies``,
    labelled as all of them) with the normal of the cell face it met (GridRays.normals).

    :return: (fractions (n,), bodies (n,) int, links (n,) int, normals (n, 3)).
    """
    origin = np.asarray(origin, dtype=float)
    ends = np.asarray(ends, dtype=float)
    starts = [origin.tolist()] * len(ends)
    if len(ends) == 0:
        return _hits(world, starts, ends, mask, world.labels.has_links)
    low, high = np.minimum(ends.min(axis=0), origin), np.maximum(ends.max(axis=0), origin)
    world.update_collision_state((low[0], low[1], high[0], high[1]))
    if not world.ray_grids:
        with world.rays_past_own(mask):
            return _hits(world, starts, ends, mask, world.labels.has_links)
    walls, which, near, reach = _cut_at_walls(world, origin, ends)
    if which is None:
        which = np.zeros(len(ends), dtype=np.intp)
    with world.rays_past_grids(reach), world.rays_past_own(mask):
        fractions, bodies, links, normals = _hits(world, starts, near, mask,
                                                  world.labels.has_links)
    grid = (fractions >= 1.0) & (walls < 1.0)
    if np.any(grid):
        grid_bodies = np.asarray(world.ray_grid_bodies)
        bodies[grid], links[grid] = grid_bodies[which[grid]], -1
        for index, rays in enumerate(world.ray_grids):
            mine = np.flatnonzero(grid & (which == index))
            if len(mine):
                normals[mine] = rays.normals(origin, ends[mine], walls[mine])
    return np.where(fractions < 1.0, fractions * walls, walls), bodies, links, normals


def _hits(world, starts, ends, mask, links=True):
    # rayTestBatch in chunks: per ray its fraction (1.0 for a miss), body, link (-1 without
    # ``links``) and normal, read out of PyBullet's result tuples by C iterators (a Python loop
    # over 30000 rays costs more than the labels are worth).
    count = len(ends)
    fractions = np.ones(count)
    bodies = np.full(count, -1, dtype=np.int64)
    parts = np.full(count, -1, dtype=np.int64)
    normals = np.zeros((count, 3))
    cid = world.client_id
    for first in range(0, count, MAX_BATCH):
        chunk = ends[first:first + MAX_BATCH].tolist()
        results = pybullet.rayTestBatch(starts[first:first + MAX_BATCH], chunk,
                                        collisionFilterMask=mask, physicsClientId=cid)
        size = len(results)
        end = first + size
        bodies[first:end] = np.fromiter(map(_BODY, results), np.int64, size)
        if links:
            parts[first:end] = np.fromiter(map(_LINK, results), np.int64, size)
        fractions[first:end] = np.fromiter(map(_FRACTION, results), np.float64, size)
        normals[first:end] = np.fromiter(chain.from_iterable(map(_NORMAL, results)),
                                         np.float64, 3 * size).reshape(size, 3)
    fractions[bodies < 0] = 1.0
    return fractions, bodies, parts, normals


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
