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
Ackermann steering geometry of the Webots driver library (Webots' driver.c).

Signs follow Webots: a positive angle steers to the RIGHT.
"""

import math


def ackermann_angles(steering_rad, track_front_m, wheelbase_m):
    """
    Return the right and left front-wheel angles for a driver steering angle.

    driver.c computes θR = atan(1 / (cot δ − Tf/(2L))) and θL = atan(1 / (cot δ + Tf/(2L)))
    (Jazar, Vehicle Dynamics, 2009). Multiplying by tan δ gives the same angles without the
    cot δ = ±inf of δ = 0: θ = atan2(tan δ, 1 ∓ tan δ·Tf/(2L)). Beyond the inner wheel's
    singularity (tan δ = 2L/Tf, far outside every preset's steering limits) atan2 continues past
    π/2 where Webots' atan flips sign; the steering limits clamp either result.

    :param steering_rad: driver steering angle δ [rad], positive = right.
    :param track_front_m: front track Tf [m].
    :param wheelbase_m: wheelbase L [m].
    :return: (right_rad, left_rad); both exactly 0 for δ = 0.
    """
    tan_delta = math.tan(steering_rad)
    half = track_front_m / (2.0 * wheelbase_m)
    right_rad = math.atan2(tan_delta, 1.0 - tan_delta * half)
    left_rad = math.atan2(tan_delta, 1.0 + tan_delta * half)
    return right_rad, left_rad
