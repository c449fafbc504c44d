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
The lane-keeping law of the lane_speed action (core/car/lane_keeping.py).

Its formula at given inputs, its limits, and its closed loop on a kinematic bicycle with the
angle held for 0.2 s decisions: a lane change settles without leaving the lane asked for, and on
a curve the car settles where the law's documented offset, v^2 LATERAL_TIME_S HEADING_TIME_S /
R, puts it.
"""

import math

import pytest

from vehicle_sim.core.car import lane_keeping as lk

STEER = 0.02            # rad: Drive-v0's max_steering of examples/train_highway.py
HOLD_S = 0.2            # a decision (action_repeat 20 of 10 ms)
DT = 0.01
LANE_M = 3.75


def test_the_law_s_angle_is_the_documented_cascade():
    assert lk.lane_keeping_steering(0.0, 0.0, 0.0, 30.0, -1.0, 1.0) == 0.0
    # 1 m to the left at 20 m/s: heading wanted atan(1 / 20), reached through a 2.7 m bicycle
    # in 0.4 s; the car already 0.01 rad to the left
    heading = math.atan2(1.0, 20.0 * lk.LATERAL_TIME_S)
    expected = math.atan(lk.GAIN_LENGTH_M * (heading - 0.01) / (20.0 * lk.HEADING_TIME_S))
    assert lk.lane_keeping_steering(1.0, 0.0, 0.01, 20.0, -1.0, 1.0) == pytest.approx(
        expected, rel=1e-12)
    # symmetric: right for a target to the right
    assert lk.lane_keeping_steering(-1.0, 0.0, -0.01, 20.0, -1.0, 1.0) == pytest.approx(
        -expected, rel=1e-12)


def test_the_heading_asked_and_the_angle_stay_within_their_limits():
    # a far target asks for at most MAX_HEADING_RAD off the lane
    far = lk.lane_keeping_steering(50.0, 0.0, 0.0, 30.0, -1.0, 1.0)
    at_limit = math.atan(lk.GAIN_LENGTH_M * lk.MAX_HEADING_RAD / (30.0 * lk.HEADING_TIME_S))
    assert far == pytest.approx(at_limit, rel=1e-12)
    # the angle within the bounds given (asymmetric bounds kept as given)
    assert lk.lane_keeping_steering(3.75, 0.0, 0.0, 30.0, -0.01, 0.005) == 0.005
    assert lk.lane_keeping_steering(-3.75, 0.0, 0.0, 30.0, -0.01, 0.005) == -0.01
    # at rest the speed taken is MIN_SPEED_MPS: a finite angle
    slow = lk.lane_keeping_steering(0.5, 0.0, 0.0, 0.0, -1.0, 1.0)
    heading = math.atan2(0.5, lk.MIN_SPEED_MPS * lk.LATERAL_TIME_S)
    assert slow == pytest.approx(math.atan(
        lk.GAIN_LENGTH_M * heading / (lk.MIN_SPEED_MPS * lk.HEADING_TIME_S)), rel=1e-12)


def _drive(target_of, speed, seconds, radius=math.inf, wheelbase=2.7):
    """Drive a kinematic bicycle in a lane's frame, the law's angle held each 0.2 s."""
    offset = heading = 0.0
    trace = []
    steering = 0.0
    for step in range(int(round(seconds / DT))):
        t = step * DT
        if step % int(round(HOLD_S / DT)) == 0:
            steering = lk.lane_keeping_steering(target_of(t, offset), offset, heading, speed,
                                                -STEER, STEER)
        # the car's yaw rate less the lane's (a curve to the left for radius > 0)
        heading += DT * (speed * math.tan(steering) / wheelbase - speed / radius)
        offset += DT * speed * math.sin(heading)
        trace.append((t + DT, offset, heading, steering))
    return trace


@pytest.mark.parametrize('speed', (10.0, 20.0, 33.3))
def test_a_lane_change_settles_in_the_next_lane_without_overshooting_it(speed):
    trace = _drive(lambda t, offset: LANE_M, speed, 12.0)
    offsets = [offset for _, offset, _, _ in trace]
    # over the line (1.875 m) within 3 s, in the new lane's centre within 0.1 m after 6 s
    crossed = next(t for t, offset, _, _ in trace if offset > 0.5 * LANE_M)
    assert crossed < 3.0
    assert all(abs(offset - LANE_M) < 0.1 for t, offset, _, _ in trace if t > 6.0)
    # no overshoot worth a lane's margin: at most 0.15 m past the new centre
    assert max(offsets) < LANE_M + 0.15
    # the heading off the lane stays near MAX_HEADING_RAD (the law asks for no more)
    assert max(abs(heading) for _, _, heading, _ in trace) < lk.MAX_HEADING_RAD + 0.01


def test_on_a_curve_the_car_settles_where_the_documented_offset_puts_it():
    speed, radius = 33.3, 1500.0
    trace = _drive(lambda t, offset: 0.0, speed, 30.0, radius)
    expected = -speed ** 2 * lk.LATERAL_TIME_S * lk.HEADING_TIME_S / radius   # outside: right
    late = [offset for t, offset, _, _ in trace if t > 20.0]
    assert expected == pytest.approx(-0.296, abs=0.001)
    assert min(late) == pytest.approx(expected, rel=0.05)
    assert max(late) == pytest.approx(expected, rel=0.05)
    # the angle held there is the curve's own, atan(L / R)
    assert trace[-1][3] == pytest.approx(math.atan(2.7 / radius), rel=0.05)
