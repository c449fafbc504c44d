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
When a speed asked of a car is reached by braking rather than by its cruise control.

Webots' cruise control (wbu_driver_set_cruising_speed) ramps the driven wheels toward the speed
at the car's acceleration limit, (100 km/h) / time0To100 (2.6 m/s^2 for the Prius), and its
brake (wbu_driver_set_brake_intensity) barely acts while the cruise control holds a speed: the
driven wheels' motors follow the ramp (driver.c). A driver who must slow down faster presses the
brake pedal, which disengages cruise control: the throttle released (wbu_driver_set_throttle(0),
torque control) and the brakes applied (the Prius at full brake: about 5.4 m/s^2 from 33 m/s).
This module decides between the two, for Drive-v0's braking_speed_steering action, the policy
node and the scenario runner's IDM actors (scenarios/actors.py): the speed asked more than
BRAKE_ABOVE_MPS slower than the car in its direction of travel -> brake, intensity
min(1, difference / FULL_BRAKE_MPS); else the cruise control takes the speed.
"""

# Brake (instead of cruising) when the speed asked is this much slower than the car's [m/s].
BRAKE_ABOVE_MPS = 1.0
# The difference [m/s] at which the brake is full; less brakes in proportion.
FULL_BRAKE_MPS = 5.0


def brake_for_speed(speed_mps, target_mps):
    """
    Return the brake intensity that slows the car toward a speed, 0.0 when cruising does.

    :param speed_mps: the car's forward speed [m/s] (negative: reversing).
    :param target_mps: the speed asked [m/s] (negative: reverse).
    :return: 0.0 (set the cruising speed), or the intensity in (0, 1] to brake with (throttle
        released).
    """
    if speed_mps > 0.0:
        slower = speed_mps - max(target_mps, 0.0)
    else:
        slower = min(target_mps, 0.0) - speed_mps
    if slower <= BRAKE_ABOVE_MPS:
        return 0.0
    return min(1.0, slower / FULL_BRAKE_MPS)
