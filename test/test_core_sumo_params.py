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
The SUMO engine's ``traffic:`` table (core/traffic/sumo_params.py), through the engine registry.

Its keys and defaults, files resolved against the world file's folder, the demand's classes and
bounds (10^7 vehicles an hour is refused, not bounded), the vehicle classes' object classes, and
the errors that name the file, the field and the value.
"""

import pytest

from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.traffic.engines import TRAFFIC_ENGINES, traffic_spec_from_dict
from vehicle_sim.core.traffic.objects import OBJECT_CLASSES
from vehicle_sim.core.traffic.sumo_params import (
    DEMAND_CLASSES,
    object_class,
    OBJECT_CLASS_OF_VCLASS,
    sumo_traffic_markdown,
)


def _parse(data, folder=None):
    return traffic_spec_from_dict({'engine': 'sumo', **data}, 'w.yaml: traffic', None,
                                  None if folder is None else str(folder))


@pytest.fixture
def routes(tmp_path):
    (tmp_path / 'city.rou.xml').write_text('<routes/>\n')
    return tmp_path


def test_the_engine_is_registered_with_its_tables():
    assert TRAFFIC_ENGINES['sumo'].markdown() == sumo_traffic_markdown()
    text = sumo_traffic_markdown()
    assert '#### `traffic:` (`engine: sumo`)' in text and '#### `demand:`' in text
    assert '| `vehicles_per_hour` | float | `0.0` | 1/h | >= 0 and <= 20000 |' in text


def test_the_docs_hold_the_generated_key_tables():
    from pathlib import Path
    docs = Path(__file__).resolve().parent.parent / 'docs'
    assert any(sumo_traffic_markdown() in path.read_text('utf-8') for path in docs.glob('*.md'))


def test_routes_are_resolved_in_the_world_files_folder_and_the_defaults(routes):
    spec = _parse({'routes': 'city.rou.xml'}, routes)
    assert spec.engine == 'sumo' and spec.routes == (str(routes / 'city.rou.xml'),)
    assert (spec.step_s, spec.seed, spec.begin_s, spec.warmup_s, spec.transport, spec.options,
            spec.demand, spec.objects_rate_hz, spec.source) == (
        0.1, 0, 0.0, 0.0, 'auto', (), None, None, 'w.yaml: traffic')
    assert spec.update_period_s == 0.1
    listed = _parse({'routes': ['city.rou.xml', 'city.rou.xml'], 'step': 0.2, 'seed': 9,
                     'transport': 'traci', 'options': ['--time-to-teleport', '-1']}, routes)
    assert listed.routes == (str(routes / 'city.rou.xml'),) * 2
    assert (listed.step_s, listed.seed, listed.transport, listed.options) == (
        0.2, 9, 'traci', ('--time-to-teleport', '-1'))


def test_a_demand_with_weights_or_a_list_of_classes():
    spec = _parse({'demand': {'vehicles_per_hour': 900, 'pedestrians_per_hour': 60,
                              'classes': {'passenger': 2, 'bus': 1}}, 'seed': 4})
    demand = spec.demand
    assert demand.classes == (('passenger', 2.0), ('bus', 1.0)) and demand.seed is None
    assert demand.class_rates() == (('passenger', 600.0), ('bus', 300.0))
    assert (demand.pedestrians_per_hour, demand.duration_s) == (60.0, 3600.0)
    listed = _parse({'demand': {'vehicles_per_hour': 100, 'classes': ['truck', 'bicycle'],
                                'seed': 3}}).demand
    assert listed.class_rates() == (('truck', 50.0), ('bicycle', 50.0)) and listed.seed == 3
    assert _parse({'demand': {'vehicles_per_hour': 10}}).demand.classes == (('passenger', 1.0),)


@pytest.mark.parametrize('data, words', [
    ({'demand': {'vehicles_per_hour': 1e7}},
     r"demand: field 'vehicles_per_hour' = 10000000\.0: must be >= 0 and <= 20000$"),
    ({'demand': {'pedestrians_per_hour': -1}},
     r"demand: field 'pedestrians_per_hour' = -1\.0: must be >= 0"),
    ({'demand': {'vehicles_per_hour': 20000, 'duration': 86400}},
     r'demand: \(vehicles_per_hour \+ pedestrians_per_hour\) x duration = 480000 departures: '
     r'at most 100000'),
    ({'demand': {'classes': {'tank': 1}}},
     r"demand: field 'classes': 'tank': not a vehicle class a demand draws; valid: passenger"),
    ({'demand': {'classes': {'bus': -1}}}, r"demand: field 'classes': bus: weight -1 must be"),
    ({'demand': {'classes': {'bus': 0}}}, r"field 'classes' = \{'bus': 0\}: the weights add up "
                                          r'to 0'),
    ({'demand': {'classes': []}}, r"field 'classes' = \[\]: must not be empty"),
    ({'demand': {'rate': 3}}, r"demand: unknown field 'rate'"),
    ({}, r'the sumo engine needs routes \(a SUMO route file\) or demand'),
    ({'routes': 'missing.rou.xml'},
     r"field 'routes' = 'missing.rou.xml': no such file \(.*/missing.rou.xml\)"),
    ({'routes': 5}, r"field 'routes' = 5: must be a file name or a list"),
    ({'routes': [3]}, r"field 'routes' = 3: must be a file name"),
    ({'demand': {}, 'step': 0}, r"field 'step' = 0\.0: must be > 0"),
    ({'demand': {}, 'transport': 'zmq'}, r"field 'transport' = 'zmq'"),
    ({'demand': {}, 'options': ['--seed', '3']}, r"field 'options': '--seed' is set by the "
                                                 r'engine'),
    ({'demand': {}, 'options': ['--step-length=0.5']}, r"'--step-length=0.5' is set by"),
    ({'demand': {}, 'vehicles': 5}, r"unknown field 'vehicles'"),
    ({'demand': {}, 'warmup': 0.15}, r"field 'warmup' = 0\.15: must be a multiple of step "
                                     r'\(0\.1 s\)$'),
])
def test_bad_values_are_refused_naming_the_field(routes, data, words):
    with pytest.raises(InvalidParameterError, match=r'^w\.yaml: traffic: .*' + words):
        _parse(data, routes)


def test_each_vehicle_class_has_an_object_class():
    assert set(OBJECT_CLASS_OF_VCLASS.values()) <= set(OBJECT_CLASSES)
    assert {vclass: object_class(vclass) for vclass in (
        'passenger', 'truck', 'delivery', 'bus', 'coach', 'motorcycle', 'moped', 'bicycle',
        'pedestrian', 'trailer', 'ship')} == {
        'passenger': 'car', 'truck': 'truck', 'delivery': 'truck', 'bus': 'bus', 'coach': 'bus',
        'motorcycle': 'motorcycle', 'moped': 'motorcycle', 'bicycle': 'bicycle',
        'pedestrian': 'pedestrian', 'trailer': 'trailer', 'ship': 'car'}
    assert set(DEMAND_CLASSES) <= set(OBJECT_CLASS_OF_VCLASS)
