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
Sensor readings: plain values with everything a ROS message converter needs, and no ROS types.

Every reading carries the sensor's ``name`` and the simulated ``time_s`` of its sample; the
frame is ``<p><name>`` (a camera image: ``<p><name>_optical``, see CameraSpec). Ranges follow
REP 117: +inf = no return within max_range, -inf = a return closer than min_range.
"""

from dataclasses import dataclass, field
from typing import Optional, Tuple

import numpy as np

from vehicle_sim.core.geometry.frames import rpy_from_quaternion

Vector = Tuple[float, float, float]
Covariance = Tuple[float, ...]       # 9 values, row-major 3 x 3

ZERO_COVARIANCE: Covariance = (0.0,) * 9


def diagonal_covariance(sigma):
    """Return the row-major 3 x 3 covariance with sigma^2 on the diagonal."""
    variance = float(sigma) ** 2
    return (variance, 0.0, 0.0, 0.0, variance, 0.0, 0.0, 0.0, variance)


@dataclass(frozen=True, eq=False)
class LidarReading:
    """
    One lidar scan (sensor_msgs/LaserScan for one layer, PointCloud2 for several).

    ``ranges_m`` has shape (layers, rays), float32, layer 0 the top one, rays counter-clockwise
    from ``angle_min_rad`` (REP 117 values). ``directions`` (layers, rays, 3) are the unit ray
    vectors in the sensor frame. A labelled lidar's (``labels: true``) also gives, of the same
    shape, what each ray hit: ``labels`` (uint8, core/sensors/labels.py ids), ``instances``
    (uint16 instance ids, 0 = none) and ``intensities`` (float32: the label's reflectivity
    times |cos| of the angle between the ray and the surface's normal); 0 where the range is
    not finite. None without the key.
    """

    name: str
    time_s: float
    angle_min_rad: float
    angle_max_rad: float
    angle_increment_rad: float
    range_min_m: float
    range_max_m: float
    scan_time_s: float
    layer_elevations_rad: Tuple[float, ...]
    ranges_m: np.ndarray
    directions: np.ndarray = field(repr=False)
    time_increment_s: float = 0.0      # every ray of a scan is cast at the same instant
    labels: Optional[np.ndarray] = field(default=None, repr=False)
    instances: Optional[np.ndarray] = field(default=None, repr=False)
    intensities: Optional[np.ndarray] = field(default=None, repr=False)

    @property
    def scan(self) -> np.ndarray:
        """The ranges of the middle layer (the only one of a 2-D lidar) [m], float32."""
        return self.ranges_m[len(self.layer_elevations_rad) // 2]

    def points(self) -> np.ndarray:
        """
        Return the organized point cloud in the sensor frame: (layers, rays, 3) float32 [m].

        Rays without a finite range (REP 117 +/-inf) give NaN points (PointCloud2 is_dense
        false, height = layers, width = rays).
        """
        ranges = self.ranges_m.astype(np.float64)
        finite = np.isfinite(ranges)
        xyz = self.directions * np.where(finite, ranges, np.nan)[..., None]
        return xyz.astype(np.float32)


@dataclass(frozen=True)
class ImuReading:
    """
    One IMU sample (sensor_msgs/Imu), in the sensor frame.

    ``orientation_xyzw``: the sensor frame in the world (ENU); ``angular_velocity_radps``;
    ``linear_acceleration_mps2``: specific force, including gravity (+9.81 on z at rest, level).
    Covariances: sigma^2 on the diagonal, all zero when the noise is off ("unknown").
    """

    name: str
    time_s: float
    orientation_xyzw: Tuple[float, float, float, float]
    angular_velocity_radps: Vector
    linear_acceleration_mps2: Vector
    orientation_covariance: Covariance = ZERO_COVARIANCE
    angular_velocity_covariance: Covariance = ZERO_COVARIANCE
    linear_acceleration_covariance: Covariance = ZERO_COVARIANCE

    @property
    def roll_pitch_yaw_rad(self) -> Vector:
        """Orientation as roll, pitch, yaw (URDF rpy, relative to the ENU world)."""
        return rpy_from_quaternion(self.orientation_xyzw)


# sensor_msgs/NavSatStatus and NavSatFix constants
STATUS_FIX = 0
SERVICE_GPS = 1
COVARIANCE_TYPE_UNKNOWN = 0
COVARIANCE_TYPE_DIAGONAL_KNOWN = 2


@dataclass(frozen=True)
class GnssReading:
    """
    One GNSS fix (sensor_msgs/NavSatFix) and the antenna's local position and velocity.

    ``position_covariance`` is in m^2, east-north-up (row-major 3 x 3); ``covariance_type`` is
    DIAGONAL_KNOWN with noise, UNKNOWN without. ``position_m`` is the (noisy) antenna position
    in the world frame (Webots' local GPS coordinates); ``velocity_mps`` its world velocity.
    """

    name: str
    time_s: float
    latitude_deg: float
    longitude_deg: float
    altitude_m: float
    position_m: Vector
    velocity_mps: Vector
    position_covariance: Covariance = ZERO_COVARIANCE
    covariance_type: int = COVARIANCE_TYPE_UNKNOWN
    status: int = STATUS_FIX
    service: int = SERVICE_GPS


# sensor_msgs/Range radiation types
RADIATION_TYPE = {'ultrasound': 0, 'infrared': 1}


@dataclass(frozen=True)
class RangeReading:
    """
    One distance sample (sensor_msgs/Range) and Webots' response value.

    ``range_m`` follows REP 117; ``variance_m2`` is the range noise's sigma^2 (Jazzy's Range
    ``variance``; 0 = unknown, the noise is off); ``distance_m`` is the nearest hit
    (``max_range_m`` when none, as a Webots ray that hits nothing); ``value`` is the
    lookup-table response to ``distance_m`` (Webots DistanceSensor.getValue()).
    """

    name: str
    time_s: float
    range_m: float
    min_range_m: float
    max_range_m: float
    field_of_view_rad: float
    radiation_type: int
    distance_m: float
    value: float
    variance_m2: float = 0.0


@dataclass(frozen=True, eq=False)
class CameraReading:
    """
    One camera frame (sensor_msgs/Image rgb8 + CameraInfo), in the optical frame.

    ``rgb``: (height, width, 3) uint8, row 0 at the top. ``k`` (3 x 3), ``p`` (3 x 4), ``r``
    (3 x 3) row-major as in CameraInfo; no distortion (plumb_bob, d = 5 zeros). A camera with
    segmentation adds ``semantic`` ((height, width) uint8 label ids, core/sensors/labels.py) and
    ``instance`` ((height, width) uint16 object ids, 0 = none); one with recognition adds
    ``objects`` (core/sensors/recognition.py RecognitionObject, in id order). None otherwise.
    """

    name: str
    time_s: float
    width: int
    height: int
    rgb: np.ndarray = field(repr=False)
    k: Tuple[float, ...]
    p: Tuple[float, ...]
    r: Tuple[float, ...] = (1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0)
    d: Tuple[float, ...] = (0.0,) * 5
    distortion_model: str = 'plumb_bob'
    encoding: str = 'rgb8'
    semantic: Optional[np.ndarray] = field(default=None, repr=False)
    instance: Optional[np.ndarray] = field(default=None, repr=False)
    objects: Optional[Tuple] = None

    @property
    def step(self):
        """Bytes per image row (sensor_msgs/Image step)."""
        return 3 * self.width

    @property
    def data(self) -> bytes:
        """The image bytes (sensor_msgs/Image data), rows top to bottom."""
        return self.rgb.tobytes()


def camera_matrices(fx, fy, cx, cy):
    """
    Return CameraInfo's K and P of an ideal pinhole camera.

    :return: (k, p): 9 and 12 row-major values.
    """
    k = (fx, 0.0, cx, 0.0, fy, cy, 0.0, 0.0, 1.0)
    p = (fx, 0.0, cx, 0.0, 0.0, fy, cy, 0.0, 0.0, 0.0, 1.0, 0.0)
    return k, p


@dataclass(frozen=True, eq=False)
class DepthReading:
    """
    One range-finder frame (sensor_msgs/Image 32FC1 + CameraInfo, PointCloud2), optical frame.

    ``depth_m``: (height, width) float32, row 0 at the top: the distance of each pixel's
    surface from the image plane, along the optical axis (z), in metres. REP 118 values: +inf
    where nothing is within ``max_range_m`` (nothing drawn, the sky), -inf where noise puts a
    depth under ``min_range_m``. ``k``, ``p``, ``r``, ``d`` as in CameraReading; it has the
    fields a CameraReading's image and camera_info builders read (ros/messages.py).
    """

    name: str
    time_s: float
    width: int
    height: int
    depth_m: np.ndarray = field(repr=False)
    k: Tuple[float, ...]
    p: Tuple[float, ...]
    min_range_m: float
    max_range_m: float
    r: Tuple[float, ...] = (1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0)
    d: Tuple[float, ...] = (0.0,) * 5
    distortion_model: str = 'plumb_bob'
    encoding: str = '32FC1'

    @property
    def step(self):
        """Bytes per image row (sensor_msgs/Image step): 4 * width."""
        return 4 * self.width

    @property
    def data(self) -> bytes:
        """The image bytes (sensor_msgs/Image data): little-endian float32, rows top to bottom."""
        return np.ascontiguousarray(self.depth_m, dtype='<f4').tobytes()

    def points(self) -> np.ndarray:
        """
        Return the organized point cloud in the optical frame: (height, width, 3) float32 [m].

        As depth_image_proc's point_cloud_xyz: x = (u - cx) z / fx, y = (v - cy) z / fy, z the
        depth; NaN points where the depth is not finite (PointCloud2 is_dense false).
        """
        fx, cx, fy, cy = self.k[0], self.k[2], self.k[4], self.k[5]
        z = self.depth_m.astype(np.float64)
        z = np.where(np.isfinite(z), z, np.nan)
        u = (np.arange(self.width) - cx) / fx
        v = (np.arange(self.height) - cy) / fy
        return np.stack((z * u[None, :], z * v[:, None], z), axis=-1).astype(np.float32)


@dataclass(frozen=True)
class RadarDetection:
    """
    One radar target (Webots WbRadarTarget, plus the ground truth of what it is).

    ``distance_m`` to the body's centre; ``received_power_dbm`` by the radar equation;
    ``speed_mps`` the radial speed relative to the radar (> 0 moving away, < 0 closing, as
    Webots); ``azimuth_rad`` the horizontal angle from the x axis (> 0 to the left, REP 103;
    Webots' sign is the opposite, its device converts). ``elevation_rad`` the vertical angle;
    ``position_m``, ``velocity_mps`` (relative to the radar) and ``size_m`` the body's, in the
    radar frame (RadarTracks); ``label`` and ``instance_id`` the body's (core/sensors/labels.py,
    physics/body_labels.py; 0 for a merged target of several instances).
    """

    distance_m: float
    received_power_dbm: float
    speed_mps: float
    azimuth_rad: float
    elevation_rad: float
    position_m: Vector
    velocity_mps: Vector
    size_m: Vector
    label: int
    instance_id: int


@dataclass(frozen=True)
class RadarReading:
    """One radar sample: its targets, nearest first (radar_msgs RadarTracks and RadarScan)."""

    name: str
    time_s: float
    targets: Tuple[RadarDetection, ...]
