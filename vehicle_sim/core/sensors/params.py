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
Sensor configuration: one ParamSpec table per sensor type, the validated specs, and their rules.

A vehicle's sensors come from its preset (``sensors:`` of a car or robot preset, or the default
set of core/sensors/defaults.py, all off) and its world entry (``vehicles[i].sensors``). Every
entry is validated by :func:`vehicle_sim.core.specs.param_spec.validate_table` against the table
of its
``type``, so a negative range, a zero resolution, an unknown key or type, a NaN or a bad name is
refused with the file and the field in the message. Keys and defaults are listed in
docs/sensors.md, which a test checks against these tables.

The rules across a vehicle's sensors (unique names, devices and topics; merging a world entry
into a preset) are in core/sensors/sets.py.

Frames and topics: a sensor's frame is ``<p><name>`` (p = the vehicle's frame prefix), mounted
at ``pose`` relative to ``<p>base_link``; a camera's image is in ``<p><name>_optical``. Default
topics are relative to the vehicle namespace (see :meth:`SensorSpec.topics`).
"""

from dataclasses import dataclass, fields
import math
from typing import Dict, Optional, Tuple

from vehicle_sim.core.geometry.frames import Pose
from vehicle_sim.core.sensors.labels import check_label_names
from vehicle_sim.core.sensors.lookup_table import LookupTable
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.param_spec import (
    fail,
    parameter_table_markdown,
    ParamSpec,
    REQUIRED,
    validate_table,
)
from vehicle_sim.core.specs.value_text import brief

RADIATION_TYPES = ('ultrasound', 'infrared')
DEFAULT_DISTANCE_RANGE_M = 5.0
TWO_PI = 2.0 * math.pi

# Sensor sizes a 2-core laptop runs: every sample is one short PyBullet call (or a few), so a
# step stays short and a node stops within a second of SIGTERM. Measured here: 65536 rays
# cast in ~0.07 s, a 1920 x 1080 frame rendered in ~0.3 s (docs/sensors.md, "Sizes").
MAX_LIDAR_RAYS_PER_LAYER = 4096     # Ouster OS1: 2048; Velodyne HDL-64E: ~2000 at 10 Hz
MAX_LIDAR_LAYERS = 128              # Ouster OS1-128
MAX_LIDAR_RAYS = 65536              # per scan: horizontal_resolution x layers
MAX_DISTANCE_RAYS = 1024
MAX_CAMERA_SIDE_PX = 3840           # a 4K UHD row
MAX_CAMERA_PIXELS = 1920 * 1080     # per frame: width x height (Full HD)
# The label classes a camera's recognition reports by default: the objects (core/sensors/labels.py)
RECOGNITION_CLASSES = ('car', 'truck', 'bus', 'motorcycle', 'bicycle', 'pedestrian', 'obstacle',
                       'traffic_light')


def _common(sensor_type, rate_hz, types=None):
    # types: the valid ``type`` values shown in the docs (a type's own table: itself).
    return (
        ParamSpec('type', 'sensor_type', 'enum', sensor_type, choices=types or (sensor_type,),
                  doc='sensor type'),
        ParamSpec('name', 'name', 'ros_name', REQUIRED,
                  doc='frame <p><name>; letters, digits, underscores; unique per vehicle'),
        ParamSpec('device', 'device', 'str', None, optional=True,
                  doc='Webots device name (Driver.getDevice); null = the name'),
        ParamSpec('pose', 'pose', 'pose', Pose(), 'm, rad',
                  'mount pose relative to base_link: {x, y, z, roll, pitch, yaw}, each default 0'),
        ParamSpec('rate_hz', 'rate_hz', 'float', rate_hz, 'Hz',
                  'sampling rate on simulated time (ROS topics)', gt=0.0),
        ParamSpec('topic', 'topic', 'topic', None, optional=True,
                  doc='topic relative to the vehicle namespace; null = the type default'),
        ParamSpec('enabled', 'enabled', 'bool', True,
                  doc='mounted: published over ROS and a Webots device (presets: false)'),
        ParamSpec('seed', 'seed', 'int', 0, ge=0, doc='seed of the noise generator'),
    )


@dataclass(frozen=True)
class SensorSpec:
    """Fields every sensor has (meaning in the tables); subclasses add their type's fields."""

    sensor_type: str
    name: str
    device: str
    pose: Pose
    rate_hz: float
    topic: Optional[str]
    enabled: bool
    seed: int

    @property
    def device_names(self) -> Tuple[str, ...]:
        """The Webots device names of this sensor (an IMU has three)."""
        return (self.device,)

    @property
    def topics(self) -> Tuple[str, ...]:
        """Topics relative to the vehicle namespace: ``topic`` or the type's default."""
        return (self.topic or self._default_topic(),)

    def _default_topic(self):
        raise NotImplementedError

    def frame_id(self, prefix=''):
        """Return the sensor frame: ``<prefix><name>``."""
        return prefix + self.name

    def optical_frame_id(self, prefix=''):
        """Return the frame of an image (z forward, x right, y down); None: no image."""
        return None

    @property
    def period_s(self):
        return 1.0 / self.rate_hz

    def as_dict(self) -> Dict:
        """Return the configuration mapping of this sensor (keys as in the file)."""
        return {spec.key: _plain(getattr(self, spec.attr))
                for spec in SENSOR_TYPES[self.sensor_type].specs}


