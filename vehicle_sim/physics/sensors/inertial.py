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
The IMU and the GNSS antenna: kinematics of the mount point.

IMU, in the sensor frame: orientation = the sensor frame in the ENU world; angular velocity =
R^T w; linear acceleration = the specific force R^T (a + g e_z), with a the acceleration of the
mount point, taken as the change of its velocity over the last basic step, (v_n - v_(n-1)) / dt.
At rest and level it reads +g on z (9.81 m/s^2). The suite records v_(n-1) on the step before a
sample is due (``track``); a first sample without a previous velocity takes a = 0.

GNSS: the antenna's world position (x east, y north, z up in the world's local tangent plane)
with optional Gaussian noise per axis, converted exactly to WGS-84 latitude, longitude and
ellipsoidal altitude (core/geometry/geodesy.py). Webots' local GPS values are the (noisy) position.
"""

import numpy as np

from vehicle_sim.core.geometry.frames import quaternion_from_rpy, rpy_from_quaternion
from vehicle_sim.core.sensors.noise import GaussianNoise
from vehicle_sim.core.sensors.readings import (
    COVARIANCE_TYPE_DIAGONAL_KNOWN,
    COVARIANCE_TYPE_UNKNOWN,
    diagonal_covariance,
    GnssReading,
    ImuReading,
    ZERO_COVARIANCE,
)
from vehicle_sim.physics.sensors.sensor import Sensor


def _covariance(sigma):
    return diagonal_covariance(sigma) if sigma > 0.0 else ZERO_COVARIANCE


class ImuSensor(Sensor):
    """
    An IMU on a vehicle body.

    :param world: the World (gravity, time step).
    :param body: the vehicle body.
    :param spec: core ImuSpec.
    :param plane: unused (the one constructor shape of physics/sensors/sensor.py).
    """

    tracks_motion = True

    def __init__(self, world, body, spec, plane=None):
        super().__init__(world, body, spec, plane)
        self._gravity = np.array((0.0, 0.0, world.gravity))
        self._previous = None          # (step, velocity of the mount point)
        stream = spec.name
        self._orientation_noise = GaussianNoise(spec.orientation_noise_rad, spec.seed,
                                                stream + '/orientation')
        self._gyro_noise = GaussianNoise(spec.angular_velocity_noise_radps, spec.seed,
                                         stream + '/angular_velocity')
        self._accel_noise = GaussianNoise(spec.linear_acceleration_noise_mps2, spec.seed,
                                          stream + '/linear_acceleration')
        self._covariances = (_covariance(spec.orientation_noise_rad),
                             _covariance(spec.angular_velocity_noise_radps),
                             _covariance(spec.linear_acceleration_noise_mps2))

    def track(self):
        """Record the mount point's velocity now (the step before a sample)."""
        if self._previous is not None and self._previous[0] == self.world.step_count:
            return          # a sample at this step has recorded it already
        position, _, _ = self.mount.world_frame()
        velocity, _ = self.mount.point_velocity(position)
        self._previous = (self.world.step_count, velocity)

    def restart(self):
        """After a reset or teleport: differentiate the next sample from the velocity now."""
        position, _, _ = self.mount.world_frame()
        velocity, _ = self.mount.point_velocity(position)
        self._previous = (self.world.step_count, velocity)

    def sample(self, time_s):
        """Return an ImuReading of the current state stamped ``time_s``."""
        position, rotation, quaternion = self.mount.world_frame()
        velocity, angular = self.mount.point_velocity(position)
        acceleration = np.zeros(3)
        previous = self._previous
        if previous is not None and previous[0] < self.world.step_count:
            elapsed = (self.world.step_count - previous[0]) * self.world.time_step_s
            acceleration = (velocity - previous[1]) / elapsed
        self._previous = (self.world.step_count, velocity)
        specific_force = rotation.T @ (acceleration + self._gravity)
        angular_body = rotation.T @ angular
        if self._orientation_noise:
            rpy = self._orientation_noise.add(np.array(rpy_from_quaternion(quaternion)))
            quaternion = quaternion_from_rpy(*rpy)
        angular_body = self._gyro_noise.add(angular_body)
        specific_force = self._accel_noise.add(specific_force)
        return ImuReading(self.spec.name, time_s, tuple(float(q) for q in quaternion),
                          tuple(float(v) for v in angular_body),
                          tuple(float(v) for v in specific_force), *self._covariances)


class GnssSensor(Sensor):
    """
    A GNSS antenna on a vehicle body.

    :param world: the World.
    :param body: the vehicle body.
    :param spec: core GnssSpec.
    :param plane: the world's LocalTangentPlane (its geodetic origin).
    """

    def __init__(self, world, body, spec, plane=None):
        super().__init__(world, body, spec, plane)
        self._noise = GaussianNoise(spec.noise_m, spec.seed, spec.name)
        self._covariance = _covariance(spec.noise_m)
        self._covariance_type = (COVARIANCE_TYPE_DIAGONAL_KNOWN if spec.noise_m > 0.0
                                 else COVARIANCE_TYPE_UNKNOWN)

    def sample(self, time_s):
        """Return a GnssReading of the antenna now stamped ``time_s``."""
        position, _, _ = self.mount.world_frame()
        velocity, _ = self.mount.point_velocity(position)
        measured = self._noise.add(position)
        latitude, longitude, altitude = self.plane.to_geodetic(*measured)
        return GnssReading(self.spec.name, time_s, latitude, longitude, altitude,
                           tuple(float(v) for v in measured), tuple(float(v) for v in velocity),
                           self._covariance, self._covariance_type)
