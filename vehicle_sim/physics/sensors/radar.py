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
pedestrians, obstacles, other vehicles), as body tables; the bodies of a table that may be
within range are sorted out with a few array operations when the table is new, the radar has
moved NEAR_ALLOWANCE_M or NEAR_HORIZON_S has passed (:meth:`RadarSensor._near`), and only those
are checked, in plain Python. A body is in the cone when part of it is: its bounding
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
from vehicle_sim.physics.traffic_kinematics import RADIUS, VX, VZ, X, Z

REFLECTIVITY = tuple(label.reflectivity for label in LABELS)
OCCLUSION_MARGIN_M = 0.05     # a hit this much nearer than the target's sphere hides it
NEAR_ALLOWANCE_M = 10.0       # the bodies near the radar are sorted again once it moved so far
NEAR_HORIZON_S = 1.0          # or after so long


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
        self._near_rows = {}       # block index -> (its table, radar position, since, rows)
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
        origin, _, matrix = self.mount.world_pose()
        found = self._checked([(self._near(k, table, since, origin) if kept else
                                table.tolist(), since)
                               for k, (table, since, kept) in enumerate(self.candidates.now())],
                              origin, matrix)
        if spec.occlusion and found:
            found = self._visible(found, np.array(origin), np.array(matrix).reshape(3, 3))
        if spec.cell_distance_m > 0.0:
            found = merge_targets(found, spec.cell_distance_m, spec.cell_speed_mps)
        found.sort(key=lambda t: t['range'])
        return [RadarDetection(t['range'], w_to_dbm(t['power']), t['speed'], t['azimuth'],
                               t['elevation'], t['position'], t['velocity'], t['size'],
                               t['label'], t['instance']) for t in found]

    def _near(self, key, table, since, origin):
        """
        Return the rows of a kept body table that may be within range, as lists.

        Sorted out with a few array operations when the table is new, the radar has moved
        NEAR_ALLOWANCE_M or NEAR_HORIZON_S has passed; else the rows of then: a body left out
        was farther than the range plus its radius, the allowance and its own travel over the
        horizon, so it cannot be within range now.
        """
        cached = self._near_rows.get(key)
        if cached is not None:
            kept, (ox, oy, oz), then, rows = cached
            dx, dy, dz = origin[0] - ox, origin[1] - oy, origin[2] - oz
            if kept is table and 0.0 <= since - then <= NEAR_HORIZON_S and \
                    dx * dx + dy * dy + dz * dz <= NEAR_ALLOWANCE_M ** 2:
                return rows
        velocity = table[:, VX:VZ + 1]
        offset = table[:, X:Z + 1] + velocity * since - origin
        reach = (self.spec.max_range_m + NEAR_ALLOWANCE_M + table[:, RADIUS]
                 + np.sqrt((velocity * velocity).sum(axis=1)) * NEAR_HORIZON_S)
        rows = table[(offset * offset).sum(axis=1) <= reach * reach].tolist()
        self._near_rows[key] = (table, origin, since, rows)
        return rows

    def _own_velocity(self, origin):
        # The mount point's world velocity: v_com + w x (p - p_com), two Bullet calls.
        cid, body = self.world.client_id, self._body_id
        com = pybullet.getBasePositionAndOrientation(body, physicsClientId=cid)[0]
        (vx, vy, vz), (wx, wy, wz) = pybullet.getBaseVelocity(body, physicsClientId=cid)
        rx, ry, rz = origin[0] - com[0], origin[1] - com[1], origin[2] - com[2]
        return (vx + wy * rz - wz * ry, vy + wz * rx - wx * rz, vz + wx * ry - wy * rx)

    def _checked(self, blocks, origin, matrix):
        # Webots' checks on each body of the blocks' rows: the targets seen, as dicts.
        spec = self.spec
        sqrt, atan2, asin = math.sqrt, math.atan2, math.asin
        half_h, half_v = self._half_h, self._half_v
        min_range, max_range = spec.min_range_m, spec.max_range_m
        low, high = spec.min_radial_speed_mps, spec.max_radial_speed_mps
        limits = bool(low or high)
        min_abs = spec.min_absolute_radial_speed_mps
        labels_of = self.world.labels.of
        factor, threshold, exact_range = self._factor, self._threshold, not self._range_noise
        ox, oy, oz = origin
        r00, r01, r02, r10, r11, r12, r20, r21, r22 = matrix
        heading0 = atan2(r10, r00)        # the radar's x axis in the world, for the sizes
        radar_velocity = None
        found = []
        for rows, since in blocks:
            for x0, y0, z0, vx, vy, vz, length, width, height, yaw, r, body in rows:
                px, py, pz = x0 + vx * since - ox, y0 + vy * since - oy, z0 + vz * since - oz
                x = px * r00 + py * r10 + pz * r20
                y = px * r01 + py * r11 + pz * r21
                z = px * r02 + py * r12 + pz * r22
                flat = sqrt(x * x + y * y)
                true_distance = sqrt(flat * flat + z * z)
                if true_distance - r > max_range:
                    continue
                if exact_range:        # no range noise: too weak a return is known already
                    label, instance = labels_of(int(body))
                    near = min(max(true_distance, min_range), max_range)
                    if factor * REFLECTIVITY[label] * width * height < threshold * near ** 4:
                        continue
                spread = asin(min(1.0, r / max(true_distance, 1e-9)))
                azimuth, elevation = atan2(y, x), atan2(z, flat)
                if abs(azimuth) - spread > half_h or abs(elevation) - spread > half_v:
                    continue
                d = float(self._range_noise.add(true_distance)) if self._range_noise \
                    else true_distance
                if d < min_range - r:
                    continue
                d = min(max(d, min_range), max_range)
                label, instance = labels_of(int(body))
                power = factor * REFLECTIVITY[label] * width * height / d ** 4
                if power < threshold:
                    continue
                if radar_velocity is None:
                    radar_velocity = self._own_velocity(origin)
                wx, wy, wz = (vx - radar_velocity[0], vy - radar_velocity[1],
                              vz - radar_velocity[2])
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
                turn = yaw - heading0
                c, s = abs(math.cos(turn)), abs(math.sin(turn))
                found.append({'range': d, 'power': power, 'speed': speed, 'azimuth': angle,
                              'elevation': elevation, 'position': (x, y, z),
                              'velocity': relative,
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
