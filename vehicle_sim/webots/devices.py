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
Webots sensor devices on the simulated sensors: ``Driver.getDevice(name)`` returns these.

Each class has the Webots Python method names and semantics (Webots reference manual: lidar.md,
camera.md, gps.md, inertial_unit.md, gyro.md, accelerometer.md, distancesensor.md,
rangefinder.md):

- ``enable(samplingPeriod)`` [ms] starts sampling; the first value is there one period later;
  before it a value reads NaN (an image or a range image: None). ``enable(0)`` and
  ``disable()`` stop it; ``getSamplingPeriod()`` returns the period or 0. A negative period
  warns and is ignored; reading a disabled device warns and returns NaN (Webots prints an
  error and returns NaN too). A wrong argument type raises TypeError, as in the other facades.
- Values are those of the mount frame (the sensor's ``pose``): Webots' device frame (x
  forward, y left, z up).

Sampling follows the device's own period on the world's basic steps (core/sensors/sampling.py); the
SensorSpec's ``rate_hz`` is for the ROS topics only.
"""

import math
import numbers
import os

import numpy as np

from vehicle_sim.core.sensors.params import check_layer
from vehicle_sim.webots.api_table import DEVICE_API
from vehicle_sim.webots.camera_recognition import CameraRecognition, CameraRecognitionObject
from vehicle_sim.webots.radar_device import RadarMethods, RadarTarget
from vehicle_sim.webots.webots_warning import warn

NAN3 = [math.nan] * 3


def _warn(message):
    warn(message, stacklevel=3)


class Device:
    """
    A Webots device backed by a mounted sensor of a vehicle.

    :param suite: the vehicle's physics SensorSuite.
    :param spec: the sensor's SensorSpec.
    :param name: the Webots device name.
    """

    _NODE = ''

    def __init__(self, suite, spec, name):
        self._suite = suite
        self._spec = spec
        self._name = name
        self._period_ms = 0
        self._since_s = None

    def getName(self):
        """Return the device name."""
        return self._name

    def getModel(self):
        """Return the device model (the Webots Solid's model field): ''."""
        return ''

    def enable(self, samplingPeriod):
        """Sample every ``samplingPeriod`` ms from now on (the first value after one period)."""
        if isinstance(samplingPeriod, bool) or not isinstance(samplingPeriod, numbers.Integral):
            raise TypeError(f'enable() expects a sampling period in ms (int), '
                            f'got {samplingPeriod!r}')
        if samplingPeriod < 0:
            _warn(f'{self._name}: enable() called with negative sampling period '
                  f'({samplingPeriod}); ignored')
            return
        if samplingPeriod == 0:
            self.disable()
            return
        self._period_ms = int(samplingPeriod)
        self._since_s = self._suite.world.time_s
        self._suite.set_period_ms(self._spec.name, self._period_ms, key=self._name)

    def disable(self):
        """Stop sampling."""
        self._period_ms = 0
        self._since_s = None
        self._suite.stop(self._name)

    def getSamplingPeriod(self):
        """Return the sampling period [ms], 0 when disabled."""
        return self._period_ms

    @property
    def sampling_period(self):
        return self.getSamplingPeriod()

    def _reading(self, function):
        """Return the reading since the last enable(), None before its first sample."""
        if not self._period_ms:
            _warn(f'{function}() called for a disabled device {self._name!r}! Please use: '
                  'enable()')
            return None
        reading = self._suite.latest(self._name)
        if reading is None or reading.time_s <= self._since_s:
            return None
        return reading

    def __repr__(self):
        return f'{type(self).__name__}({self._name!r})'


class Lidar(Device):
    """Webots Lidar: range image left to right (Webots' order), top layer first."""

    def __init__(self, suite, spec, name):
        super().__init__(suite, spec, name)
        self._point_cloud = False

    def _ranges(self, function):
        reading = self._reading(function)
        if reading is None:
            return None
        # Webots: left (+fov/2) to right; a return outside [minRange, maxRange] is inf
        ranges = reading.ranges_m[:, ::-1].astype(float)
        ranges[~(ranges >= 0.0)] = math.inf     # REP 117 -inf (too close) -> inf
        return ranges

    def getRangeImage(self):
        """Return every layer's ranges [m], left to right, top layer first (None before a scan)."""
        ranges = self._ranges('getRangeImage')
        return None if ranges is None else ranges.ravel().tolist()

    def getRangeImageArray(self):
        """Return the range image as a list of layers, each a list left to right [m]."""
        ranges = self._ranges('getRangeImageArray')
        return None if ranges is None else ranges.tolist()

    def getLayerRangeImage(self, layer):
        """Return one layer's ranges [m], left to right (layer 0 = the top one)."""
        ranges = self._ranges('getLayerRangeImage')
        if ranges is None:
            return None
        if not 0 <= layer < len(ranges):
            _warn(f'getLayerRangeImage({layer}): layer outside 0..{len(ranges) - 1}')
            return None
        return ranges[layer].tolist()

    def enablePointCloud(self):
        """Compute the point cloud too (it costs little here; kept for the API)."""
        self._point_cloud = True

    def disablePointCloud(self):
        self._point_cloud = False

    def isPointCloudEnabled(self):
        return self._point_cloud

    def getNumberOfPoints(self):
        """Return the number of points of a scan (rays x layers)."""
        return self._spec.horizontal_resolution * self._spec.layers

    def getPointCloud(self, data_type='list'):
        """
        Return the points of the last scan in the lidar frame, Webots' order.

        Each point has x, y, z [m] (inf where a ray has no return), layer_id and time (0: the
        whole scan is taken at one instant). None before the first scan or when the point cloud
        is not enabled.
        """
        if data_type != 'list':
            raise NotImplementedError("getPointCloud(data_type='buffer') is not provided")
        if not self._point_cloud:
            _warn('getPointCloud(): the point cloud is disabled; use enablePointCloud()')
            return None
        reading = self._reading('getPointCloud')
        if reading is None:
            return None
        points = reading.points()[:, ::-1]
        result = []
        for layer, row in enumerate(points):
            for x, y, z in row.tolist():
                if math.isnan(x):
                    x = y = z = math.inf
                result.append(LidarPoint(x, y, z, layer, 0.0))
        return result

    def getFrequency(self):
        """Return the head's rotation frequency: 0 (a fixed lidar)."""
        return 0.0

    def setFrequency(self, frequency):
        """Warn: only rotating lidars have a frequency (Webots)."""
        _warn(f'{self._name}: setFrequency() is only for rotating lidars; ignored')


class LidarPoint:
    """Webots LidarPoint: x, y, z [m], layer_id, time [s]."""

    __slots__ = ('x', 'y', 'z', 'layer_id', 'time')

    def __init__(self, x, y, z, layer_id, time):
        self.x, self.y, self.z, self.layer_id, self.time = x, y, z, layer_id, time

    def __repr__(self):
        return f'LidarPoint(x={self.x}, y={self.y}, z={self.z}, layer_id={self.layer_id})'


class Camera(CameraRecognition, Device):
    """Webots Camera: BGRA image bytes, rows top to bottom (recognition: its base class)."""

    def getImage(self):
        """Return the last image as BGRA bytes (width * height * 4), None before the first."""
        reading = self._reading('getImage')
        if reading is None:
            return None
        rgb = reading.rgb
        bgra = bytearray(reading.width * reading.height * 4)
        bgra[0::4] = rgb[:, :, 2].tobytes()
        bgra[1::4] = rgb[:, :, 1].tobytes()
        bgra[2::4] = rgb[:, :, 0].tobytes()
        bgra[3::4] = b'\xff' * (reading.width * reading.height)
        return bytes(bgra)

    def getImageArray(self):
        """Return the last image as image[x][y] = [red, green, blue] (Webots' layout)."""
        reading = self._reading('getImageArray')
        return None if reading is None else reading.rgb.transpose(1, 0, 2).tolist()

    @staticmethod
    def imageGetRed(image, width, x, y):
        return image[4 * (y * width + x) + 2]

    @staticmethod
    def imageGetGreen(image, width, x, y):
        return image[4 * (y * width + x) + 1]

    @staticmethod
    def imageGetBlue(image, width, x, y):
        return image[4 * (y * width + x)]

    @staticmethod
    def imageGetGray(image, width, x, y):
        offset = 4 * (y * width + x)
        return (image[offset] + image[offset + 1] + image[offset + 2]) // 3


class GPS(Device):
    """Webots GPS: local coordinates (the world frame, x east, y north, z up)."""

    LOCAL = 0
    WGS84 = 1

    def getValues(self):
        """Return the antenna position [x, y, z] in the world frame [m] (NaN before a fix)."""
        reading = self._reading('getValues')
        return list(NAN3) if reading is None else list(reading.position_m)

    def getSpeed(self):
        """Return the antenna's speed [m/s] (NaN before a fix)."""
        reading = self._reading('getSpeed')
        return math.nan if reading is None else math.sqrt(sum(v * v for v in
                                                              reading.velocity_mps))

    def getSpeedVector(self):
        """Return the antenna's velocity [vx, vy, vz] in the world frame [m/s]."""
        reading = self._reading('getSpeedVector')
        return list(NAN3) if reading is None else list(reading.velocity_mps)

    def getCoordinateSystem(self):
        """Return LOCAL: getValues() gives world coordinates (the ROS topic gives WGS-84)."""
        return self.LOCAL

    @staticmethod
    def convertToDegreesMinutesSeconds(decimalDegree):
        """Format decimal degrees as degrees, minutes and seconds: 48°7'30.00" for 48.125."""
        sign = '-' if decimalDegree < 0 else ''
        value = abs(decimalDegree)
        degrees = int(value)
        minutes = int((value - degrees) * 60.0)
        seconds = (value - degrees - minutes / 60.0) * 3600.0
        return f'{sign}{degrees}°{minutes}\'{seconds:.2f}"'


class InertialUnit(Device):
    """Webots InertialUnit: attitude relative to the ENU world."""

    def getRollPitchYaw(self):
        """Return [roll, pitch, yaw] [rad] (NaN before the first sample)."""
        reading = self._reading('getRollPitchYaw')
        return list(NAN3) if reading is None else list(reading.roll_pitch_yaw_rad)

    def getQuaternion(self):
        """Return the orientation [x, y, z, w] (NaN before the first sample)."""
        reading = self._reading('getQuaternion')
        return [math.nan] * 4 if reading is None else list(reading.orientation_xyzw)

    def getNoise(self):
        """Return the noise field: the orientation sigma relative to pi/2 (Webots)."""
        return self._spec.orientation_noise_rad / (math.pi / 2.0)


class Gyro(Device):
    """Webots Gyro: angular velocity in the device frame [rad/s]."""

    def getValues(self):
        reading = self._reading('getValues')
        return list(NAN3) if reading is None else list(reading.angular_velocity_radps)

    def getLookupTable(self):
        """Return [] (no lookup table: the values are the angular velocity itself)."""
        return []


class Accelerometer(Device):
    """Webots Accelerometer: specific force in the device frame, gravity included [m/s^2]."""

    def getValues(self):
        reading = self._reading('getValues')
        return list(NAN3) if reading is None else list(reading.linear_acceleration_mps2)

    def getLookupTable(self):
        """Return [] (no lookup table: the values are the acceleration itself)."""
        return []


class DistanceSensor(Device):
    """Webots DistanceSensor: the lookup table's response to the nearest ray's distance."""

    GENERIC = 0
    INFRA_RED = 1
    SONAR = 2
    LASER = 3

    def __init__(self, suite, spec, name):
        super().__init__(suite, spec, name)
        self._table = spec.table()

    def getValue(self):
        """Return the response value of the last sample (NaN before the first)."""
        reading = self._reading('getValue')
        return math.nan if reading is None else reading.value

    def getMaxValue(self):
        """Return the largest value of the lookup table's second column."""
        return self._table.max_value

    def getMinValue(self):
        """Return the smallest value of the lookup table's second column."""
        return self._table.min_value

    def getType(self):
        """Return SONAR (ultrasound) or INFRA_RED: both report the nearest ray here."""
        return self.SONAR if self._spec.radiation_type == 'ultrasound' else self.INFRA_RED

    def getLookupTable(self):
        """Return the lookup table as a flat list [distance, value, noise, ...]."""
        return [value for row in self._table.rows for value in row]


class RangeFinder(Device):
    """
    Webots RangeFinder: depth [m] along the optical axis, rows top to bottom, left to right.

    A pixel with nothing within ``maxRange`` (or, with noise, a depth outside ``[minRange,
    maxRange]``) reads inf, as in Webots (the ROS image keeps REP 118's -inf for the latter).
    """

    def _depth(self, function):
        reading = self._reading(function)
        if reading is None:
            return None
        depth = reading.depth_m.astype(np.float32)
        depth[np.isneginf(depth)] = np.inf
        return depth

    def getRangeImage(self, data_type='list'):
        """
        Return the last range image: width * height floats, row by row (None before one).

        ``data_type='buffer'``: the same values as native float32 bytes (Webots' buffer).
        """
        if data_type not in ('list', 'buffer'):
            raise ValueError(f"getRangeImage(data_type={data_type!r}): 'list' or 'buffer'")
        depth = self._depth('getRangeImage')
        if depth is None:
            return None
        return depth.tobytes() if data_type == 'buffer' else depth.ravel().tolist()

    def getRangeImageArray(self):
        """Return the last range image as a list of rows (image[y][x], Webots' Python)."""
        depth = self._depth('getRangeImageArray')
        return None if depth is None else depth.tolist()

    @staticmethod
    def rangeImageGetDepth(image, width, x, y):
        """Return the depth of pixel (x, y) of a getRangeImage() list."""
        return image[y * width + x]

    imageGetDepth = rangeImageGetDepth      # Webots' C name: wb_range_finder_image_get_depth

    def saveImage(self, filename, quality):
        """
        Save the last range image as a grey PNG or JPEG, as Webots does; return 0, or -1.

        Grey = 255 (depth - minRange) / maxRange, bounded to 0..255 (inf: 255). ``quality``
        (1..100) is the JPEG quality. Needs Pillow (the 'maps' extra). -1 (with a warning) for
        another extension, a bad quality, no image yet or a file that cannot be written.
        """
        extension = os.path.splitext(str(filename))[1].lower()
        if extension not in ('.png', '.jpg', '.jpeg'):
            _warn(f'saveImage({filename!r}): only .png, .jpg and .jpeg are provided')
            return -1
        if isinstance(quality, bool) or not isinstance(quality, numbers.Integral) \
                or not 1 <= quality <= 100:
            _warn(f'saveImage(): quality = {quality!r}: must be an integer in 1..100')
            return -1
        depth = self._depth('saveImage')
        if depth is None:
            return -1
        try:
            from PIL import Image
        except ImportError as error:
            raise ImportError("RangeFinder.saveImage needs Pillow: pip install "
                              "'vehicle_sim[maps]'") from error
        spec = self._spec
        scaled = np.clip((depth.astype(np.float64) - spec.min_range_m) / spec.max_range_m,
                         0.0, 1.0)
        grey = (scaled * 255.0).astype(np.uint8)
        try:
            Image.fromarray(np.repeat(grey[:, :, None], 3, axis=2), 'RGB').save(
                filename, quality=int(quality))
        except OSError as error:
            _warn(f'saveImage({filename!r}): {error}')
            return -1
        return 0


def _make_spec_getter(name, attr, kind):
    def getter(self):
        return kind(getattr(self._spec, attr))
    getter.__name__ = name
    getter.__doc__ = f"Webots {name}(): the sensor's {attr}."
    return getter


class Radar(RadarMethods, Device):
    """Webots Radar: the targets of the last sample, none before the first (radar_device.py)."""


# The Webots registration is DEVICE_API (webots/api_table.py): each row names a device class of
# this module and the core sensor type it serves; checked against the core types when imported.
check_layer('Webots DEVICE_API (webots/api_table.py)', {row.sensor_type for row in DEVICE_API})
DEVICE_CLASSES = {row.device_class: globals()[row.device_class] for row in DEVICE_API}
for _row in DEVICE_API:
    for _name, _attr, _kind in _row.spec_getters:
        setattr(DEVICE_CLASSES[_row.device_class], _name, _make_spec_getter(_name, _attr, _kind))


def devices_of(suite):
    """
    Build the Webots devices of a vehicle's mounted sensors, in sensor order.

    :param suite: the vehicle's SensorSuite.
    :return: {device name: Device}.
    """
    devices = {}
    for spec in suite.specs.values():
        for row in DEVICE_API:
            if row.sensor_type == spec.sensor_type:
                name = getattr(spec, row.name_attr)
                devices[name] = DEVICE_CLASSES[row.device_class](suite, spec, name)
    return devices


__all__ = ['Accelerometer', 'Camera', 'CameraRecognitionObject', 'DEVICE_CLASSES', 'Device',
           'DistanceSensor', 'GPS', 'Gyro', 'InertialUnit', 'Lidar', 'LidarPoint', 'Radar',
           'RadarTarget', 'RangeFinder', 'devices_of']
