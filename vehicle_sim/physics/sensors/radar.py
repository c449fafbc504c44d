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
import pybullet

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
        self._body_id = body.body_id
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
        velocity = self._own_velocity(origin)
        found = self._checked(index, ids, local, distance, radius, azimuth, elevation,
                              velocities, extents, yaw, velocity, rotation)
        if spec.occlusion and found:
            found = self._visible(found, origin, rotation)
        if spec.cell_distance_m > 0.0:
            found = merge_targets(found, spec.cell_distance_m, spec.cell_speed_mps)
        found.sort(key=lambda t: t['range'])
        return [RadarTarget(t['range'], w_to_dbm(t['power']), t['speed'], t['azimuth'],
                            t['elevation'], t['position'], t['velocity'], t['size'], t['label'],
                            t['instance']) for t in found]

    def _own_velocity(self, origin):
        # The mount point's world velocity: v_com + w x (p - p_com), two Bullet calls.
        cid, body = self.world.client_id, self._body_id
        com = pybullet.getBasePositionAndOrientation(body, physicsClientId=cid)[0]
        (vx, vy, vz), (wx, wy, wz) = pybullet.getBaseVelocity(body, physicsClientId=cid)
        rx, ry, rz = (float(origin[0]) - com[0], float(origin[1]) - com[1],
                      float(origin[2]) - com[2])
        return np.array((vx + wy * rz - wz * ry, vy + wz * rx - wx * rz,
                         vz + wx * ry - wy * rx))

    def _checked(self, index, ids, local, distance, radius, azimuth, elevation, velocities,
                 extents, yaw, radar_velocity, rotation):
        # Webots' checks on the bodies in the cone, all at once; the targets seen, as dicts.
        spec = self.spec
        true_distance = distance[index]
        d = np.asarray(self._range_noise.add(true_distance), dtype=float)
        r = radius[index]
        keep = d >= spec.min_range_m - r
        d = np.clip(d, spec.min_range_m, spec.max_range_m)
        labels_of = self.world.labels.of
        label, instance = np.array([labels_of(body) for body in ids[index].tolist()],
                                   dtype=np.int64).reshape(-1, 2).T
        size = extents[index]
        power = self._factor * REFLECTIVITY[label] * size[:, 1] * size[:, 2] / d ** 4
        keep &= power >= self._threshold
        relative = (velocities[index] - radar_velocity) @ rotation
        line = local[index] / np.maximum(true_distance, 1e-9)[:, None]
        speed = np.asarray(self._speed_noise.add((line * relative).sum(axis=1)), dtype=float)
        low, high = spec.min_radial_speed_mps, spec.max_radial_speed_mps
        if low or high:
            keep &= (speed >= low) & (speed <= high)
        keep &= np.abs(speed) >= spec.min_absolute_radial_speed_mps
        half = self._half_h
        angle = np.asarray(self._angle_noise.add(np.clip(azimuth[index], -half, half)),
                           dtype=float)
        # each body's extents along the radar's axes (its heading relative to the x axis)
        heading = yaw[index] - math.atan2(rotation[1, 0], rotation[0, 0])
        c, s = np.abs(np.cos(heading)), np.abs(np.sin(heading))
        along = np.stack([size[:, 0] * c + size[:, 1] * s, size[:, 0] * s + size[:, 1] * c,
                          size[:, 2]], axis=1)
        at = index
        return [{'range': float(d[k]), 'power': float(power[k]), 'speed': float(speed[k]),
                 'azimuth': float(angle[k]), 'elevation': float(elevation[at[k]]),
                 'position': tuple(local[at[k]].tolist()),
                 'velocity': tuple(relative[k].tolist()), 'size': tuple(along[k].tolist()),
                 'label': int(label[k]), 'instance': int(instance[k]), 'radius': float(r[k])}
                for k in np.flatnonzero(keep).tolist()]

    def _visible(self, found, origin, rotation):
        # One ray to each target's centre: hidden when something is hit before its sphere.
        centres = np.array([t['position'] for t in found])
        reach = np.linalg.norm(centres, axis=1)
        fractions = cast_rays(self.world, origin, origin + centres @ rotation.T, self._mask)
        radii = np.array([t['radius'] for t in found])
        hidden = fractions * reach < reach - radii - OCCLUSION_MARGIN_M
        return [t for t, h in zip(found, hidden.tolist()) if not h]
