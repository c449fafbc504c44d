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
The RGB camera: its ParamSpec table, its spec and its cross-field check.

The table has the segmentation and recognition keys too. Registered as ``camera`` in
core/sensors/params.py; keys in docs/sensors.md.
"""

from dataclasses import dataclass
import math
from typing import Tuple

from vehicle_sim.core.sensors.labels import check_label_names
from vehicle_sim.core.sensors.sensor_spec import (
    common_specs,
    MAX_CAMERA_PIXELS,
    MAX_CAMERA_SIDE_PX,
    SensorSpec,
)
from vehicle_sim.core.specs.param_spec import fail, ParamSpec

# The label classes a camera's recognition reports by default: the objects (core/sensors/labels.py)
RECOGNITION_CLASSES = ('car', 'truck', 'bus', 'motorcycle', 'bicycle', 'pedestrian', 'obstacle',
                       'traffic_light')


# The image keys of a camera's view, shared by the range finder (a depth camera).
IMAGE_SPECS = (
    ParamSpec('width', 'width', 'int', 320, 'px',
              f'image width; width x height <= {MAX_CAMERA_PIXELS} px', ge=1,
              le=MAX_CAMERA_SIDE_PX),
    ParamSpec('height', 'height', 'int', 240, 'px', 'image height', ge=1,
              le=MAX_CAMERA_SIDE_PX),
    ParamSpec('fov', 'fov_rad', 'float', 1.0, 'rad', 'horizontal field of view', gt=0.0,
              lt=math.pi),
)

CAMERA_SPECS = common_specs('camera', 10.0) + IMAGE_SPECS + (
    ParamSpec('near', 'near_m', 'float', 0.05, 'm', 'near clipping distance', gt=0.0),
    ParamSpec('far', 'far_m', 'float', 100.0, 'm', 'far clipping distance', gt=0.0),
    ParamSpec('segmentation', 'segmentation', 'bool', False,
              doc='semantic (label id) and instance (object id) images beside the colour one '
                  '(docs/sensors.md, "Segmentation and recognition")'),
    ParamSpec('recognition', 'recognition', 'bool', False,
              doc="Webots' Recognition node: the visible objects (Camera.getRecognitionObjects, "
                  'ROS detections)'),
    ParamSpec('recognition_max_range', 'recognition_max_range_m', 'float', 100.0, 'm',
              "Webots Recognition maxRange: an object's centre farther than this is not "
              'recognised', gt=0.0),
    ParamSpec('recognition_max_objects', 'recognition_max_objects', 'int', -1, '',
              'Webots Recognition maxObjects: the most objects, the biggest on the image first; '
              '-1 = no limit', ge=-1),
    ParamSpec('recognition_min_pixels', 'recognition_min_pixels', 'int', 10, 'px',
              'the fewest visible pixels of a recognised object', ge=1),
    ParamSpec('recognition_classes', 'recognition_classes', 'str_list', RECOGNITION_CLASSES,
              doc='labels (the label table of docs/sensors.md) of the objects recognised',
              check=lambda names: check_label_names(names, 'a class') and None),
)


@dataclass(frozen=True)
class CameraSpec(SensorSpec):
    """An RGB camera (PyBullet's CPU renderer)."""

    width: int
    height: int
    fov_rad: float
    near_m: float
    far_m: float
    segmentation: bool
    recognition: bool
    recognition_max_range_m: float
    recognition_max_objects: int
    recognition_min_pixels: int
    recognition_classes: Tuple[str, ...]

    def _default_topic(self):
        return 'camera'

    @property
    def masked(self):
        """Whether a frame needs the body mask (segmentation or recognition)."""
        return self.segmentation or self.recognition

    @property
    def topics(self):
        """
        ``<topic>/image_raw`` and ``<topic>/camera_info`` (topic default 'camera').

        With segmentation also ``<topic>/semantic/image_raw`` and ``<topic>/instance/image_raw``;
        with recognition ``<topic>/detections`` and ``<topic>/labels``.
        """
        base = self.topic or self._default_topic()
        topics = (f'{base}/image_raw', f'{base}/camera_info')
        if self.segmentation:
            topics += (f'{base}/semantic/image_raw', f'{base}/instance/image_raw')
        if self.recognition:
            topics += (f'{base}/detections', f'{base}/labels')
        return topics

    def optical_frame_id(self, prefix=''):
        """Return the image frame ``<prefix><name>_optical`` (z forward, x right, y down)."""
        return f'{prefix}{self.name}_optical'

    @property
    def vertical_fov_rad(self):
        """Vertical field of view of square pixels: 2 atan(tan(fov / 2) * height / width)."""
        return 2.0 * math.atan(math.tan(self.fov_rad / 2.0) * self.height / self.width)

    @property
    def intrinsics(self):
        """
        Pinhole intrinsics (fx, fy, cx, cy) [px] of the ideal rendering.

        fx = fy = (width / 2) / tan(fov / 2); the principal point is the image centre in the
        OpenCV / ROS convention (integer coordinates at pixel centres): ((width - 1) / 2,
        (height - 1) / 2).
        """
        focal = self.width / 2.0 / math.tan(self.fov_rad / 2.0)
        return focal, focal, (self.width - 1) / 2.0, (self.height - 1) / 2.0


def check_camera(source, values, clip_keys=('near', 'far')):
    """Refuse a camera's values that do not fit together (pixels per frame, clip planes)."""
    pixels = values['width'] * values['height']
    if pixels > MAX_CAMERA_PIXELS:
        fail(source, 'height', values['height'],
              f'{values["width"]} x {values["height"]} = {pixels} pixels per frame; at most '
              f'{MAX_CAMERA_PIXELS} (1920 x 1080)')
    near, far = clip_keys
    if values['near_m'] >= values['far_m']:
        fail(source, near, values['near_m'], f'must be < {far} ({values["far_m"]:g} m)')
