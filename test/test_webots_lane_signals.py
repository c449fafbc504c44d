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
The Webots facade's ``Driver.getLaneState()`` names the next stop line and its signal.

On test/signal_helpers.py's road with its hand-made 'signals' part: a Driver of its own world
file, and a controller hosted by the scenario runner, read the traffic light line 9001 ahead
(group 7001) at its distance and the group's state as the world's controller gives it; on the
shipped config/worlds/city_block_signals.yaml, a Driver reads the ring intersection's line.
"""

import pytest
from signal_helpers import with_hand_signals, write_world
import yaml


def test_a_drivers_lane_state_carries_the_next_signal_and_its_distance(tmp_path, monkeypatch):
    from vehicle_sim.webots import driver as driver_module
    with_hand_signals(monkeypatch, driver_module)
    driver = driver_module.Driver(world_file=str(write_world(tmp_path)))
    try:
        driver.step()
        state = driver.getLaneState()
        assert (state.lane_id, state.s_m) == (100001, pytest.approx(20.0, abs=0.01))
        assert (state.stop_line_ahead, state.stop_line_id, state.stop_line_kind,
                state.traffic_light_group_id, state.signal_state) == (
            True, 9001, 'traffic_light', 7001, 'green')
        assert state.stop_line_distance_m == pytest.approx(30.0, abs=0.01)
        while driver.getTime() < 0.6 - 1e-9:         # 7001 turns yellow at 0.55 s
            driver.step()
        assert driver.getLaneState().signal_state == 'yellow'
    finally:
        driver.close()


def test_a_hosted_controller_reads_the_signal_ahead(tmp_path, monkeypatch):
    from vehicle_sim.scenarios import sim as sim_module
    from vehicle_sim.scenarios.runner import run_scenario
    with_hand_signals(monkeypatch, sim_module)
    world = write_world(tmp_path)
    record = tmp_path / 'signal.txt'
    controller = tmp_path / 'signal_reader.py'
    controller.write_text(
        'from vehicle_sim.webots import Driver\n'
        'driver = Driver()\n'
        'seen = []\n'
        'while driver.step() != -1:\n'
        '    state = driver.getLaneState()\n'
        '    seen.append(f"{state.stop_line_id} {state.signal_state} '
        '{state.stop_line_distance_m:.1f}")\n'
        f'    open({str(record)!r}, "w").write(seen[0] + " | " + seen[-1])\n',
        encoding='utf-8')
    scenario = tmp_path / 'signal_scenario.yaml'
    scenario.write_text(yaml.safe_dump({
        'name': 'signal_reader', 'world': str(world), 'duration': 0.8,
        'driver': {'controller': str(controller)},
        'criteria': [{'kind': 'stay_in_lane', 'max_offset': 0.1}]}), encoding='utf-8')
    result = run_scenario(str(scenario))
    assert result.passed
    assert record.read_text() == '9001 green 30.0 | 9001 red 30.0'     # red from 0.75 s


def test_on_the_shipped_signalised_city_the_driver_reads_the_intersections_signal():
    from vehicle_sim.webots import Driver
    driver = Driver(world_file='config/worlds/city_block_signals.yaml')
    try:
        driver.step()
        state = driver.getLaneState()
        # the car at x = -60 on the ring's south side heading east: the ring's first
        # intersection's entry at x = -6; its group is in the first phase: green from 0 s
        assert (state.lane_id, state.stop_line_id, state.stop_line_kind,
                state.traffic_light_group_id, state.signal_state) == (
            100001, 3000100001, 'traffic_light', 4000100101, 'green')
        assert state.stop_line_distance_m == pytest.approx(54.0, abs=0.01)
    finally:
        driver.close()