def _plain(value):
    if isinstance(value, Pose):
        return value.as_dict()
    if isinstance(value, tuple):
        return [_plain(v) for v in value]
    return value


LIDAR_SPECS = _common('lidar', 10.0) + (
    ParamSpec('fov', 'fov_rad', 'float', 1.5 * math.pi, 'rad',
              'horizontal field of view, centred on the x axis', gt=0.0, le=TWO_PI),
    ParamSpec('horizontal_resolution', 'horizontal_resolution', 'int', 1080, '',
              'rays per layer; angle_increment = fov / (rays - 1)', ge=2,
              le=MAX_LIDAR_RAYS_PER_LAYER),
    ParamSpec('layers', 'layers', 'int', 1, '', 'number of layers (1: LaserScan, >1: '
              'PointCloud2)', ge=1, le=MAX_LIDAR_LAYERS),
    ParamSpec('vertical_fov', 'vertical_fov_rad', 'float', 0.0, 'rad',
              'angle between the top and the bottom layer (> 0 with several layers)',
              ge=0.0, le=math.pi),
    ParamSpec('min_range', 'min_range_m', 'float', 0.1, 'm',
              'returns closer than this read -inf (REP 117)', ge=0.0),
    ParamSpec('max_range', 'max_range_m', 'float', 30.0, 'm',
              'no return within this reads +inf (REP 117)', gt=0.0),
    ParamSpec('noise', 'noise_m', 'float', 0.0, 'm',
              'standard deviation of the Gaussian range noise', ge=0.0),
    ParamSpec('labels', 'labels', 'bool', False, '',
              'each point also gets the label, instance id and intensity of what it hit '
              '(PointCloud2 fields intensity, label, instance; LaserScan intensities)'),
)


@dataclass(frozen=True)
class LidarSpec(SensorSpec):
    """A scanning lidar (PyBullet rayTestBatch from the mount pose)."""

    fov_rad: float
    horizontal_resolution: int
    layers: int
    vertical_fov_rad: float
    min_range_m: float
    max_range_m: float
    noise_m: float
    labels: bool = False

    def _default_topic(self):
        return 'scan' if self.layers == 1 else 'points'

    @property
    def angle_min_rad(self):
        return -self.fov_rad / 2.0

    @property
    def angle_max_rad(self):
        return self.fov_rad / 2.0

    @property
    def angle_increment_rad(self):
        return self.fov_rad / (self.horizontal_resolution - 1)

    @property
    def layer_elevations_rad(self) -> Tuple[float, ...]:
        """Elevation of each layer, top layer first (0 for a single layer)."""
        if self.layers == 1:
            return (0.0,)
        step = self.vertical_fov_rad / (self.layers - 1)
        return tuple(self.vertical_fov_rad / 2.0 - i * step for i in range(self.layers))


