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
Traffic in the live view's scene: each traffic vehicle a box where the physics has it.

A short stretch of the highway world with two placed traffic cars (test/test_physics_traffic.py
builds the same way): the entities follow the boxes as they drive, with the preset's size and
the part's colours, and a car that leaves the map is deleted from the view.
"""

import copy

import pytest

from vehicle_sim.config import read_yaml, world_from_data, world_path
from vehicle_sim.foxglove.scene_stream import SceneStream
from vehicle_sim.physics.scene import build_scene
from vehicle_sim.physics.traffic_bodies import COLOURS, GROUND_CLEARANCE_M, model_dimensions

MIDDLE = 100002             # the ego's lane: y = -5.625 m, along +x from x = 0


@pytest.fixture
def traffic_scene():
    data = copy.deepcopy(read_yaml(world_path('highway')))
    data['vehicles'][0].update(model='Car', pose={'x': 20.0, 'y': -5.625, 'yaw': 0.0})
    data['traffic'] = {'update_period': 0.01, 'placed': [
        {'model': 'ToyotaPrius', 'lanelet': MIDDLE, 's': 60.0, 'speed': 10.0},
        {'model': 'BmwX5', 'lanelet': MIDDLE, 's': 120.0, 'speed': 10.0}]}
    scene = build_scene(world_from_data(data, 'highway_test.yaml'))
    yield scene
    scene.world.close()


def test_traffic_cars_are_boxes_that_follow_the_physics(traffic_scene):
    scene, stream = traffic_scene, SceneStream()
    traffic = scene.parts['traffic']
    first = stream.frame(scene, full=False)
    ids = [e.id for e in first.entities]
    assert 'vehicle/Car' in ids and 'lanes/markings' in ids
    cars = {e.id: e for e in first.entities if e.id.startswith('traffic/')}
    names = [v.name for v in traffic.manager.vehicles]
    assert sorted(cars) == sorted(f'traffic/{name}' for name in names)
    for v, body_id in zip(traffic.manager.vehicles, traffic.body_ids):
        (cube,) = cars[f'traffic/{v.name}'].primitives
        length, width, height = model_dimensions(v.model)
        assert cube.kind == 'cube'
        assert cube.size_m == pytest.approx((length, width, height - GROUND_CLEARANCE_M))
        assert cube.color_rgba == COLOURS[v.index % len(COLOURS)]
        (position, orientation), *_ = scene.world.body_state(body_id)
        assert cube.position_m == pytest.approx(position) and cube.orientation == orientation
    before = {i: e.primitives[0].position_m[0] for i, e in cars.items()}
    for _ in range(50):                              # 0.5 s at 10 m/s: about 5 m on
        scene.world.step()
    moved = stream.frame(scene, full=False)
    assert all(not e.id.startswith('lanes/') for e in moved.entities)     # static: once
    after = {e.id: e.primitives[0].position_m[0] for e in moved.entities if e.id in cars}
    for key, x in after.items():
        assert x - before[key] == pytest.approx(5.0, abs=0.5)
    # A car that leaves the map (parked under the ground) is deleted from the view.
    gone = traffic.manager.vehicles[1]
    gone.active = False
    last = stream.frame(scene, full=False)
    assert last.deleted_ids == (f'traffic/{gone.name}',)
    assert f'traffic/{gone.name}' not in [e.id for e in last.entities]


def test_a_pedestrian_is_an_upright_cylinder_of_its_diameter(monkeypatch):
    # An engine whose bodies are of classes (test/traffic_helpers.py): the contract's boxes()
    # gives each body's shape, a pedestrian's a cylinder (diameter, diameter, height).
    from traffic_helpers import register_classes_engine, WALKER_M
    register_classes_engine(monkeypatch)
    data = copy.deepcopy(read_yaml(world_path('highway')))
    data['traffic'] = {'engine': 'classes', 'classes': ['bus', 'pedestrian'], 'placed': [
        {'model': 'ToyotaPrius', 'lanelet': MIDDLE, 's': 60.0, 'speed': 10.0},
        {'model': 'BmwX5', 'lanelet': MIDDLE, 's': 120.0, 'speed': 1.0}]}
    scene = build_scene(world_from_data(data, 'classes.yaml'))
    try:
        entities = {e.id: e for e in SceneStream().frame(scene, full=False).entities}
        traffic = scene.parts['traffic']
        bus, walker = (entities[f'traffic/{v.name}'].primitives for v in traffic.manager.vehicles)
        diameter, height = WALKER_M
        assert [p.kind for p in bus + walker] == ['cube', 'cylinder']
        assert walker[0].size_m == (diameter, diameter, height)
        (position, _), *_ = scene.world.body_state(traffic.body_ids[1])
        assert walker[0].position_m == pytest.approx(position)
    finally:
        scene.world.close()
