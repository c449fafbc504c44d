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
A Webots-style controller that ignores every obstacle: it cruises straight ahead at 20 km/h.

The counter-example of lidar_stop_controller.py: scenarios/drive_into_obstacle.yaml runs it on
the obstacle course, where it hits the wall and fails the scenario's no_collision criterion.
"""

from vehicle_sim.webots import Driver

CRUISING_SPEED_KMH = 20.0

driver = Driver()
driver.setCruisingSpeed(CRUISING_SPEED_KMH)
while driver.step() != -1:
    pass