def _check_lidar(source, values):
    rays = values['horizontal_resolution'] * values['layers']
    if rays > MAX_LIDAR_RAYS:
        fail(source, 'layers', values['layers'],
              f'{values["horizontal_resolution"]} rays x {values["layers"]} layers = {rays} '
              f'rays per scan; at most {MAX_LIDAR_RAYS}')
    if values['min_range_m'] >= values['max_range_m']:
        fail(source, 'min_range', values['min_range_m'],
              f'must be < max_range ({values["max_range_m"]:g} m)')
    if values['layers'] > 1 and values['vertical_fov_rad'] <= 0.0:
        fail(source, 'vertical_fov', values['vertical_fov_rad'],
              f'must be > 0 with {values["layers"]} layers')


IMU_SPECS = _common('imu', 100.0) + (
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


GNSS_SPECS = _common('gnss', 10.0) + (
    ParamSpec('noise', 'noise_m', 'float', 0.0, 'm',
              'standard deviation of the position noise along east, north and up', ge=0.0),
)


@dataclass(frozen=True)
class GnssSpec(SensorSpec):
    """A GNSS antenna: WGS-84 position of the mount point (the world's geodetic origin)."""

    noise_m: float

    def _default_topic(self):
        return 'gnss/fix'


DISTANCE_SPECS = _common('distance', 20.0) + (
    ParamSpec('rays', 'rays', 'int', 1, '', 'rays in the cone (the nearest hit counts)', ge=1,
              le=MAX_DISTANCE_RAYS),
    ParamSpec('aperture', 'aperture_rad', 'float', 0.0, 'rad',
              'opening angle of the cone of rays (sensor_msgs/Range field_of_view)', ge=0.0,
              lt=math.pi),
    ParamSpec('min_range', 'min_range_m', 'float', 0.0, 'm',
              'returns closer than this read -inf (REP 117)', ge=0.0),
    ParamSpec('max_range', 'max_range_m', 'float', None, 'm',
              "length of the rays; null = the lookup table's last distance, or "
              f'{DEFAULT_DISTANCE_RANGE_M:g} m', gt=0.0, optional=True),
    ParamSpec('lookup_table', 'lookup_table', 'rows', None, '',
              'Webots rows [distance, value, noise] for getValue(); null = the distance in m',
              length=3, optional=True),
    ParamSpec('radiation_type', 'radiation_type', 'enum', 'ultrasound',
              choices=RADIATION_TYPES, doc='sensor_msgs/Range radiation_type'),
    ParamSpec('noise', 'noise_m', 'float', 0.0, 'm',
              'standard deviation of the Gaussian range noise', ge=0.0),
)


@dataclass(frozen=True)
class DistanceSpec(SensorSpec):
    """A distance sensor: a ray (or a cone of rays) along the mount's x axis."""

    rays: int
    aperture_rad: float
    min_range_m: float
    max_range_m: float
    lookup_table: Optional[Tuple[Tuple[float, float, float], ...]]
    radiation_type: str
    noise_m: float

    def _default_topic(self):
        return self.name

    def table(self) -> LookupTable:
        """Return the lookup table of getValue(): the given one, or the distance itself."""
        if self.lookup_table is None:
            return LookupTable.identity(self.max_range_m)
        return LookupTable(self.lookup_table)


def _check_distance(source, values):
    table = values['lookup_table']
    if table is not None:
        try:
            LookupTable(table)
        except ValueError as error:
            fail(source, 'lookup_table', [list(r) for r in table], str(error))
    if values['max_range_m'] is None:
        values['max_range_m'] = (table[-1][0] if table is not None
                                 else DEFAULT_DISTANCE_RANGE_M)
    if values['min_range_m'] >= values['max_range_m']:
        fail(source, 'min_range', values['min_range_m'],
              f'must be < max_range ({values["max_range_m"]:g} m)')


CAMERA_SPECS = _common('camera', 10.0) + (
    ParamSpec('width', 'width', 'int', 320, 'px',
              f'image width; width x height <= {MAX_CAMERA_PIXELS} px', ge=1,
              le=MAX_CAMERA_SIDE_PX),
    ParamSpec('height', 'height', 'int', 240, 'px', 'image height', ge=1,
              le=MAX_CAMERA_SIDE_PX),
    ParamSpec('fov', 'fov_rad', 'float', 1.0, 'rad', 'horizontal field of view', gt=0.0,
              lt=math.pi),
    ParamSpec('near', 'near_m', 'float', 0.05, 'm', 'near clipping distance', gt=0.0),
    ParamSpec('far', 'far_m', 'float', 100.0, 'm', 'far clipping distance', gt=0.0),
    ParamSpec('segmentation', 'segmentation', 'bool', False,
              doc='semantic (label id) and instance (object id) images beside the colour one '
                  '(docs/sensors.md, "Segmentation and recognition")'),
    ParamSpec('recognition', 'recognition', 'bool', False,
              doc="Webots' Recognition node: the visible objects (Camera.getRecognitionObjects, "
                  'ROS detections)'),
    ParamSpec('recognition_max_range', 'recognition_max_range_m', 'float', 100.0, 'm',
              "Webots Recognition maxRange: an object's centre farther than this is not "
              'recognised', gt=0.0),
    ParamSpec('recognition_max_objects', 'recognition_max_objects', 'int', -1, '',
              'Webots Recognition maxObjects: the most objects, the biggest on the image first; '
              '-1 = no limit', ge=-1),
    ParamSpec('recognition_min_pixels', 'recognition_min_pixels', 'int', 10, 'px',
              'the fewest visible pixels of a recognised object', ge=1),
    ParamSpec('recognition_classes', 'recognition_classes', 'str_list', RECOGNITION_CLASSES,
              doc='labels (the label table of docs/sensors.md) of the objects recognised',
              check=lambda names: check_label_names(names, 'a class') and None),
)


@dataclass(frozen=True)
class CameraSpec(SensorSpec):
    """An RGB camera (PyBullet's CPU renderer)."""

    width: int
    height: int
    fov_rad: float
    near_m: float
    far_m: float
    segmentation: bool
    recognition: bool
    recognition_max_range_m: float
    recognition_max_objects: int
    recognition_min_pixels: int
    recognition_classes: Tuple[str, ...]

    def _default_topic(self):
        return 'camera'

    @property
    def masked(self):
        """Whether a frame needs the body mask (segmentation or recognition)."""
        return self.segmentation or self.recognition

    @property
    def topics(self):
        """
        ``<topic>/image_raw`` and ``<topic>/camera_info`` (topic default 'camera').

        With segmentation also ``<topic>/semantic/image_raw`` and ``<topic>/instance/image_raw``;
        with recognition ``<topic>/detections`` and ``<topic>/labels``.
        """
        base = self.topic or self._default_topic()
        topics = (f'{base}/image_raw', f'{base}/camera_info')
        if self.segmentation:
            topics += (f'{base}/semantic/image_raw', f'{base}/instance/image_raw')
        if self.recognition:
            topics += (f'{base}/detections', f'{base}/labels')
        return topics

    def optical_frame_id(self, prefix=''):
        """Return the image frame ``<prefix><name>_optical`` (z forward, x right, y down)."""
        return f'{prefix}{self.name}_optical'

    @property
    def vertical_fov_rad(self):
        """Vertical field of view of square pixels: 2 atan(tan(fov / 2) * height / width)."""
        return 2.0 * math.atan(math.tan(self.fov_rad / 2.0) * self.height / self.width)

    @property
    def intrinsics(self):
        """
        Pinhole intrinsics (fx, fy, cx, cy) [px] of the ideal rendering.

        fx = fy = (width / 2) / tan(fov / 2); the principal point is the image centre in the
        OpenCV / ROS convention (integer coordinates at pixel centres): ((width - 1) / 2,
        (height - 1) / 2).
        """
        focal = self.width / 2.0 / math.tan(self.fov_rad / 2.0)
        return focal, focal, (self.width - 1) / 2.0, (self.height - 1) / 2.0


def _check_camera(source, values, clip_keys=('near', 'far')):
    pixels = values['width'] * values['height']
    if pixels > MAX_CAMERA_PIXELS:
        fail(source, 'height', values['height'],
              f'{values["width"]} x {values["height"]} = {pixels} pixels per frame; at most '
              f'{MAX_CAMERA_PIXELS} (1920 x 1080)')
    near, far = clip_keys
    if values['near_m'] >= values['far_m']:
        fail(source, near, values['near_m'], f'must be < {far} ({values["far_m"]:g} m)')


RANGE_FINDER_SPECS = _common('range_finder', 10.0) + (
    ParamSpec('width', 'width', 'int', 320, 'px',
              f'image width; width x height <= {MAX_CAMERA_PIXELS} px', ge=1,
              le=MAX_CAMERA_SIDE_PX),
    ParamSpec('height', 'height', 'int', 240, 'px', 'image height', ge=1,
              le=MAX_CAMERA_SIDE_PX),
    ParamSpec('fov', 'fov_rad', 'float', 1.0, 'rad', 'horizontal field of view', gt=0.0,
              lt=math.pi),
    ParamSpec('min_range', 'min_range_m', 'float', 0.05, 'm',
              'near clipping plane: nothing closer is drawn', gt=0.0),
    ParamSpec('max_range', 'max_range_m', 'float', 100.0, 'm',
              'far clipping plane: nothing drawn within it reads +inf', gt=0.0),
    ParamSpec('noise', 'noise_m', 'float', 0.0, 'm',
              'standard deviation of the Gaussian depth noise (each pixel)', ge=0.0),
    ParamSpec('point_cloud', 'point_cloud', 'bool', False,
              doc='also publish the organized PointCloud2 <topic>/points'),
)


@dataclass(frozen=True)
class RangeFinderSpec(SensorSpec):
    """
    A depth camera (Webots RangeFinder): metric depth along the optical axis per pixel.

    Its view is a camera's (square pixels, horizontal ``fov``) with the clip planes at
    ``min_range`` and ``max_range``, so that a camera with the same size, fov, near and far at
    the same mount shares its render (physics/sensors/render.py).
    """

    width: int
    height: int
    fov_rad: float
    min_range_m: float
    max_range_m: float
    noise_m: float
    point_cloud: bool

    def _default_topic(self):
        return f'{self.name}/depth'

    @property
    def topics(self):
        """``<topic>/image_raw``, ``<topic>/camera_info`` (and ``<topic>/points``)."""
        base = self.topic or self._default_topic()
        cloud = (f'{base}/points',) if self.point_cloud else ()
        return (f'{base}/image_raw', f'{base}/camera_info') + cloud

    # the pinhole geometry of a camera's image (CameraSpec: fields of the same names)
    optical_frame_id = CameraSpec.optical_frame_id
    vertical_fov_rad = CameraSpec.vertical_fov_rad
    intrinsics = CameraSpec.intrinsics


def _check_range_finder(source, values):
    _check_camera(source, dict(values, near_m=values['min_range_m'],
                               far_m=values['max_range_m']), ('min_range', 'max_range'))


RADAR_SPECS = _common('radar', 20.0) + (
    ParamSpec('min_range', 'min_range_m', 'float', 1.0, 'm',
              'nearer targets are not seen (Webots minRange)', ge=0.0),
    ParamSpec('max_range', 'max_range_m', 'float', 50.0, 'm',
              'farther targets are not seen (Webots maxRange)', gt=0.0),
    ParamSpec('horizontal_fov', 'horizontal_fov_rad', 'float', 0.78, 'rad',
              'horizontal field of view of the cone, centred on the x axis', gt=0.0,
              le=TWO_PI),
    ParamSpec('vertical_fov', 'vertical_fov_rad', 'float', 0.1, 'rad',
              'vertical field of view of the cone', gt=0.0, le=math.pi),
    ParamSpec('min_absolute_radial_speed', 'min_absolute_radial_speed_mps', 'float', 0.0,
              'm/s', 'targets slower than this (radially, relative) are not seen', ge=0.0),
    ParamSpec('min_radial_speed', 'min_radial_speed_mps', 'float', 0.0, 'm/s',
              'slowest radial speed seen (both 0: no limits; < 0 = closing)'),
    ParamSpec('max_radial_speed', 'max_radial_speed_mps', 'float', 0.0, 'm/s',
              'fastest radial speed seen (both 0: no limits)'),
    ParamSpec('cell_distance', 'cell_distance_m', 'float', 0.0, 'm',
              'targets closer in range than this merge into one (0: never)', ge=0.0),
    ParamSpec('cell_speed', 'cell_speed_mps', 'float', 0.0, 'm/s',
              'and closer in radial speed than this (0: range alone decides)', ge=0.0),
    ParamSpec('range_noise', 'range_noise_m', 'float', 0.0, 'm',
              'standard deviation of the Gaussian distance noise', ge=0.0),
    ParamSpec('speed_noise', 'speed_noise_mps', 'float', 0.0, 'm/s',
              'standard deviation of the Gaussian radial speed noise', ge=0.0),
    ParamSpec('angular_noise', 'angular_noise_rad', 'float', 0.0, 'rad',
              'standard deviation of the Gaussian azimuth noise', ge=0.0),
    ParamSpec('antenna_gain', 'antenna_gain_dbi', 'float', 20.0, 'dBi',
              'antenna gain (radar equation)'),
    ParamSpec('frequency', 'frequency_ghz', 'float', 24.0, 'GHz',
              'carrier frequency (wavelength of the radar equation)', gt=0.0),
    ParamSpec('transmitted_power', 'transmitted_power_dbm', 'float', 20.0, 'dBm',
              'transmitted power (radar equation)'),
    ParamSpec('min_detectable_signal', 'min_detectable_signal_dbm', 'float', -100.0, 'dBm',
              'targets returning less power are not seen'),
    ParamSpec('occlusion', 'occlusion', 'bool', False,
              doc='a target hidden behind another body (a ray to its centre) is not seen'),
)


@dataclass(frozen=True)
class RadarSpec(SensorSpec):
    """A radar (Webots Radar): targets with distance, received power, radial speed, azimuth."""

    min_range_m: float
    max_range_m: float
    horizontal_fov_rad: float
    vertical_fov_rad: float
    min_absolute_radial_speed_mps: float
    min_radial_speed_mps: float
    max_radial_speed_mps: float
    cell_distance_m: float
    cell_speed_mps: float
    range_noise_m: float
    speed_noise_mps: float
    angular_noise_rad: float
    antenna_gain_dbi: float
    frequency_ghz: float
    transmitted_power_dbm: float
    min_detectable_signal_dbm: float
    occlusion: bool

    def _default_topic(self):
        return self.name

    @property
    def topics(self):
        """``<topic>/tracks`` (radar_msgs/RadarTracks) and ``<topic>/scan`` (RadarScan)."""
        base = self.topic or self._default_topic()
        return (f'{base}/tracks', f'{base}/scan')


def _check_radar(source, values):
    if values['min_range_m'] >= values['max_range_m']:
        fail(source, 'min_range', values['min_range_m'],
              f'must be < max_range ({values["max_range_m"]:g} m)')
    low, high = values['min_radial_speed_mps'], values['max_radial_speed_mps']
    if (low or high) and low >= high:
        fail(source, 'min_radial_speed', low,
              f'must be < max_radial_speed ({high:g} m/s), or both 0 (no limits)')


@dataclass(frozen=True)
class SensorType:
    """One registry row: the spec class, its ParamSpec table and its cross-field check."""

    spec_class: type
    specs: Tuple[ParamSpec, ...]
    check: object


# The core registration of the sensor types, in docs order: the one list of type names. Each
# other layer registers its part under these names (physics class, ROS rows, Webots devices);
# check_layer refuses a layer that misses one (docs/sensors.md, "Adding a sensor type").
SENSOR_TYPES: Dict[str, SensorType] = {
    'lidar': SensorType(LidarSpec, LIDAR_SPECS, _check_lidar),
    'imu': SensorType(ImuSpec, IMU_SPECS, None),
    'gnss': SensorType(GnssSpec, GNSS_SPECS, None),
    'distance': SensorType(DistanceSpec, DISTANCE_SPECS, _check_distance),
    'camera': SensorType(CameraSpec, CAMERA_SPECS, _check_camera),
    'range_finder': SensorType(RangeFinderSpec, RANGE_FINDER_SPECS, _check_range_finder),
    'radar': SensorType(RadarSpec, RADAR_SPECS, _check_radar),
}


def check_layer(layer, registered):
    """
    Refuse a layer's sensor registration that misses a core sensor type or names an unknown one.

    :param layer: what registers (quoted in the error), e.g. 'physics SENSOR_CLASSES'.
    :param registered: the sensor type names the layer registers.
    :raises RuntimeError: naming the missing and the unknown types.
    """
    names = set(registered)
    missing = [name for name in SENSOR_TYPES if name not in names]
    unknown = sorted(names - set(SENSOR_TYPES))
    if missing or unknown:
        raise RuntimeError(f'{layer}: sensor types missing: {", ".join(missing) or "none"}; '
                           f'unknown: {", ".join(unknown) or "none"} (registered in '
                           f'core/sensors/params.py SENSOR_TYPES: {", ".join(SENSOR_TYPES)})')


def sensor_from_dict(data, source, enabled_default=True) -> SensorSpec:
    """
    Validate one sensor mapping.

    :param data: the mapping (keys of the type's table; ``type`` and ``name`` required).
    :param source: file and place quoted in errors (``'w.yaml: vehicles[0].sensors[1]'``).
    :param enabled_default: ``enabled`` when the mapping does not say (presets: False).
    :return: the type's SensorSpec subclass.
    :raises InvalidParameterError: naming source, field and value.
    """
    if not isinstance(data, dict):
        raise InvalidParameterError(f'{source}: a sensor must be a mapping, got {brief(data)}')
    sensor_type = data.get('type', REQUIRED)
    if sensor_type is REQUIRED:
        raise InvalidParameterError(f"{source}: field 'type' is required; one of "
                                    + ', '.join(SENSOR_TYPES))
    row = SENSOR_TYPES.get(sensor_type) if isinstance(sensor_type, str) else None
    if row is None:
        raise InvalidParameterError(f"{source}: field 'type' = {brief(sensor_type)}: unknown "
                                    f'sensor type; valid: {", ".join(SENSOR_TYPES)}')
    defaults = {spec.key: spec.default for spec in row.specs}
    defaults['enabled'] = enabled_default
    values = validate_table(row.specs, data, source, defaults, 'a sensor')
    if values['device'] is None:
        values['device'] = values['name']
    if row.check is not None:
        row.check(source, values)
    return row.spec_class(**values)


COMMON_KEYS = tuple(spec.key for spec in _common('any', 1.0))


def sensors_markdown():
    """Return the key tables of docs/sensors.md: the common keys, then each type's own."""
    parts = ['#### Keys of every sensor\n\n',
             parameter_table_markdown(_common('required', 'see the type', tuple(SENSOR_TYPES)),
                                      'key')]
    for name, row in SENSOR_TYPES.items():
        rate = next(spec.default for spec in row.specs if spec.key == 'rate_hz')
        parts.append(f'\n#### `{name}` (default `rate_hz`: {rate:g} Hz)\n\n'
                     + parameter_table_markdown(row.specs, 'key', skip=COMMON_KEYS))
    return ''.join(parts)


def spec_field_names(sensor_type) -> Tuple[str, ...]:
    """Return the keys of a sensor type's table, in table order (docs, tests)."""
    return tuple(spec.key for spec in SENSOR_TYPES[sensor_type].specs)


assert all(len(fields(row.spec_class)) == len(row.specs) for row in SENSOR_TYPES.values())
