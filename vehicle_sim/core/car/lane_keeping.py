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
A lane-keeping steering law: the steering angle that brings a car to a lateral offset in its lane.

Drive-v0's ``lane_speed`` action (core/learning/actions.py) asks for a lateral offset from the
centreline of the lane the car is on (its lane state: offset, + = left, and heading error, yaw
minus the lane's direction) and lets this law steer, as highway-env's meta-actions leave the
steering to a lane-following controller and the policy picks lanes and speeds. A cascade of two
proportional loops on a kinematic bicycle, evaluated once per decision and held until the next:

- the heading wanted: the lateral error e = target - offset closed in about LATERAL_TIME_S at the
  car's speed v: atan(e / (v LATERAL_TIME_S)), within +-MAX_HEADING_RAD of the lane's direction
  (at 33 m/s, 0.1 rad moves the car sideways at 3.3 m/s: a lane of 3.75 m in about 1.5 s);
- the steering angle that turns the car to it in about HEADING_TIME_S: a bicycle of wheelbase L
  turns at v tan(delta) / L, so delta = atan(L (heading wanted - heading error) /
  (v HEADING_TIME_S)), with L = GAIN_LENGTH_M (a car's wheelbase, 2.5 to 3 m; the law needs no
  exact value), within the steering bounds the action allows.

The speed is taken as at least MIN_SPEED_MPS (at rest the law would ask for any angle). Holding
the angle for a decision of 0.2 s stays stable while HEADING_TIME_S is twice that or more. On a
curve of radius R the law has no feed-forward, so the car settles v^2 LATERAL_TIME_S
HEADING_TIME_S / R off its target toward the outside (0.29 m at 33 m/s on a 1 500 m arc): the
policy sees its offset and may ask for more.
"""

import math

# The lateral error is closed in about this time [s].
LATERAL_TIME_S = 1.0
# The heading error is closed in about this time [s] (twice the 0.2 s decision or more).
HEADING_TIME_S = 0.4
# The largest heading off the lane's direction the law asks for [rad].
MAX_HEADING_RAD = 0.1
# The bicycle's length in the law [m]: a car's wheelbase.
GAIN_LENGTH_M = 2.7
# The speed the law takes at least [m/s].
MIN_SPEED_MPS = 5.0


def lane_keeping_steering(target_offset_m, offset_m, heading_error_rad, forward_mps,
                          low_rad, high_rad):
    """
    Return the steering angle [rad], + = left (REP 103), toward a lateral offset in the lane.

    :param target_offset_m: the offset asked, from the lane's centreline, + = left [m].
    :param offset_m: the car's offset now, + = left [m] (its lane state).
    :param heading_error_rad: the car's yaw minus the lane's direction [rad].
    :param forward_mps: the car's forward speed [m/s].
    :param low_rad: the smallest steering angle allowed (+ = left) [rad]; ``high_rad`` the
        largest. The law's angle is kept within them (a controller's output limit).
    """
    speed = max(abs(forward_mps), MIN_SPEED_MPS)
    heading = math.atan2(target_offset_m - offset_m, speed * LATERAL_TIME_S)
    heading = min(max(heading, -MAX_HEADING_RAD), MAX_HEADING_RAD)
    steering = math.atan(GAIN_LENGTH_M * (heading - heading_error_rad) / (speed * HEADING_TIME_S))
    return min(max(steering, low_rad), high_rad)
