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


"""The live view's scene and transforms: entity values, the entity-source registry, bad input."""

import math
from types import SimpleNamespace

import pytest

from vehicle_sim.config import load_car, load_robot
from vehicle_sim.core.geometry.footprint import car_outline, Outline, robot_outline
from vehicle_sim.core.world.params import obstacle_from_dict
from vehicle_sim.foxglove import scene as fs


def _yaw_q(yaw_rad):
    return (0.0, 0.0, math.sin(yaw_rad / 2.0), math.cos(yaw_rad / 2.0))


def test_car_boxes_are_its_preset_collision_boxes():
    params = load_car('Car')
    boxes = fs.vehicle_boxes(params, car_outline(params))
    # The Car preset's collisionBoxes: one 5 x 1.7 x 1 m box centred at (2, 0, 0.5) m.
    assert [(centre, size) for centre, _, size in boxes] == [((2.0, 0.0, 0.5), (5.0, 1.7, 1.0))]
    assert boxes[0][1] == pytest.approx((0.0, 0.0, 0.0, 1.0))


def test_robot_box_is_its_body_centred_on_the_axle_height():
    params = load_robot('caster_robot')
    (centre, orientation, size), = fs.vehicle_boxes(params, robot_outline(params))
    assert centre == (0.0, 0.0, params.wheel_radius_m)
    assert size == tuple(params.body_size_m)
    assert orientation == fs.IDENTITY


def test_body_without_boxes_is_drawn_as_its_footprint():
    outline = Outline(x_min_m=-1.0, x_max_m=3.0, y_min_m=-0.5, y_max_m=1.5)
    (centre, _, size), = fs.vehicle_boxes(SimpleNamespace(), outline)
    assert centre == (1.0, 0.5, fs.FOOTPRINT_BOX_HEIGHT_M / 2.0)
    assert size == (4.0, 2.0, fs.FOOTPRINT_BOX_HEIGHT_M)


def test_vehicle_entity_turned_left_puts_a_box_ahead_of_base_link_on_the_left():
    # base_link at (10, 5, 0) heading +90 deg: a box 2 m ahead (base_link x) is at
    # (10, 7) in the world, turned by the same quarter turn.
    boxes = [((2.0, 0.0, 0.5), fs.IDENTITY, (5.0, 1.7, 1.0))]
    entity = fs.vehicle_entity('ego', (10.0, 5.0, 0.0) + _yaw_q(math.pi / 2.0), boxes)
    assert entity.id == 'vehicle/ego' and entity.frame_id == fs.WORLD_FRAME
    (cube,) = entity.primitives
    assert cube.kind == 'cube'
    assert cube.position_m == pytest.approx((10.0, 7.0, 0.5), abs=1e-12)
    assert cube.orientation == pytest.approx(_yaw_q(math.pi / 2.0), abs=1e-12)
    assert cube.size_m == (5.0, 1.7, 1.0)
    assert cube.color_rgba == fs.VEHICLE_COLOR


@pytest.mark.parametrize('data, kind, size', [
    ({'shape': 'box', 'size': [1.0, 2.0, 3.0]}, 'cube', (1.0, 2.0, 3.0)),
    ({'shape': 'cylinder', 'radius': 0.25, 'height': 2.0}, 'cylinder', (0.5, 0.5, 2.0)),
    ({'shape': 'sphere', 'radius': 0.4}, 'sphere', (0.8, 0.8, 0.8)),
])
def test_obstacle_entity_has_its_shape_size_pose_and_colour(data, kind, size):
    spec = obstacle_from_dict(dict(data, name='thing', position=[4.0, -1.0, 0.5], yaw=math.pi),
                              'world.yaml')
    entity = fs.obstacle_entity(spec)
    assert entity.id == 'obstacle/thing'
    (primitive,) = entity.primitives
    assert primitive.kind == kind
    assert primitive.size_m == pytest.approx(size)
    assert primitive.position_m == (4.0, -1.0, 0.5)
    assert primitive.orientation == pytest.approx(_yaw_q(math.pi), abs=1e-12)
    assert primitive.color_rgba == tuple(spec.color_rgba)


