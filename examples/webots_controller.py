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
A Webots-style automobile controller that runs on vehicle_sim unchanged apart from its import.

In Webots the first line reads ``from vehicle import Driver``. Pick the car with the
environment variable VEHICLE_SIM_CAR (e.g. ``VEHICLE_SIM_CAR=ToyotaPrius``).
"""

from vehicle_sim.webots import Driver

driver = Driver()
time_step = int(driver.getBasicTimeStep())

driver.setSteeringAngle(0.0)
driver.setCruisingSpeed(30.0)
driver.setDippedBeams(True)

while driver.step() != -1:
    time = driver.getTime()
    if time > 4.0:
        driver.setIndicator(Driver.INDICATOR_RIGHT)
        driver.setSteeringAngle(0.1)
    if time > 8.0:
        driver.setSteeringAngle(0.0)
        driver.setCruisingSpeed(0.0)
        driver.setBrakeIntensity(1.0)
    if int(time * 1000) % 1000 == 0:
        print(f't={time:5.2f} s  speed={driver.getCurrentSpeed():6.2f} km/h  '
              f'steering={driver.getSteeringAngle():+.3f} rad  indicator={driver.getIndicator()}')
    if time >= 10.0:
        break
