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
Lane maps built into worlds, in-process: scene builder, automobile node, Webots facade, runner.

The Lanelet2 map is test/lane_helpers.py's (lanelets 2001/2002 along +x for x 0 .. 50, split
by the dashed line 1002 at y = 3.5; a curbstone 1007 at y = 0 for x 100 .. 150); the roads are
written here. The node runs in this process on the embedded transport; its lane topics are read
by a subscription of its own node (matched, so the rows are built and published).
"""

import math
from pathlib import Path

from automobile_helpers import wait_for
from lane_helpers import write_world
import pytest
import yaml

from vehicle_sim.config import load_world
from vehicle_sim.core.map.kinds import map_from_dict, MAP_KINDS
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.physics.map_layer import MAP_BUILDERS
from vehicle_sim.physics.scene import build_scene
from vehicle_sim.ros import automobile_interfaces as itf
from vehicle_sim.ros.endpoints import EACH_PUBLISH
from vehicle_sim.ros.map_interfaces import MAP_TOPICS

pytest.importorskip('lanelet2', reason="lanelet2 is not installed (pip install "
                                       "'vehicle_sim[lanelet2]'; the test extra has it)")

REPO = Path(__file__).resolve().parent.parent
SHIPPED_LANELET2 = REPO / 'config' / 'worlds' / 'lanelet2.yaml'
ON_2001 = {'name': 'Car', 'namespace': 'ego', 'model': 'ToyotaPrius',
           'pose': {'lanelet': 2001, 's': 10.0}}


def _node(world):
    from vehicle_sim.ros.automobile_node import AutomobileNode
    return AutomobileNode(transport='dds', parameter_overrides={
        'world': str(world), 'synchronous': True})


@pytest.fixture
def app(tmp_path):
    made = _node(write_world(tmp_path, [ON_2001]))
    try:
        yield made
    finally:
        made.close()


def _listen(app, row, name):
    received = []
    app.node.create_subscription(row.ros_type, name, received.append, row.qos)
    return received


def _yaw(body):
    _, _, _, qx, qy, qz, qw = body.pose()
    return 2.0 * math.atan2(qz, qw)


# ----------------------------------------------------------------------- registries, scene

def test_the_three_map_registries_name_the_same_kinds():
    assert sorted(MAP_KINDS) == sorted(MAP_BUILDERS) == sorted(MAP_TOPICS) == [
        'lanelet2', 'occupancy_grid', 'opendrive', 'osm', 'sumo']


def test_lanelet2_and_roads_worlds_give_scene_lanes_and_a_world_without_gives_nothing(tmp_path):
    scene = build_scene(load_world(str(write_world(tmp_path, [ON_2001])), 'ToyotaPrius'))
    try:
        assert scene.parts['map'].lanes is scene.lanes
        assert 2001 in scene.lanes.lanes and scene.parts['map'].barrier_count == 1
        assert scene.parts['map'].visual_ids       # surface and markings drawn
    finally:
        scene.world.close()
    scene = build_scene(load_world(str(REPO / 'config/worlds/highway.yaml'), 'ToyotaPrius'))
    try:
        assert scene.parts['roads'].lanes is scene.lanes and len(scene.lanes.lanes) == 30
    finally:
        scene.world.close()
    scene = build_scene(load_world(str(REPO / 'config/worlds/obstacle_course.yaml'),
                                   'ToyotaPrius'))
    try:
        assert scene.lanes is None and scene.parts == {}
    finally:
        scene.world.close()


def test_the_shipped_lanelet2_world_puts_the_car_at_rest_on_lanelet_2001():
    scene = build_scene(load_world(str(SHIPPED_LANELET2), 'ToyotaPrius'))
    try:
        assert sorted(scene.lanes.lanes) == [2001, 2002, 2003, 2004, 2005, 2006]
        assert scene.lanes.lanes[2001].successors == (2003,)
        body = scene.vehicles['Car'].body
        for _ in range(200):                   # 2 s: settled on its wheels
            scene.world.step()
        x, y, z = body.pose()[:3]
        found = scene.lanes.locate(x, y, _yaw(body))
        assert found.lane_id == 2001
        assert found.s_m == pytest.approx(10.0, abs=0.01)
        assert found.offset_m == pytest.approx(0.0, abs=0.01)
        assert z == pytest.approx(0.0, abs=0.01)          # base_link on the ground, not falling
        assert math.hypot(*body.velocity()[0]) < 0.01
    finally:
        scene.world.close()


def test_a_lanelet2_world_without_origin_is_refused_naming_the_key(tmp_path):
    data = yaml.safe_load(SHIPPED_LANELET2.read_text(encoding='utf-8'))
    origin = data.pop('origin')
    data['map']['file'] = str(REPO / 'config' / 'maps' / 'lanelet2_map.osm')
    data['map'].pop('projector')                  # the default: local_cartesian
    world = tmp_path / 'no_origin.yaml'
    world.write_text(yaml.safe_dump(data), encoding='utf-8')
    with pytest.raises(InvalidParameterError) as refused:
        build_scene(load_world(str(world), 'ToyotaPrius'))
    assert str(refused.value).endswith(
        "set the world file's origin: near the map, e.g. origin: {latitude: "
        f"{origin['latitude']:g}, longitude: {origin['longitude']:g}}} (or, its nodes having "
        "local_x/local_y tags, the map's projector: autoware_local)")
    assert f'{world}: map.file: ' in str(refused.value)


def test_the_road_surface_has_no_collision_shape_and_rays_pass_it(tmp_path):
    import pybullet
    scene = build_scene(load_world(str(write_world(tmp_path, [ON_2001])), 'ToyotaPrius'))
    try:
        cid = scene.world.client_id
        car = scene.vehicles['Car'].body.body_id
        for body_id in scene.parts['map'].visual_ids:     # nothing to be near: no shape
            assert pybullet.getClosestPoints(body_id, car, 100.0, physicsClientId=cid) == ()
        hit = pybullet.rayTest((20.0, 1.75, 2.0), (20.0, 1.75, -1.0), physicsClientId=cid)[0]
        assert hit[0] not in scene.parts['map'].visual_ids
    finally:
        scene.world.close()


# ----------------------------------------------------------------------- lane state, invasion

def test_a_car_placed_at_s_10_reads_offset_0_and_the_lanelets_id(app):
    vehicle = app._vehicles[0]
    assert vehicle.spec.x_m == pytest.approx(10.0) and vehicle.spec.y_m == pytest.approx(1.75)
    app.step(1)
    message = vehicle.lane_outputs.messages(EACH_PUBLISH, vehicle)[itf.LANE_STATE]
    assert message.on_lane and message.lane_id == 2001
    assert message.offset == pytest.approx(0.0, abs=0.01)
    assert message.s == pytest.approx(10.0, abs=0.01)
    assert message.width == pytest.approx(3.5, abs=0.01)
    assert message.speed_limit == pytest.approx(13.9)
    assert message.header.frame_id == 'map'


def test_driving_across_the_dashed_line_gives_exactly_one_lane_invasion_naming_it(app):
    invasions = _listen(app, itf.LANE_INVASION, '/ego/lane_invasion')
    states = _listen(app, itf.LANE_STATE, '/ego/lane_state')
    vehicle = app._vehicles[0]
    body, logic = vehicle.body, vehicle.logic
    logic.set_cruising_speed_kmh(20.0)
    while body.pose()[0] < 45.0:      # a lane change into 2002 (centre y = 5.25), then along it
        left = 0.08 * (5.25 - body.pose()[1]) - 0.6 * _yaw(body)
        logic.set_steering_angle(-max(-0.1, min(0.1, left)))     # Webots: + = right
        app.step(1)
        app.node.spin_once(0.0)
    assert wait_for(lambda: invasions, spin=app.node)
    assert not wait_for(lambda: len(invasions) > 1, timeout_s=1.0, spin=app.node)
    event = invasions[0]
    assert (event.boundary_id, event.line_type) == (1002, 'dashed')
    assert event.position.y == pytest.approx(3.5, abs=1e-6) and event.header.frame_id == 'map'
    assert vehicle.lane_state.lane_id == 2002
    assert states and states[-1].lane_id == 2002


def test_a_teleport_across_lines_is_no_crossing_and_the_state_follows(app):
    from vehicle_sim.core.world.placement import ground_pose
    invasions = _listen(app, itf.LANE_INVASION, '/ego/lane_invasion')
    vehicle = app._vehicles[0]
    app.step(1)
    vehicle.teleport(ground_pose((30.0, 5.25, 0.0), (0.0, 0.0, 0.0, 1.0)))  # over line 1002
    app.step(2)
    assert vehicle.lane_state.lane_id == 2002
    assert vehicle.lane_state.s_m == pytest.approx(30.0, abs=0.01)
    vehicle.reset()                                   # back to 2001, again over the line
    app.step(2)
    assert vehicle.lane_state.lane_id == 2001
    assert not wait_for(lambda: invasions, timeout_s=1.0, spin=app.node)


# ----------------------------------------------------------------------- barriers

def _roads_world(tmp_path, vehicle_pose):
    data = {'vehicles': [{'name': 'Car', 'namespace': 'ego', 'model': 'ToyotaPrius',
                          'pose': vehicle_pose}],
            'roads': [{'lanes': 3, 'lane_width': 3.5, 'edge_line': 'wall',
                       'segments': [{'type': 'straight', 'length': 100.0}]}]}
    path = tmp_path / 'walled.yaml'
    path.write_text(yaml.safe_dump(data), encoding='utf-8')
    return path


def test_a_wall_of_the_road_stops_a_car_with_one_collision(tmp_path):
    # The right edge of three lanes of 3.5 m is a wall at y = -10.5; the car faces it.
    app = _node(_roads_world(tmp_path, {'x': 50.0, 'y': 0.0, 'yaw': -math.pi / 2}))
    try:
        collisions = _listen(app, itf.COLLISION, '/ego/collision')
        vehicle = app._vehicles[0]
        vehicle.logic.set_cruising_speed_kmh(10.0)
        for _ in range(600):
            app.step(1)
            app.node.spin_once(0.0)
        assert wait_for(lambda: collisions, spin=app.node)
        assert not wait_for(lambda: len(collisions) > 1, timeout_s=1.0, spin=app.node)
        assert collisions[0].other == 'lanes'
        assert abs(vehicle.body.forward_speed_mps()) < 0.1       # held at the wall
        assert vehicle.body.pose()[1] > -10.5
    finally:
        app.close()


def test_a_curbstone_is_static_geometry_named_lanes_that_a_teleport_cannot_enter(app):
    from vehicle_sim.core.specs.errors import InvalidPoseError
    from vehicle_sim.core.world.placement import ground_pose
    vehicle = app._vehicles[0]
    with pytest.raises(InvalidPoseError, match='lanes'):   # astride the curbstone at y = 0
        vehicle.teleport(ground_pose((120.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0)))
    assert vehicle.body.pose()[0] == pytest.approx(10.0, abs=0.05)   # it stayed


def test_driving_onto_a_curbstone_touches_it_and_crosses_its_line(tmp_path):
    # Lanelet 2005 (x 100 .. 150, centre y = 1.75) has the curbstone on its right: steer right.
    app = _node(write_world(tmp_path, [dict(ON_2001, pose={'lanelet': 2005, 's': 5.0})]))
    try:
        collisions = _listen(app, itf.COLLISION, '/ego/collision')
        invasions = _listen(app, itf.LANE_INVASION, '/ego/lane_invasion')
        logic = app._vehicles[0].logic
        logic.set_cruising_speed_kmh(10.0)
        logic.set_steering_angle(0.3)
        for _ in range(400):
            app.step(1)
            app.node.spin_once(0.0)
        assert wait_for(lambda: collisions and invasions, spin=app.node)
        assert collisions[0].other == 'lanes'
        assert [(e.boundary_id, e.line_type) for e in invasions] == [(1007, 'curbstone')]
    finally:
        app.close()


# ----------------------------------------------------------------------- placing by lane

@pytest.mark.parametrize('pose, match', [
    ({'lanelet': 2001, 's': 80.0}, r'vehicles\[0\]\.pose: .*80'),
    ({'lanelet': 2001, 's': 10.0, 'offset': 3.0}, r'vehicles\[0\]\.pose: .*offset'),
    ({'lanelet': 9999}, r'vehicles\[0\]\.pose: .*9999'),
    ({'lanelet': 2001, 'x': 1.0}, r"vehicles\[0\]\.pose: unknown field 'x'"),
])
def test_a_vehicle_placed_off_its_lane_is_refused_naming_file_and_field(tmp_path, pose, match):
    world = write_world(tmp_path, [dict(ON_2001, pose=pose)])
    with pytest.raises(InvalidParameterError, match=match) as error:
        _node(world)
    assert str(world) in str(error.value)


def test_a_lane_pose_without_a_lane_map_and_two_lane_maps_are_refused(tmp_path):
    path = tmp_path / 'plain.yaml'
    path.write_text(yaml.safe_dump({'vehicles': [dict(ON_2001)]}), encoding='utf-8')
    with pytest.raises(InvalidParameterError, match=r'plain.yaml: vehicles\[0\]\.pose: placed '
                                                    r'on lanelet 2001, but the world has no '
                                                    r'lane map'):
        build_scene(load_world(str(path), 'ToyotaPrius'))
    world = write_world(tmp_path, [ON_2001])
    data = yaml.safe_load(world.read_text())
    data['roads'] = [{'segments': [{'type': 'straight', 'length': 10.0}]}]
    world.write_text(yaml.safe_dump(data))
    with pytest.raises(InvalidParameterError, match='both roads: and a lanelet2 map'):
        load_world(str(world), 'ToyotaPrius')


def test_a_lanelet2_map_moved_by_world_in_map_is_refused():
    with pytest.raises(InvalidParameterError, match=r"w.yaml: map: field 'world_in_map' must "
                                                    r'be the identity'):
        map_from_dict({'type': 'lanelet2', 'file': 'a.osm', 'world_in_map': {'x': 1.0}},
                      'w.yaml: map', '')


# ----------------------------------------------------------------------- Webots facade, runner

def test_the_webots_driver_reads_its_lane_state(tmp_path):
    from vehicle_sim.webots import Driver
    driver = Driver(world_file=str(write_world(tmp_path, [ON_2001])))
    try:
        driver.step()
        state = driver.getLaneState()
        assert (state.on_lane, state.lane_id) == (True, 2001)
        assert state.offset_m == pytest.approx(0.0, abs=0.01)
        assert state.s_m == pytest.approx(10.0, abs=0.01)
    finally:
        driver.close()
    plain = Driver()
    try:
        assert plain.getLaneState() is None
    finally:
        plain.close()


def test_the_shipped_highway_scenario_with_stay_in_lane_passes_through_the_runner():
    from vehicle_sim.scenarios.runner import run_scenario
    result = run_scenario(str(REPO / 'scenarios' / 'highway_stay_in_lane.yaml'))
    verdicts = {c.kind: c.passed for c in result.criteria}
    assert verdicts == {'stay_in_lane': True, 'speed_limit': True, 'reach_lanelet': True}
    assert result.passed


def test_docs_maps_embeds_the_lane_tables_and_lanes_md_has_no_wiring_left():
    from vehicle_sim.core.map.kinds import LANELET2_MAP_SPECS
    from vehicle_sim.core.specs.param_spec import parameter_table_markdown
    from vehicle_sim.ros.endpoints import service_table_markdown, topic_table_markdown
    from vehicle_sim.ros.map_interfaces import MAP_LANES
    maps = (REPO / 'docs' / 'maps.md').read_text('utf-8')
    assert parameter_table_markdown(LANELET2_MAP_SPECS, 'key') in maps
    assert topic_table_markdown((MAP_LANES,) + itf.LANE_TOPICS) in maps
    assert service_table_markdown(itf.LANE_SERVICES) in maps
    assert 'Wiring still to do' not in (REPO / 'docs' / 'lanes.md').read_text('utf-8')


def test_a_hosted_controller_reads_the_runs_lane_state(tmp_path):
    from vehicle_sim.scenarios.runner import run_scenario
    world = write_world(tmp_path, [dict(ON_2001, namespace='')])
    record = tmp_path / 'lanes.txt'
    controller = tmp_path / 'lane_reader.py'
    controller.write_text(
        'from vehicle_sim.webots import Driver\n'
        'driver = Driver()\n'
        'driver.step()\n'
        'state = driver.getLaneState()\n'
        f'open({str(record)!r}, "w").write(f"{{state.lane_id}} {{state.s_m:.3f}}")\n',
        encoding='utf-8')
    scenario = tmp_path / 'lanes_scenario.yaml'
    scenario.write_text(yaml.safe_dump({
        'name': 'lane_reader', 'world': str(world), 'duration': 0.1,
        'driver': {'controller': str(controller)},
        'criteria': [{'kind': 'stay_in_lane', 'max_offset': 0.1}]}), encoding='utf-8')
    result = run_scenario(str(scenario))
    assert result.passed
    assert record.read_text() == '2001 10.000'


@pytest.mark.parametrize('doc', ['README.md', 'docs/maps.md', 'docs/lanes.md'])
def test_the_docs_lanelet2_examples_are_the_shipped_world(doc):
    shipped = SHIPPED_LANELET2.read_text(encoding='utf-8').splitlines()
    text = (REPO / doc).read_text(encoding='utf-8')
    examples = [line for line in text.splitlines() if line.startswith('map: {type: lanelet2')]
    assert examples and set(examples) == {line for line in shipped if line.startswith('map:')}
    origins = [line.split('#')[0].rstrip() for line in text.splitlines()
               if line.startswith('origin:')]
    assert origins and set(origins) == {line for line in shipped if line.startswith('origin:')}
    assert 'config/worlds/lanelet2.yaml' in text
