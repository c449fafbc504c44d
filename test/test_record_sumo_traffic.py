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
A recording of a world with SUMO's traffic reads back with its objects and signals.

A 20 s scenario on the signalised SUMO city of test/test_physics_sumo_city.py recorded into an
MCAP file (``run_scenario(record=...)``, as ``vehicle-sim scenario --record``), read with rosbags
(its own CDR decoder and the file's schemas): /perception/object_recognition/objects holds CAR
and PEDESTRIAN objects (a car a BOUNDING_BOX, a pedestrian an upright CYLINDER), and
/perception/traffic_light_recognition/traffic_signals every group of the city.
"""

from collections import Counter

import pytest
import yaml

pytest.importorskip('libsumo', reason="needs the 'sumo' extra")
pytest.importorskip('mcap', reason="recording needs the mcap package (the 'record' extra)")

from record_helpers import typestore  # noqa: E402
from rosbags.rosbag2 import Reader  # noqa: E402
from test_physics_sumo_city import city_net, DEMAND, EGO_LANE, EGO_S  # noqa: E402

from vehicle_sim.scenarios.runner import run_scenario  # noqa: E402

OBJECTS = '/perception/object_recognition/objects'
SIGNALS = '/perception/traffic_light_recognition/traffic_signals'
DURATION_S = 20.0


def test_a_recorded_sumo_world_reads_back_with_its_objects_and_signals(tmp_path):
    scenario = tmp_path / 'record_city.yaml'
    scenario.write_text(yaml.safe_dump({
        'name': 'record_city',
        'world': {'vehicles': [{'name': 'ego', 'model': 'Car',
                                'pose': {'lane': EGO_LANE, 's': EGO_S}}],
                  'map': {'type': 'sumo', 'net': city_net(tmp_path)},
                  'traffic': {'engine': 'sumo', 'demand': DEMAND, 'seed': 1}},
        'vehicle': 'ego', 'duration': DURATION_S,
        'driver': {'commands': [{'t': 0.0, 'cruising_speed': 0.0, 'brake_intensity': 1.0}]},
        'criteria': [{'kind': 'no_collision', 'vehicle': 'ego'}]}), encoding='utf-8')
    path = tmp_path / 'city.mcap'
    result = run_scenario(scenario, record=str(path))
    assert result.passed, [c.detail for c in result.criteria]
    labels, shapes, groups, counts = Counter(), set(), set(), Counter()
    with Reader(path) as reader:
        store = typestore(reader.connections)
        for connection, _, raw in reader.messages():
            if connection.topic not in (OBJECTS, SIGNALS):
                continue
            counts[connection.topic] += 1
            msg = store.deserialize_cdr(raw, connection.msgtype)
            if connection.topic == OBJECTS:
                for item in msg.objects:
                    label = item.classification[0].label
                    labels[label] += 1
                    shapes.add((label, item.shape.type))
            else:
                groups.update(g.traffic_light_group_id for g in msg.traffic_light_groups)
    assert counts[OBJECTS] >= DURATION_S * 10 and counts[SIGNALS] >= DURATION_S * 10
    assert labels[1] > 100 and labels[7] > 100                     # CAR, PEDESTRIAN
    assert shapes == {(1, 0), (7, 1)}            # a car a BOUNDING_BOX, a pedestrian a CYLINDER
    assert len(groups) == 156                    # every group of the city (9 four-armed junctions)
