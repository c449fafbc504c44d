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
The base of every sensor type: the common keys, the SensorSpec contract and the size bounds.

Each sensor type's module (lidar_spec.py, inertial_spec.py, distance_spec.py, camera_spec.py,
range_finder_spec.py, radar_spec.py) starts its ParamSpec table with :func:`common_specs` and
subclasses :class:`SensorSpec`; the registry of the types is core/sensors/params.py.

Frames and topics: a sensor's frame is ``<p><name>`` (p = the vehicle's frame prefix), mounted
at ``pose`` relative to ``<p>base_link``; a camera's image is in ``<p><name>_optical``. Default
topics are relative to the vehicle namespace (see :meth:`SensorSpec.topics`).
"""

from dataclasses import dataclass
import math
from typing import Optional, Tuple

from vehicle_sim.core.geometry.frames import Pose
from vehicle_sim.core.specs.param_spec import ParamSpec, REQUIRED

TWO_PI = 2.0 * math.pi

# Sensor sizes a 2-core laptop runs: every sample is one short PyBullet call (or a few), so a
# step stays short and a node stops within a second of SIGTERM. Measured here: 65536 rays
# cast in ~0.07 s, a 1920 x 1080 frame rendered in ~0.3 s (docs/sensors.md, "Sizes").
MAX_LIDAR_RAYS_PER_LAYER = 4096     # Ouster OS1: 2048; Velodyne HDL-64E: ~2000 at 10 Hz
MAX_LIDAR_LAYERS = 128              # Ouster OS1-128
MAX_LIDAR_RAYS = 65536              # per scan: horizontal_resolution x layers
MAX_DISTANCE_RAYS = 1024
MAX_CAMERA_SIDE_PX = 3840           # a 4K UHD row
MAX_CAMERA_PIXELS = 1920 * 1080     # per frame: width x height (Full HD)


def common_specs(sensor_type, rate_hz, types=None):
    """
    Return the ParamSpec rows every sensor type's table starts with (the common keys).

    :param types: the valid ``type`` values shown in the docs (a type's own table: itself).
    """
    return (
        ParamSpec('type', 'sensor_type', 'enum', sensor_type, choices=types or (sensor_type,),
                  doc='sensor type'),
        ParamSpec('name', 'name', 'ros_name', REQUIRED,
                  doc='frame <p><name>; letters, digits, underscores; unique per vehicle'),
        ParamSpec('device', 'device', 'str', None, optional=True,
                  doc='Webots device name (Driver.getDevice); null = the name'),
        ParamSpec('pose', 'pose', 'pose', Pose(), 'm, rad',
                  'mount pose relative to base_link: {x, y, z, roll, pitch, yaw}, each default 0'),
        ParamSpec('rate_hz', 'rate_hz', 'float', rate_hz, 'Hz',
                  'sampling rate on simulated time (ROS topics)', gt=0.0),
        ParamSpec('topic', 'topic', 'topic', None, optional=True,
                  doc='topic relative to the vehicle namespace; null = the type default'),
        ParamSpec('enabled', 'enabled', 'bool', True,
                  doc='mounted: published over ROS and a Webots device (presets: false)'),
        ParamSpec('seed', 'seed', 'int', 0, ge=0, doc='seed of the noise generator'),
    )


@dataclass(frozen=True)
class SensorSpec:
    """Fields every sensor has (meaning in the tables); subclasses add their type's fields."""

    sensor_type: str
    name: str
    device: str
    pose: Pose
    rate_hz: float
    topic: Optional[str]
    enabled: bool
    seed: int

    @property
    def device_names(self) -> Tuple[str, ...]:
        """The Webots device names of this sensor (an IMU has three)."""
        return (self.device,)

    @property
    def topics(self) -> Tuple[str, ...]:
        """Topics relative to the vehicle namespace: ``topic`` or the type's default."""
        return (self.topic or self._default_topic(),)

    def _default_topic(self):
        raise NotImplementedError

    def frame_id(self, prefix=''):
        """Return the sensor frame: ``<prefix><name>``."""
        return prefix + self.name

    def optical_frame_id(self, prefix=''):
        """Return the frame of an image (z forward, x right, y down); None: no image."""
        return None

    @property
    def period_s(self):
        return 1.0 / self.rate_hz
