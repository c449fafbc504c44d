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
Lanes in the physics world: the road surface and its markings, drawn, and the barriers, solid.

A world's lane map (``spec.lanes``: a LaneGraph from a lanelet2 map, a SUMO network or
``roads:``, loaded by vehicle_sim/maps/lane_maps.py before the bodies) becomes, through
core/map/lane_geometry.py:

- the road surface and the painted lines, and the rules' paint and areas (``graph.rules``:
  stop lines as white bars, crosswalks as zebra stripes, the other areas flat in their kind's
  colour, core/map/lane_geometry.py): a few visual-only meshes just above the ground (no
  collision shape: cars drive on the ground plane as before, rays pass through, cameras see
  them), one body per colour and label (the lines' paint in one, the crosswalks' in another;
  :data:`AREA_LABELS`) and per VERTICES_PER_BODY vertices; the same meshes as a raster of
  labels (core/map/surface_raster.py, ``World.labels.add_surface``) for the rays, which pass
  them and meet the ground plane;
- curbstones, road borders and walls/fences/guard rails: one box per line piece
  (``BARRIER_WIDTH_M`` wide, the height of its type), merged into static triangle meshes as the
  occupancy grid's walls are, named ``lanes`` through ``World.add_static`` (collisions report
  ``other: lanes``, rays and teleport checks see them).

A lane map of a ``map:`` key (lanelet2, a SUMO network) is built by :func:`build_lane_map`
(its kind's row of ``MAP_BUILDERS`` in physics/map_layer.py, ``scene.parts['map']``), a
world's ``roads:`` by the :class:`RoadLayer` scene part (``scene.parts['roads']``); both
return a :class:`LaneMap`. A world without a lane map gets neither and pays nothing.
"""

from dataclasses import dataclass
from typing import Optional, Tuple

import numpy as np
import pybullet

from vehicle_sim.core.map.lane_geometry import (
    area_color,
    area_meshes,
    BARRIER_WIDTH_M,
    barriers,
    crosswalk_mesh,
    join_meshes,
    marking_mesh,
    Mesh,
    PAINT_COLOR,
    stop_line_mesh,
    surface_mesh,
)
from vehicle_sim.core.map.lane_graph import LaneGraph
from vehicle_sim.core.map.surface_raster import SurfaceRaster
from vehicle_sim.core.sensors.labels import LABEL_IDS
from vehicle_sim.core.specs.value_text import count

LANES_BODY_NAME = 'lanes'
SURFACE_COLOR = (0.3, 0.3, 0.32, 1.0)     # asphalt
MARKING_COLOR = PAINT_COLOR               # white paint
BARRIER_COLOR = (0.7, 0.7, 0.68, 1.0)     # concrete
# The label (core/sensors/labels.py) of the areas drawn flat, by MapArea kind; any other kind
# (parking, keepout, a regulatory element's area) lies on the road: 'road'. The road surface
# (junctions included) is 'road', the painted lines and stop lines 'lane_marking', crosswalks'
# stripes 'crosswalk', the barriers 'wall'.
AREA_LABELS = {'walkway': 'sidewalk', 'sidewalk': 'sidewalk', 'building': 'wall'}
# Vertices of one mesh body (PyBullet takes at most 131072 per mesh).
VERTICES_PER_BODY = 65536
# The faces of a box from its 8 corners (0..3 at the ground, 4..7 on top, counter-clockwise
# seen from above): four sides and the top, two triangles each, facing out.
BOX_TRIANGLES = np.array([[0, 1, 5], [0, 5, 4], [1, 2, 6], [1, 6, 5], [2, 3, 7], [2, 7, 6],
                          [3, 0, 4], [3, 4, 7], [4, 5, 6], [4, 6, 7]], dtype=np.int64)


@dataclass(eq=False)
class LaneMap:
    """
    A built lane map: what the ROS layer publishes, the Webots facade and scenarios read.

    :param spec: the world's ``map:`` spec (a lane map kind's), or None for ``roads:``.
    :param lanes: the LaneGraph.
    :param visual_ids: the bodies of the road surface and the markings (visual only).
    :param barrier_ids: the static collision bodies of the barriers.
    :param barrier_count: the barrier pieces (boxes) in them.
    """

    spec: object
    lanes: LaneGraph
    visual_ids: Tuple[int, ...] = ()
    barrier_ids: Tuple[int, ...] = ()
    barrier_count: int = 0

    def wall_boxes(self):
        """None: a lane map's barriers are drawn and measured with its lanes."""
        return None

    def describe(self) -> str:
        """One line for logs: where the lanes come from, how many, the barriers."""
        return (f"{self.lanes.source}: {count(len(self.lanes.lanes), 'lane', 'lanes')}, "
                f"{count(len(self.lanes.boundaries()), 'boundary', 'boundaries')}, "
                f"{count(self.barrier_count, 'barrier piece', 'barrier pieces')}")