def test_movable_obstacle_is_drawn_where_the_physics_has_it():
    spec = obstacle_from_dict({'name': 'ball', 'shape': 'sphere', 'radius': 0.5, 'mass': 2.0,
                               'position': [1.0, 1.0, 0.5]}, 'world.yaml')
    now = ((3.0, 1.0, 0.5), _yaw_q(0.3))
    world = SimpleNamespace(body_state=lambda body_id: (now, ((0, 0, 0), (0, 0, 0)), []))
    scene = SimpleNamespace(spec=SimpleNamespace(obstacles=(spec,)), obstacles={'ball': 7},
                            world=world)
    (entity,) = fs.obstacle_entities(scene)
    assert entity.primitives[0].position_m == (3.0, 1.0, 0.5)
    assert entity.primitives[0].orientation == pytest.approx(_yaw_q(0.3))


def test_obstacle_of_unknown_shape_is_refused_naming_it():
    spec = SimpleNamespace(name='blob', shape='capsule')
    with pytest.raises(ValueError, match="obstacle 'blob': shape 'capsule' has no Foxglove"):
        fs.obstacle_entity(spec)


def test_registering_a_source_twice_is_refused_and_changes_nothing():
    before = dict(fs.ENTITY_SOURCES)
    with pytest.raises(ValueError, match="entity source 'vehicles' is already registered"):
        fs.register_entity_source('vehicles', lambda scene: [])
    assert fs.ENTITY_SOURCES == before


def test_a_registered_source_adds_its_entities_after_the_built_in_ones(monkeypatch):
    monkeypatch.setattr(fs, 'ENTITY_SOURCES', dict(fs.ENTITY_SOURCES))
    sign = fs.Entity('sign/1', fs.WORLD_FRAME, ())
    fs.register_entity_source('signs', lambda scene: [sign])
    scene = SimpleNamespace(vehicles={}, spec=SimpleNamespace(obstacles=()), obstacles={})
    assert fs.scene_entities(scene) == [sign]
    assert list(fs.ENTITY_SOURCES) == ['vehicles', 'obstacles', 'traffic', 'map', 'lanes',
                                       'signals', 'radar_targets', 'signs']
    assert fs.STATIC_SOURCES == {'map', 'lanes'}


def test_unknown_source_and_duplicate_ids_are_refused(monkeypatch):
    scene = SimpleNamespace(vehicles={}, spec=SimpleNamespace(obstacles=()), obstacles={})
    with pytest.raises(ValueError, match="unknown entity source 'cones'; registered: vehicles"):
        fs.scene_entities(scene, ['cones'])
    monkeypatch.setattr(fs, 'ENTITY_SOURCES', dict(fs.ENTITY_SOURCES))
    twice = fs.Entity('x', fs.WORLD_FRAME, ())
    fs.register_entity_source('twice', lambda scene: [twice, twice])
    with pytest.raises(ValueError, match="entity id 'x' given twice"):
        fs.scene_entities(scene)


def test_radar_targets_are_spheres_at_their_centres_with_a_line_from_the_radar():
    from vehicle_sim.core.sensors.labels import LABELS
    from vehicle_sim.core.sensors.params import sensor_from_dict
    from vehicle_sim.physics import World
    from vehicle_sim.physics.sensors import SensorSuite
    from vehicle_sim.physics.simulated_car import SimulatedCar
    with World() as world:
        car = SimulatedCar(world, load_car('Car'), (0.0, 0.0, 0.0), name='ego')
        world.add_obstacle(obstacle_from_dict(
            {'name': 'crate', 'shape': 'box', 'size': [1.0, 2.0, 1.5],
             'position': [20.0, 3.0, 0.75]}, 'w.yaml'))
        spec = sensor_from_dict({'type': 'radar', 'name': 'front', 'horizontal_fov': 1.0,
                                 'pose': {'x': 2.0, 'z': 0.75}}, 'w.yaml')
        suite = SensorSuite(world, car.body, [spec])
        scene = SimpleNamespace(vehicles={'ego': SimpleNamespace(sensors=suite)})
        assert fs.scene_entities(scene, ['radar_targets']) == []          # no reading yet
        reading = suite.sample('front')
        entity, = fs.scene_entities(scene, ['radar_targets'])
        origin = suite.sensors['front'].mount.world_frame()[0]
    assert entity.id == 'radar/ego/front' and entity.frame_id == fs.WORLD_FRAME
    sphere, = entity.primitives
    assert sphere.kind == 'sphere' and sphere.position_m == pytest.approx((20.0, 3.0, 0.75),
                                                                          abs=1e-6)
    label = LABELS[reading.targets[0].label]
    assert sphere.color_rgba[:3] == pytest.approx(tuple(c / 255.0 for c in label.colour))
    line, = entity.lines
    assert line.kind == 'line_list'
    assert line.points_m.ravel().tolist() == pytest.approx(
        [*origin.tolist(), 20.0, 3.0, 0.75], abs=1e-6)
