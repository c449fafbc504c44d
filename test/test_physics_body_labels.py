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


"""The label table and the world's body labels (core/sensors/labels.py, physics/body_labels.py)."""

import uuid

import numpy as np
import pytest

from vehicle_sim.core.sensors.labels import (
    check_label_names,
    LABEL_IDS,
    label_of_class,
    labels_markdown,
)
from vehicle_sim.core.traffic.objects import OBJECT_CLASSES
from vehicle_sim.physics.body_labels import BodyLabels, instance_uuid, MAX_INSTANCE
from vehicle_sim.physics.world import World


def test_every_traffic_class_has_its_own_label_and_unknown_ones_are_obstacles():
    assert label_of_class('pedestrian') == LABEL_IDS['pedestrian']
    assert label_of_class('trailer') == LABEL_IDS['truck']
    assert label_of_class('tram') == LABEL_IDS['obstacle']
    assert all(label_of_class(name) != LABEL_IDS['obstacle'] for name in OBJECT_CLASSES)


def test_a_class_list_naming_an_unknown_label_is_refused_naming_it():
    assert check_label_names(['car', 'road'], 'w.yaml') == ('car', 'road')
    with pytest.raises(ValueError, match=r"w.yaml: 'cars' is not a label"):
        check_label_names(['car', 'cars'], 'w.yaml')
    assert '| 12 | `pedestrian` |' in labels_markdown()


def test_lookup_gives_labels_and_instances_per_body_and_link():
    labels = BodyLabels()
    labels.set(3, 'car', labels.instance('car_a'))
    labels.set(5, 'road')
    labels.set(5, 'lane_marking', link=2)
    got_labels, got_instances = labels.lookup([3, 5, 5, -1, 9, 4], [-1, -1, 2, -1, -1, -1])
    assert got_labels.tolist() == [LABEL_IDS[n] for n in
                                   ('car', 'road', 'lane_marking', 'none', 'obstacle',
                                    'obstacle')]
    assert got_instances.tolist() == [1, 0, 0, 0, 0, 0]
    assert labels.of(5, 2) == (LABEL_IDS['lane_marking'], 0)
    labels.forget(3)
    assert labels.of(3) == (LABEL_IDS['obstacle'], 0)


def test_instances_are_per_name_in_order_of_appearance_and_wrap_after_65535():
    labels = BodyLabels()
    assert [labels.instance(n) for n in ('a', 'b', 'a', 'c')] == [1, 2, 1, 3]
    for index in range(MAX_INSTANCE - 4):
        labels.instance(f'x{index}')
    assert labels.instance('last') == MAX_INSTANCE
    assert labels.instance('wrapped') == 1
    assert uuid.UUID(bytes=instance_uuid(258)).int == 258


def test_bad_labels_change_nothing():
    labels = BodyLabels()
    labels.set(1, 'car', 7)
    with pytest.raises(ValueError, match="label 'cat' is not in the label table"):
        labels.set(1, 'cat', 7)
    with pytest.raises(ValueError, match='instance id 70000: must be in 0..65535'):
        labels.set(1, 'car', 70000)
    assert labels.of(1) == (LABEL_IDS['car'], 7)


def test_the_worlds_ground_is_labelled_ground():
    world = World()
    try:
        got, _ = world.labels.lookup(np.array([world.ground_id]))
        assert got.tolist() == [LABEL_IDS['ground']]
    finally:
        world.close()
