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
The plain values a Foxglove scene is described with, SDK-free: :class:`Entity` and its shapes.

An entity holds any of: :class:`Primitive` shapes (cubes, cylinders, spheres, each posed and
sized), :class:`Lines` (a line strip or a line list of points) and :class:`Triangles` (a
triangle list, indexed). :mod:`.scene_messages` turns them into Foxglove's ``SceneEntity``
(``CubePrimitive``, ``LinePrimitive``, ``TriangleListPrimitive``, ...).
"""

from dataclasses import dataclass
from typing import Tuple

import numpy as np

WORLD_FRAME = 'world'

Vector = Tuple[float, float, float]
Quaternion = Tuple[float, float, float, float]
Color = Tuple[float, float, float, float]
IDENTITY = (0.0, 0.0, 0.0, 1.0)
LINE_KINDS = ('line_strip', 'line_list')


def _points(points, what) -> np.ndarray:
    array = np.asarray(points, dtype=float)
    if array.ndim != 2 or array.shape[1] != 3:
        raise ValueError(f'{what}: expected (N, 3) points [m], got shape {array.shape}')
    return array


@dataclass(frozen=True)
class Primitive:
    """
    One shape: ``kind`` 'cube', 'cylinder' (axis along its z) or 'sphere'.

    :param position_m: its centre in the entity's frame [m].
    :param orientation: (x, y, z, w).
    :param size_m: its full extents along its own x, y, z [m].
    :param color_rgba: [0, 1] each.
    """

    kind: str
    position_m: Vector
    orientation: Quaternion
    size_m: Vector
    color_rgba: Color


@dataclass(frozen=True, eq=False)
class Lines:
    """
    Lines through points of the entity's frame.

    :param kind: 'line_strip' (each point joined to the next) or 'line_list' (points taken in
        pairs, each pair one segment: dashes).
    :param points_m: float (N, 3) [m].
    :param thickness_m: the line's width in the world [m] (it scales with the distance).
    :param color_rgba: [0, 1] each.
    """

    kind: str
    points_m: np.ndarray
    thickness_m: float
    color_rgba: Color

    def __post_init__(self):
        if self.kind not in LINE_KINDS:
            raise ValueError(f'lines kind {self.kind!r}; known: {", ".join(LINE_KINDS)}')
        points = _points(self.points_m, 'lines points_m')
        if self.kind == 'line_list' and len(points) % 2:
            raise ValueError(f'a line list takes points in pairs; got {len(points)} points')
        object.__setattr__(self, 'points_m', points)


@dataclass(frozen=True, eq=False)
class Triangles:
    """
    A triangle list: ``points_m`` float (N, 3) [m], ``indices`` int (M, 3) into them.

    :param color_rgba: [0, 1] each, the whole surface.
    """

    points_m: np.ndarray
    indices: np.ndarray
    color_rgba: Color

    def __post_init__(self):
        points = _points(self.points_m, 'triangles points_m')
        indices = np.asarray(self.indices, dtype=np.int64).reshape(-1, 3) \
            if np.size(self.indices) % 3 == 0 else None
        if indices is None or (indices.size and (indices.min() < 0
                                                 or indices.max() >= len(points))):
            raise ValueError(f'triangles indices must be triples into the {len(points)} points')
        object.__setattr__(self, 'points_m', points)
        object.__setattr__(self, 'indices', indices)


@dataclass(frozen=True)
class Entity:
    """
    A scene entity: its id (unique in the scene), frame and shapes.

    The same id sent again replaces the entity (a moving body: the same id, a new pose each
    frame).
    """

    id: str
    frame_id: str
    primitives: Tuple[Primitive, ...]
    lines: Tuple[Lines, ...] = ()
    triangles: Tuple[Triangles, ...] = ()


@dataclass(frozen=True)
class Transform:
    """One transform of the tree: ``child`` in ``parent`` (translation [m], rotation)."""

    parent: str
    child: str
    translation_m: Vector
    rotation: Quaternion
