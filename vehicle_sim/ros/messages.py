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
Message builders: one per published ROS type, constant parts fixed once, values per call.

``<type>_builder(msg, *constants)`` runs when a node wires a row (``msg`` is the transport's
``node.msg`` class lookup): it resolves the message classes and keeps the parts that never change
for that row (frame ids, the joint-name list, the frame pairs of a TF message). The ``build``
function it returns makes one message from the values that change (stamp, readings), so the
per-step path allocates nothing constant. Row converters (:func:`.endpoints.converter`) join a
value reader to a builder; a transport's fast serializer for a type (:data:`BUILT_TYPES` says
which type a builder builds) stands in for its builder with the same arguments, without changing
a row, and the row publishes the bytes. The messages are the same on rclpy and on the
embedded transport.
"""

from array import array
import math
from typing import Sequence, Tuple

import numpy as np

from vehicle_sim.core.specs.units import seconds_to_stamp

TIME = 'builtin_interfaces/msg/Time'
HEADER = 'std_msgs/msg/Header'
STRING = 'std_msgs/msg/String'
FLOAT64_MULTI_ARRAY = 'std_msgs/msg/Float64MultiArray'
CLOCK = 'rosgraph_msgs/msg/Clock'
FLOAT64_STAMPED = 'vehicle_msgs/msg/Float64Stamped'
DIFFERENTIAL_COMMAND = 'vehicle_msgs/msg/DifferentialCommand'
ODOMETRY = 'nav_msgs/msg/Odometry'
JOINT_STATE = 'sensor_msgs/msg/JointState'
TF_MESSAGE = 'tf2_msgs/msg/TFMessage'
TRANSFORM_STAMPED = 'geometry_msgs/msg/TransformStamped'
TWIST = 'geometry_msgs/msg/Twist'
TWIST_STAMPED = 'geometry_msgs/msg/TwistStamped'
VELOCITY_REPORT = 'autoware_vehicle_msgs/msg/VelocityReport'
STEERING_REPORT = 'autoware_vehicle_msgs/msg/SteeringReport'
GEAR_REPORT = 'autoware_vehicle_msgs/msg/GearReport'
TURN_INDICATORS_REPORT = 'autoware_vehicle_msgs/msg/TurnIndicatorsReport'
HAZARD_LIGHTS_REPORT = 'autoware_vehicle_msgs/msg/HazardLightsReport'
CONTROL_MODE_REPORT = 'autoware_vehicle_msgs/msg/ControlModeReport'
LASER_SCAN = 'sensor_msgs/msg/LaserScan'
POINT_CLOUD2 = 'sensor_msgs/msg/PointCloud2'
POINT_FIELD = 'sensor_msgs/msg/PointField'
IMU = 'sensor_msgs/msg/Imu'
NAV_SAT_FIX = 'sensor_msgs/msg/NavSatFix'
RANGE = 'sensor_msgs/msg/Range'
IMAGE = 'sensor_msgs/msg/Image'
CAMERA_INFO = 'sensor_msgs/msg/CameraInfo'
COLLISION = 'vehicle_msgs/msg/Collision'
OCCUPANCY_GRID = 'nav_msgs/msg/OccupancyGrid'
MAP_META_DATA = 'nav_msgs/msg/MapMetaData'

Vector = Tuple[float, float, float]
Quaternion = Tuple[float, float, float, float]


def stamp_builder(msg):
    """Return ``stamp(time_s)``: builtin_interfaces/Time of a simulated time [s]."""
    time_type = msg(TIME)

    def stamp(time_s):
        sec, nanosec = seconds_to_stamp(time_s)
        return time_type(sec=sec, nanosec=nanosec)
    return stamp


def clock_builder(msg):
    """Return ``build(stamp)``: rosgraph_msgs/Clock."""
    clock_type = msg(CLOCK)
    return lambda stamp: clock_type(clock=stamp)


def string_builder(msg):
    """Return ``build(text)``: std_msgs/String."""
    string_type = msg(STRING)
    return lambda text: string_type(data=text)


def float64_stamped_builder(msg, frame_id: str):
    """
    Return ``build(stamp, value)``: vehicle_msgs/Float64Stamped in ``frame_id``.

    Messages of one stamp share one header (the rows of a vehicle share this builder).
    """
    header_type, value_type = msg(HEADER), msg(FLOAT64_STAMPED)
    last = [None, None]      # the last stamp and its header (kept: its id cannot be reused)

    def build(stamp, value):
        if stamp is not last[0]:
            last[0], last[1] = stamp, header_type(stamp=stamp, frame_id=frame_id)
        return value_type(header=last[1], data=float(value))
    return build


def odometry_builder(msg, frame_id: str, child_frame_id: str):
    """
    Return ``build(stamp, xyz, q, linear, angular)``: nav_msgs/Odometry, zero covariances.

    The pose is the child frame's in ``frame_id``; the twist is expressed in ``child_frame_id``.
    """
    odometry_type = msg(ODOMETRY)

    def build(stamp, xyz, q, linear, angular):
        odometry = odometry_type()
        odometry.header.stamp = stamp
        odometry.header.frame_id = frame_id
        odometry.child_frame_id = child_frame_id
        pose = odometry.pose.pose
        position, orientation = pose.position, pose.orientation
        position.x, position.y, position.z = float(xyz[0]), float(xyz[1]), float(xyz[2])
        orientation.x, orientation.y = float(q[0]), float(q[1])
        orientation.z, orientation.w = float(q[2]), float(q[3])
        twist = odometry.twist.twist
        twist.linear.x, twist.linear.y, twist.linear.z = (
            float(linear[0]), float(linear[1]), float(linear[2]))
        twist.angular.x, twist.angular.y, twist.angular.z = (
            float(angular[0]), float(angular[1]), float(angular[2]))
        return odometry
    return build


def joint_state_builder(msg, names: Sequence[str], frame_id: str = ''):
    """
    Return ``build(stamp, positions, velocities)``: sensor_msgs/JointState, no efforts.

    The name list is made once here and shared by every message (nothing writes to it).
    """
    header_type, state_type = msg(HEADER), msg(JOINT_STATE)
    names = list(names)

    def build(stamp, positions, velocities):
        return state_type(header=header_type(stamp=stamp, frame_id=frame_id), name=names,
                          position=[float(p) for p in positions],
                          velocity=[float(v) for v in velocities], effort=[])
    return build


def tf_message_builder(msg, frames: Sequence[Tuple[str, str]]):
    """
    Return ``build(stamp, poses)``: tf2_msgs/TFMessage, one transform per (parent, child) frame.

    :param frames: (parent, child) frame ids, in the order of the poses.
    :return: ``build(stamp, poses)``, ``poses`` one (xyz, q) of each child in its parent.
    """
    tf_type, transform_type = msg(TF_MESSAGE), msg(TRANSFORM_STAMPED)
    frames = tuple(frames)

    def transform(stamp, parent, child, xyz, q):
        stamped = transform_type()
        stamped.header.stamp = stamp
        stamped.header.frame_id = parent
        stamped.child_frame_id = child
        translation, rotation = stamped.transform.translation, stamped.transform.rotation
        translation.x, translation.y, translation.z = float(xyz[0]), float(xyz[1]), float(xyz[2])
        rotation.x, rotation.y = float(q[0]), float(q[1])
        rotation.z, rotation.w = float(q[2]), float(q[3])
        return stamped

    def build(stamp, poses):
        return tf_type(transforms=[transform(stamp, parent, child, xyz, q)
                                   for (parent, child), (xyz, q) in zip(frames, poses)])
    return build


def differential_command_builder(msg, frame_id: str):
    """Return ``build(stamp, left_mps, right_mps)``: vehicle_msgs/DifferentialCommand."""
    command_type = msg(DIFFERENTIAL_COMMAND)

    def build(stamp, left_mps, right_mps):
        command = command_type()
        command.header.stamp = stamp
        command.header.frame_id = frame_id
        command.left_wheel.velocity = left_mps
        command.right_wheel.velocity = right_mps
        return command
    return build


def float64_multi_array_builder(msg):
    """Return ``build(values)``: std_msgs/Float64MultiArray without a layout."""
    array_type = msg(FLOAT64_MULTI_ARRAY)
    return lambda values: array_type(data=values)


def twist_builder(msg):
    """Return ``build(speed_mps, yaw_rate_radps)``: geometry_msgs/Twist (x and yaw only)."""
    twist_type = msg(TWIST)

    def build(speed_mps, yaw_rate_radps):
        twist = twist_type()
        twist.linear.x = speed_mps
        twist.angular.z = yaw_rate_radps
        return twist
    return build


def twist_stamped_builder(msg, frame_id: str):
    """Return ``build(stamp, speed_mps, yaw_rate_radps)``: geometry_msgs/TwistStamped."""
    stamped_type = msg(TWIST_STAMPED)

    def build(stamp, speed_mps, yaw_rate_radps):
        stamped = stamped_type()
        stamped.header.stamp = stamp
        stamped.header.frame_id = frame_id
        stamped.twist.linear.x = speed_mps
        stamped.twist.angular.z = yaw_rate_radps
        return stamped
    return build


def velocity_report_builder(msg, frame_id: str):
    """Return ``build(stamp, speed_mps, heading_rate_radps)``: Autoware VelocityReport."""
    report_type = msg(VELOCITY_REPORT)

    def build(stamp, speed_mps, heading_rate_radps):
        report = report_type()
        report.header.stamp = stamp
        report.header.frame_id = frame_id
        report.longitudinal_velocity = speed_mps
        report.lateral_velocity = 0.0
        report.heading_rate = heading_rate_radps
        return report
    return build


def stamped_field_builder(ros_type: str, field: str):
    """
    Return a builder of an Autoware report made of ``stamp`` and one value field.

    :param ros_type: e.g. GEAR_REPORT.
    :param field: the value field (``report``, ``mode``, ``steering_tire_angle``).
    :return: ``builder(msg)`` returning ``build(stamp, value)``.
    """
    def builder(msg):
        report_type = msg(ros_type)
        return lambda stamp, value: report_type(**{'stamp': stamp, field: value})
    return builder


steering_report_builder = stamped_field_builder(STEERING_REPORT, 'steering_tire_angle')
gear_report_builder = stamped_field_builder(GEAR_REPORT, 'report')
turn_indicators_report_builder = stamped_field_builder(TURN_INDICATORS_REPORT, 'report')
hazard_lights_report_builder = stamped_field_builder(HAZARD_LIGHTS_REPORT, 'report')
control_mode_report_builder = stamped_field_builder(CONTROL_MODE_REPORT, 'mode')


# ---------------------------------------------------------------------------------------------
# Sensors: ``build(stamp, reading)`` from a core reading (core/sensors/readings.py). Array fields
# get ``array.array`` values: rclpy takes them without a per-element check, the embedded
# transport packs them as it packs lists.


def _float32s(values):
    return array('f', np.ascontiguousarray(values, dtype=np.float32).tobytes())


def _set_vector(vector, values):
    vector.x, vector.y, vector.z = float(values[0]), float(values[1]), float(values[2])


# One point of a labelled lidar's PointCloud2 (little-endian, packed).
LABELLED_POINT = np.dtype([('x', '<f4'), ('y', '<f4'), ('z', '<f4'), ('intensity', '<f4'),
                           ('label', '<u2'), ('instance', '<u2')])


def laser_scan_builder(msg, frame_id: str):
    """Return ``build(stamp, reading)``: sensor_msgs/LaserScan of a one-layer LidarReading."""
    header_type, scan_type = msg(HEADER), msg(LASER_SCAN)

    def build(stamp, reading):
        return scan_type(
            header=header_type(stamp=stamp, frame_id=frame_id),
            angle_min=float(reading.angle_min_rad), angle_max=float(reading.angle_max_rad),
            angle_increment=float(reading.angle_increment_rad),
            time_increment=float(reading.time_increment_s),
            scan_time=float(reading.scan_time_s), range_min=float(reading.range_min_m),
            range_max=float(reading.range_max_m), ranges=_float32s(reading.scan),
            intensities=(array('f') if reading.intensities is None else
                         _float32s(reading.intensities[len(reading.layer_elevations_rad) // 2])))
    return build


def point_cloud2_builder(msg, frame_id: str):
    """
    Return ``build(stamp, reading)``: sensor_msgs/PointCloud2 of a LidarReading or DepthReading.

    Organized (height = layers, width = rays; a depth image's rows and columns), fields x, y,
    z FLOAT32 at offsets 0, 4, 8, little-endian, NaN points for rays without a return
    (is_dense false). A labelled lidar's (its reading has ``intensities``) adds intensity
    FLOAT32 at 12, label UINT16 at 16 and instance UINT16 at 18 (:data:`LABELLED_POINT`,
    point_step 20).
    """
    header_type, cloud_type, field_type = msg(HEADER), msg(POINT_CLOUD2), msg(POINT_FIELD)
    datatypes = {'<f4': field_type.FLOAT32, '<u2': field_type.UINT16}
    fields = [field_type(name=axis, offset=4 * index, datatype=field_type.FLOAT32, count=1)
              for index, axis in enumerate('xyz')]
    labelled_fields = [field_type(name=name, offset=LABELLED_POINT.fields[name][1],
                                  datatype=datatypes[LABELLED_POINT.fields[name][0].str],
                                  count=1)
                       for name in LABELLED_POINT.names]

    def build(stamp, reading):
        points = reading.points()
        layers, rays = points.shape[0], points.shape[1]
        if getattr(reading, 'intensities', None) is None:    # a depth image has none
            found, point_step = fields, 12
            data = np.ascontiguousarray(points, dtype='<f4').tobytes()
        else:
            found, point_step = labelled_fields, LABELLED_POINT.itemsize
            cloud = np.empty((layers, rays), dtype=LABELLED_POINT)
            cloud['x'], cloud['y'], cloud['z'] = points[..., 0], points[..., 1], points[..., 2]
            cloud['intensity'] = reading.intensities
            cloud['label'] = reading.labels
            cloud['instance'] = reading.instances
            data = cloud.tobytes()
        return cloud_type(
            header=header_type(stamp=stamp, frame_id=frame_id), height=layers, width=rays,
            fields=found, is_bigendian=False, point_step=point_step,
            row_step=point_step * rays, data=array('B', data), is_dense=False)
    return build


def imu_builder(msg, frame_id: str):
    """Return ``build(stamp, reading)``: sensor_msgs/Imu of an ImuReading (sensor frame)."""
    imu_type = msg(IMU)

    def build(stamp, reading):
        imu = imu_type()
        imu.header.stamp = stamp
        imu.header.frame_id = frame_id
        q = reading.orientation_xyzw
        orientation = imu.orientation
        orientation.x, orientation.y = float(q[0]), float(q[1])
        orientation.z, orientation.w = float(q[2]), float(q[3])
        _set_vector(imu.angular_velocity, reading.angular_velocity_radps)
        _set_vector(imu.linear_acceleration, reading.linear_acceleration_mps2)
        imu.orientation_covariance = list(reading.orientation_covariance)
        imu.angular_velocity_covariance = list(reading.angular_velocity_covariance)
        imu.linear_acceleration_covariance = list(reading.linear_acceleration_covariance)
        return imu
    return build


def nav_sat_fix_builder(msg, frame_id: str):
    """Return ``build(stamp, reading)``: sensor_msgs/NavSatFix of a GnssReading."""
    fix_type = msg(NAV_SAT_FIX)

    def build(stamp, reading):
        fix = fix_type()
        fix.header.stamp = stamp
        fix.header.frame_id = frame_id
        fix.status.status = int(reading.status)
        fix.status.service = int(reading.service)
        fix.latitude = float(reading.latitude_deg)
        fix.longitude = float(reading.longitude_deg)
        fix.altitude = float(reading.altitude_m)
        fix.position_covariance = list(reading.position_covariance)
        fix.position_covariance_type = int(reading.covariance_type)
        return fix
    return build


def range_builder(msg, frame_id: str):
    """
    Return ``build(stamp, reading)``: sensor_msgs/Range.

    Jazzy's Range has ``variance``; Humble's has not (the reading's variance is then not sent).
    """
    header_type, range_type = msg(HEADER), msg(RANGE)
    with_variance = hasattr(range_type, 'variance')

    def build(stamp, reading):
        extra = {'variance': float(reading.variance_m2)} if with_variance else {}
        return range_type(
            header=header_type(stamp=stamp, frame_id=frame_id),
            radiation_type=int(reading.radiation_type),
            field_of_view=float(reading.field_of_view_rad),
            min_range=float(reading.min_range_m), max_range=float(reading.max_range_m),
            range=float(reading.range_m), **extra)
    return build


def image_builder(msg, frame_id: str):
    """Return ``build(stamp, reading)``: sensor_msgs/Image (rgb8) of a CameraReading."""
    header_type, image_type = msg(HEADER), msg(IMAGE)

    def build(stamp, reading):
        return image_type(
            header=header_type(stamp=stamp, frame_id=frame_id), height=int(reading.height),
            width=int(reading.width), encoding=reading.encoding, is_bigendian=0,
            step=int(reading.step), data=array('B', reading.data))
    return build


def camera_info_builder(msg, frame_id: str):
    """Return ``build(stamp, reading)``: sensor_msgs/CameraInfo of a CameraReading."""
    info_type = msg(CAMERA_INFO)

    def build(stamp, reading):
        info = info_type()
        info.header.stamp = stamp
        info.header.frame_id = frame_id
        info.height, info.width = int(reading.height), int(reading.width)
        info.distortion_model = reading.distortion_model
        info.d = array('d', reading.d)
        info.k, info.r, info.p = list(reading.k), list(reading.r), list(reading.p)
        return info
    return build


def collision_builder(msg, frame_id: str):
    """Return ``build(stamp, event)``: vehicle_msgs/Collision of a core CollisionEvent."""
    header_type, collision_type = msg(HEADER), msg(COLLISION)

    def build(stamp, event):
        return collision_type(header=header_type(stamp=stamp, frame_id=frame_id),
                              other=event.other, normal_force=float(event.normal_force_n))
    return build


def _map_info(info, load_stamp, grid):
    # nav_msgs/MapMetaData of a core OccupancyGrid (its origin: the lower-left cell's corner).
    x, y, yaw = grid.origin
    info.map_load_time = load_stamp
    info.resolution = float(grid.resolution_m)
    info.width, info.height = int(grid.width), int(grid.height)
    info.origin.position.x, info.origin.position.y = float(x), float(y)
    info.origin.orientation.z, info.origin.orientation.w = math.sin(yaw / 2), math.cos(yaw / 2)


def map_meta_data_builder(msg):
    """Return ``build(stamp, grid)``: nav_msgs/MapMetaData of a core OccupancyGrid."""
    info_type = msg(MAP_META_DATA)

    def build(stamp, grid):
        info = info_type()
        _map_info(info, stamp, grid)
        return info
    return build


def occupancy_grid_builder(msg, frame_id: str):
    """
    Return ``build(stamp, grid)``: nav_msgs/OccupancyGrid of a core OccupancyGrid.

    As nav2 map_server publishes it: ``info.map_load_time`` and the header's stamp are the
    loading time, ``data`` the cell values row by row from the bottom row.
    """
    grid_type = msg(OCCUPANCY_GRID)

    def build(stamp, grid):
        message = grid_type()
        message.header.stamp = stamp
        message.header.frame_id = frame_id
        _map_info(message.info, stamp, grid)
        message.data = array('b', grid.data.tobytes())
        return message
    return build


# The type each builder builds, for the builders a transport's fast serializer may stand in for
# (``NodePort.serializer``: same constants, same values, the message's bytes).
BUILT_TYPES = {
    clock_builder: CLOCK,
    float64_stamped_builder: FLOAT64_STAMPED,
    odometry_builder: ODOMETRY,
    joint_state_builder: JOINT_STATE,
    tf_message_builder: TF_MESSAGE,
}
