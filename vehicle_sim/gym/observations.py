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
The observation parts of the Gym environment: each one fills some keys of the Dict.

- ``pose``: (3,) float32 [m, m, rad]: base_link x, y in the world (unbounded) and its heading
  in [-pi, pi] (REP 103, ground truth).
- ``twist``: (3,) float32 [m/s, m/s, rad/s]: base_link velocity in base_link axes: forward,
  left, yaw rate (+ left); unbounded.
- ``lidar``: (rays,) float32, or (layers, rays) [m], in [0, max_range]: the ranges, first ray
  at -fov/2 (right), counter-clockwise; no return reads max_range, closer than min_range 0.
- ``camera``: (height, width, 3) uint8 in [0, 255]: an RGB picture of a camera on the ego,
  rows top to bottom.
- ``semantic`` (a camera with ``segmentation: true``): (height, width) uint8: the label id of
  each pixel of that picture (core/sensors/labels.py).
- ``depth`` (option ``range_finder``): (height, width) float32 [m] in [0, max_range]: the depth
  along the optical axis of a range finder on the ego, rows top to bottom; nothing within
  max_range (+inf on the ROS image) reads max_range, a noisy depth under min_range 0 (as the
  lidar: a Box needs finite bounds).

- ``lane``, ``lane_id`` (a world with lanes): the ego's lane state (lanes.py).
- ``objects`` (option ``objects``): the nearest traffic bodies and obstacles as a table
  (objects.py).

A part is an object with ``spaces()`` ({key: (low, high, shape, dtype)}), ``reset()`` (after the
world was reset) and ``read(out)`` (writes its keys into the dict ``out``). More parts: pass
them in ``observation_parts`` of the environment, or append a factory to
:data:`PART_FACTORIES` so every environment gets it (the lane state comes in that way).
"""

from dataclasses import replace
import math

import numpy as np

from vehicle_sim.core.geometry.angles import yaw_from_quaternion
from vehicle_sim.core.sensors.labels import LABELS
from vehicle_sim.core.sensors.params import sensor_from_dict
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.gym.lanes import lane_part
from vehicle_sim.gym.objects import objects_part
from vehicle_sim.gym.options import CAMERA, DEPTH, LIDAR, RANGE_FINDER
from vehicle_sim.physics.sensors.camera import CameraSensor
from vehicle_sim.physics.sensors.lidar import LidarSensor
from vehicle_sim.physics.sensors.range_finder import RangeFinderSensor

INF = np.inf
# Default mounts of a lidar (true) above base_link [m]: a car's roof, a robot's top.
CAR_SENSOR_HEIGHT_M = 1.5
ROBOT_SENSOR_HEIGHT_M = 0.3
DEFAULT_CAMERA = {'width': 84, 'height': 84, 'fov': 1.2}
# The default range finder has the default camera's view (near, far: the camera's defaults), so
# the two at the same mount share one render.
DEFAULT_RANGE_FINDER = dict(DEFAULT_CAMERA, min_range=0.05, max_range=100.0)
SEMANTIC = 'semantic'


class OdometryPart:
    """``pose`` and ``twist`` of the ego's body (ground truth)."""

    def __init__(self, body):
        self.body = body

    def spaces(self):
        return {
            'pose': ((-INF, -INF, -math.pi), (INF, INF, math.pi), (3,), np.float32),
            'twist': ((-INF,) * 3, (INF,) * 3, (3,), np.float32),
        }

    def reset(self):
        pass

    def read(self, out):
        body = self.body
        pose = body.pose()
        x, y, _, qx, qy, qz, qw = pose
        (vx, vy, vz), (wx, wy, wz) = body.world.base_link_velocity(body.body_id, pose[:3])
        # the body's x, y, z axes in the world (columns of the rotation of the quaternion)
        ax = (1.0 - 2.0 * (qy * qy + qz * qz), 2.0 * (qx * qy + qz * qw),
              2.0 * (qx * qz - qy * qw))
        ay = (2.0 * (qx * qy - qz * qw), 1.0 - 2.0 * (qx * qx + qz * qz),
              2.0 * (qy * qz + qx * qw))
        az = (2.0 * (qx * qz + qy * qw), 2.0 * (qy * qz - qx * qw),
              1.0 - 2.0 * (qx * qx + qy * qy))
        out['pose'] = np.array((x, y, yaw_from_quaternion(qx, qy, qz, qw)), dtype=np.float32)
        out['twist'] = np.array((vx * ax[0] + vy * ax[1] + vz * ax[2],
                                 vx * ay[0] + vy * ay[1] + vz * ay[2],
                                 wx * az[0] + wy * az[1] + wz * az[2]), dtype=np.float32)


