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
A Webots-style adaptive cruise control: cruise, and keep a time gap to the vehicle ahead (lidar).

Runs unchanged in Webots apart from its import (``from vehicle import Driver``) on a car with a
lidar ('Sick LMS 291') looking ahead. On vehicle_sim, scenarios/cut_in.yaml runs it on the
highway while a traffic car cuts in ahead (docs/traffic.md)::

    vehicle-sim scenario scenarios/cut_in.yaml

The rays within half a lane width of the car's axis give the distance ahead; its change over time
gives the leader's speed. The wanted gap is ``MIN_GAP_M + TIME_GAP_S * speed``; the cruising
speed steers towards the leader's speed plus a share of the gap error, and the brakes help when
the car is more than BRAKE_ABOVE_MPS faster than wanted (with cruising speed 0, as Webots'
cruise control holds its speed against the brakes).
"""

import math

from vehicle_sim.webots import Driver

CRUISING_SPEED_KMH = 90.0
BUMPER_OFFSET_M = 3.5        # from the lidar (1 m ahead of the rear axle) to the front bumper
HALF_LANE_M = 1.5            # rays hitting within this of the car's axis count as ahead
MIN_GAP_M = 5.0              # wanted gap when standing
TIME_GAP_S = 1.5             # wanted time gap
GAIN_PER_S = 0.4             # speed change per metre of gap error [1/s]
BRAKE_ABOVE_MPS = 1.0        # brake when this much faster than wanted
BRAKE_PER_MPS = 0.15         # brake intensity per m/s of speed above the wanted one

driver = Driver()
time_step = int(driver.getBasicTimeStep())
lidar = driver.getDevice('Sick LMS 291')
lidar.enable(5 * time_step)
width = lidar.getHorizontalResolution()
fov = lidar.getFov()

driver.setCruisingSpeed(CRUISING_SPEED_KMH)
last_gap, last_time, leader_speed = None, None, None
step = 0
while driver.step() != -1:
    step += 1
    ranges = lidar.getRangeImage()
    if ranges is None:               # no scan yet
        continue
    now = driver.getTime()
    speed = driver.getCurrentSpeed() / 3.6
    ahead = math.inf
    for i, r in enumerate(ranges):
        angle = fov / 2.0 - i * fov / (width - 1)
        if math.isfinite(r) and abs(r * math.sin(angle)) < HALF_LANE_M:
            ahead = min(ahead, r * math.cos(angle))
    wanted = CRUISING_SPEED_KMH / 3.6
    if math.isfinite(ahead):
        gap = ahead - BUMPER_OFFSET_M
        if last_gap is not None and now > last_time:
            rate = (gap - last_gap) / (now - last_time)
            estimate = speed + rate
            leader_speed = estimate if leader_speed is None else \
                leader_speed + 0.3 * (estimate - leader_speed)
        last_gap, last_time = gap, now
        if leader_speed is not None:
            target = MIN_GAP_M + TIME_GAP_S * speed
            wanted = min(wanted, max(0.0, leader_speed + GAIN_PER_S * (gap - target)))
    else:
        last_gap, leader_speed = None, None
    excess = speed - wanted
    if excess > BRAKE_ABOVE_MPS:     # the cruise control slows too gently: brake
        driver.setCruisingSpeed(0.0)
        driver.setBrakeIntensity(min(1.0, BRAKE_PER_MPS * excess))
    else:
        driver.setBrakeIntensity(0.0)
        driver.setCruisingSpeed(wanted * 3.6)
    if step % 100 == 0:
        print(f't={now:5.2f} s  speed={speed * 3.6:6.2f} km/h  ahead={ahead:7.2f} m  '
              f'wanted={wanted * 3.6:6.2f} km/h')
