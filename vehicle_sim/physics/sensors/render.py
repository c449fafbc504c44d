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
One render of a pinhole view: colour, metric depth and the body mask, shared by the sensors.

PyBullet's CPU renderer (ER_TINY_RENDERER) gives the colour image, the depth buffer and the
segmentation mask in one ``getCameraImage`` call. Cameras and range finders ask for a
:class:`View` (size, vertical field of view, near and far planes) from a world pose; two sensors
asking for the same view from the same pose at the same world step get the same :class:`Frame`
(one render), so a camera and a range finder mounted together cost one frame.

Pixel centres: Bullet's renderer samples pixel (u, v) at its corner, so the plain projection
of ``computeProjectionMatrixFOV`` puts the optical axis at (width / 2, height / 2 - 1) in the
pixel-centre coordinates of ROS and OpenCV, half a pixel off the intrinsics' principal point
((width - 1) / 2, (height - 1) / 2; CameraSpec.intrinsics). The projection is shifted by half a
pixel so that the rendering is that of the intrinsics: a ray through a pixel's centre is what
the pixel shows (measured: the ground's depth fits the principal point to 2e-4 px).

Depth: Bullet's buffer holds the normalised device depth d in [0, 1]; the distance along the
optical axis is z = far near / (far - (far - near) d) (the OpenGL perspective projection
inverted). Nothing drawn leaves the cleared buffer: 1 less float32 rounding (measured: at
most 2 units of 2^-24 from 1 over near 0.001..0.5 m and far 1..3000 m), so a buffer value
within FAR_BUFFER_MARGIN (4 units of 2^-24) of 1 reads +inf, as does whatever lies that close
to the far plane: the last (far / near) 2.4e-7 of the range (5 cm of 100 m with near 0.05 m).
A margin in metres instead would fail where far / near is large: 2 units of 2^-24 are 1.2e-4
of far with far / near = 1000. The mask
holds, per pixel, the body id and link index (-1 the base) of what is drawn there, -1 / -1
where nothing is (``ER_SEGMENTATION_MASK_OBJECT_AND_LINKINDEX``: value = body + ((link + 1)
<< 24)).
"""

from dataclasses import dataclass
import math
from typing import Optional

import numpy as np
import pybullet

# A fixed sun: from above, slightly from the front-left of the world x axis, so that vertical
# faces that look at -x (towards a car driving along +x) are lit.
LIGHT_DIRECTION = (-0.4, 0.3, 1.0)
FAR_BUFFER_MARGIN = 4.0 * 2.0 ** -24     # a depth buffer value this close to 1: nothing drawn


@dataclass(frozen=True)
class View:
    """The intrinsic part of a render: pixels, vertical field of view [rad], clip planes [m]."""

    width: int
    height: int
    vertical_fov_rad: float
    near_m: float
    far_m: float


@dataclass(frozen=True, eq=False)
class Frame:
    """
    One rendered view.

    ``rgb``: (height, width, 3) uint8; ``depth_m``: (height, width) float32 distance along the
    optical axis, +inf where nothing is drawn; ``bodies`` and ``links``: (height, width) int32
    body ids and link indices (None when the render was made without the mask). Row 0 is the
    top of the picture.
    """

    rgb: np.ndarray
    depth_m: np.ndarray
    bodies: Optional[np.ndarray]
    links: Optional[np.ndarray]


def metric_depth(buffer, near_m, far_m) -> np.ndarray:
    """Return the distance along the optical axis [m] of Bullet depth-buffer values; far -> inf."""
    buffer = np.asarray(buffer, dtype=np.float64)
    depth = far_m * near_m / (far_m - (far_m - near_m) * np.minimum(buffer, 1.0))
    return np.where(buffer >= 1.0 - FAR_BUFFER_MARGIN, np.inf, depth).astype(np.float32)


class Renderer:
    """
    The renders of one world, cached until the world steps or bodies move (World.revision).

    :param world: the World (``World.renderer`` holds the one instance).
    """

    def __init__(self, world):
        self.world = world
        self._projections = {}
        self._step = None
        self._frames = {}
        self._masked = set()           # views once asked for with the mask: always with it

    def render(self, view: View, position, rotation, mask=False) -> Frame:
        """
        Render ``view`` from a world pose, or return this step's render of it.

        :param view: the View.
        :param position: (3,) the optical centre in the world [m].
        :param rotation: (3, 3) the sensor frame (columns: x the viewing direction, z up in
            the picture).
        :param mask: also the body mask (a frame rendered without it is rendered again). A
            view once asked for with the mask is rendered with it from then on, so that a
            sensor sampled before a segmenting camera of the same view (a range finder) does
            not cost a second render (the mask costs Bullet nothing more).
        """
        if mask:
            self._masked.add(view)
        mask = mask or view in self._masked
        world = self.world
        world.prepare_render()       # lamps made, placed bodies (traffic) where they are now
        step = world.revision          # a step, or bodies moved between steps
        if step != self._step:
            self._step, self._frames = step, {}
        key = (view, np.asarray(position, dtype=float).tobytes(),
               np.asarray(rotation, dtype=float).tobytes())
        found = self._frames.get(key)
        if found is not None and (found.bodies is not None or not mask):
            return found
        frame = self._render(view, np.asarray(position, dtype=float),
                             np.asarray(rotation, dtype=float), mask)
        self._frames[key] = frame
        return frame

    def _projection(self, view):
        found = self._projections.get(view)
        if found is None:
            matrix = list(pybullet.computeProjectionMatrixFOV(
                math.degrees(view.vertical_fov_rad), view.width / view.height, view.near_m,
                view.far_m, physicsClientId=self.world.client_id))
            # half a pixel to the left and down (NDC: 2 / width per pixel; the entries are the
            # third column of the column-major matrix, which w = -z divides out)
            matrix[8] += 1.0 / view.width
            matrix[9] += 1.0 / view.height
            found = self._projections[view] = matrix
        return found

    def _render(self, view, position, rotation, mask):
        cid = self.world.client_id
        target = position + rotation[:, 0]
        matrix = pybullet.computeViewMatrix(position.tolist(), target.tolist(),
                                            rotation[:, 2].tolist(), physicsClientId=cid)
        flags = (pybullet.ER_SEGMENTATION_MASK_OBJECT_AND_LINKINDEX if mask
                 else pybullet.ER_NO_SEGMENTATION_MASK)
        _, _, rgba, depth, seg = pybullet.getCameraImage(
            view.width, view.height, matrix, self._projection(view),
            lightDirection=LIGHT_DIRECTION, renderer=pybullet.ER_TINY_RENDERER, flags=flags,
            physicsClientId=cid)
        shape = (view.height, view.width)
        rgb = np.ascontiguousarray(
            np.asarray(rgba, dtype=np.uint8).reshape(shape + (4,))[:, :, :3])
        depth_m = metric_depth(np.asarray(depth, dtype=np.float32).reshape(shape),
                               view.near_m, view.far_m)
        bodies = links = None
        if mask:
            raw = np.asarray(seg, dtype=np.int64).reshape(shape)
            drawn = raw >= 0
            bodies = np.where(drawn, raw & ((1 << 24) - 1), -1).astype(np.int32)
            links = np.where(drawn, (raw >> 24) - 1, -1).astype(np.int32)
        return Frame(rgb, depth_m, bodies, links)
