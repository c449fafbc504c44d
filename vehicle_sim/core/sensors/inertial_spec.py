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
The IMU and the GNSS antenna: their ParamSpec tables and specs.

Neither has a cross-field check. Registered as ``imu`` and ``gnss`` in core/sensors/params.py;
keys in docs/sensors.md.
"""

from dataclasses import dataclass

from vehicle_sim.core.sensors.sensor_spec import common_specs, SensorSpec
from vehicle_sim.core.specs.param_spec import ParamSpec

IMU_SPECS = common_specs('imu', 100.0) + (
    ParamSpec('orientation_noise', 'orientation_noise_rad', 'float', 0.0, 'rad',
              'standard deviation of the noise of each roll, pitch, yaw angle', ge=0.0),
    ParamSpec('angular_velocity_noise', 'angular_velocity_noise_radps', 'float', 0.0, 'rad/s',
              'standard deviation of the angular velocity noise (each axis)', ge=0.0),
    ParamSpec('linear_acceleration_noise', 'linear_acceleration_noise_mps2', 'float', 0.0,
              'm/s^2', 'standard deviation of the linear acceleration noise (each axis)',
              ge=0.0),
    ParamSpec('gyro_device', 'gyro_device', 'str', 'gyro', doc='Webots Gyro device name'),
    ParamSpec('accelerometer_device', 'accelerometer_device', 'str', 'accelerometer',
              doc='Webots Accelerometer device name'),
)


@dataclass(frozen=True)
class ImuSpec(SensorSpec):
    """An IMU: orientation, angular velocity, linear acceleration including gravity."""

    orientation_noise_rad: float
    angular_velocity_noise_radps: float
    linear_acceleration_noise_mps2: float
    gyro_device: str
    accelerometer_device: str

    def _default_topic(self):
        return 'imu'

    @property
    def device_names(self):
        """InertialUnit (``device``), Gyro and Accelerometer names."""
        return (self.device, self.gyro_device, self.accelerometer_device)


GNSS_SPECS = common_specs('gnss', 10.0) + (
    ParamSpec('noise', 'noise_m', 'float', 0.0, 'm',
              'standard deviation of the position noise along east, north and up', ge=0.0),
)


@dataclass(frozen=True)
class GnssSpec(SensorSpec):
    """A GNSS antenna: WGS-84 position of the mount point (the world's geodetic origin)."""

    noise_m: float

    def _default_topic(self):
        return 'gnss/fix'
