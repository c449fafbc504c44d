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
Scenarios and sweeps see SUMO's traffic as the builtin traffic.

A scenario on the signalised SUMO city of test/test_physics_sumo_city.py: our car waits before
the stop line of junction B1 (lane A1B1_1) while SUMO's vehicles cross the junction ahead of it;
its ``min_gap`` criterion (which reads the traffic bodies' contract) measures the gap to them,
naming the SUMO body (``sumo_<k>``) it came closest to. A sweep over two seeds runs it in worker
processes (each its own SUMO) with the same criterion values as the scenario run alone.
"""

import pytest
import yaml

pytest.importorskip('libsumo', reason="needs the 'sumo' extra")

from test_physics_sumo_city import city_net, DEMAND  # noqa: E402

from vehicle_sim.scenarios.runner import run_scenario  # noqa: E402

DURATION_S = 30.0


@pytest.fixture(scope='module')
def scenario(tmp_path_factory):
    folder = tmp_path_factory.mktemp('sumo_scenario')
    path = folder / 'wait_at_b1.yaml'
    path.write_text(yaml.safe_dump({
        'name': 'wait_at_b1',
        'world': {'vehicles': [{'name': 'ego', 'model': 'Car',
                                'pose': {'lane': 'A1B1_1', 's': 95.0}}],
                  'map': {'type': 'sumo', 'net': city_net(folder)},
                  'traffic': {'engine': 'sumo', 'demand': DEMAND, 'seed': 1}},
        'vehicle': 'ego',
        'duration': DURATION_S,
        'driver': {'commands': [{'t': 0.0, 'cruising_speed': 0.0, 'brake_intensity': 1.0}]},
        'criteria': [{'kind': 'min_gap', 'vehicle': 'ego', 'min': 0.5}]}), encoding='utf-8')
    return path


def test_a_scenarios_gap_criterion_measures_the_sumo_traffic_ahead(scenario):
    result = run_scenario(scenario)
    gap = result.criterion('min_gap')
    assert gap.value is not None and 0.5 < gap.value < 60.0, gap.detail
    assert 'sumo_' in gap.detail
    assert result.criterion('min_gap').passed


def test_a_sweep_runs_the_sumo_scenario_in_workers_as_alone(scenario, tmp_path):
    from vehicle_sim.sweep.run import run_sweep
    alone = run_scenario(scenario).criterion('min_gap').value
    result = run_sweep(str(scenario), seeds=[0, 1], out_dir=str(tmp_path / 'sweep'), workers=2,
                       plot=False)
    assert result.done == 2, [r['error'] for r in result.records]
    values = [{c['name']: c['value'] for c in r['criteria']}['min_gap']
              for r in sorted(result.records, key=lambda r: r['seed'])]
    assert all(value is not None for value in values)
    # the world's SUMO seed is its traffic's own (seed: 1): the same traffic in both cases
    assert values == [pytest.approx(alone), pytest.approx(alone)]
