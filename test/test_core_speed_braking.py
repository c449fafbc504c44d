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

"""When a speed asked of a car is reached with the brakes (core/car/speed_braking.py)."""

import pytest

from vehicle_sim.config import load_car
from vehicle_sim.core.car.drivetrain import ControlMode
from vehicle_sim.core.car.logic import CarLogic
from vehicle_sim.core.car.speed_braking import (
    brake_for_deceleration,
    brake_for_speed,
    cruise_ramp_mps2,
    full_brake_deceleration_mps2,
    full_stop,
)


@pytest.mark.parametrize('speed, target, brake', [
    (20.0, 20.0, 0.0), (20.0, 25.0, 0.0),       # as fast or faster: cruise
    (20.0, 19.0, 0.0),                          # 1 m/s slower: the cruise control's ramp
    (20.0, 18.0, 0.4),                          # 2 m/s slower: 2/5 of the brake
    (20.0, 15.0, 1.0), (20.0, 0.0, 1.0),        # 5 m/s slower or more: full brake
    (3.0, -5.0, 0.6),                           # forward, reverse asked: brake to a stand first
    (0.5, -5.0, 0.0),                           # near the stand: the cruise control reverses
    (-4.0, -1.0, 0.6),                          # reversing, a slower reverse asked
    (-4.0, 5.0, 0.8),                           # reversing, forward asked
    (-4.0, -6.0, 0.0), (0.0, 10.0, 0.0), (0.0, -3.0, 0.0),
])
def test_the_brake_grows_with_how_much_slower_the_speed_asked_is(speed, target, brake):
    assert brake_for_speed(speed, target) == pytest.approx(brake)


def test_the_prius_brakes_at_4_81_mps2_and_its_cruise_control_ramps_at_2_6():
    prius = load_car('ToyotaPrius')
    # 4 wheels x 700 N·m / 0.317 m over 1805 kg + 4 x 8 kg
    assert full_brake_deceleration_mps2(prius) == pytest.approx(4 * 700.0 / 0.317 / 1837.0)
    assert cruise_ramp_mps2(prius) == pytest.approx(100.0 / 3.6 / 10.7)


@pytest.mark.parametrize('deceleration, brake', [
    (-1.0, 0.0), (0.0, 0.0), (2.0, 0.0), (2.6, 0.0),   # within the ramp: the cruise control
    (3.0, 0.6), (4.0, 0.8), (5.0, 1.0), (9.0, 1.0),    # beyond: in proportion to full brake
])
def test_the_brake_gives_the_deceleration_beyond_the_cruise_ramp(deceleration, brake):
    assert brake_for_deceleration(deceleration, 2.6, 5.0) == pytest.approx(brake)


def test_brakes_weaker_than_the_ramp_leave_the_slowing_to_the_cruise_control():
    assert brake_for_deceleration(5.0, 5.9, 3.7) == 0.0


@pytest.mark.parametrize('model, released', [('ToyotaPrius', True), ('Car', True),
                                             ('RangeRoverSportSVR', False)])
def test_full_stop_releases_the_throttle_where_the_brakes_slow_harder(model, released):
    logic = CarLogic(load_car(model))
    logic.set_cruising_speed_kmh(50.0)
    full_stop(logic)
    assert (logic.target_cruising_speed_kmh, logic.brake_intensity) == (0.0, 1.0)
    mode = ControlMode.TORQUE if released else ControlMode.SPEED
    assert (logic.control_mode, logic.throttle) == (mode, 0.0)