class LidarPart:
    """``lidar``: the ranges of one lidar on the ego, sampled at each observation."""

    def __init__(self, world, body, spec):
        self.world = world
        self.body = body
        self.spec = spec
        self.sensor = LidarSensor(world, body, spec)
        self._shape = (spec.horizontal_resolution,) if spec.layers == 1 else \
            (spec.layers, spec.horizontal_resolution)

    def spaces(self):
        return {LIDAR: (0.0, self.spec.max_range_m, self._shape, np.float32)}

    def reseed(self, seed):
        """Give the lidar a new noise generator (same rays) from ``seed`` (a reset's seed)."""
        if self.spec.noise_m > 0.0:
            self.spec = replace(self.spec, seed=int(seed))
            self.sensor = LidarSensor(self.world, self.body, self.spec)

    def reset(self):
        pass

    def read(self, out):
        ranges = self.sensor.sample(self.world.time_s).ranges_m.reshape(self._shape)
        ranges = np.where(ranges == INF, self.spec.max_range_m, ranges)
        out[LIDAR] = np.clip(ranges, 0.0, self.spec.max_range_m).astype(np.float32)


class CameraPart:
    """``camera``: a camera on the ego, rendered at each observation (CPU renderer)."""

    def __init__(self, world, body, spec):
        self.spec = spec
        self.world = world
        self.sensor = CameraSensor(world, body, spec)

    def spaces(self):
        size = (self.spec.height, self.spec.width)
        found = {CAMERA: (0, 255, size + (3,), np.uint8)}
        if self.spec.segmentation:
            found[SEMANTIC] = (0, len(LABELS) - 1, size, np.uint8)
        return found

    def reset(self):
        pass

    def read(self, out):
        reading = self.sensor.sample(self.world.time_s)
        out[CAMERA] = reading.rgb
        if self.spec.segmentation:
            out[SEMANTIC] = reading.semantic


class RangeFinderPart:
    """``depth``: a range finder on the ego, rendered at each observation (CPU renderer)."""

    def __init__(self, world, body, spec):
        self.spec = spec
        self.world = world
        self.sensor = RangeFinderSensor(world, body, spec)

    def spaces(self):
        return {DEPTH: (0.0, self.spec.max_range_m, (self.spec.height, self.spec.width),
                        np.float32)}

    def reset(self):
        pass

    def read(self, out):
        depth = self.sensor.sample(self.world.time_s).depth_m
        depth = np.where(depth == INF, self.spec.max_range_m, depth)
        out[DEPTH] = np.clip(depth, 0.0, self.spec.max_range_m).astype(np.float32)


def sensor_spec(option, kind, vehicle, source):
    """
    Return the SensorSpec an option asks for (``lidar``, ``camera``, ``range_finder``), or None.

    :param option: None/False (none), True (the default one), a sensor name of the ego's
        world entry, or a mapping of the type's keys (docs/sensors.md).
    :param kind: LIDAR, CAMERA or RANGE_FINDER (the type names).
    :param vehicle: the ego's SceneVehicle.
    :raises InvalidParameterError: for an unknown name or a bad key, naming the option.
    """
    if option is None or option is False:
        return None
    where = f'{source}: option {kind!r}'
    if isinstance(option, str):
        own = [s for s in getattr(vehicle.spec, 'sensors', ()) if hasattr(s, 'sensor_type')]
        for spec in own:
            if spec.name == option and spec.sensor_type == kind:
                return spec
        names = ', '.join(s.name for s in own if s.sensor_type == kind) or 'none'
        raise InvalidParameterError(f'{where} = {option!r}: the ego {vehicle.name!r} has no '
                                    f'{kind} of that name; its {kind}s: {names}')
    height = CAR_SENSOR_HEIGHT_M if vehicle.car is not None else ROBOT_SENSOR_HEIGHT_M
    data = {'type': kind, 'name': f'gym_{kind}', 'pose': {'z': height}}
    if kind == CAMERA:
        data.update(DEFAULT_CAMERA)
    if kind == RANGE_FINDER:
        data.update(DEFAULT_RANGE_FINDER)
    if isinstance(option, dict):
        data.update(option)
    return sensor_from_dict(data, where)


def ego_parts(world, vehicle, lidar_spec, camera_spec, range_finder_spec=None):
    """Return the built-in parts of the ego: odometry, then the lidar, camera, range finder."""
    parts = [OdometryPart(vehicle.body)]
    if lidar_spec is not None:
        parts.append(LidarPart(world, vehicle.body, lidar_spec))
    if camera_spec is not None:
        parts.append(CameraPart(world, vehicle.body, camera_spec))
    if range_finder_spec is not None:
        parts.append(RangeFinderPart(world, vehicle.body, range_finder_spec))
    return parts


# Factories (sim) -> part or None, run for every environment after the built-in parts, in
# order; None = nothing for this world (lane_part: a world without lanes).
PART_FACTORIES = [lane_part, objects_part]
