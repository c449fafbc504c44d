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

from vehicle_sim.core.car.speed_braking import brake_for_speed


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
