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
The range finder (a depth camera): its ParamSpec table, its spec and its check.

Registered as ``range_finder`` in core/sensors/params.py; keys in docs/sensors.md. Its image
keys, geometry and size check are the camera's (camera_spec.py).
"""

from dataclasses import dataclass

from vehicle_sim.core.sensors.camera_spec import CameraSpec, check_camera, IMAGE_SPECS
from vehicle_sim.core.sensors.sensor_spec import common_specs, SensorSpec
from vehicle_sim.core.specs.param_spec import ParamSpec

RANGE_FINDER_SPECS = common_specs('range_finder', 10.0) + IMAGE_SPECS + (
    ParamSpec('min_range', 'min_range_m', 'float', 0.05, 'm',
              'near clipping plane: nothing closer is drawn', gt=0.0),
    ParamSpec('max_range', 'max_range_m', 'float', 100.0, 'm',
              'far clipping plane: nothing drawn within it reads +inf', gt=0.0),
    ParamSpec('noise', 'noise_m', 'float', 0.0, 'm',
              'standard deviation of the Gaussian depth noise (each pixel)', ge=0.0),
    ParamSpec('point_cloud', 'point_cloud', 'bool', False,
              doc='also publish the organized PointCloud2 <topic>/points'),
)


@dataclass(frozen=True)
class RangeFinderSpec(SensorSpec):
    """
    A depth camera (Webots RangeFinder): metric depth along the optical axis per pixel.

    Its view is a camera's (square pixels, horizontal ``fov``) with the clip planes at
    ``min_range`` and ``max_range``, so that a camera with the same size, fov, near and far at
    the same mount shares its render (physics/sensors/render.py).
    """

    width: int
    height: int
    fov_rad: float
    min_range_m: float
    max_range_m: float
    noise_m: float
    point_cloud: bool

    def _default_topic(self):
        return f'{self.name}/depth'

    @property
    def topics(self):
        """``<topic>/image_raw``, ``<topic>/camera_info`` (and ``<topic>/points``)."""
        base = self.topic or self._default_topic()
        cloud = (f'{base}/points',) if self.point_cloud else ()
        return (f'{base}/image_raw', f'{base}/camera_info') + cloud

    # the pinhole geometry of a camera's image (CameraSpec: fields of the same names)
    optical_frame_id = CameraSpec.optical_frame_id
    vertical_fov_rad = CameraSpec.vertical_fov_rad
    intrinsics = CameraSpec.intrinsics


def check_range_finder(source, values):
    """Refuse a range finder's values that do not fit together: the camera's check."""
    check_camera(source, dict(values, near_m=values['min_range_m'],
                              far_m=values['max_range_m']), ('min_range', 'max_range'))
