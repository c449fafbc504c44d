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
The radar: the object bodies in its cone as targets, computed as Webots' WbRadar does.

Candidates are the world's object bodies (physics/sensors/radar_candidates.py: traffic,
pedestrians, obstacles, other vehicles). A body is in the cone when part of it is: its bounding
sphere (radius r, half its extents' diagonal) reaches within ``max_range`` and within half the
horizontal and vertical field of view of the x axis. Then, per body, in Webots' order:

1. distance ``d`` = from the radar to the body's centre, plus the range noise; a body with
   ``d < min_range - r`` is not seen; ``d`` is clamped to [min_range, max_range];
2. received power by the radar equation (core/sensors/radar_equation.py) with the body's radar
   cross-section (its label's reflectivity x width x height); below ``min_detectable_signal``
   it is not seen;
3. radial speed: the body's velocity relative to the radar's (the mount point's, Bullet's
   velocity of the vehicle; traffic: the engine's speed along the heading) along the line of
   sight, > 0 moving away, plus the speed noise; outside [min_radial_speed,
   max_radial_speed] (when either is set) or below ``min_absolute_radial_speed`` in absolute
   value it is not seen;
4. azimuth from the x axis (REP 103: > 0 to the left), clamped to the field of view, plus the
   angular noise.

With ``occlusion`` a ray is cast from the radar to each target's centre: a target is hidden when
something is hit nearer than its bounding sphere (Webots: a ray to the target hitting another
body). With ``cell_distance`` > 0 targets merge (radar_equation.merge_targets). Targets are
listed nearest first. Webots differentiates positions between samples for the speeds; the
velocities here are the bodies' own, the same for the straight motion between samples and
without a first sample of zero speeds.
"""

import math

import numpy as np

from vehicle_sim.core.sensors.labels import LABELS
from vehicle_sim.core.sensors.noise import GaussianNoise
from vehicle_sim.core.sensors.radar_equation import (
    dbm_to_w,
    merge_targets,
    power_factor_w,
    w_to_dbm,
)
from vehicle_sim.core.sensors.readings import RadarReading, RadarTarget
from vehicle_sim.physics.sensors.radar_candidates import RadarCandidates
from vehicle_sim.physics.sensors.rays import cast_rays
from vehicle_sim.physics.sensors.sensor import Sensor

REFLECTIVITY = np.array([label.reflectivity for label in LABELS])
OCCLUSION_MARGIN_M = 0.05     # a hit this much nearer than the target's sphere hides it


class RadarSensor(Sensor):
    """
    A radar on a vehicle body.

    :param world: the World.
    :param body: the vehicle body.
    :param spec: core RadarSpec.
    :param plane: unused (the one constructor shape of physics/sensors/sensor.py).
    """

    def __init__(self, world, body, spec, plane=None):
        super().__init__(world, body, spec, plane)
        self.candidates = RadarCandidates(world, body.body_id)
        self._factor = power_factor_w(spec)
        self._threshold = dbm_to_w(spec.min_detectable_signal_dbm)
        self._half_h = spec.horizontal_fov_rad / 2.0
        self._half_v = spec.vertical_fov_rad / 2.0
        self._mask = world.ray_mask_excluding(body.body_id) if spec.occlusion else None
        self._range_noise = GaussianNoise(spec.range_noise_m, spec.seed, spec.name + '/range')
        self._speed_noise = GaussianNoise(spec.speed_noise_mps, spec.seed, spec.name + '/speed')
        self._angle_noise = GaussianNoise(spec.angular_noise_rad, spec.seed,
                                          spec.name + '/angle')

    def sample(self, time_s):
        """Find the targets now; return a RadarReading stamped ``time_s``."""
        return RadarReading(self.spec.name, time_s, tuple(self.targets()))

    def targets(self):
        """Return the RadarTargets now, nearest first."""
        spec = self.spec
        ids, positions, velocities, extents, yaw = self.candidates.now()
        if len(ids) == 0:
            return []
        origin, rotation, _ = self.mount.world_frame()
        local = (positions - origin) @ rotation
        x, y, z = local[:, 0], local[:, 1], local[:, 2]
        flat = np.hypot(x, y)
        distance = np.hypot(flat, z)
        radius = 0.5 * np.sqrt((extents * extents).sum(axis=1))
        spread = np.arcsin(np.minimum(1.0, radius / np.maximum(distance, 1e-9)))
        azimuth = np.arctan2(y, x)
        elevation = np.arctan2(z, flat)
        seen = ((distance - radius <= spec.max_range_m)
                & (np.abs(azimuth) - spread <= self._half_h)
                & (np.abs(elevation) - spread <= self._half_v))
        index = np.flatnonzero(seen)
        if len(index) == 0:
            return []
        velocity, _ = self.mount.point_velocity(origin)
        labels_of = self.world.labels.of
        found = []
        for i in index.tolist():
            found.extend(self._target(i, ids, local, distance, radius, azimuth, elevation,
                                      velocities, extents, yaw, velocity, rotation, labels_of))
        if spec.occlusion and found:
            found = self._visible(found, origin, rotation)
        if spec.cell_distance_m > 0.0:
            found = merge_targets(found, spec.cell_distance_m, spec.cell_speed_mps)
        found.sort(key=lambda t: t['range'])
        return [RadarTarget(t['range'], w_to_dbm(t['power']), t['speed'], t['azimuth'],
                            t['elevation'], t['position'], t['velocity'], t['size'], t['label'],
                            t['instance']) for t in found]

    def _target(self, i, ids, local, distance, radius, azimuth, elevation, velocities, extents,
                yaw, radar_velocity, rotation, labels_of):
        # Webots' checks on one body in the cone; [] when it is not seen, else [its target].
        spec = self.spec
        d = float(self._range_noise.add(distance[i]))
        r = float(radius[i])
        if d < spec.min_range_m - r:
            return []
        d = min(max(d, spec.min_range_m), spec.max_range_m)
        label, instance = labels_of(int(ids[i]))
        length, width, height = extents[i].tolist()
        power = self._factor * REFLECTIVITY[label] * width * height / d ** 4
        if power < self._threshold:
            return []
        relative = (velocities[i] - radar_velocity) @ rotation
        line = local[i] / max(float(distance[i]), 1e-9)
        speed = float(self._speed_noise.add(float(line @ relative)))
        low, high = spec.min_radial_speed_mps, spec.max_radial_speed_mps
        if (low or high) and not low <= speed <= high:
            return []
        if abs(speed) < spec.min_absolute_radial_speed_mps:
            return []
        half = self._half_h
        angle = float(self._angle_noise.add(min(max(float(azimuth[i]), -half), half)))
        # the body's heading relative to the radar's x axis, for its size in the radar frame
        heading = float(yaw[i]) - math.atan2(rotation[1, 0], rotation[0, 0])
        c, s = abs(math.cos(heading)), abs(math.sin(heading))
        size = (length * c + width * s, length * s + width * c, height)
        return [{'range': d, 'power': power, 'speed': speed, 'azimuth': angle,
                 'elevation': float(elevation[i]), 'position': tuple(local[i].tolist()),
                 'velocity': tuple(relative.tolist()), 'size': size, 'label': int(label),
                 'instance': int(instance), 'radius': r}]

    def _visible(self, found, origin, rotation):
        # One ray to each target's centre: hidden when something is hit before its sphere.
        centres = np.array([t['position'] for t in found])
        reach = np.linalg.norm(centres, axis=1)
        fractions = cast_rays(self.world, origin, origin + centres @ rotation.T, self._mask)
        radii = np.array([t['radius'] for t in found])
        hidden = fractions * reach < reach - radii - OCCLUSION_MARGIN_M
        return [t for t, h in zip(found, hidden.tolist()) if not h]
