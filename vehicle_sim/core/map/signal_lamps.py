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
What the traffic lights of a lane map look like: their lamps, housings and poles, engine-free.

Every Bulb of every TrafficLightGroup (``graph.rules``, core/map/lane_rules.py) is one lamp: a
sphere of ``LAMP_RADIUS_M`` at the bulb's position, in front of a dark housing box
(``HOUSING_DEPTH_M`` deep, ``HOUSING_SIDE_M`` wide and high) that stands behind it. A lamp
faces the traffic it governs: against the direction of its group's lanes at their stop line
(the first lane's end when the group has no stop line). Lamps whose bulbs lie within
``CLUSTER_M`` of each other (seen from above) are one light on one pole: a box
``POLE_WIDTH_M`` square from the ground to the top of the light's highest housing, behind it;
a light over a lane (on a mast arm or gantry in the real world) gets no pole, so that nothing
stands in the road.

A lamp is lit in its colour when its group's state is its bulb's colour (a red state lights
the red bulbs, ...; 'off' none) and dark grey otherwise (:func:`lamp_color`). The physics
(physics/signal_lamps.py) and the Foxglove scene (foxglove/map_scene.py) draw these values.
"""

from dataclasses import dataclass
import math
from typing import Dict, List, Sequence, Tuple

import numpy as np

from vehicle_sim.core.geometry.angles import wrap_angle_rad
from vehicle_sim.core.map.lane_geometry import Mesh
from vehicle_sim.core.map.lane_rules import Bulb

LAMP_RADIUS_M = 0.12
HOUSING_DEPTH_M = 0.25
HOUSING_SIDE_M = 0.36
POLE_WIDTH_M = 0.15
CLUSTER_M = 1.0
# RGBA of a lit lamp by bulb colour, of a dark lamp, the housing and the pole.
LAMP_COLORS = {'red': (1.0, 0.1, 0.05, 1.0), 'yellow': (1.0, 0.75, 0.0, 1.0),
               'green': (0.05, 0.9, 0.25, 1.0)}
DARK_LAMP_COLOR = (0.2, 0.2, 0.2, 1.0)
HOUSING_COLOR = (0.05, 0.05, 0.06, 1.0)
POLE_COLOR = (0.45, 0.45, 0.48, 1.0)
# The faces of a box from its 8 corners (0..3 at the bottom, 4..7 on top, counter-clockwise
# seen from above): bottom, four sides and top, two triangles each, facing out.
CLOSED_BOX_TRIANGLES = np.array(
    [[0, 2, 1], [0, 3, 2], [0, 1, 5], [0, 5, 4], [1, 2, 6], [1, 6, 5], [2, 3, 7], [2, 7, 6],
     [3, 0, 4], [3, 4, 7], [4, 5, 6], [4, 6, 7]], dtype=np.int64)


@dataclass(frozen=True)
class Lamp:
    """
    One bulb as drawn.

    :param group_id: its TrafficLightGroup's id.
    :param bulb: the Bulb (colour, shape, position [m]).
    :param yaw_rad: the direction it shines to (towards the traffic it governs) [rad].
    """

    group_id: int
    bulb: Bulb
    yaw_rad: float

    @property
    def housing_centre_m(self) -> Tuple[float, float, float]:
        """The centre of its housing box: behind the bulb, half the housing's depth [m]."""
        back = 0.5 * HOUSING_DEPTH_M
        return (self.bulb.x_m - back * math.cos(self.yaw_rad),
                self.bulb.y_m - back * math.sin(self.yaw_rad), self.bulb.z_m)

    @property
    def housing_size_m(self) -> Tuple[float, float, float]:
        """The housing box's size along the lamp's direction, across it and up [m]."""
        return (HOUSING_DEPTH_M, HOUSING_SIDE_M, HOUSING_SIDE_M)


@dataclass(frozen=True)
class Pole:
    """A light's pole: a box ``POLE_WIDTH_M`` square centred at (x, y), ``height_m`` high."""

    x_m: float
    y_m: float
    height_m: float


def lit(bulb_color: str, state: str) -> bool:
    """Return whether a bulb of ``bulb_color`` is lit in a group state (SIGNAL_STATES)."""
    return state == bulb_color


def lamp_color(bulb_color: str, state: str):
    """Return the RGBA of a bulb of ``bulb_color`` when its group is in ``state``."""
    return LAMP_COLORS[bulb_color] if lit(bulb_color, state) else DARK_LAMP_COLOR


def _facing(graph, group, lines) -> float:
    # The lamps look against the traffic of the group's first stop line's lane (or first lane);
    # ``lines``: {id: StopLine} of the rules.
    for line_id in group.stop_lines:
        line = lines.get(line_id)
        if line is not None:
            return graph.lanes[line.lane_id].centre_pose(line.s_m)[2] + math.pi
    lane = graph.lanes[group.lanes[0]] if group.lanes else None
    return 0.0 if lane is None else lane.centre_pose(lane.length_m)[2] + math.pi


def lamps(graph) -> Tuple[Lamp, ...]:
    """Return every bulb of the lane map's traffic light groups as a Lamp, in group order."""
    found = []
    lines = {line.id: line for line in graph.rules.stop_lines}
    for group in graph.rules.groups:
        if group.bulbs:
            yaw = wrap_angle_rad(_facing(graph, group, lines))
            found.extend(Lamp(group.id, bulb, yaw) for bulb in group.bulbs)
    return tuple(found)


def lamp_clusters(found: Sequence[Lamp]) -> List[List[Lamp]]:
    """
    Return the lights: the lamps clustered, in order.

    Each lamp joins the first cluster with a lamp within ``CLUSTER_M`` of it (seen from above),
    else starts one. The clusters near a lamp are found through a grid of ``CLUSTER_M`` cells
    (a city's thousands of lamps in linear time).
    """
    clusters: List[List[Lamp]] = []
    cells: Dict[Tuple[int, int], List[int]] = {}      # cell -> clusters with a lamp in it
    for lamp in found:
        x, y = lamp.bulb.x_m, lamp.bulb.y_m
        i, j = math.floor(x / CLUSTER_M), math.floor(y / CLUSTER_M)
        near = sorted({k for di in (-1, 0, 1) for dj in (-1, 0, 1)
                       for k in cells.get((i + di, j + dj), ())})
        joined = next((k for k in near if any(
            math.hypot(x - o.bulb.x_m, y - o.bulb.y_m) <= CLUSTER_M for o in clusters[k])),
            None)
        if joined is None:
            joined = len(clusters)
            clusters.append([])
        clusters[joined].append(lamp)
        members = cells.setdefault((i, j), [])
        if joined not in members:
            members.append(joined)
    return clusters


def poles(graph, found: Tuple[Lamp, ...]) -> Tuple[Pole, ...]:
    """Return the poles of the lights (lamps within ``CLUSTER_M``) that stand off every lane."""
    clusters = lamp_clusters(found)
    result = []
    for cluster in clusters:
        centres = [lamp.housing_centre_m for lamp in cluster]
        yaw = cluster[0].yaw_rad
        back = 0.5 * (HOUSING_DEPTH_M + POLE_WIDTH_M)
        x = sum(c[0] for c in centres) / len(centres) - back * math.cos(yaw)
        y = sum(c[1] for c in centres) / len(centres) - back * math.sin(yaw)
        height = max(c[2] for c in centres) + 0.5 * HOUSING_SIDE_M
        if height > 0.0 and graph.locate(x, y) is None:
            result.append(Pole(x, y, height))
    return tuple(result)


def box_corners(centres, sizes, yaws) -> np.ndarray:
    """Return float (n, 8, 3): the corners of boxes (centre, size along x y z, yaw) [m]."""
    centres = np.asarray(centres, float).reshape(-1, 3)
    half = 0.5 * np.asarray(sizes, float).reshape(-1, 3)
    yaws = np.asarray(yaws, float).reshape(-1)
    signs = np.array([(-1, -1), (1, -1), (1, 1), (-1, 1)], dtype=float)
    c, s = np.cos(yaws)[:, None], np.sin(yaws)[:, None]
    local_x, local_y = signs[None, :, 0] * half[:, :1], signs[None, :, 1] * half[:, 1:2]
    ground = np.stack((centres[:, :1] + c * local_x - s * local_y,
                       centres[:, 1:2] + s * local_x + c * local_y), axis=-1)
    corners = np.empty((len(centres), 8, 3))
    corners[:, :4, :2] = corners[:, 4:, :2] = ground
    corners[:, :4, 2] = (centres[:, 2] - half[:, 2])[:, None]
    corners[:, 4:, 2] = (centres[:, 2] + half[:, 2])[:, None]
    return corners


def housing_corners(found: Sequence[Lamp]) -> np.ndarray:
    """Return the corners (n, 8, 3) of the lamps' housing boxes [m]."""
    return box_corners([lamp.housing_centre_m for lamp in found],
                       [lamp.housing_size_m for lamp in found],
                       [lamp.yaw_rad for lamp in found])


def pole_corners(standing: Sequence[Pole]) -> np.ndarray:
    """Return the corners (n, 8, 3) of the poles' boxes [m]."""
    return box_corners([(p.x_m, p.y_m, 0.5 * p.height_m) for p in standing],
                       [(POLE_WIDTH_M, POLE_WIDTH_M, p.height_m) for p in standing],
                       [0.0] * len(standing))


def box_mesh(corners) -> Mesh:
    """Return closed boxes (their corners, (n, 8, 3)) as one triangle mesh."""
    corners = np.asarray(corners, float).reshape(-1, 8, 3)
    triangles = CLOSED_BOX_TRIANGLES[None, :, :] + 8 * np.arange(len(corners))[:, None, None]
    return Mesh(corners.reshape(-1, 3), triangles.reshape(-1, 3))


def lamp_mesh(subdivisions: int = 1) -> Mesh:
    """
    Return a lamp: a sphere of ``LAMP_RADIUS_M`` about the origin, an icosphere [m].

    One subdivision of the icosahedron: 42 vertices, 80 triangles (PyBullet's own sphere
    has several hundred, and PyBullet builds them for every body).
    """
    t = 0.5 * (1.0 + math.sqrt(5.0))
    points = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
              (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    vertices = [np.array(p, float) / np.linalg.norm(p) for p in points]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
             (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
             (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(subdivisions):
        middle = {}

        def between(a, b):
            key = (min(a, b), max(a, b))
            if key not in middle:
                point = vertices[a] + vertices[b]
                vertices.append(point / np.linalg.norm(point))
                middle[key] = len(vertices) - 1
            return middle[key]
        split = []
        for a, b, c in faces:
            ab, bc, ca = between(a, b), between(b, c), between(c, a)
            split += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = split
    return Mesh(LAMP_RADIUS_M * np.array(vertices), np.array(faces, dtype=np.int64))
