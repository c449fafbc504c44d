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
A camera's recognised object: what Webots' CameraRecognitionObject and a Detection2D carry.

The camera (physics/sensors/recognition.py) finds the objects in its instance image: every
instance id other than 0 whose label is one of the camera's ``recognition_classes``, with at
least ``recognition_min_pixels`` visible pixels and its centre within ``recognition_max_range``.
Positions are in the camera's frame (the mount: x forward, y left, z up; Webots' camera frame),
the image box is the visible part's (occlusion from the instance mask): pixel columns ``u`` left
to right, rows ``v`` top to bottom, bounds inclusive.
"""

from dataclasses import dataclass
from typing import Tuple


@dataclass(frozen=True)
class RecognitionObject:
    """
    One recognised object.

    ``id``: its instance id (the object id everywhere: instance image, PredictedObjects);
    ``label``: its label id and ``model`` its label name (core/sensors/labels.py);
    ``position_m``: the centre of its box in the camera frame; ``orientation_xyzw``: its box's
    axes in the camera frame; ``dimensions_m``: the box's length, width and height along its own
    axes; ``size_m``: the box's extent across the view and upwards (Webots' size: the camera's
    y and z); ``box_px``: (u_min, v_min, u_max, v_max) of the visible pixels, inclusive;
    ``pixels``: how many are visible; ``colour``: the label colour, r, g, b in [0, 1].
    """

    id: int
    label: int
    model: str
    position_m: Tuple[float, float, float]
    orientation_xyzw: Tuple[float, float, float, float]
    dimensions_m: Tuple[float, float, float]
    size_m: Tuple[float, float]
    box_px: Tuple[int, int, int, int]
    pixels: int
    colour: Tuple[float, float, float]

    @property
    def size_on_image(self) -> Tuple[int, int]:
        """Width and height of the visible part's box [px] (Webots' size_on_image)."""
        u_min, v_min, u_max, v_max = self.box_px
        return u_max - u_min + 1, v_max - v_min + 1

    @property
    def position_on_image(self) -> Tuple[int, int]:
        """The box's centre pixel, (u, v) rounded down (Webots' position_on_image)."""
        u_min, v_min, u_max, v_max = self.box_px
        return (u_min + u_max) // 2, (v_min + v_max) // 2

    @property
    def centre_px(self) -> Tuple[float, float]:
        """The box's centre in pixel coordinates (integers at pixel centres; Detection2D)."""
        u_min, v_min, u_max, v_max = self.box_px
        return (u_min + u_max) / 2.0, (v_min + v_max) / 2.0
