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
Example: test a car with plain pytest and the vehicle_sim plugin (docs/testing.md).

Run: ``.venv/bin/python -m pytest examples/test_user_example.py`` (the installed plugin is
active by itself; ``-p vehicle_sim.testing`` is accepted too).
The ``automobile_node`` fixture starts a synchronous simulation; nothing moves until
``client.step(...)``, so every assertion below holds exactly, run after run.
"""

import pytest

from vehicle_sim.testing import stamp_s


def test_cruising_speed_30_for_200_steps_moves_the_car_and_advances_clock_2s(automobile_node):
    car = automobile_node.client
    start_s = car.sim_time()

    assert car.call('set_cruising_speed', 30.0).success
    end_s = car.step(200)                          # 200 basic steps of 10 ms

    assert car.latest('current_speed').data > 0.0  # km/h, Webots units
    assert stamp_s(car.latest('/clock')) - start_s == pytest.approx(2.0, abs=1e-9)
    assert end_s - start_s == pytest.approx(2.0, abs=1e-9)


def test_set_gear_outside_the_gearbox_is_refused(automobile_node):
    car = automobile_node.client
    assert not car.call('set_gear', 99).success    # Car has gears -1..5
    assert car.call('set_gear', 2).success
    assert car.call('get_gear').value == 2


@pytest.mark.vehicle_sim(car='TeslaModel3')
def test_throttle_switches_to_torque_mode_and_publishes_rpm(automobile_node):
    car = automobile_node.client
    assert car.call('set_gear', 1).success
    assert car.call('set_throttle', 0.5).success
    car.step(50)
    assert car.call('get_control_mode').value == 1  # TORQUE
    assert car.latest('rpm').data > 0.0
