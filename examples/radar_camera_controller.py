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
A Webots-style controller that sees the car ahead with its camera and measures it with its radar.

Runs unchanged in Webots apart from its import (``from vehicle import Driver``) on a car with a
Camera called 'camera' that has a Recognition node and a Radar called 'radar' in its front slot.
On vehicle_sim, mount both with a world file::

    VEHICLE_SIM_WORLD=radar_camera python examples/radar_camera_controller.py

config/worlds/radar_camera.yaml parks a second car 60 m ahead. The camera recognises it (its id,
its model, where it is); the radar target at the same bearing gives its distance and the speed
we close in at; the controller cruises and brakes to stop behind it.
"""

import math

from vehicle_sim.webots import Driver

CRUISING_SPEED_KMH = 40.0
BEARING_TOLERANCE = 0.05       # [rad] a radar target this close in bearing is the object seen
HALF_LENGTH_M = 2.5            # half a car's length: both sensors see its centre
MARGIN_M = 3.0                 # wanted gap between our bumper and the car
DECELERATION_MPS2 = 2.5        # what the brakes achieve at least

driver = Driver()
time_step = int(driver.getBasicTimeStep())
camera = driver.getDevice('camera')
camera.enable(5 * time_step)
camera.recognitionEnable(5 * time_step)
radar = driver.getDevice('radar')
radar.enable(5 * time_step)

driver.setCruisingSpeed(CRUISING_SPEED_KMH)
braking = False
step = 0
while driver.step() != -1:
    step += 1
    targets = radar.getTargets()
    ahead = None
    for recognised in camera.getRecognitionObjects():
        if recognised.getModel() != 'car':
            continue
        x, y, _ = recognised.getPosition()      # in the camera frame: x forward, y left
        bearing = math.atan2(y, x)
        # the radar's azimuth is positive to the right
        matches = [t for t in targets if abs(-t.azimuth - bearing) < BEARING_TOLERANCE]
        if matches:
            target = min(matches, key=lambda t: t.distance)
            if ahead is None or target.distance < ahead[1].distance:
                ahead = (recognised, target, x)
    if ahead is None:
        continue
    recognised, target, camera_x = ahead
    closing_mps = -target.speed
    gap_m = target.distance - HALF_LENGTH_M
    stopping_m = max(closing_mps, 0.0) ** 2 / (2.0 * DECELERATION_MPS2)
    if step % 50 == 0:
        print(f't={driver.getTime():5.2f} s  speed={driver.getCurrentSpeed():6.2f} km/h  '
              f'car {recognised.getId()} ({recognised.getModel()}): radar '
              f'{target.distance:6.2f} m, closing at {closing_mps:5.2f} m/s; camera '
              f'{camera_x:6.2f} m ahead, {recognised.getSizeOnImage()[0]} px wide')
    if not braking and gap_m < MARGIN_M + stopping_m:
        braking = True
        driver.setCruisingSpeed(0.0)
        driver.setBrakeIntensity(1.0)
        print(f't={driver.getTime():5.2f} s  braking: car {recognised.getId()} '
              f'{target.distance:.2f} m ahead')
    if braking and abs(driver.getCurrentSpeed()) < 0.01:
        print(f't={driver.getTime():5.2f} s  stopped: car {recognised.getId()} radar '
              f'{target.distance:.2f} m, camera {camera_x:.2f} m ahead')
        break
    if driver.getTime() > 40.0:
        print('gave up: no car ahead')
        break
