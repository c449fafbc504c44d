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
SUMO as the traffic engine (``traffic: {engine: sumo}``): its vehicles and persons as bodies.

On a netgenerate grid (test/sumo_helpers.py): the bodies are where SUMO has its vehicles and
persons (footprint centres behind SUMO's front bumpers; between SUMO's steps gone on straight),
sized from their SUMO types and classed from their vehicle classes; our car stopped in a lane
queues SUMO's vehicles behind it (and without it they drive on); a seed gives the same
trajectories twice and another seed others; reset starts SUMO again; two worlds in one process
run (the second over TraCI); closing the world closes SUMO.
"""

from dataclasses import replace
import math
import re

import pybullet
import pytest

pytest.importorskip('traci', reason="needs the 'sumo' extra")

from vehicle_sim.physics import sumo_session  # noqa: E402

if sumo_session.load_libsumo() is None:      # (imported quietly: its pyarrow notice)
    pytest.skip("needs the 'sumo' extra (libsumo)", allow_module_level=True)

from sumo_helpers import one_lane_grid_net, write_routes  # noqa: E402

from vehicle_sim.config import world_from_data  # noqa: E402
from vehicle_sim.core.specs.errors import InvalidParameterError  # noqa: E402
from vehicle_sim.physics import sumo_pool  # noqa: E402
from vehicle_sim.physics.scene import build_scene  # noqa: E402
from vehicle_sim.physics.sensors.rays import cast_rays  # noqa: E402
from vehicle_sim.physics.sumo_pool import (  # noqa: E402
    extend_trail,
    follow_trail,
    JUMP_M,
    TRAIL_POINTS,
    trail_pose,
)
from vehicle_sim.physics.traffic_boxes import NEAR_M  # noqa: E402

LANE_X = 1.6          # edge A0A1's lane (northbound) runs along x = 1.6, y from 5.2 to 92.8
STEPS_PER_S = 100     # world steps a second (the default step, 0.01 s)


@pytest.fixture(scope='module')
def net(tmp_path_factory):
    return one_lane_grid_net(tmp_path_factory.mktemp('sumo_net'))


@pytest.fixture(autouse=True)
def _cache(tmp_path_factory, monkeypatch):
    # the demand's trips are made once for the module, not in the user's cache
    monkeypatch.setenv('XDG_CACHE_HOME', str(tmp_path_factory.getbasetemp() / 'cache'))


def _world(net, traffic, ego=(LANE_X, 40.0, math.pi / 2), folder=None):
    x, y, yaw = ego
    data = {'vehicles': [{'name': 'ego', 'model': 'Car',
                          'pose': {'x': x, 'y': y, 'yaw': yaw}}],
            'map': {'type': 'sumo', 'net': net}, 'traffic': {'engine': 'sumo', **traffic}}
    return build_scene(world_from_data(data, 'w.yaml', base_dir=str(folder or '.')))


def _run(scene, seconds):
    for _ in range(int(round(seconds * STEPS_PER_S))):
        scene.world.step()


DEMAND = {'vehicles_per_hour': 2400, 'pedestrians_per_hour': 1200, 'seed': 5,
          'classes': {'passenger': 3, 'bus': 1, 'bicycle': 1, 'truck': 1}}


def test_a_turning_vehicles_box_is_centred_on_the_path_its_front_took():
    # a 5 m vehicle's front on a right turn of radius 6 m (a quarter circle round (0, 0), from
    # heading +y to heading +x), 0.1 m a step: at the turn's end its heading is along the chord
    # from its rear (a length of arc behind) to its front, its centre halfway between the
    # chord's middle and the circle half a length of arc behind the front (the axis nearest the
    # arc: half the sagitta off it either way); behind the front along SUMO's heading its rear
    # would swing out by about length^2 / 8R off the path
    radius, length, trail = 6.0, 5.0, []
    path = [(-radius, -10.0 + 0.1 * k, math.pi / 2) for k in range(101)]  # up to (-R, 0)
    path += [(-radius * math.cos(a), radius * math.sin(a), math.pi / 2 - a)
             for a in (0.5 * math.pi * k / 94 for k in range(1, 95))]
    for x, y, heading in path:
        cx, cy, yaw = follow_trail(trail, x, y, heading, length, 0.1 + JUMP_M)
    fx, fy, _ = path[-1]
    arc = 0.5 * length / radius                     # the middle's angle back along the arc
    rear = (-radius * math.sin(2 * arc), radius * math.cos(2 * arc))
    middle = (-radius * math.sin(arc), radius * math.cos(arc))
    assert (cx, cy) == pytest.approx((0.5 * middle[0] + 0.25 * (fx + rear[0]),
                                      0.5 * middle[1] + 0.25 * (fy + rear[1])), abs=0.01)
    sagitta = radius * (1.0 - math.cos(arc))
    assert math.hypot(cx, cy) == pytest.approx(radius - 0.5 * sagitta, abs=0.01)
    assert yaw == pytest.approx(math.atan2(fy - rear[1], fx - rear[0]), abs=0.01)
    assert len(trail) < 60                          # the points behind its rear dropped
    # a jump (a teleport) starts the trail again: the box straight behind the new front
    cx, cy, yaw = follow_trail(trail, 50.0, 50.0, 0.0, length, 0.1 + JUMP_M)
    assert (cx, cy, yaw) == pytest.approx((47.5, 50.0, 0.0))
    assert trail == [(50.0, 50.0, 0.0)]               # (x, y, arc length)


def test_a_box_worked_out_when_read_is_the_one_worked_out_at_every_step():
    # the engine extends a vehicle's trail at each SUMO step and works its box out when
    # something reads it: the same box as follow_trail's at every step, a long trail cut short
    # on the way (a car creeping 2 cm a step round a bend, 600 steps; a jump starts it again)
    path = [(20.0 * math.cos(0.002 * k), 20.0 * math.sin(0.002 * k), math.pi / 2 + 0.002 * k)
            for k in range(600)] + [(90.0, 0.0, 0.0), (90.5, 0.0, 0.0)]
    length, eager, lazy = 4.5, [], []
    for k, (x, y, heading) in enumerate(path):
        box = follow_trail(eager, x, y, heading, length, 0.1 + JUMP_M)
        extend_trail(lazy, x, y, 0.1 + JUMP_M, length)
        assert len(lazy) <= TRAIL_POINTS + 1
        if k in (0, 450) or k >= 599:
            assert trail_pose(lazy, x, y, heading, length) == box
    assert box == pytest.approx((88.25, 0.0, 0.0))


def _boxes_worked_out(monkeypatch):
    calls = []
    original = sumo_pool.trail_pose
    monkeypatch.setattr(sumo_pool, 'trail_pose', lambda *a: calls.append(a) or original(*a))
    return calls


def test_boxes_are_worked_out_only_for_what_reads_them(net, monkeypatch):
    # nothing reads the world (our car 300 m off): SUMO's steps work out no vehicle's box;
    # reading the agents works each out once; all of them the boxes of a world where every
    # body is put where it is at every step
    calls = _boxes_worked_out(monkeypatch)
    found = []
    for every_step in (False, True):
        scene = _world(net, {'demand': DEMAND, 'seed': 3}, ego=(-300.0, -300.0, 0.0))
        try:
            for _ in range(10 * STEPS_PER_S):
                scene.world.step()
                if every_step:
                    scene.world.sync_bodies()
            if not every_step:
                assert calls == []
            found.append(sorted(scene.parts['traffic'].agents()))
        finally:
            scene.world.close()
    moving = sum(speed > 0.5 for *_, speed in found[0])
    assert moving > 5 and found[0] == found[1]


def test_the_bodies_are_where_sumo_has_its_vehicles_and_persons(net):
    scene = _world(net, {'demand': DEMAND, 'seed': 2}, ego=(-30.0, -30.0, 0.0))
    try:
        bodies = scene.parts['traffic']
        api = bodies.session.api
        _run(scene, 30.0)
        agents = bodies.agents()
        classes = {o.name: o.object_class for o in bodies.objects()}
        assert {'car', 'bus', 'bicycle', 'truck', 'pedestrian'} <= set(classes.values())
        assert len(agents) > 10
        checked = 0
        for name, x, y, yaw, length, width, speed in agents:
            sumo_id = bodies.sumo_id(name)
            person = classes[name] == 'pedestrian'
            domain = api.person if person else api.vehicle
            fx, fy = domain.getPosition(sumo_id)
            type_id = domain.getTypeID(sumo_id)
            assert (length, width) == (api.vehicletype.getLength(type_id),
                                       api.vehicletype.getWidth(type_id))
            # the footprint centre half a length behind SUMO's front bumper: a person's along
            # its heading; a vehicle's on the path its front took (follow_trail), which on a
            # straight lane is the same
            straight = person or (not domain.getLaneID(sumo_id).startswith(':')
                                  and domain.getLanePosition(sumo_id) > 2.0 * length)
            if straight:
                assert x + 0.5 * length * math.cos(yaw) == pytest.approx(fx, abs=1e-6)
                assert y + 0.5 * length * math.sin(yaw) == pytest.approx(fy, abs=1e-6)
                turn = (math.degrees(yaw) - (90.0 - domain.getAngle(sumo_id))) % 360.0
                assert min(turn, 360.0 - turn) == pytest.approx(0.0, abs=1e-6)
                checked += not person
            else:                         # on a curve the chord to the front is shorter
                assert 0.4 * length <= math.hypot(fx - x, fy - y) <= 0.5 * length + 1e-6
            assert speed == pytest.approx(domain.getSpeed(sumo_id), abs=1e-9)
        assert checked > 3
        # SUMO stepped at 29.9 s (every 0.1 s, before the world's step): since then each body
        # went on straight at its speed
        for steps, since in ((0, 0.1), (4, 0.04)):
            for _ in range(steps):
                scene.world.step()
            scene.world.sync_bodies()
            assert bodies.since_update_s == pytest.approx(since)
            for name, x, y, yaw, _, _, speed in bodies.agents():
                position, _ = pybullet.getBasePositionAndOrientation(
                    bodies.body_of(name), physicsClientId=scene.world.client_id)
                assert position[:2] == pytest.approx((x + speed * since * math.cos(yaw),
                                                      y + speed * since * math.sin(yaw)),
                                                     abs=1e-6)
        assert {name for name, *_ in agents} <= bodies.moving_names()
        # the markers' colour of each object (bodies.colours by its index) is its body's
        colours = {name: colour for name, _, _, colour, _ in bodies.boxes()}
        assert all(bodies.colours[o.index % len(bodies.colours)] == colours[o.name]
                   for o in bodies.objects())
    finally:
        scene.world.close()


def test_rays_put_the_bodies_where_they_go_and_leave_the_others_standing(net, tmp_path):
    # a ray batch puts where they are only the bodies within its reach (a lidar's rays in a
    # city pass near a tenth of them), and those standing there since an earlier update; any
    # other reading puts every one where it is. Three cars on three parallel streets 100 m apart
    routes = write_routes(tmp_path, [(name, 0.0, f'{column}0{column}1 {column}1{column}2')
                                     for name, column in (('a', 'A'), ('b', 'B'), ('c', 'C'))])
    scene = _world(net, {'routes': routes}, ego=(-300.0, -300.0, 0.0), folder=tmp_path)
    try:
        bodies, world = scene.parts['traffic'], scene.world
        cid = world.client_id

        def standing(sumo_id):
            return pybullet.getBasePositionAndOrientation(
                bodies.body_of(bodies.name_of(sumo_id)), physicsClientId=cid)[0]

        def now(sumo_id):                  # where SUMO has it, gone on straight since
            name = bodies.name_of(sumo_id)
            since = bodies.since_update_s
            _, x, y, yaw, _, _, speed = next(a for a in bodies.agents() if a[0] == name)
            return x + speed * since * math.cos(yaw), y + speed * since * math.sin(yaw)

        def down(x, y):                    # the height a ray straight down hits
            return 20.0 - 21.0 * cast_rays(world, (x, y, 20.0), [(x, y, -1.0)], -1)[0]
        _run(scene, 4.0)
        world.sync_bodies()
        stood = {sumo_id: standing(sumo_id) for sumo_id in 'abc'}
        _run(scene, 1.0)                   # nothing read the world: they stand where they were
        assert {sumo_id: standing(sumo_id) for sumo_id in 'abc'} == stood
        assert math.dist(now('a'), stood['a'][:2]) > 5.0
        assert down(*stood['a'][:2]) < 0.5                 # where a stood: the road
        assert standing('a')[:2] == pytest.approx(now('a'), abs=1e-6)
        bx, by = now('b')
        assert down(bx, by) > 1.0                           # where b is now: its roof
        assert standing('c') == stood['c']                  # c, 100 m off: where it stood
        world.sync_bodies()
        assert standing('c')[:2] == pytest.approx(now('c'), abs=1e-6)
    finally:
        scene.world.close()


def test_bodies_near_ours_out_of_its_reach_stand_until_read_and_reads_see_them_moved(
        net, tmp_path):
    # our car stands off the road 25 m east of street A: SUMO's car a drives north past it,
    # within NEAR_M (its contacts with ours read after each step) but never within reach of
    # touching it. Its body stands where it was put (no reset at each step) while nothing
    # reads the world; a ray read right after a step, or any reading, finds it where SUMO has
    # it now (gone on straight since SUMO's last step)
    routes = write_routes(tmp_path, [('a', 0.0, 'A0A1 A1A2')])
    ego = (LANE_X + 25.0, 40.0, math.pi / 2)
    scene = _world(net, {'routes': routes}, ego=ego, folder=tmp_path)
    try:
        bodies, world = scene.parts['traffic'], scene.world
        cid = world.client_id

        def standing():
            return pybullet.getBasePositionAndOrientation(
                bodies.body_of(bodies.name_of('a')), physicsClientId=cid)[0]

        def now():
            since = bodies.since_update_s
            _, x, y, yaw, _, _, speed = bodies.agents()[0]
            return x + speed * since * math.cos(yaw), y + speed * since * math.sin(yaw)

        def down(x, y):
            return 20.0 - 21.0 * cast_rays(world, (x, y, 20.0), [(x, y, -1.0)], -1)[0]
        while not bodies.agents() or now()[1] < 20.0:
            world.step()
        checked = 0
        for _ in range(40):                # 0.4 s: 5 m or more at SUMO's speed there
            world.sync_bodies()
            stood = standing()
            assert stood[:2] == pytest.approx(now(), abs=1e-6)
            assert 20.0 < math.dist(now(), ego[:2]) < NEAR_M
            world.step()
            assert bodies.name_of('a') in {slot.name for slot in bodies._near_all}
            if bodies.since_update_s > 0.011:   # not SUMO's step: nothing put it anew
                assert standing() == stood
                assert math.dist(now(), stood[:2]) > 0.05
                checked += 1
        assert checked > 30
        world.step()
        while bodies.since_update_s > 0.011:  # a ray read right after the step of SUMO's
            world.step()
        x, y = now()
        assert math.dist((x, y), standing()[:2]) > 0.3
        assert down(x, y) > 1.0             # its roof where SUMO has it now
        assert standing()[:2] == pytest.approx((x, y), abs=1e-6)
    finally:
        scene.world.close()


def _routed(net, route, folder):
    data = {'vehicles': [{'name': 'ego', 'model': 'Car', 'route': route,
                          'pose': {'x': LANE_X, 'y': 40.0, 'yaw': math.pi / 2}}],
            'map': {'type': 'sumo', 'net': net},
            'traffic': {'engine': 'sumo', 'routes': write_routes(folder, [])}}
    return build_scene(world_from_data(data, 'w.yaml', base_dir=str(folder)))


def test_our_vehicle_has_its_route_in_sumo(net, tmp_path):
    # ours on A0A1 (northbound) with route [A1B1_1] (east at A1: a right turn): SUMO's route
    # for it is A0A1 A1B1 and its next link turns right onto A1B1; without a route SUMO's
    # route ends with the edge it is on (no link ahead: SUMO does not know where it turns)
    for route, edges, links in ((['A1B1_1'], ('A0A1', 'A1B1'), [('A1B1_1', 'r')]),
                                ([], ('A0A1',), [])):
        scene = _routed(net, route, tmp_path)
        try:
            _run(scene, 0.2)
            api = scene.parts['traffic'].session.api
            assert api.vehicle.getRoute('vehicle_sim.ego') == edges
            assert [(link[0], link[6]) for link in api.vehicle.getNextLinks(
                'vehicle_sim.ego')] == links
        finally:
            scene.world.close()


def test_a_route_sumo_cannot_take_is_refused_naming_the_lane(net, tmp_path):
    for route, message in (
            (['A1B1_1', 'NOPE_0'], "vehicles[0]: field 'route': lane 'NOPE_0' is not in the map"),
            ([':A1_0_0'], "field 'route': lane ':A1_0_0' is inside a junction")):
        with pytest.raises(InvalidParameterError, match=re.escape(message)):
            _routed(net, route, tmp_path)
    data = {'vehicles': [{'name': 'ego', 'route': ['A1B1_1']}],
            'map': {'type': 'sumo', 'net': net}}
    with pytest.raises(InvalidParameterError,
                       match=re.escape("vehicles[0]: field 'route' = ['A1B1_1']: a route is "
                                       'given to the sumo traffic engine')):
        world_from_data(data, 'w.yaml', base_dir=str(tmp_path))


def _queue(net, folder, ego):
    routes = write_routes(folder, [(f'q{i}', 2.0 * i, 'A0A1 A1A2') for i in range(3)])
    scene = _world(net, {'routes': routes}, ego=ego, folder=folder)
    try:
        bodies = scene.parts['traffic']
        _run(scene, 40.0)
        api = bodies.session.api
        present = api.vehicle.getIDList()
        return ({vid: (api.vehicle.getRoadID(vid), api.vehicle.getLanePosition(vid),
                       api.vehicle.getSpeed(vid)) if vid in present else None
                 for vid in ('q0', 'q1', 'q2')},
                {bodies.sumo_id(name): (x, y, speed) for name, x, y, _, _, _, speed
                 in bodies.agents()},
                api.vehicle.getLanePosition('vehicle_sim.ego')
                if 'vehicle_sim.ego' in present else None)
    finally:
        scene.world.close()


def test_our_car_stopped_in_a_lane_queues_sumo_traffic_behind_it(net, tmp_path):
    # the car is held (no command): it stands at y = 50 in SUMO's lane, facing north
    sumo, bodies, ego_front = _queue(net, tmp_path, (LANE_X, 50.0, math.pi / 2))
    ego_s = ego_front - 5.2        # its front at lane position ego_front (from y 5.2)
    for vid in ('q0', 'q1', 'q2'):
        edge, s, speed = sumo[vid]
        assert edge == 'A0A1' and s < ego_front - 3.0 and speed < 0.1, (vid, sumo[vid])
        assert bodies[vid][1] < 50.0 - 2.0 and bodies[vid][2] < 0.1
    assert sumo['q0'][1] > sumo['q1'][1] > sumo['q2'][1] > 0.0
    assert ego_s > 30.0
    # with the car off their road they drive on: in 40 s past where it stood (or arrived)
    free, _, absent = _queue(net, tmp_path, (-30.0, -30.0, 0.0))
    assert absent is None           # 30 m off every road: not in SUMO
    assert all(free[vid] is None or free[vid][0] != 'A0A1' for vid in free), free


def _trajectory(net, seed, seconds=20.0):
    scene = _world(net, {'demand': DEMAND, 'seed': seed}, ego=(-30.0, -30.0, 0.0))
    try:
        found = []
        for _ in range(int(seconds)):
            _run(scene, 1.0)
            found.append(sorted(scene.parts['traffic'].agents()))
        return found
    finally:
        scene.world.close()


def test_a_seed_gives_the_same_trajectories_twice_and_another_seed_others(net):
    first = _trajectory(net, 4)
    assert first[-1] and first == _trajectory(net, 4)
    assert _trajectory(net, 9) != first


def test_reset_starts_sumo_again_with_its_seed(net):
    scene = _world(net, {'demand': DEMAND, 'seed': 4}, ego=(-30.0, -30.0, 0.0))
    try:
        bodies = scene.parts['traffic']
        _run(scene, 5.0)
        assert bodies.agents()
        assert 'SUMO started again' in bodies.reset(4)
        assert bodies.agents() == [] and bodies.session.api.simulation.getTime() == 0.0
        found = []
        for _ in range(20):
            _run(scene, 1.0)
            found.append(sorted(bodies.agents()))
    finally:
        scene.world.close()
    assert found == _trajectory(net, 4)


def test_two_worlds_in_one_process_the_second_over_traci(net):
    first = _world(net, {'demand': DEMAND}, ego=(-30.0, -30.0, 0.0))
    try:
        second = _world(net, {'demand': DEMAND}, ego=(-30.0, -30.0, 0.0))
        try:
            a, b = first.parts['traffic'], second.parts['traffic']
            assert (a.session.transport, b.session.transport) == ('libsumo', 'traci')
            for _ in range(1000):
                first.world.step()
                second.world.step()
            assert a.agents() and sorted(a.agents()) == sorted(b.agents())
            process = b.session.api._process
        finally:
            second.world.close()
        assert process.wait(timeout=60) is not None      # closing the world ended SUMO
        assert b.session.closed
    finally:
        first.world.close()
    assert a.session.closed and sumo_session._libsumo_user[0] is None


def test_libsumo_is_read_by_its_getters_and_traci_by_subscriptions(net):
    # SUMO works out every subscribed value at each of its steps (with 250 vehicles and persons
    # that doubled its step): over libsumo the engine calls the getters and subscribes to no
    # vehicle or person; over TraCI, where each getter is a round trip, one subscription each.
    # The same bodies and objects (their predicted paths from each vehicle's lane) either way
    first = _world(net, {'demand': DEMAND}, ego=(-30.0, -30.0, 0.0))
    try:
        second = _world(net, {'demand': DEMAND}, ego=(-30.0, -30.0, 0.0))
        try:
            a, b = first.parts['traffic'], second.parts['traffic']
            for _ in range(1500):
                first.world.step()
                second.world.step()
            assert (a.session.transport, b.session.transport) == ('libsumo', 'traci')
            for domain in ('vehicle', 'person'):
                assert getattr(a.session.api, domain).getAllSubscriptionResults() == {}
                assert len(getattr(b.session.api, domain).getAllSubscriptionResults()) > 3
            assert len(a.agents()) > 10 and sorted(a.agents()) == sorted(b.agents())
            objects = [sorted((o.name, o.path) for o in bodies.objects()) for bodies in (a, b)]
            assert objects[0] == objects[1]
            assert sum(len(set(path)) > 1 for _, path in objects[0]) > 5
        finally:
            second.world.close()
    finally:
        first.world.close()


def test_our_car_is_in_sumo_at_its_pose_and_speed_while_on_a_lane(net, tmp_path):
    routes = write_routes(tmp_path, [('a', 0, 'B0B1')])
    scene = _world(net, {'routes': routes}, ego=(LANE_X, 12.0, math.pi / 2), folder=tmp_path)
    try:
        bodies = scene.parts['traffic']
        api = bodies.session.api
        logic = scene.vehicles['ego'].car.logic
        logic.set_gear(1)
        logic.set_throttle(0.5)
        body = scene.vehicles['ego'].body
        _run(scene, 0.11)              # SUMO's first step at 0.1 s
        for _ in range(40):
            assert 'vehicle_sim.ego' in api.vehicle.getIDList()
            _run(scene, 0.1)
        speed = body.forward_speed_mps()
        assert speed > 3.0
        # SUMO's speed of the car: its move over SUMO's last step (the physics' speed then)
        assert api.vehicle.getSpeed('vehicle_sim.ego') == pytest.approx(speed, rel=0.1)
        assert api.vehicle.getRoadID('vehicle_sim.ego') == 'A0A1'
        fx, fy = api.vehicle.getPosition('vehicle_sim.ego')
        _, y, *_ = body.pose()          # the rear axle; SUMO has the front bumper
        assert fx == pytest.approx(LANE_X, abs=0.2) and y < fy < y + 5.0
        # 30 m off every road it is out of SUMO
        scene.vehicles['ego'].body.rebuild((-30.0, -30.0, 0.0))
        _run(scene, 0.2)
        assert 'vehicle_sim.ego' not in api.vehicle.getIDList()
    finally:
        scene.world.close()


def _crossing(net, folder, ego, seconds):
    # a person walking north on A0A1's sidewalk, across the crossing :A1_c2 (over A0A1 and
    # A1A0, y 92.8 to 96.8) and south on A1A0's: where is it after ``seconds``?
    routes = folder / 'walk.rou.xml'
    routes.write_text('<routes>\n  <person id="p" depart="0" departPos="80">'
                      '<walk edges="A0A1 A1A0"/></person>\n</routes>\n')
    scene = _world(net, {'routes': str(routes)}, ego=ego, folder=folder)
    try:
        bodies = scene.parts['traffic']
        _run(scene, seconds)
        api = bodies.session.api
        (obj,) = bodies.objects()
        assert (obj.object_class, obj.length_m, obj.width_m, obj.height_m) == (
            'pedestrian', 0.215, 0.478, 1.719)           # SUMO's DEFAULT_PEDTYPE
        assert bodies.sumo_id(obj.name) == 'p'
        return api.person.getRoadID('p'), obj.x_m
    finally:
        scene.world.close()


def test_a_pedestrian_waits_for_our_car_standing_on_the_crossing(net, tmp_path):
    # our car's front on the crossing (it stopped there, 1.8 m wide): the person walking west
    # over the crossing stops east of it and stays there
    edge, x = _crossing(net, tmp_path, (LANE_X, 93.0, math.pi / 2), 90.0)
    assert edge in (':A1_w2', ':A1_c2') and x > LANE_X + 0.9
    # without it, the person crosses at its green (about 45 s) and walks on
    assert _crossing(net, tmp_path, (-30.0, -30.0, 0.0), 60.0)[0] == 'A1A0'


def test_a_warmup_starts_the_world_with_traffic_and_each_reset_runs_it_again(net):
    scene = _world(net, {'demand': DEMAND, 'seed': 4, 'warmup': 30.0}, ego=(-30.0, -30.0, 0.0))
    try:
        bodies = scene.parts['traffic']
        api = bodies.session.api
        assert api.simulation.getTime() == pytest.approx(30.0) and scene.world.time_s == 0.0
        warm = sorted(bodies.agents())
        assert len(warm) > 5 and bodies.since_update_s == 0.0
        scene.world.sync_bodies()       # what any reader of the world does first
        for name, x, y, *_ in warm:     # its bodies already where SUMO has them
            position, _ = pybullet.getBasePositionAndOrientation(
                bodies.body_of(name), physicsClientId=scene.world.client_id)
            assert position[:2] == pytest.approx((x, y), abs=1e-6)
        _run(scene, 5.0)
        bodies.reset(4)
        assert api.simulation.getTime() == pytest.approx(30.0) and sorted(bodies.agents()) == warm
    finally:
        scene.world.close()
    # SUMO's state 30 s in: that of a world without a warmup 30 s later (its SUMO step at
    # 30 s comes before the world's step from 30 s)
    cold = _world(net, {'demand': DEMAND, 'seed': 4}, ego=(-30.0, -30.0, 0.0))
    try:
        _run(cold, 30.01)
        assert sorted(cold.parts['traffic'].agents()) == warm
    finally:
        cold.world.close()


def test_persons_queueing_closer_than_their_width_have_bodies_that_do_not_overlap(net,
                                                                                  tmp_path):
    # 15 persons walking north up A0A1's sidewalk wait at the red of crossing :A1_c2 (until
    # about 45 s): SUMO keeps each a length and a minGap (0.215 + 0.25 m) behind the next, short
    # of the cylinder's 0.478 m, and packs those waiting on the walking area closer still:
    # their bodies are moved apart, and no two overlap right after a SUMO step nor between
    routes = tmp_path / 'queue.rou.xml'
    routes.write_text('<routes>\n' + ''.join(
        f'  <person id="q{k}" depart="{k}" departPos="60"><walk edges="A0A1 A1A0"/></person>\n'
        for k in range(15)) + '</routes>\n')
    scene = _world(net, {'routes': str(routes)}, ego=(-30.0, -30.0, 0.0), folder=tmp_path)
    try:
        world, bodies = scene.world, scene.parts['traffic']
        api, cid = bodies.session.api, scene.world.client_id
        close, shifts, overlaps = 0, [], []
        for _ in range(45 * STEPS_PER_S):
            world.step()
            since = round(bodies.since_update_s / world.time_step_s)
            if world.time_s < 20.0 or since not in (1, 5):
                continue
            world.sync_bodies()
            agents = bodies.agents()
            if since == 1:                     # right after a SUMO step: SUMO's centres then
                centres = []
                for name, x, y, _, length, *_ in agents:
                    pid = bodies.sumo_id(name)
                    (fx, fy), heading = api.person.getPosition(pid), math.radians(
                        90.0 - api.person.getAngle(pid))
                    centres.append((fx - 0.5 * length * math.cos(heading),
                                    fy - 0.5 * length * math.sin(heading)))
                    shifts.append(math.dist((x, y), centres[-1]))
                close += sum(math.dist(a, b) < 0.478
                             for i, a in enumerate(centres) for b in centres[i + 1:])
            ids = [bodies.body_of(name) for name, *_ in agents]
            for i, a in enumerate(ids):
                for b in ids[i + 1:]:
                    depth = min((p[8] for p in pybullet.getClosestPoints(
                        a, b, 0.0, physicsClientId=cid)), default=0.0)
                    if depth < -1e-3:
                        overlaps.append((world.time_s, a, b, depth))
        assert close > 100                     # SUMO's closer than their width
        assert overlaps == []
        # moved by less than a person's width (0.32 m at most here: the crowd SUMO packs on
        # the walking area at the red, some 0.34 m apart), most not at all
        assert 0.0 < max(shifts) < 0.478
        assert sum(shift > 1e-6 for shift in shifts) < 0.5 * len(shifts)
    finally:
        scene.world.close()


def test_a_person_riding_a_vehicle_has_no_body_of_its_own(net, tmp_path):
    routes = tmp_path / 'ride.rou.xml'
    routes.write_text('<routes>\n  <vehicle id="car" depart="0" departSpeed="0">'
                      '<route edges="A0A1 A1A2"/></vehicle>\n'
                      '  <person id="rider" depart="triggered">'
                      '<ride from="A0A1" to="A1A2" lines="car"/></person>\n</routes>\n')
    scene = _world(net, {'routes': str(routes)}, ego=(-30.0, -30.0, 0.0), folder=tmp_path)
    try:
        bodies = scene.parts['traffic']
        api = bodies.session.api
        _run(scene, 5.0)
        assert api.person.getVehicle('rider') == 'car'
        assert [bodies.sumo_id(name) for name, *_ in bodies.agents()] == ['car']
        assert [o.object_class for o in bodies.objects()] == ['car']
    finally:
        scene.world.close()


def test_a_sumo_vehicles_predicted_path_follows_its_route_through_the_junction(net, tmp_path):
    # two cars 60 m up their edges, northbound: one turns right at A1 onto A1B1 (east), the
    # other goes straight on at B1 onto B1B2
    routes = tmp_path / 'turns.rou.xml'
    routes.write_text('<routes>\n'
                      '  <vehicle id="turn" depart="0" departPos="60" departSpeed="max">'
                      '<route edges="A0A1 A1B1"/></vehicle>\n'
                      '  <vehicle id="straight" depart="0" departPos="60" departSpeed="max">'
                      '<route edges="B0B1 B1B2"/></vehicle>\n</routes>\n')
    scene = _world(net, {'routes': str(routes)}, ego=(-30.0, -30.0, 0.0), folder=tmp_path)
    try:
        bodies = scene.parts['traffic']
        _run(scene, 1.0)
        objects = {bodies.sumo_id(o.name): o for o in bodies.objects()}
        turn, straight = objects['turn'], objects['straight']
        assert turn.speed_mps > 5.0 and straight.speed_mps > 5.0
        assert len(turn.path) == len(straight.path) == 10
        # straight on: along x = 101.6, north
        assert all(x == pytest.approx(101.6, abs=0.3) and yaw == pytest.approx(math.pi / 2,
                                                                                abs=0.05)
                   for x, _, yaw in straight.path)
        # the turn: north along x = 1.6, then east along A1B1 (y = 98.4)
        x0, _, yaw0 = turn.path[0]
        x9, y9, yaw9 = turn.path[-1]
        assert x0 == pytest.approx(1.6, abs=0.3) and yaw0 == pytest.approx(math.pi / 2, abs=0.05)
        assert x9 > 10.0 and y9 == pytest.approx(98.4, abs=0.3) and yaw9 == pytest.approx(
            0.0, abs=0.05)
        # without paths (the Gym env's readers): the same objects, each path empty
        bare = {bodies.sumo_id(o.name): o for o in bodies.objects(paths=False)}
        assert bare == {key: replace(o, path=()) for key, o in objects.items()}
    finally:
        scene.world.close()
