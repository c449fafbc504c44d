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
Simulated sensors on vehicle bodies: lidar, IMU, GNSS, distance, camera, collisions.

Each sensor turns a core SensorSpec into readings (core/sensors/readings.py) from the PyBullet
state after a world step; SensorSuite schedules them. See docs/sensors.md.
"""

from vehicle_sim.physics.sensors.camera import CameraSensor
from vehicle_sim.physics.sensors.collisions import CollisionMonitor
from vehicle_sim.physics.sensors.distance import RayDistanceSensor
from vehicle_sim.physics.sensors.feed import SensorFeed
from vehicle_sim.physics.sensors.inertial import GnssSensor, ImuSensor
from vehicle_sim.physics.sensors.lidar import LidarSensor
from vehicle_sim.physics.sensors.sensor import Sensor
from vehicle_sim.physics.sensors.suite import SENSOR_CLASSES, SensorSuite

__all__ = ['CameraSensor', 'CollisionMonitor', 'GnssSensor', 'ImuSensor', 'LidarSensor',
           'RayDistanceSensor', 'SENSOR_CLASSES', 'Sensor', 'SensorFeed', 'SensorSuite']
