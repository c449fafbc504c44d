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
The headway guard: the highest speed a car may ask for behind the vehicles ahead in its lane.

Drive-v0's ``guarded_speed_steering`` action (core/learning/actions.py) asks for
min(the policy's speed, this speed): the policy chooses where to drive and how fast, the guard
keeps it from running into the car ahead, as a car's adaptive cruise control or Autoware's
obstacle_cruise_planner does under a planner. It reads the same objects table the policy reads
(core/learning/objects_table.py, highway-env's Kinematics layout: presence, x, y, vx, vy, ...
relative to the ego, over the table's range and speed scale), so that the environment in
process and the policy node over ROS (from ``/perception/object_recognition/objects``) compute
the same speed.

A row is a **lead** when it is ahead (x > 0: within the table's range) and within
:data:`PATH_HALF_WIDTH_M` of the ego's lane centre line, across its lane: offset + x sin(heading
error) + y cos(heading error), from the ego's lane state (a straight lane is assumed: on an arc
of radius R a car x metres ahead reads x^2 / 2R further out, 0.6 m at 40 m on R = 1500 m). For
a lead of speed v_l (the ego's forward speed plus the row's vx) whose centre is x ahead of the
ego's base_link, the speed allowed is the one from which braking at :data:`DECELERATION_MPS2`
after a reaction time :data:`REACTION_S` ends at the lead's speed with
:data:`STANDSTILL_DISTANCE_M` left (a constant-deceleration stop, the lead holding its speed):

    v_allowed = v_l + sqrt(2 b max(0, x - d_0 - t_r max(0, v - v_l)))

and the guard's speed is the least over the leads (infinity with none). The guard sees what the
table holds: its nearest ``count`` objects within its ``range`` (80 m by default), so a car at
rest is met in time only from below sqrt(2 b (range - d_0)), 20.6 m/s at 80 m. Asked of
braking_speed_steering's rule (core/car/speed_braking.py), a speed well below the car's brakes
in proportion, so the guard brakes harder the later it is.

Numpy only; no state.
"""

import math

import numpy as np

# The deceleration the guard plans with [m/s^2]: well under the Prius's 4.8-5.4 m/s^2 full brake
# (core/car/speed_braking.py), since that rule's brake is proportional to the speed error and
# builds up late (at 4.0 the car reached a parked box from 16-20 m/s; at 3.0 it stops short).
DECELERATION_MPS2 = 3.0
# The time before the brake acts [s]: a 0.2 s policy period and the brake's build-up.
REACTION_S = 0.5
# A lead's centre this far ahead of the ego's base_link at the end of a stop [m]: base_link lies
# below the rear axle, the Prius's front bumper 3.7 m ahead of it, half a 4.5 m car to the
# lead's centre, and about 3 m between the bumpers.
STANDSTILL_DISTANCE_M = 9.0
# A row within this of the ego's lane centre line is in its path [m]: half a 3.75 m lane and a
# little, so that a car halfway over the line into the ego's lane counts.
PATH_HALF_WIDTH_M = 2.0


def guard_speed(table, range_m, speed_scale_mps, forward_mps, lane_offset_m=0.0,
                heading_error_rad=0.0):
    """
    Return the highest speed [m/s] the guard allows (``math.inf`` with no lead).

    :param table: the objects table (rows of presence, x, y, vx, vy, ...; normalised).
    :param range_m: the table's range (x and y are over it) [m].
    :param speed_scale_mps: its speed scale (vx and vy are over it) [m/s].
    :param forward_mps: the ego's forward speed [m/s].
    :param lane_offset_m: its lateral offset from its lane's centre line, + = left [m] (0 off
        every lane: the ego's own axis is the path then).
    :param heading_error_rad: its yaw minus its lane's direction [rad].
    """
    rows = np.asarray(table, dtype=np.float64)
    present = rows[:, 0] > 0.5
    x = rows[:, 1] * range_m
    y = rows[:, 2] * range_m
    across = lane_offset_m + x * math.sin(heading_error_rad) + y * math.cos(heading_error_rad)
    lead = present & (x > 0.0) & (np.abs(across) <= PATH_HALF_WIDTH_M)
    if not lead.any():
        return math.inf
    lead_speed = forward_mps + rows[lead, 3] * speed_scale_mps
    closing = np.maximum(0.0, forward_mps - lead_speed)
    room = np.maximum(0.0, x[lead] - STANDSTILL_DISTANCE_M - REACTION_S * closing)
    return float(np.min(lead_speed + np.sqrt(2.0 * DECELERATION_MPS2 * room)))
