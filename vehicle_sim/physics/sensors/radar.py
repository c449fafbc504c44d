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
from vehicle_sim.core.sensors.readings import RadarDetection, RadarReading
from vehicle_sim.physics.sensors.radar_candidates import RadarCandidates
from vehicle_sim.physics.sensors.rays import cast_rays
from vehicle_sim.physics.sensors.sensor import Sensor
from vehicle_sim.physics.traffic_kinematics import BODY, HEIGHT, LENGTH, RADIUS, VX, VZ, YAW

REFLECTIVITY = tuple(label.reflectivity for label in LABELS)
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
        # the sensor axes and the outward normals of the horizontal cone's two sides, as columns
        cos_h, sin_h = math.cos(self._half_h), math.sin(self._half_h)
        self._sides = np.array([[1.0, 0.0, 0.0, -sin_h, -sin_h], [0.0, 1.0, 0.0, cos_h, -cos_h],
                                [0.0, 0.0, 1.0, 0.0, 0.0]])
        self._mask = world.ray_mask_excluding(body.body_id) if spec.occlusion else None
        self._range_noise = GaussianNoise(spec.range_noise_m, spec.seed, spec.name + '/range')
        self._speed_noise = GaussianNoise(spec.speed_noise_mps, spec.seed, spec.name + '/speed')
        self._angle_noise = GaussianNoise(spec.angular_noise_rad, spec.seed,
                                          spec.name + '/angle')

    def sample(self, time_s):
        """Find the targets now; return a RadarReading stamped ``time_s``."""
        return RadarReading(self.spec.name, time_s, tuple(self.targets()))

    def targets(self):
        """Return the RadarDetections now, nearest first."""
        spec = self.spec
        table = self.candidates.now()
        if len(table) == 0:
            return []
        origin, rotation, _ = self.mount.world_frame()
        # one product gives each centre in the radar frame (x, y, z) and its distances past
        # the two sides of the horizontal cone; a body is culled when its bounding sphere is
        # beyond the range or wholly past a side (the exact test follows per body)
        projected = (table[:, :3] - origin) @ (rotation @ self._sides)
        local = projected[:, :3]
        radius = table[:, RADIUS]
        keep = np.einsum('ij,ij->i', local, local) <= (radius + spec.max_range_m) ** 2
        if self._half_h < math.pi / 2.0:
            keep &= projected[:, 3:].max(axis=1) <= radius
        index = np.flatnonzero(keep)
        if len(index) == 0:
            return []
        found = self._checked(table[index].tolist(), local[index].tolist(), origin,
                              rotation.tolist())
        if spec.occlusion and found:
            found = self._visible(found, origin, rotation)
        if spec.cell_distance_m > 0.0:
            found = merge_targets(found, spec.cell_distance_m, spec.cell_speed_mps)
        found.sort(key=lambda t: t['range'])
        return [RadarDetection(t['range'], w_to_dbm(t['power']), t['speed'], t['azimuth'],
                               t['elevation'], t['position'], t['velocity'], t['size'],
                               t['label'], t['instance']) for t in found]

    def _own_velocity(self, origin):
        # The mount point's world velocity: v_com + w x (p - p_com), two Bullet calls.
        cid, body = self.world.client_id, self._body_id
        com = pybullet.getBasePositionAndOrientation(body, physicsClientId=cid)[0]
        (vx, vy, vz), (wx, wy, wz) = pybullet.getBaseVelocity(body, physicsClientId=cid)
        rx, ry, rz = (float(origin[0]) - com[0], float(origin[1]) - com[1],
                      float(origin[2]) - com[2])
        return (vx + wy * rz - wz * ry, vy + wz * rx - wx * rz, vz + wx * ry - wy * rx)

    def _checked(self, rows, local, origin, rotation):
        # Webots' checks on each body left by the cull (few): the targets seen, as dicts.
        spec = self.spec
        sqrt, atan2, asin = math.sqrt, math.atan2, math.asin
        half_h, half_v = self._half_h, self._half_v
        min_range, max_range = spec.min_range_m, spec.max_range_m
        low, high = spec.min_radial_speed_mps, spec.max_radial_speed_mps
        limits = bool(low or high)
        min_abs = spec.min_absolute_radial_speed_mps
        labels_of = self.world.labels.of
        (r00, r01, r02), (r10, r11, r12), (r20, r21, r22) = rotation
        heading0 = atan2(r10, r00)        # the radar's x axis in the world, for the sizes
        radar_velocity = None
        found = []
        for row, (x, y, z) in zip(rows, local):
            flat = sqrt(x * x + y * y)
            true_distance = sqrt(flat * flat + z * z)
            r = row[RADIUS]
            spread = asin(min(1.0, r / max(true_distance, 1e-9)))
            azimuth, elevation = atan2(y, x), atan2(z, flat)
            if (true_distance - r > max_range or abs(azimuth) - spread > half_h
                    or abs(elevation) - spread > half_v):
                continue
            d = float(self._range_noise.add(true_distance)) if self._range_noise \
                else true_distance
            if d < min_range - r:
                continue
            d = min(max(d, min_range), max_range)
            label, instance = labels_of(int(row[BODY]))
            length, width, height = row[LENGTH:HEIGHT + 1]
            power = self._factor * REFLECTIVITY[label] * width * height / d ** 4
            if power < self._threshold:
                continue
            if radar_velocity is None:
                radar_velocity = self._own_velocity(origin)
            wx, wy, wz = (v - w for v, w in zip(row[VX:VZ + 1], radar_velocity))
            relative = (wx * r00 + wy * r10 + wz * r20, wx * r01 + wy * r11 + wz * r21,
                        wx * r02 + wy * r12 + wz * r22)
            speed = (x * relative[0] + y * relative[1] + z * relative[2]) / max(
                true_distance, 1e-9)
            if self._speed_noise:
                speed = float(self._speed_noise.add(speed))
            if (limits and not low <= speed <= high) or abs(speed) < min_abs:
                continue
            angle = min(max(azimuth, -half_h), half_h)
            if self._angle_noise:
                angle = float(self._angle_noise.add(angle))
            turn = row[YAW] - heading0
            c, s = abs(math.cos(turn)), abs(math.sin(turn))
            found.append({'range': d, 'power': power, 'speed': speed, 'azimuth': angle,
                          'elevation': elevation, 'position': (x, y, z), 'velocity': relative,
                          'size': (length * c + width * s, length * s + width * c, height),
                          'label': label, 'instance': instance, 'radius': r})
        return found

    def _visible(self, found, origin, rotation):
        # One ray to each target's centre: hidden when something is hit before its sphere.
        centres = np.array([t['position'] for t in found])
        reach = np.linalg.norm(centres, axis=1)
        fractions = cast_rays(self.world, origin, origin + centres @ rotation.T, self._mask)
        radii = np.array([t['radius'] for t in found])
        hidden = fractions * reach < reach - radii - OCCLUSION_MARGIN_M
        return [t for t, h in zip(found, hidden.tolist()) if not h]
