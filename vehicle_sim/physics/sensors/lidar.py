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
The lidar: a fan of rays (one or several layers) cast with rayTestBatch from the mount pose.

Ray directions in the sensor frame: azimuth a_i = angle_min + i * angle_increment,
counter-clockwise from x (angle_min = -fov / 2, angle_increment = fov / (rays - 1)); elevation
e_j from +vertical_fov / 2 (layer 0, the top) down to -vertical_fov / 2; unit vector
(cos e cos a, cos e sin a, sin e). A ray hitting nothing within max_range reads +inf, a hit
closer than min_range reads -inf (REP 117); Gaussian noise, if any, is added to the other hits.

A labelled lidar (``labels: true``) also reads what each ray hit (``World.labels``: its label
and instance id) and an intensity: the label's reflectivity (core/sensors/labels.py) times
|cos| of the angle between the ray and the surface normal at the hit (rayTestBatch's; the
occupancy grid's cell face, core/map/grid_rays.py); rays without a finite range get label 0,
instance 0, intensity 0. A ray that meets the ground plane reads what the lane layer draws
there (``World.labels.ground_labels``: road, lane_marking, crosswalk, sidewalk), else
``ground``.
"""

from dataclasses import replace

import numpy as np

from vehicle_sim.core.sensors.labels import LABELS
from vehicle_sim.core.sensors.noise import GaussianNoise
from vehicle_sim.core.sensors.readings import LidarReading
from vehicle_sim.physics.sensors.rays import cast_rays, cast_rays_hits
from vehicle_sim.physics.sensors.sensor import Sensor

# reflectivity by label id
REFLECTIVITY = np.array([label.reflectivity for label in LABELS], dtype=np.float32)


def ray_directions(azimuths_rad, elevations_rad):
    """
    Return unit ray vectors in the sensor frame.

    :param azimuths_rad: (n,) angles counter-clockwise from x [rad].
    :param elevations_rad: (m,) angles above the xy plane [rad].
    :return: (m, n, 3) array.
    """
    azimuth = np.asarray(azimuths_rad, dtype=float)[None, :]
    elevation = np.asarray(elevations_rad, dtype=float)[:, None]
    return np.stack(np.broadcast_arrays(np.cos(elevation) * np.cos(azimuth),
                                        np.cos(elevation) * np.sin(azimuth),
                                        np.sin(elevation) + 0.0 * azimuth), axis=-1)


class LidarSensor(Sensor):
    """
    A lidar on a vehicle body.

    :param world: the World.
    :param body: the vehicle body (CarBody, DiffRobotBody).
    :param spec: core LidarSpec.
    :param plane: unused (the one constructor shape of physics/sensors/sensor.py).
    """

    def __init__(self, world, body, spec, plane=None):
        super().__init__(world, body, spec, plane)
        self._mask = world.ray_mask_excluding(body.body_id)
        azimuths = spec.angle_min_rad + spec.angle_increment_rad * np.arange(
            spec.horizontal_resolution)
        self.directions = ray_directions(azimuths, spec.layer_elevations_rad)
        self._shape = self.directions.shape[:2]
        self._ray_vectors = self.directions.reshape(-1, 3) * spec.max_range_m
        self._noise = GaussianNoise(spec.noise_m, spec.seed, spec.name)

    def sample(self, time_s):
        """Cast the rays now; return a LidarReading stamped ``time_s``."""
        spec = self.spec
        origin, rotation, _ = self.mount.world_frame()
        ends = origin + self._ray_vectors @ rotation.T
        if spec.labels:
            fractions, bodies, links, normals = cast_rays_hits(self.world, origin, ends,
                                                               self._mask)
        else:
            fractions = cast_rays(self.world, origin, ends, self._mask)
        hit = fractions < 1.0
        ranges = np.where(hit, fractions * spec.max_range_m, np.inf)
        if self._noise:
            ranges[hit] = self._noise.add(ranges[hit])
        ranges[hit & (ranges < spec.min_range_m)] = -np.inf
        reading = LidarReading(
            spec.name, time_s, spec.angle_min_rad, spec.angle_max_rad, spec.angle_increment_rad,
            spec.min_range_m, spec.max_range_m, spec.period_s, spec.layer_elevations_rad,
            ranges.reshape(self._shape).astype(np.float32), self.directions)
        if not spec.labels:
            return reading
        bodies[~np.isfinite(ranges)] = -1
        world = self.world
        labels, instances = world.labels.lookup(bodies, links)
        if world.labels.has_surfaces:      # on the ground: what is drawn there (a road)
            ground = np.flatnonzero(bodies == world.ground_id)
            if len(ground):
                points = origin + (ends[ground] - origin) * fractions[ground, None]
                labels[ground] = world.labels.ground_labels(points[:, 0], points[:, 1])
        cosine = np.abs(np.einsum('ij,ij->i', normals, ends - origin)) / spec.max_range_m
        intensities = REFLECTIVITY[labels] * cosine.astype(np.float32)
        shape = self._shape
        return replace(reading, labels=labels.reshape(shape), instances=instances.reshape(shape),
                       intensities=intensities.reshape(shape))