def _chunks(mesh: Mesh):
    # (vertices, indices) lists of at most VERTICES_PER_BODY vertices each, whole triangles.
    triangles = mesh.triangles
    per_chunk = max(1, VERTICES_PER_BODY // 3)
    for start in range(0, len(triangles), per_chunk):
        part = triangles[start:start + per_chunk]
        used, local = np.unique(part.reshape(-1), return_inverse=True)
        yield mesh.vertices[used].tolist(), local.astype(np.int64).tolist()


def visual_body(world, visual, position=(0.0, 0.0, 0.0)) -> int:
    """
    Return a visual-only static body of a visual shape: drawn, and free for the physics step.

    Nothing collides with it and rays pass it. It is a Bullet rigid body put to sleep (a
    multibody, PyBullet's default, costs every step about 1 us, even static and shapeless).
    """
    cid = world.client_id
    body_id = pybullet.createMultiBody(0.0, -1, visual, basePosition=list(position),
                                       useMaximalCoordinates=True, physicsClientId=cid)
    pybullet.changeDynamics(body_id, -1, activationState=pybullet.ACTIVATION_STATE_SLEEP,
                            physicsClientId=cid)
    return body_id


def visual_bodies(world, mesh: Mesh, rgba) -> Tuple[int, ...]:
    """Return visual-only static bodies of a mesh (:func:`visual_body`)."""
    cid, ids = world.client_id, []
    for vertices, indices in _chunks(mesh):
        visual = pybullet.createVisualShape(pybullet.GEOM_MESH, vertices=vertices,
                                            indices=indices, rgbaColor=list(rgba),
                                            physicsClientId=cid)
        ids.append(visual_body(world, visual))
    return tuple(ids)


def label_bodies(world, body_ids, label) -> Tuple[int, ...]:
    """Give ``body_ids`` the label ``label`` (``World.labels``, no instance); return them."""
    for body_id in body_ids:
        world.labels.set(body_id, label)
    return tuple(body_ids)


def barrier_boxes(graph: LaneGraph) -> np.ndarray:
    """Return float (n, 8, 3): the corners of every barrier piece's box, world frame [m]."""
    pieces = barriers(graph)
    if not pieces:
        return np.zeros((0, 8, 3))
    a = np.array([(p.x0_m, p.y0_m) for p in pieces])
    b = np.array([(p.x1_m, p.y1_m) for p in pieces])
    height = np.array([p.height_m for p in pieces])
    d = b - a
    d /= np.maximum(np.hypot(d[:, 0], d[:, 1]), 1e-12)[:, None]
    n = 0.5 * BARRIER_WIDTH_M * np.column_stack((-d[:, 1], d[:, 0]))
    ground = np.stack([a - n, b - n, b + n, a + n], axis=1)       # counter-clockwise
    corners = np.empty((len(pieces), 8, 3))
    corners[:, :4, :2] = corners[:, 4:, :2] = ground
    corners[:, :4, 2] = 0.0
    corners[:, 4:, 2] = height[:, None]
    return corners


def solid_box_bodies(world, corners, rgba=BARRIER_COLOR) -> Tuple[int, ...]:
    """
    Return static triangle-mesh bodies (Bullet's BVH meshes) of boxes, as a map's walls are.

    :param corners: float (n, 8, 3): each box's corners as :func:`barrier_boxes` gives them.
    """
    cid, ids = world.client_id, []
    per_body = VERTICES_PER_BODY // 8
    for start in range(0, len(corners), per_body):
        chunk = corners[start:start + per_body]
        vertices = chunk.reshape(-1, 3).tolist()
        indices = (BOX_TRIANGLES.reshape(-1)[None, :]
                   + 8 * np.arange(len(chunk))[:, None]).ravel().tolist()
        collision = pybullet.createCollisionShape(
            pybullet.GEOM_MESH, vertices=vertices, indices=indices,
            flags=pybullet.GEOM_FORCE_CONCAVE_TRIMESH, physicsClientId=cid)
        visual = pybullet.createVisualShape(pybullet.GEOM_MESH, vertices=vertices,
                                            indices=indices, rgbaColor=list(rgba),
                                            physicsClientId=cid)
        ids.append(pybullet.createMultiBody(0.0, collision, visual, physicsClientId=cid))
    return tuple(ids)


def inside_boxes(corners):
    """Return ``blocked(x, y)``: the point lies within a box's footprint (None: no boxes)."""
    if len(corners) == 0:
        return None
    a = corners[:, 0, :2]
    u = corners[:, 1, :2] - a
    v = corners[:, 3, :2] - a
    uu, vv = (u * u).sum(axis=1), (v * v).sum(axis=1)

    def blocked(x_m, y_m):
        rel = np.array((x_m, y_m)) - a
        s, t = (rel * u).sum(axis=1) / uu, (rel * v).sum(axis=1) / vv
        return bool(np.any((s >= 0.0) & (s <= 1.0) & (t >= 0.0) & (t <= 1.0)))
    return blocked


def build_lane_bodies(world, graph: LaneGraph, spec=None) -> LaneMap:
    """
    Draw a lane map's surface and markings into ``world`` and build its barriers.

    :param spec: the map spec it comes from (None: ``roads:``).
    :raises InvalidPoseError: a vehicle that starts inside a barrier (nothing is kept).
    """
    corners = barrier_boxes(graph)
    barrier_ids = solid_box_bodies(world, corners)
    if barrier_ids:
        world.add_static(LANES_BODY_NAME, barrier_ids, inside_boxes(corners))
    label_bodies(world, barrier_ids, 'wall')
    # (label, mesh, colour) from the bottom layer up, as drawn
    layers = [('road', surface_mesh(graph), SURFACE_COLOR)]
    layers += [(AREA_LABELS.get(kind, 'road'), mesh, area_color(kind))
               for kind, mesh in area_meshes(graph).items()]
    layers += [('lane_marking', join_meshes(marking_mesh(graph), stop_line_mesh(graph)),
                MARKING_COLOR), ('crosswalk', crosswalk_mesh(graph), MARKING_COLOR)]
    visual_ids = ()
    for label, mesh, colour in layers:
        visual_ids += label_bodies(world, visual_bodies(world, mesh, colour), label)
    # rays pass the drawn meshes: a ray that meets the ground under them reads them from here
    world.labels.add_surface(SurfaceRaster([(LABEL_IDS[label], mesh.vertices, mesh.triangles)
                                            for label, mesh, _ in layers]))
    return LaneMap(spec, graph, visual_ids, barrier_ids, len(corners))


def build_lane_map(world, spec) -> LaneMap:
    """Build a lane map's lanes into ``world`` (the lane map kinds' ``MAP_BUILDERS`` row)."""
    return build_lane_bodies(world, spec.lanes, spec.map)


class RoadLayer:
    """The scene part of a world's ``roads:``: builds its lanes' bodies (``parts['roads']``)."""

    name = 'roads'

    def build(self, world, spec) -> Optional[LaneMap]:
        if not spec.roads or spec.lanes is None:
            return None
        return build_lane_bodies(world, spec.lanes)
