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
The lidar: its ParamSpec table, its spec and its cross-field check.

Registered as ``lidar`` in core/sensors/params.py; keys in docs/sensors.md.
"""

from dataclasses import dataclass
import math
from typing import Tuple

from vehicle_sim.core.sensors.sensor_spec import (
    common_specs,
    MAX_LIDAR_LAYERS,
    MAX_LIDAR_RAYS,
    MAX_LIDAR_RAYS_PER_LAYER,
    SensorSpec,
    TWO_PI,
)
from vehicle_sim.core.specs.param_spec import fail, ParamSpec

LIDAR_SPECS = common_specs('lidar', 10.0) + (
    ParamSpec('fov', 'fov_rad', 'float', 1.5 * math.pi, 'rad',
              'horizontal field of view, centred on the x axis', gt=0.0, le=TWO_PI),
    ParamSpec('horizontal_resolution', 'horizontal_resolution', 'int', 1080, '',
              'rays per layer; angle_increment = fov / (rays - 1)', ge=2,
              le=MAX_LIDAR_RAYS_PER_LAYER),
    ParamSpec('layers', 'layers', 'int', 1, '', 'number of layers (1: LaserScan, >1: '
              'PointCloud2)', ge=1, le=MAX_LIDAR_LAYERS),
    ParamSpec('vertical_fov', 'vertical_fov_rad', 'float', 0.0, 'rad',
              'angle between the top and the bottom layer (> 0 with several layers)',
              ge=0.0, le=math.pi),
    ParamSpec('min_range', 'min_range_m', 'float', 0.1, 'm',
              'returns closer than this read -inf (REP 117)', ge=0.0),
    ParamSpec('max_range', 'max_range_m', 'float', 30.0, 'm',
              'no return within this reads +inf (REP 117)', gt=0.0),
    ParamSpec('noise', 'noise_m', 'float', 0.0, 'm',
              'standard deviation of the Gaussian range noise', ge=0.0),
    ParamSpec('labels', 'labels', 'bool', False, '',
              'each point also gets the label, instance id and intensity of what it hit '
              '(PointCloud2 fields intensity, label, instance; LaserScan intensities)'),
)


@dataclass(frozen=True)
class LidarSpec(SensorSpec):
    """A scanning lidar (PyBullet rayTestBatch from the mount pose)."""

    fov_rad: float
    horizontal_resolution: int
    layers: int
    vertical_fov_rad: float
    min_range_m: float
    max_range_m: float
    noise_m: float
    labels: bool = False

    def _default_topic(self):
        return 'scan' if self.layers == 1 else 'points'

    @property
    def angle_min_rad(self):
        return -self.fov_rad / 2.0

    @property
    def angle_max_rad(self):
        return self.fov_rad / 2.0

    @property
    def angle_increment_rad(self):
        return self.fov_rad / (self.horizontal_resolution - 1)

    @property
    def layer_elevations_rad(self) -> Tuple[float, ...]:
        """Elevation of each layer, top layer first (0 for a single layer)."""
        if self.layers == 1:
            return (0.0,)
        step = self.vertical_fov_rad / (self.layers - 1)
        return tuple(self.vertical_fov_rad / 2.0 - i * step for i in range(self.layers))


def check_lidar(source, values):
    """Refuse a lidar's values that do not fit together (rays per scan, ranges, layers)."""
    rays = values['horizontal_resolution'] * values['layers']
    if rays > MAX_LIDAR_RAYS:
        fail(source, 'layers', values['layers'],
              f'{values["horizontal_resolution"]} rays x {values["layers"]} layers = {rays} '
              f'rays per scan; at most {MAX_LIDAR_RAYS}')
    if values['min_range_m'] >= values['max_range_m']:
        fail(source, 'min_range', values['min_range_m'],
              f'must be < max_range ({values["max_range_m"]:g} m)')
    if values['layers'] > 1 and values['vertical_fov_rad'] <= 0.0:
        fail(source, 'vertical_fov', values['vertical_fov_rad'],
              f'must be > 0 with {values["layers"]} layers')
