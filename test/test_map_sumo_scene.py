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
A SUMO network's world: what is drawn, and what reads its lanes through the lane-graph contract.

The road surface (lanes and junctions), markings, curbstones, sidewalks, crossings and lamps;
``/map/lanes``, the Foxglove scene, the lane state and lane invasions, the lane criteria and the
Gym lane observation, on netgenerate's signalised grid (test/sumo_helpers.py), with no code
that names the map's kind.
"""

import numpy as np
import pytest
import yaml

pytest.importorskip('sumolib', reason="sumolib is not installed (pip install "
                                      "'vehicle_sim[sumo]')")

from sumo_helpers import grid_net  # noqa: E402

from vehicle_sim.config import load_world  # noqa: E402
from vehicle_sim.core.map.lane_geometry import (  # noqa: E402
    area_meshes,
    barriers,
    crosswalk_mesh,
    surface_mesh,
)
from vehicle_sim.core.map.signal_programs import SUMO_STATES  # noqa: E402
from vehicle_sim.core.map.vehicle_lanes import VehicleLanes  # noqa: E402
from vehicle_sim.physics.scene import build_scene  # noqa: E402

# the eastbound right lane of the grid's first row (y = -1.6 .. -4.8 m below the row's axis)
EAST = 'A0B0_1'


@pytest.fixture(scope='module')
def net_path(tmp_path_factory):
    return grid_net(tmp_path_factory.mktemp('grid'))


def world_data(net_path, lane=EAST, s_m=10.0, offset_m=0.0):
    return {'vehicles': [{'name': 'Car', 'model': 'ToyotaPrius',
                          'pose': {'lane': lane, 's': s_m, 'offset': offset_m}}],
            'map': {'type': 'sumo', 'net': str(net_path)}}


def write_world(folder, net_path, **pose):
    world = folder / 'grid_world.yaml'
    world.write_text(yaml.safe_dump(world_data(net_path, **pose)), encoding='utf-8')
    return world


@pytest.fixture(scope='module')
def scene(net_path, tmp_path_factory):
    built = build_scene(load_world(str(write_world(tmp_path_factory.mktemp('w'), net_path)),
                                   'ToyotaPrius'))
    yield built
    built.world.close()


# ----------------------------------------------------------------------------------- drawing

def test_the_drawn_surface_covers_every_lane_centre_and_junction(scene):
    import pybullet
    graph = scene.lanes
    mesh = surface_mesh(graph)              # what the lane layer draws, made solid here
    cid = pybullet.connect(pybullet.DIRECT)
    try:
        shape = pybullet.createCollisionShape(
            pybullet.GEOM_MESH, vertices=mesh.vertices.tolist(),
            indices=mesh.triangles.reshape(-1).tolist(),
            flags=pybullet.GEOM_FORCE_CONCAVE_TRIMESH, physicsClientId=cid)
        body = pybullet.createMultiBody(0.0, shape, physicsClientId=cid)
        points = [lane.centre_pose(s)[:2] for lane in graph.lanes.values()
                  for s in np.linspace(0.0, lane.length_m, 5)]
        junctions = [area.polygon.mean(axis=0) for area in graph.rules.areas
                     if area.kind == 'junction']
        blocks = [(50.0, 50.0), (150.0, 50.0), (50.0, 150.0)]      # inside the blocks
        rays = points + junctions + blocks
        hits = pybullet.rayTestBatch([(x, y, 1.0) for x, y in rays],
                                     [(x, y, -1.0) for x, y in rays], physicsClientId=cid)
        hit = [h[0] == body for h in hits]
        assert len(points) > 800 and len(junctions) == 9
        assert all(hit[:len(points) + len(junctions)])
        assert not any(hit[-len(blocks):])
        assert all(h[3][2] == pytest.approx(0.002) for h in hits[:len(points)])
    finally:
        pybullet.disconnect(cid)


def test_the_world_draws_sidewalks_crossings_curbs_stop_lines_and_lamps(scene):
    graph, built = scene.lanes, scene.parts['map']
    areas = area_meshes(graph)
    assert set(areas) == {'walkway'}                   # junctions are road surface
    stripes = crosswalk_mesh(graph)
    assert len(stripes.triangles) >= 2 * 20            # 20 crossings, several stripes each
    curbs = [piece for piece in barriers(graph) if piece.line_type == 'curbstone']
    assert curbs and built.barrier_count == len(barriers(graph))
    assert len(built.visual_ids) >= 3                  # surface, walkways, paint
    lamps = scene.parts['signal_lamps']
    assert len(lamps.lamps) == sum(len(group.bulbs) for group in graph.rules.groups) > 0


def test_map_lanes_has_the_junctions_in_the_surface_and_the_crossings(scene):
    from vehicle_msgs_py import message_type
    from vehicle_sim.ros.lane_messages import lane_markers_builder
    graph = scene.lanes
    array = lane_markers_builder(message_type, 'map')(None, graph)
    by_ns = {}
    for marker in array.markers:
        by_ns.setdefault(marker.ns, []).append(marker)
    (surface,) = by_ns['road_surface']
    assert len(surface.points) == 3 * len(surface_mesh(graph).triangles)
    assert len(by_ns['crosswalks']) == sum(a.kind == 'crosswalk' for a in graph.rules.areas)
    assert len(by_ns['areas']) == sum(a.kind == 'walkway' for a in graph.rules.areas)
    assert len(by_ns['stop_lines']) == len(graph.rules.stop_lines)
    assert len(by_ns['centrelines']) == len(graph.lanes)


def test_the_foxglove_scene_draws_the_lanes_and_lamps(scene):
    from vehicle_sim.foxglove import scene as fs
    entities = {entity.id: entity for entity in fs.scene_entities(scene, ['lanes', 'signals'])}
    assert {'lanes/surface', 'lanes/markings', 'lanes/centerlines', 'lanes/crosswalks',
            'lanes/barriers'} <= set(entities)
    (surface,) = entities['lanes/surface'].triangles
    assert len(surface.indices) == len(surface_mesh(scene.lanes).triangles)
    heads = [key for key in entities if key.startswith('signals/')]
    assert len(heads) == sum(1 for group in scene.lanes.rules.groups if group.bulbs)


# ------------------------------------------------------------------------ the lane contract

def test_lane_state_reads_the_next_signal_and_its_programs_state(scene):
    graph = scene.lanes
    signals = scene.parts['signals'].controller
    lanes = VehicleLanes(graph, signals)
    east = graph.lane_named(EAST)
    x, y, yaw = graph.pose_at(east.id, 20.0)
    state, invasions = lanes.update(x, y, yaw, 0.0)
    assert (state.lane_id, state.s_m) == (east.id, pytest.approx(20.0)) and not invasions
    assert state.stop_line_ahead and state.stop_line_kind == 'traffic_light'
    straight = graph.lanes[east.successors[0]]
    assert state.stop_line_distance_m == pytest.approx(east.length_m - 20.0)
    group = graph.rules.group(state.traffic_light_group_id)
    assert straight.id in group.lanes
    program = next(p for p in graph.rules.programs if group.id in p.links)
    link = program.links.index(group.id)
    assert state.signal_state == SUMO_STATES[program.state_at(signals.time_s)[link]]


def test_crossing_the_dashed_line_between_an_edges_lanes_is_one_invasion(scene):
    graph = scene.lanes
    lanes = VehicleLanes(graph)
    right, left = graph.lane_named(EAST), graph.lane_named('A0B0_2')
    invasions = []
    for k, s in enumerate(np.linspace(10.0, 40.0, 61)):
        offset = min(max((s - 20.0) / 10.0, 0.0), 1.0) * 3.2     # over to the left lane
        x, y, yaw = graph.pose_at(right.id, s, offset) if offset <= 1.6 else graph.pose_at(
            left.id, s, offset - 3.2)
        state, found = lanes.update(x, y, yaw, 0.1 * k)
        invasions += found
    assert [(event.boundary_id, event.line_type) for event in invasions] == [
        (right.left.id, 'dashed')]
    assert state.lane_id == left.id


def test_the_lane_criteria_judge_a_car_crossing_a_junction(tmp_path, net_path):
    from sumolib.net import readNet

    from vehicle_sim.maps.sumo_net import lane_ids
    from vehicle_sim.scenarios.runner import run_scenario
    goal = lane_ids(readNet(net_path, withInternal=True))['B0C0_1']
    scenario = tmp_path / 'cross.yaml'
    scenario.write_text(yaml.safe_dump({
        'name': 'cross', 'world': str(write_world(tmp_path, net_path, s_m=40.0)),
        'duration': 12.0, 'driver': {'commands': [{'t': 0.0, 'cruising_speed': 30.0}]},
        'criteria': [{'kind': 'stay_in_lane', 'max_offset': 0.3},
                     {'kind': 'reach_lanelet', 'lanelet': goal, 'min_s': 5.0, 'within': 12.0},
                     {'kind': 'speed_limit'}]}), encoding='utf-8')
    result = run_scenario(str(scenario))
    verdicts = {c.kind: c.passed for c in result.criteria}
    assert verdicts == {'stay_in_lane': True, 'reach_lanelet': True, 'speed_limit': True}


def test_the_gym_lane_observation_reads_the_sumo_lane(make, net_path):
    pytest.importorskip('gymnasium', reason="needs the 'gym' extra (gymnasium)")
    import vehicle_sim.gym  # noqa: F401  (registers the ids)
    env = make(world=world_data(net_path, s_m=15.0, offset_m=0.4))
    obs, info = env.reset(seed=0)
    lane = env.unwrapped.sim.scene.lanes.lane_named(EAST)
    assert obs['lane_id'][0] == lane.id and info['on_lane']
    s, offset, heading, width, limit, on_lane = obs['lane'].tolist()
    assert s == pytest.approx(15.0, abs=0.02) and offset == pytest.approx(0.4, abs=0.02)
    assert width == pytest.approx(3.2) and limit == pytest.approx(13.89, abs=1e-3)


def test_the_builtin_traffic_stops_at_the_programs_red_and_goes_at_green(tmp_path, net_path):
    # a car comes to a junction on a straight link that is red for the first 30 s or more of
    # its program, green after
    from sumolib.net import readNet
    net = readNet(net_path, withInternal=True, withPrograms=True)

    def red_for(connection):
        phases = list(net.getTLS(connection.getTLSID()).getPrograms().values())[-1].getPhases()
        red = 0.0
        for phase in phases:
            if phase.state[connection.getTLLinkIndex()] != 'r':
                return red if phase.state[connection.getTLLinkIndex()] in 'Gg' else 0.0
            red += phase.duration
        return 0.0
    link = next(c for edge in net.getEdges(withInternal=False) for lane in edge.getLanes()
                for c in lane.getOutgoing()
                if c.getTLSID() and c.getDirection() == 's' and red_for(c) >= 30.0)
    red_s = red_for(link)
    approach = link.getFromLane()
    data = world_data(net_path)
    data['vehicles'][0]['pose'] = {'lane': 'B2C2_1', 's': 10.0}        # ours: out of the way
    data['traffic'] = {'vehicles': 0, 'placed': [{
        'lanelet': _id(net, approach.getID()), 's': approach.getLength() - 40.0, 'speed': 8.0,
        'route': [_id(net, link.getViaLaneID()), _id(net, link.getToLane().getID())]}]}
    world = tmp_path / 'traffic_world.yaml'
    world.write_text(yaml.safe_dump(data), encoding='utf-8')
    scene = build_scene(load_world(str(world), 'ToyotaPrius'))
    try:
        graph, traffic = scene.lanes, scene.parts['traffic']
        (line,) = graph.rules.stop_lines_on(_id(net, link.getViaLaneID()))
        stop_x, stop_y = line.points.mean(axis=0)
        steps = int(round(1.0 / scene.world.time_step_s))
        for second in range(int(red_s) + 15):
            for _ in range(steps):
                scene.world.step()
            (_, x, y, yaw, length, _, speed), = traffic.agents()
            ahead = (stop_x - x) * np.cos(yaw) + (stop_y - y) * np.sin(yaw)   # centre -> line
            if second + 1 < red_s:
                assert ahead > 0.5 * length, second          # its front before the line
            if 20 <= second + 1 < red_s:
                assert speed < 0.1, second                   # standing at red
        assert ahead < -10.0                                 # through on green
    finally:
        scene.world.close()


def _id(net, name):
    from vehicle_sim.maps.sumo_net import lane_ids
    return lane_ids(net)[name]


def test_the_node_publishes_map_lanes_lane_state_and_the_programs_signals(tmp_path, net_path):
    from automobile_helpers import wait_for

    from vehicle_sim.ros import automobile_interfaces as itf
    from vehicle_sim.ros.automobile_node import AutomobileNode
    from vehicle_sim.ros.map_interfaces import MAP_LANES
    data = world_data(net_path, s_m=20.0)
    data['vehicles'][0]['namespace'] = 'ego'
    world = tmp_path / 'node_world.yaml'
    world.write_text(yaml.safe_dump(data), encoding='utf-8')
    app = AutomobileNode(transport='dds', parameter_overrides={'world': str(world),
                                                               'synchronous': True})
    try:
        lanes, states = [], []
        app.node.create_subscription(MAP_LANES.ros_type, '/map/lanes', lanes.append,
                                     MAP_LANES.qos)
        app.node.create_subscription(itf.LANE_STATE.ros_type, '/ego/lane_state', states.append,
                                     itf.LANE_STATE.qos)
        app.step(10)
        assert wait_for(lambda: lanes and states, spin=app.node)
        (array,) = lanes
        assert {marker.header.frame_id for marker in array.markers} == {'map'}
        assert {'road_surface', 'crosswalks', 'areas', 'stop_lines'} <= {
            marker.ns for marker in array.markers}
        graph = app.scene.lanes
        state = states[-1]
        assert state.header.frame_id == 'map' and state.lane_id == graph.lane_named(EAST).id
        controller = app.scene.parts['signals'].controller
        assert state.traffic_light_group_id and state.signal_state == controller.state(
            state.traffic_light_group_id)
    finally:
        app.close()


def test_the_lamps_clusters_are_the_first_near_cluster_of_each_lamp(scene):
    # the grid's clustering against its definition, on the network's lamps and on a dense
    # random scatter
    import math
    import random
    from types import SimpleNamespace

    from vehicle_sim.core.map.signal_lamps import CLUSTER_M, lamp_clusters, lamps

    def reference(found):
        clusters = []
        for lamp in found:
            for cluster in clusters:
                if any(math.hypot(lamp.bulb.x_m - o.bulb.x_m, lamp.bulb.y_m - o.bulb.y_m)
                       <= CLUSTER_M for o in cluster):
                    cluster.append(lamp)
                    break
            else:
                clusters.append([lamp])
        return clusters
    generator = random.Random(7)
    scatter = [SimpleNamespace(bulb=SimpleNamespace(x_m=generator.uniform(-5.0, 5.0),
                                                    y_m=generator.uniform(-5.0, 5.0)))
               for _ in range(300)]
    for found in (lamps(scene.lanes), scatter):
        assert lamp_clusters(found) == reference(found)
