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
A Webots-style controller that drives towards an obstacle and uses the lidar to stop before it.

Runs unchanged in Webots apart from its import (``from vehicle import Driver``) on a car whose
front sensor slot holds a SickLms291. On vehicle_sim, mount the sensors with a world file::

    VEHICLE_SIM_WORLD=obstacle_course python examples/lidar_stop_controller.py

config/worlds/obstacle_course.yaml puts a wall 19.5 m ahead of the car and mounts the Car
preset's lidar ('Sick LMS 291') 1 m ahead of the rear axle, 3.5 m behind the front bumper.
"""

from vehicle_sim.webots import Driver

CRUISING_SPEED_KMH = 20.0
BUMPER_OFFSET_M = 3.5        # from the lidar to the front bumper (Car preset, obstacle course)
MARGIN_M = 2.0               # wanted gap between the bumper and the obstacle
DECELERATION_MPS2 = 2.0      # what the cruise control achieves when asked for 0 km/h, at least
CONE_RAYS = 5                # rays either side of straight ahead that count

driver = Driver()
time_step = int(driver.getBasicTimeStep())
lidar = driver.getDevice('Sick LMS 291')
lidar.enable(5 * time_step)
width = lidar.getHorizontalResolution()

driver.setCruisingSpeed(CRUISING_SPEED_KMH)
braking = False
step = 0
while driver.step() != -1:
    step += 1
    ranges = lidar.getRangeImage()
    if ranges is None:               # no scan yet: the first comes one sampling period later
        continue
    ahead = min(ranges[width // 2 - CONE_RAYS:width // 2 + CONE_RAYS + 1])
    speed_mps = driver.getCurrentSpeed() / 3.6
    stopping_m = speed_mps ** 2 / (2.0 * DECELERATION_MPS2)
    if not braking and ahead < BUMPER_OFFSET_M + MARGIN_M + stopping_m:
        braking = True
        driver.setCruisingSpeed(0.0)
        driver.setBrakeIntensity(1.0)
        print(f't={driver.getTime():5.2f} s  braking: obstacle {ahead:.2f} m ahead')
    if step % 50 == 0:
        print(f't={driver.getTime():5.2f} s  speed={driver.getCurrentSpeed():6.2f} km/h  '
              f'ahead={ahead:6.2f} m')
    if braking and abs(driver.getCurrentSpeed()) < 0.01:
        print(f't={driver.getTime():5.2f} s  stopped: obstacle {ahead:.2f} m ahead of the lidar, '
              f'{ahead - BUMPER_OFFSET_M:.2f} m ahead of the bumper')
        break
    if driver.getTime() > 30.0:
        print('gave up: no obstacle ahead')
        break
