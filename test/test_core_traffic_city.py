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
Dense traffic in the city block, signalised and not, for 10 simulated minutes: no overlap.

The core TrafficManager alone on the lane maps of config/worlds/city_block.yaml (five
unsignalled intersections) and city_block_signals.yaml (the same, each with a light per
approach, on the world's plan), 80 vehicles (about 28 per km of lane); every vehicle's
footprint (its model's rectangle at the manager's pose) is tested against every other's at
every 100 ms update (``footprints.overlapping``, checked against a plain separating-axis test in
test_core_traffic_rules.py).
"""

import pytest

from vehicle_sim.config import load_world, read_yaml, world_from_data, world_path
from vehicle_sim.core.map.signal_params import SignalSpec
from vehicle_sim.core.map.signal_plan import SignalController
from vehicle_sim.core.traffic.footprints import overlapping
from vehicle_sim.core.traffic.manager import TrafficManager
from vehicle_sim.core.traffic.params import traffic_from_dict
from vehicle_sim.maps.lane_maps import with_lanes
from vehicle_sim.physics.traffic_bodies import model_dimensions

DT = 0.1
MODELS = ['ToyotaPrius', 'BmwX5', 'TeslaModel3', 'CitroenCZero', 'LincolnMKZ']
SIZES = {m: model_dimensions(m)[:2] for m in MODELS}


def city(world, vehicles=80, seed=1):
    if world == 'city_block_stop_signs':         # every intersection an all-way stop
        data = read_yaml(world_path('city_block'))
        for road in data['roads']:
            for segment in road['segments']:
                if segment['type'] == 'intersection':
                    segment['stop_signs'] = True
        spec = with_lanes(world_from_data(data, 'city_block_stop_signs.yaml'))
    else:
        spec = with_lanes(load_world(world))
    graph = spec.lanes
    signals = None
    if graph.rules.groups:
        signals = SignalController(graph, (spec.signals or SignalSpec()).fixed_time_plan())
    traffic = traffic_from_dict({'vehicles': vehicles, 'seed': seed, 'models': MODELS,
                                 'spawn': {'spacing': 15.0}}, f'{world}: traffic')
    return TrafficManager(graph, traffic, SIZES, signals=signals), signals


def junction_lanes(graph):
    return {lane for c in graph.rules.conflicts for lane in (c.lane_id, c.other_id)}


@pytest.mark.parametrize('world', ['city_block_signals', 'city_block'])
def test_ten_minutes_of_dense_city_traffic_without_an_overlap(world):
    m, signals = city(world)
    inside = junction_lanes(m.graph)
    was = [v.lane for v in m.vehicles]
    through = [0] * 10                  # vehicles out of an intersection, per minute
    stood_at_red = 0
    for step in range(int(600.0 / DT)):
        m.step(DT)
        if signals is not None:
            signals.update(m.time_s)
        touching = overlapping([(*m.pose(v), v.length_m, v.width_m)
                                for v in m.vehicles if v.active])
        assert touching == [], (world, m.time_s, touching)
        for v in m.vehicles:
            if v.active and was[v.index] in inside and v.lane not in inside:
                through[min(int(m.time_s // 60.0), 9)] += 1
            was[v.index] = v.lane if v.active else None
        stood_at_red += sum(1 for why in m.rules.waiting.values() if why == 'stop line')
    print(world, 'vehicles out of the intersections per minute:', through)
    # the traffic keeps flowing to the end: no gridlock
    assert min(through) >= 20, through
    if signals is not None:
        assert stood_at_red > 0 and signals.time_s == pytest.approx(600.0)
    else:
        assert stood_at_red == 0


def test_city_traffic_at_signals_is_deterministic():
    def run():
        m, signals = city('city_block_signals', vehicles=60, seed=4)
        rows = []
        for _ in range(int(60.0 / DT)):
            m.step(DT)
            signals.update(m.time_s)
            rows.append(tuple((v.lane, v.s_m, v.speed_mps) for v in m.vehicles))
        return rows
    assert run() == run()


def test_an_all_way_stop_city_block_stands_at_every_line_and_never_overlaps():
    m, _ = city('city_block_stop_signs', vehicles=60)
    assert {line.kind for line in m.graph.rules.stop_lines} == {'stop_sign'}
    standing, passed = set(), 0
    lines = {line.lane_id: line for line in m.graph.rules.stop_lines}
    for _ in range(int(180.0 / DT)):
        before = [v.lane for v in m.vehicles]
        m.step(DT)
        assert overlapping([(*m.pose(v), v.length_m, v.width_m)
                            for v in m.vehicles if v.active]) == []
        for v in m.vehicles:
            line = lines.get(v.lane)
            if line is not None and v.speed_mps < 0.1 and \
                    line.s_m - (v.s_m + 0.5 * v.length_m) < m.idm.min_gap_m + 1.5:
                standing.add((v.index, line.id))
            if before[v.index] in lines and v.lane != before[v.index] and v.active:
                passed += 1
                key = (v.index, lines[before[v.index]].id)
                assert key in standing          # it stood at the line, then went on
                standing.discard(key)
    assert passed >= 100
