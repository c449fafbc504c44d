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
A Webots-style controller that watches the road ahead with a radar and stops behind what it sees.

Runs unchanged in Webots apart from its import (``from vehicle import Driver``) on a car with
a Radar called 'radar' in its front slot (a solid ahead needs a radarCrossSection > 0 there).
On vehicle_sim, mount the radar with a world file::

    VEHICLE_SIM_WORLD=radar_stop python examples/radar_controller.py

config/worlds/radar_stop.yaml parks a car-sized box 60 m ahead of the car, its radar at the
front bumper. The controller cruises, keeps the targets within a lane's width ahead, and brakes
when the nearest one is within the distance it needs to stop at the speed it closes in.
"""

import math

from vehicle_sim.webots import Driver

CRUISING_SPEED_KMH = 40.0
LANE_HALF_WIDTH_M = 1.5       # targets further to the side are not in our lane
MARGIN_M = 3.0                # wanted gap between the bumper and the target
HALF_LENGTH_M = 2.25          # half a car's length: the radar reads the distance to its centre
DECELERATION_MPS2 = 2.5       # what the brakes achieve at least

driver = Driver()
time_step = int(driver.getBasicTimeStep())
radar = driver.getDevice('radar')
radar.enable(5 * time_step)

driver.setCruisingSpeed(CRUISING_SPEED_KMH)
braking = False
step = 0
while driver.step() != -1:
    step += 1
    ahead = None
    for target in radar.getTargets():
        lateral = target.distance * math.sin(target.azimuth)
        nearer = ahead is None or target.distance < ahead.distance
        if abs(lateral) < LANE_HALF_WIDTH_M and nearer:
            ahead = target
    if ahead is None:
        continue
    closing_mps = -ahead.speed                   # the radial speed: < 0 while we close in
    gap_m = ahead.distance - HALF_LENGTH_M
    stopping_m = max(closing_mps, 0.0) ** 2 / (2.0 * DECELERATION_MPS2)
    if not braking and gap_m < MARGIN_M + stopping_m:
        braking = True
        driver.setCruisingSpeed(0.0)
        driver.setBrakeIntensity(1.0)
        print(f't={driver.getTime():5.2f} s  braking: target {ahead.distance:.2f} m ahead, '
              f'closing at {closing_mps:.2f} m/s')
    if step % 50 == 0:
        print(f't={driver.getTime():5.2f} s  speed={driver.getCurrentSpeed():6.2f} km/h  '
              f'target {ahead.distance:6.2f} m, radial speed {ahead.speed:6.2f} m/s, '
              f'power {ahead.received_power:6.1f} dBm')
    if braking and abs(driver.getCurrentSpeed()) < 0.01:
        print(f't={driver.getTime():5.2f} s  stopped: target {ahead.distance:.2f} m ahead of the '
              f'radar, radial speed {ahead.speed:.3f} m/s')
        break
    if driver.getTime() > 40.0:
        print('gave up: nothing ahead')
        break
