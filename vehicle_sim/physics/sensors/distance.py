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
The distance sensor: one ray, or a cone of rays, along the mount's x axis; the nearest hit counts.

With ``rays`` = n > 1 the first ray is on the axis and the others are spread evenly on a circle
at half the ``aperture`` from it. The reading has the REP 117 range (sensor_msgs/Range) and
Webots' response value: the lookup table applied to the nearest distance (``max_range`` when
nothing is hit, as a Webots ray of that length), with the table's relative noise.
"""

import math

import numpy as np

from vehicle_sim.core.sensors.noise import GaussianNoise
from vehicle_sim.core.sensors.readings import RADIATION_TYPE, RangeReading
from vehicle_sim.physics.sensors.rays import cast_rays
from vehicle_sim.physics.sensors.sensor import Sensor


def cone_directions(rays, aperture_rad):
    """
    Return the unit ray vectors of a cone around x in the sensor frame.

    :param rays: number of rays (>= 1): the axis, then rays - 1 on the rim.
    :param aperture_rad: full opening angle of the cone [rad].
    :return: (rays, 3) array.
    """
    directions = [(1.0, 0.0, 0.0)]
    half = aperture_rad / 2.0
    for index in range(rays - 1):
        roll = 2.0 * math.pi * index / (rays - 1)
        directions.append((math.cos(half), math.sin(half) * math.cos(roll),
                           math.sin(half) * math.sin(roll)))
    return np.array(directions)


class RayDistanceSensor(Sensor):
    """
    A distance sensor on a vehicle body.

    :param world: the World.
    :param body: the vehicle body.
    :param spec: core DistanceSpec.
    :param plane: unused (the one constructor shape of physics/sensors/sensor.py).
    """

    def __init__(self, world, body, spec, plane=None):
        super().__init__(world, body, spec, plane)
        self.table = spec.table()
        self._mask = world.ray_mask_excluding(body.body_id)
        self._ray_vectors = cone_directions(spec.rays, spec.aperture_rad) * spec.max_range_m
        self._noise = GaussianNoise(spec.noise_m, spec.seed, spec.name)
        # the table's noise column: relative to the value (its own stream of the seed)
        self._table_noise = GaussianNoise(0.0, spec.seed, spec.name + '/lookup_table')

    def sample(self, time_s):
        """Cast the rays now; return a RangeReading stamped ``time_s``."""
        spec = self.spec
        origin, rotation, _ = self.mount.world_frame()
        fraction = float(cast_rays(self.world, origin, origin + self._ray_vectors @ rotation.T,
                                   self._mask).min())
        if fraction < 1.0:
            distance = float(self._noise.add(fraction * spec.max_range_m))
            range_m = -math.inf if distance < spec.min_range_m else distance
        else:
            distance, range_m = spec.max_range_m, math.inf
        value = self._table_noise.add_relative(self.table.value(distance),
                                               self.table.relative_noise(distance))
        return RangeReading(spec.name, time_s, range_m, spec.min_range_m, spec.max_range_m,
                            spec.aperture_rad, RADIATION_TYPE[spec.radiation_type], distance,
                            value, spec.noise_m ** 2)
