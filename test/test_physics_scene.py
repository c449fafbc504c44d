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
The scene builder and the vehicle body contract (issue 17, "Ready to grow", items 1 and 2).

Every world is built by ``physics/scene.py``: an ast scan over the package fails when a module
outside ``vehicle_sim/physics`` loads a body, adds an obstacle or makes a World itself.
CarBody and DiffRobotBody share one VehicleBody contract (pose, twist, reset, teleport,
outline, sensor mount frame), so callers read a body without knowing which it is.
"""

import ast
import math
from pathlib import Path

import pytest

from vehicle_sim.config import load_car, load_robot, world_from_data
from vehicle_sim.core.geometry.footprint import car_outline, robot_outline
from vehicle_sim.core.geometry.geodesy import GeodeticOrigin
from vehicle_sim.core.specs.errors import InvalidParameterError, InvalidPoseError
from vehicle_sim.core.world.params import obstacle_from_dict, RobotSpec, VehicleSpec, WorldSpec
from vehicle_sim.physics.car_body import CarBody
from vehicle_sim.physics.diff_robot import DiffRobotBody
from vehicle_sim.physics.scene import build_scene, mount_suite
from vehicle_sim.physics.sensors import SensorSuite
from vehicle_sim.physics.vehicle_body import VehicleBody

PACKAGE = Path(__file__).resolve().parent.parent / 'vehicle_sim'
# Calls that put something into a World, and the constructors of what holds bodies.
WORLD_BUILDING_METHODS = {'load_urdf', 'reload_urdf', 'add_obstacle'}
WORLD_BUILDING_CLASSES = {'World', 'SimulatedCar', 'CarBody', 'DiffRobotBody'}


def world_building_calls(source):
    """Return the (line, name) of each call in ``source`` that builds a world or its bodies."""
    found = []
    for node in ast.walk(ast.parse(source)):
        if not isinstance(node, ast.Call):
            continue
        func = node.func
        if isinstance(func, ast.Attribute) and func.attr in WORLD_BUILDING_METHODS:
            found.append((node.lineno, func.attr))
        elif isinstance(func, ast.Attribute) and func.attr in WORLD_BUILDING_CLASSES:
            found.append((node.lineno, func.attr))
        elif isinstance(func, ast.Name) and func.id in WORLD_BUILDING_CLASSES:
            found.append((node.lineno, func.id))
    return found


def _outside_physics():
    return sorted(path for path in PACKAGE.rglob('*.py')
                  if (PACKAGE / 'physics') not in path.parents)


@pytest.mark.parametrize('path', _outside_physics(), ids=lambda p: str(p.relative_to(PACKAGE)))
def test_every_world_is_built_through_the_scene_builder(path):
    calls = world_building_calls(path.read_text(encoding='utf-8'))
    assert not calls, (f'{path.relative_to(PACKAGE)} builds world content itself at '
                       f'{calls}: go through vehicle_sim.physics.scene.build_scene')


@pytest.mark.parametrize('source, expected', [
    ('world.add_obstacle(spec)', [(1, 'add_obstacle')]),
    ('self.world.load_urdf(urdf, pose)', [(1, 'load_urdf')]),
    ('w.reload_urdf(b, urdf, pose)', [(1, 'reload_urdf')]),
    ('car = SimulatedCar(world, params)', [(1, 'SimulatedCar')]),
    ('import x\nrobot = physics.DiffRobotBody(world, p)', [(2, 'DiffRobotBody')]),
    ('def f():\n    return World(time_step_s=0.01)', [(2, 'World')]),
    ('CarBody(world, params)', [(1, 'CarBody')]),
    ('world.add_body(director)', []),
    ('build_scene(spec, world)', []),
])
def test_the_scan_sees_every_world_building_call(source, expected):
    assert world_building_calls(source) == expected


def test_the_scan_covers_the_modules_that_built_worlds_before():
    scanned = {str(path.relative_to(PACKAGE)) for path in _outside_physics()}
    assert {'ros/automobile_node.py', 'ros/diff_robot_node.py', 'webots/driver.py',
            'scenarios/sim.py', 'scenarios/served_sim.py', 'tools/end_to_end.py'} <= scanned


# ---------------------------------------------------------------------------- the builder

WALL = obstacle_from_dict({'name': 'wall', 'shape': 'box', 'size': [1.0, 4.0, 1.0],
                           'position': [20.0, 0.0, 0.5]}, 'test')
ORIGIN = GeodeticOrigin(48.0, 11.0, 500.0)


def _car(name, y_m, model='Car'):
    return VehicleSpec(name, name.lower(), model, 1.0, y_m, 0.5, load_car(model).sensor_set)


class _Part:
    """A scene part that records when it ran and what it saw."""

    name = 'probe'

    def __init__(self, log):
        self.log = log

    def build(self, world, spec):
        self.log.append(('part', len(world.bodies), spec.source))
        return 'built'


class _Hook:
    pass


def test_build_scene_fills_a_new_world_in_the_documented_order():
    spec = WorldSpec(ORIGIN, (_car('A', 0.0), _car('B', 6.0)), (WALL,), 'test.yaml')
    robot = RobotSpec('R', 'caster_robot', 0.0, -5.0, 0.0)
    log, hook = [], _Hook()

    def mount(vehicle, scene):
        log.append(('mount', vehicle.name, len(scene.world.bodies)))
        return vehicle.name + ' sensors'

    scene = build_scene(spec, time_step_s=0.02, robots=(robot,), hooks=(hook,), mount=mount,
                        parts=(_Part(log),))
    try:
        world = scene.world
        assert world.time_step_s == 0.02
        assert scene.origin == ORIGIN and scene.spec is spec
        assert scene.obstacles == {'wall': world.obstacles['wall']}
        assert list(scene.vehicles) == ['A', 'B', 'R']
        # The hook first, then the cars, then the robot: the world's step order.
        a, b, r = (scene.vehicles[n] for n in 'ABR')
        assert world.bodies == (hook, a.car, b.car, r.body)
        assert a.body is a.car.body and r.car is None and r.vehicle is r.body
        assert scene.cars == {'A': a.car, 'B': b.car}
        x, y, _, _, _, qz, qw = a.body.pose()
        assert (x, y) == pytest.approx((1.0, 0.0), abs=1e-6)
        assert 2.0 * math.atan2(qz, qw) == pytest.approx(0.5, abs=1e-6)
        assert r.body.pose()[:2] == pytest.approx((0.0, -5.0), abs=1e-6)
        # Parts after every vehicle, sensors last.
        assert log == [('part', 4, 'test.yaml'), ('mount', 'A', 4), ('mount', 'B', 4),
                       ('mount', 'R', 4)]
        assert scene.parts == {'probe': 'built'}
        assert [v.sensors for v in scene.vehicles.values()] == \
            ['A sensors', 'B sensors', 'R sensors']
    finally:
        scene.world.close()


def test_build_scene_adds_to_a_given_world_and_takes_given_params():
    first = build_scene(WorldSpec(ORIGIN, (_car('A', 0.0),), ()))
    params = load_car('ToyotaPrius')
    try:
        second = build_scene(WorldSpec(ORIGIN, (_car('B', 8.0),), (WALL,)), first.world,
                             params={'B': params}, mount=mount_suite)
        assert second.world is first.world
        assert first.world.bodies == (first.vehicles['A'].car, second.vehicles['B'].car)
        assert second.vehicles['B'].car.params is params
        assert isinstance(second.vehicles['B'].sensors, SensorSuite)
        assert set(first.world.obstacles) == {'wall'}
    finally:
        first.world.close()


def test_build_scene_refuses_a_car_inside_an_obstacle_and_closes_its_world():
    inside = VehicleSpec('A', '', 'Car', 20.0, 0.0, 0.0, ())
    worlds = []

    class Spy:
        name = 'spy'

        def build(self, world, spec):     # never reached
            worlds.append(world)

    with pytest.raises(InvalidPoseError, match="vehicle 'A' starts inside obstacle 'wall'"):
        build_scene(WorldSpec(ORIGIN, (inside,), (WALL,)), parts=(Spy(),))
    assert worlds == []


# ---------------------------------------------------------------------------- the body contract

def _bodies():
    scene = build_scene(WorldSpec(ORIGIN, (_car('A', 0.0),), (WALL,)),
                        robots=(RobotSpec('R', 'caster_robot', 0.0, -5.0, 0.0),))
    return scene.world, scene.vehicles['A'].body, scene.vehicles['R'].body


def test_car_and_robot_bodies_share_the_vehicle_body_contract():
    world, car, robot = _bodies()
    try:
        assert isinstance(car, CarBody) and isinstance(robot, DiffRobotBody)
        for body, outline in ((car, car_outline(load_car('Car'))),
                              (robot, robot_outline(load_robot('caster_robot')))):
            assert isinstance(body, VehicleBody)
            assert body.outline == outline
            assert body.mount_frame == 'base_link'
            assert body.forward_speed_mps() == pytest.approx(0.0, abs=1e-9)
            assert body.body_twist()[0][0] == pytest.approx(body.forward_speed_mps(), abs=1e-12)
            # teleport: at rest at the pose; reset: back at the spawn pose.
            body.teleport((3.0, 30.0, 1.0))
            assert body.pose()[:2] == pytest.approx((3.0, 30.0), abs=1e-6)
            assert body.yaw_rad() == pytest.approx(1.0, abs=1e-6)
            body.reset()
            assert body.pose()[:2] == pytest.approx(body.spawn[:2], abs=1e-3)
            assert sum(body.velocity(), ()) == pytest.approx((0.0,) * 6, abs=1e-9)
            with pytest.raises(InvalidParameterError, match="unknown joint 'nope'"):
                body.joint_index('nope')
    finally:
        world.close()


def test_a_teleport_into_an_obstacle_is_refused_for_either_kind():
    world, car, robot = _bodies()
    try:
        for body in (car, robot):
            before = body.pose()
            with pytest.raises(InvalidPoseError, match='that place is inside wall'):
                body.teleport((20.0, 0.0, 0.0))
            assert body.pose() == pytest.approx(before, abs=1e-9)
    finally:
        world.close()


# ---------------------------------------------------------------------------- one world parser

def test_the_world_parser_reads_a_world_without_vehicles_when_asked():
    data = {'origin': {'latitude': 48.0}, 'obstacles': [
        {'name': 'wall', 'shape': 'box', 'size': [1.0, 4.0, 1.0], 'position': [20.0, 0.0, 0.5]}]}
    spec = world_from_data(data, 'inline', vehicles_required=False)
    assert spec.vehicles == () and [o.name for o in spec.obstacles] == ['wall']
    assert spec.origin.latitude_deg == 48.0 and spec.source == 'inline'
    with pytest.raises(InvalidParameterError, match='needs a non-empty list "vehicles"'):
        world_from_data(data, 'inline')
    with pytest.raises(InvalidParameterError, match=r"unknown key\(s\) \['terrain'\]"):
        world_from_data(dict(data, terrain='x'), 'inline', vehicles_required=False)


def test_build_scene_refuses_two_vehicles_of_one_name_before_building():
    first = VehicleSpec('A', '', 'Car', 0.0, 0.0, 0.0, ())
    second = VehicleSpec('A', '/other', 'Car', 0.0, 10.0, 0.0, ())
    with pytest.raises(InvalidParameterError, match=r"vehicle name\(s\) used twice: \['A'\]"):
        build_scene(WorldSpec(ORIGIN, (first, second), ()))


def test_a_driver_named_like_another_vehicle_of_its_world_file_is_refused(tmp_path):
    # Driver(name=...) renames the file's first vehicle: it must not take a second one's name.
    from vehicle_sim.webots import Driver
    path = tmp_path / 'two.yaml'
    path.write_text('vehicles:\n  - {name: ego}\n'
                    '  - {name: other, namespace: /o, pose: {y: 10}}\n', encoding='utf-8')
    with pytest.raises(InvalidParameterError, match=r"used twice: \['other'\]"):
        Driver(world_file=str(path), name='other')
