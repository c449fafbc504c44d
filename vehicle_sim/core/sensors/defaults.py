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
The default sensor sets of the car and robot presets: mounted on the body, all switched off.

A preset without a ``sensors:`` list gets these. They cost nothing until a world entry or a
parameter mounts them (``enabled``). The car set carries the device names of the Webots car
PROTOs' sensor slots and of the sensors Webots' automobile sample controllers ask for
(autonomous_vehicle.c: 'camera', 'Sick LMS 291', 'gps'; InertialUnit, Gyro and Accelerometer
keep their Webots default names), so those controllers find them with ``getDevice``.

Mount points follow the body: the lidar in the middle of the front face (Webots'
``sensorsSlotFront``), the camera and the GNSS antenna on the roof (``sensorsSlotTop``), the IMU
at the centre of mass (``sensorsSlotCenter``).
"""

import math

from vehicle_sim.core.sensors.params import sensor_from_dict

# Above the roof, so that the roof is not in the camera's picture or the antenna's shadow [m].
ROOF_CLEARANCE_M = 0.05
# Behind the front edge of the highest box (the top of the windscreen) [m].
CAMERA_SETBACK_M = 0.3


def _sensors(source, *entries):
    return tuple(sensor_from_dict(entry, f'{source}[{index}]', enabled_default=False)
                 for index, entry in enumerate(entries))


def _imu(x, y, z):
    return {'type': 'imu', 'name': 'imu', 'device': 'inertial unit',
            'pose': {'x': x, 'y': y, 'z': z}, 'rate_hz': 100.0}


def default_car_sensors(params):
    """
    Return the default (unmounted) sensors of a car from its geometry.

    - ``lidar`` ('Sick LMS 291'): Webots' SickLms291 PROTO: 180 rays over 180 degrees, 80 m.
    - ``camera`` ('camera'): 320 x 240, horizontal fov 1 rad, 10 Hz.
    - ``gnss`` ('gps'), 10 Hz; ``imu`` ('inertial unit', 'gyro', 'accelerometer'), 100 Hz.

    :param params: CarParams (collision boxes, centre of mass; base_link lies the rear tyre
        radius below the Webots vehicle frame).
    :return: tuple of SensorSpec, every ``enabled`` False.
    """
    lift = params.rear_tire_radius_m
    boxes = params.collision_boxes
    front = max(boxes, key=lambda b: b.position_m[0] + b.size_m[0] / 2.0)
    top = max(boxes, key=lambda b: b.position_m[2] + b.size_m[2] / 2.0)
    front_x = front.position_m[0] + front.size_m[0] / 2.0
    roof_z = top.position_m[2] + top.size_m[2] / 2.0 + lift + ROOF_CLEARANCE_M
    camera_x = top.position_m[0] + top.size_m[0] / 2.0 - CAMERA_SETBACK_M
    com = params.center_of_mass_m
    return _sensors(
        f'{params.model} default sensors',
        {'type': 'lidar', 'name': 'lidar', 'device': 'Sick LMS 291',
         'pose': {'x': front_x, 'z': front.position_m[2] + lift}, 'fov': math.pi,
         'horizontal_resolution': 180, 'min_range': 0.1, 'max_range': 80.0, 'rate_hz': 10.0},
        {'type': 'camera', 'name': 'camera', 'pose': {'x': camera_x, 'z': roof_z},
         'width': 320, 'height': 240, 'fov': 1.0, 'rate_hz': 10.0},
        {'type': 'gnss', 'name': 'gnss', 'device': 'gps',
         'pose': {'x': params.wheelbase_m / 2.0, 'z': roof_z}, 'rate_hz': 10.0},
        _imu(com[0], com[1], com[2] + lift),
    )


def default_robot_sensors(params):
    """
    Return the default (unmounted) sensors of a differential-drive robot.

    - ``lidar`` ('lidar'): a 360-degree scanner on top of the body: 360 rays one degree apart,
      0.12-12 m, 10 Hz.
    - ``imu`` ('inertial unit', 'gyro', 'accelerometer') at base_link raised to the axle, 100 Hz.

    :param params: RobotParams.
    :return: tuple of SensorSpec, every ``enabled`` False.
    """
    height = params.body_size_m[2]
    radius = params.wheel_radius_m
    return _sensors(
        f'{params.model} default sensors',
        {'type': 'lidar', 'name': 'lidar',
         'pose': {'x': params.body_offset_m, 'z': radius + height / 2.0 + ROOF_CLEARANCE_M},
         'fov': 2.0 * math.pi * 359.0 / 360.0, 'horizontal_resolution': 360,
         'min_range': 0.12, 'max_range': 12.0, 'rate_hz': 10.0},
        _imu(0.0, 0.0, radius),
    )
