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
A Webots-style controller that drives towards a wall and stops before it using a RangeFinder.

Written against Webots' RangeFinder API (getRangeImage, rangeImageGetDepth, getWidth, ...);
runs in Webots apart from its import (``from vehicle import Driver``) on a car with a
RangeFinder named 'depth_cam' looking forward. On vehicle_sim, mount it with a world file (the
test's world has one, 1.5 m ahead of base_link, 3 m behind the front bumper)::

    VEHICLE_SIM_WORLD=test/data/depth_course.yaml python examples/range_finder_stop_controller.py
"""

from vehicle_sim.webots import Driver

CRUISING_SPEED_KMH = 20.0
BUMPER_OFFSET_M = 3.0        # from the range finder to the front bumper (Car preset)
MARGIN_M = 2.0               # wanted gap between the bumper and the obstacle
DECELERATION_MPS2 = 2.0      # what the cruise control achieves when asked for 0 km/h, at least
PATCH = 2                    # pixels either side of the image centre that count

driver = Driver()
time_step = int(driver.getBasicTimeStep())
range_finder = driver.getDevice('depth_cam')
range_finder.enable(5 * time_step)
width, height = range_finder.getWidth(), range_finder.getHeight()
print(f'range finder {width} x {height}, fov {range_finder.getFov():.2f} rad, '
      f'{range_finder.getMinRange():.2f} .. {range_finder.getMaxRange():.1f} m')

driver.setCruisingSpeed(CRUISING_SPEED_KMH)
braking = False
while driver.step() != -1:
    image = range_finder.getRangeImage()
    if image is None:                # no image yet: the first comes one sampling period later
        continue
    ahead = min(range_finder.rangeImageGetDepth(image, width, x, y)
                for x in range(width // 2 - PATCH, width // 2 + PATCH)
                for y in range(height // 2 - PATCH, height // 2 + PATCH))
    speed_mps = driver.getCurrentSpeed() / 3.6
    stopping_m = speed_mps ** 2 / (2.0 * DECELERATION_MPS2)
    if not braking and ahead < BUMPER_OFFSET_M + MARGIN_M + stopping_m:
        braking = True
        driver.setCruisingSpeed(0.0)
        driver.setBrakeIntensity(1.0)
        print(f't={driver.getTime():5.2f} s  braking: obstacle {ahead:.2f} m ahead')
    if braking and abs(driver.getCurrentSpeed()) < 0.01:
        print(f't={driver.getTime():5.2f} s  stopped: obstacle {ahead:.2f} m ahead of the range '
              f'finder, {ahead - BUMPER_OFFSET_M:.2f} m ahead of the bumper')
        break
    if driver.getTime() > 30.0:
        print('gave up: no obstacle ahead')
        break
