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
``transport: worker``: libsumo in a process of its own, its step in flight while the world steps.

With our car off every road (so not in SUMO) a worker's world has the bodies, objects and
lanes of a libsumo world step for step, seed for seed, any number of them in one process beside
libsumo; a step is in flight between SUMO's updates and our car reaches SUMO one SUMO step
later; closing the world ends the worker; a reset starts it again; beside it, this process's
libsumo stays free for another world. (SUMO refusing a route, failing mid-run or its worker
killed, and a worker without libsumo: test_physics_sumo_bad_input.py.)
"""

import math

import pytest

pytest.importorskip('traci', reason="needs the 'sumo' extra")

from vehicle_sim.physics import sumo_session  # noqa: E402

if sumo_session.load_libsumo() is None:      # (imported quietly: its pyarrow notice)
    pytest.skip("needs the 'sumo' extra (libsumo)", allow_module_level=True)

from sumo_helpers import one_lane_grid_net, write_routes  # noqa: E402

from vehicle_sim.config import world_from_data  # noqa: E402
from vehicle_sim.physics.scene import build_scene  # noqa: E402
from vehicle_sim.physics.sumo_ours import OURS_PREFIX  # noqa: E402

OFF_ROAD = (-30.0, -30.0, 0.0)       # our car's pose: 30 m from every road of the grid
LANE_X = 1.6                         # edge A0A1's lane (northbound) along x = 1.6
DEMAND = {'vehicles_per_hour': 2400, 'pedestrians_per_hour': 1200, 'seed': 5,
          'classes': {'passenger': 3, 'bus': 1, 'bicycle': 1, 'truck': 1}}


@pytest.fixture(scope='module')
def net(tmp_path_factory):
    return one_lane_grid_net(tmp_path_factory.mktemp('sumo_net'))


@pytest.fixture(autouse=True)
def _cache(tmp_path_factory, monkeypatch):
    # the demand's trips are made once for the module, not in the user's cache
    monkeypatch.setenv('XDG_CACHE_HOME', str(tmp_path_factory.getbasetemp() / 'cache'))


def _world(net, traffic, ego=OFF_ROAD, folder='.'):
    x, y, yaw = ego
    data = {'vehicles': [{'name': 'ego', 'model': 'Car', 'pose': {'x': x, 'y': y, 'yaw': yaw}}],
            'map': {'type': 'sumo', 'net': net}, 'traffic': {'engine': 'sumo', **traffic}}
    return build_scene(world_from_data(data, 'w.yaml', base_dir=str(folder)))


def _state(bodies):
    return sorted(bodies.agents()), sorted((o.name, o.path) for o in bodies.objects())


def test_a_worker_gives_the_bodies_and_objects_of_libsumo_step_for_step(net):
    worlds = [_world(net, {'demand': DEMAND, 'seed': 3, 'transport': transport})
              for transport in ('libsumo', 'worker', 'worker')]
    try:
        bodies = [scene.parts['traffic'] for scene in worlds]
        assert [b.session.transport for b in bodies] == ['libsumo', 'worker', 'worker']
        workers = [b.session.api.worker for b in bodies[1:]]
        assert workers[0].exit_status is None and workers[1].exit_status is None
        compared = 0
        for step in range(2000):
            for scene in worlds:
                scene.world.step()
            # between SUMO's updates (every 10 world steps) a worker's next step is in flight
            # (until something reads SUMO: a call waits for it)
            assert all(worker.in_flight for worker in workers) == (step >= 10)
            if step % 250 == 249:
                states = [_state(b) for b in bodies]
                assert states[1] == states[0] and states[2] == states[0], step
                compared += len(states[0][0])
        assert compared > 50
        # the objects' paths came from each vehicle's lane in the worker's readings (not one
        # getter each), as over libsumo
        lanes = [slot.lane for slot in bodies[1]._by_id.values() if not slot.person]
        assert len(lanes) > 5 and all(lane[0] for lane in lanes)
        # read by libsumo's getters in the worker: no vehicle or person subscribed (each
        # subscription costs SUMO's step)
        for domain in ('vehicle', 'person'):
            assert getattr(bodies[1].session.api, domain).getAllSubscriptionResults() == {}
    finally:
        for scene in worlds:
            scene.world.close()
    assert all(worker.exit_status is None and worker._process is None for worker in workers)
    assert [b.session.closed for b in bodies] == [True, True, True]


def _ours_in_sumo(net, tmp_path, transport):
    # our car driving north on A0A1: after each SUMO update from 1 s on, SUMO's time and where
    # SUMO has the car (its front), SUMO read after the step in flight where there is one
    routes = write_routes(tmp_path, [('a', 200, 'A0A1')])
    scene = _world(net, {'routes': routes, 'transport': transport},
                   ego=(LANE_X, 12.0, math.pi / 2), folder=tmp_path)
    try:
        logic = scene.vehicles['ego'].car.logic
        logic.set_gear(1)
        logic.set_throttle(0.5)
        api = scene.parts['traffic'].session.api
        found = []
        for step in range(1, 301):
            scene.world.step()                 # SUMO's update at each tenth (0.1 s)
            if step % 10 == 1 and step > 100:
                if transport == 'worker':
                    api.worker.wait()
                found.append((round(scene.world.time_s - 0.01, 6),
                              round(api.simulation.getTime(), 6),
                              api.vehicle.getPosition(f'{OURS_PREFIX}ego')))
        return found
    finally:
        scene.world.close()


def test_our_car_reaches_sumo_one_sumo_step_later_through_a_worker(net, tmp_path):
    libsumo = _ours_in_sumo(net, tmp_path, 'libsumo')
    worker = _ours_in_sumo(net, tmp_path, 'worker')
    assert libsumo[-1][2][1] - libsumo[0][2][1] > 3.0              # the car drives
    # over libsumo SUMO's step at an update has our car where it is then; through a worker
    # the step in flight, one SUMO step further on, has it there
    assert [t for t, _, _ in libsumo] == [t for t, _, _ in worker]
    assert all(sumo == t for t, sumo, _ in libsumo)
    assert all(sumo == pytest.approx(t + 0.1, abs=1e-9) for t, sumo, _ in worker)
    for (_, _, a), (_, _, b) in zip(libsumo, worker):
        assert b == pytest.approx(a, abs=1e-6)


def test_reset_starts_the_worker_again_with_its_seed(net):
    def run(scene, steps):
        found = []
        for step in range(steps):
            scene.world.step()
            if step % 100 == 99:
                found.append(sorted(scene.parts['traffic'].agents()))
        return found

    scene = _world(net, {'demand': DEMAND, 'seed': 4, 'transport': 'worker'})
    try:
        bodies = scene.parts['traffic']
        first = run(scene, 1000)
        old = bodies.session.api.worker._process
        assert 'SUMO started again' in bodies.reset(4)
        assert old.poll() is not None                   # the first worker ended
        assert bodies.agents() == [] and bodies.session.api.simulation.getTime() == 0.0
        assert run(scene, 1000) == first and first[-1]
    finally:
        scene.world.close()


def test_a_worker_beside_libsumo_leaves_this_process_libsumo_to_its_world(net, tmp_path):
    routes = write_routes(tmp_path, [('a', 0, 'A0A1')])
    worker = _world(net, {'routes': routes, 'transport': 'worker'}, folder=tmp_path)
    try:
        # the worker's libsumo is its own: this process's is still free for a world
        assert sumo_session._libsumo_user[0] is None
        inside = _world(net, {'routes': routes}, folder=tmp_path)
        try:
            assert inside.parts['traffic'].session.transport == 'libsumo'
        finally:
            inside.world.close()
    finally:
        worker.world.close()


def test_our_vehicles_route_reaches_sumo_through_the_worker(net, tmp_path):
    # ours on A0A1 (northbound) with route [A1B1_1] (east at A1): the engine asks SUMO's
    # router (simulation.findRoute, whose libsumo result comes back as its fields) and SUMO's
    # route for it is A0A1 A1B1, its next link the right turn onto A1B1
    data = {'vehicles': [{'name': 'ego', 'model': 'Car', 'route': ['A1B1_1'],
                          'pose': {'x': LANE_X, 'y': 40.0, 'yaw': math.pi / 2}}],
            'map': {'type': 'sumo', 'net': net},
            'traffic': {'engine': 'sumo', 'routes': write_routes(tmp_path, []),
                        'transport': 'worker'}}
    scene = build_scene(world_from_data(data, 'w.yaml', base_dir=str(tmp_path)))
    try:
        for _ in range(20):
            scene.world.step()
        api = scene.parts['traffic'].session.api
        assert api.vehicle.getRoute(f'{OURS_PREFIX}ego') == ('A0A1', 'A1B1')
        assert [(link[0], link[6]) for link in api.vehicle.getNextLinks(
            f'{OURS_PREFIX}ego')] == [('A1B1_1', 'r')]
        assert api.simulation.findRoute('A0A1', 'A1B1').edges == ('A0A1', 'A1B1')
    finally:
        scene.world.close()
