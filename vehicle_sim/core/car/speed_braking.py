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

A controller that knows the deceleration it wants (the scenario actors' IDM) asks
:func:`brake_for_deceleration` instead: the cruise control gives up to its ramp,
:func:`cruise_ramp_mps2`; beyond it the brake, in proportion to the car's full-brake
deceleration :func:`full_brake_deceleration_mps2` (the brakes' torque, brakeCoefficient per
wheel, over the tyre radii and the car's mass with its wheels: the Prius 4.8 m/s^2; the
wheels' damping and rolling add 0.1 to 0.3 m/s^2, more at speed).
"""

from vehicle_sim.core.car.drivetrain import speed_ramp_mps2

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


def cruise_ramp_mps2(params):
    """Return the cruise control's acceleration limit (100 km/h) / time0To100 [m/s^2]."""
    return speed_ramp_mps2(params.time_0_to_100_s)


def full_brake_deceleration_mps2(params):
    """
    Return the deceleration [m/s^2] of a car's brakes at intensity 1 on a level road.

    brakeCoefficient [N·m] on each of the four wheels, over its tyre radius, divided by the
    mass of the body and the four wheels (the wheels' rotation, damping and rolling left out).

    :param params: CarParams.
    """
    force_n = 2.0 * params.brake_coefficient_nm * (1.0 / params.front_tire_radius_m +
                                                   1.0 / params.rear_tire_radius_m)
    mass_kg = params.mass_kg + 2.0 * (params.wheel_mass_kg(True) + params.wheel_mass_kg(False))
    return force_n / mass_kg


def brake_for_deceleration(deceleration_mps2, ramp_mps2, full_brake_mps2):
    """
    Return the brake intensity for a deceleration, 0.0 when the cruise control's ramp gives it.

    :param deceleration_mps2: the deceleration asked [m/s^2] (> 0 slows down).
    :param ramp_mps2: the cruise control's limit (:func:`cruise_ramp_mps2`).
    :param full_brake_mps2: the car's deceleration at full brake
        (:func:`full_brake_deceleration_mps2`).
    :return: 0.0 (the cruise control slows the car: the deceleration is within its ramp, or
        the car's brakes slow it less than its ramp), or the intensity in (0, 1] to brake with
        (throttle released): deceleration / full_brake, at most 1.
    """
    if deceleration_mps2 <= ramp_mps2 or full_brake_mps2 <= ramp_mps2:
        return 0.0
    return min(1.0, deceleration_mps2 / full_brake_mps2)


def full_stop(logic):
    """
    Stop a car as hard as it can: a safety stop (a command watchdog's).

    The cruising speed becomes 0 and the brake 1; where the brakes slow the car harder than the
    cruise control's ramp (every preset but the RangeRoverSportSVR, whose brakes give 3.7 m/s^2
    against its 5.9 m/s^2 ramp) the throttle is released too (TORQUE mode), so that the brakes
    act: the car slows at :func:`full_brake_deceleration_mps2`, else at the ramp.

    :param logic: the car's CarLogic.
    """
    params = logic.params
    logic.set_cruising_speed_kmh(0.0)
    if full_brake_deceleration_mps2(params) > cruise_ramp_mps2(params):
        logic.set_throttle(0.0)
    logic.set_brake_intensity(1.0)
