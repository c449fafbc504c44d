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
The SUMO engine refuses what it cannot run, with SUMO's own words, and stops when SUMO does.

Routes on edges the network lacks (SUMO's message, at the build); a world without a SUMO
network; a step that is no multiple of the world's; SUMO, libsumo or traci missing (the error
names the ``sumo`` extra; without libsumo, ``transport: auto`` runs SUMO over TraCI); SUMO
failing while the world runs (a route SUMO reads late, a sumo process or a SUMO worker killed):
the world's step raises SumoError with SUMO's message, and the next world starts; the same
through a worker (``transport: worker``). Our car touching a SUMO
vehicle is a collision naming its body, and the SUMO vehicle stops for good.
"""

import math
import sys

import pytest

pytest.importorskip('traci', reason="needs the 'sumo' extra")

from vehicle_sim.physics import sumo_session  # noqa: E402

if sumo_session.load_libsumo() is None:      # (imported quietly: its pyarrow notice)
    pytest.skip("needs the 'sumo' extra (libsumo)", allow_module_level=True)

from sumo_helpers import one_lane_grid_net, write_routes  # noqa: E402

from vehicle_sim.config import world_from_data  # noqa: E402
from vehicle_sim.core.specs.errors import InvalidParameterError  # noqa: E402
from vehicle_sim.physics.scene import build_scene  # noqa: E402
from vehicle_sim.physics.sensors import CollisionMonitor  # noqa: E402
from vehicle_sim.physics.sumo_session import SumoError, SumoUnavailable  # noqa: E402

OFF_ROAD = (-30.0, -30.0, 0.0)       # our car's pose: 30 m from every road of the grid


@pytest.fixture(scope='module')
def net(tmp_path_factory):
    return one_lane_grid_net(tmp_path_factory.mktemp('sumo_net'))


def _spec(net, traffic, folder, ego=OFF_ROAD, time_step=None):
    x, y, yaw = ego
    data = {'vehicles': [{'name': 'ego', 'model': 'Car', 'pose': {'x': x, 'y': y, 'yaw': yaw}}],
            'map': {'type': 'sumo', 'net': net}, 'traffic': {'engine': 'sumo', **traffic}}
    return world_from_data(data, 'w.yaml', base_dir=str(folder))


def _still_runs(net, folder):
    # SUMO starts again in this process after the failure (libsumo was given back)
    scene = build_scene(_spec(net, {'routes': write_routes(folder, [('a', 0, 'A0A1')],
                                                           'ok.rou.xml')}, folder))
    try:
        assert scene.parts['traffic'].session.transport == 'libsumo'
        for _ in range(100):
            scene.world.step()
        assert len(scene.parts['traffic'].agents()) == 1
    finally:
        scene.world.close()


@pytest.mark.parametrize('transport', ['auto', 'worker'])
def test_routes_on_edges_not_in_the_network_are_refused_with_sumos_message(net, tmp_path,
                                                                           transport):
    routes = write_routes(tmp_path, [('a', 0, 'A0A1 NOPE')])
    with pytest.raises(InvalidParameterError,
                       match=r"^w\.yaml: traffic: SUMO did not start: The edge 'NOPE' within "
                             r"the route for vehicle 'a' is not known"):
        build_scene(_spec(net, {'routes': routes, 'transport': transport}, tmp_path))
    assert sumo_session._libsumo_user[0] is None
    _still_runs(net, tmp_path)


def test_a_world_without_a_sumo_network_is_refused_naming_its_map(tmp_path):
    routes = write_routes(tmp_path, [('a', 0, 'A0A1')])
    data = {'vehicles': [{'name': 'ego', 'model': 'Car'}],
            'traffic': {'engine': 'sumo', 'routes': routes}}
    spec = world_from_data(data, 'w.yaml', base_dir=str(tmp_path))
    with pytest.raises(InvalidParameterError,
                       match=r'^w\.yaml: traffic: the sumo engine runs on a SUMO network: give '
                             r'the world a map of kind sumo .*; it has no map$'):
        build_scene(spec)


def test_a_step_that_is_no_multiple_of_the_worlds_is_refused(net, tmp_path):
    routes = write_routes(tmp_path, [('a', 0, 'A0A1')])
    with pytest.raises(InvalidParameterError,
                       match=r"^w\.yaml: traffic: field 'step' = 0\.015: must be a multiple of "
                             r'the world step 0\.01 s$'):
        build_scene(_spec(net, {'routes': routes, 'step': 0.015}, tmp_path))


def test_sumo_missing_names_the_extra(net, tmp_path, monkeypatch):
    routes = write_routes(tmp_path, [('a', 0, 'A0A1')])
    monkeypatch.setitem(sys.modules, 'sumo', None)          # import sumo fails
    with pytest.raises(SumoUnavailable,
                       match=r'^the sumo traffic engine needs the eclipse-sumo package: pip '
                             r"install 'vehicle_sim\[sumo\]'"):
        build_scene(_spec(net, {'routes': routes}, tmp_path))


def test_without_libsumo_auto_runs_sumo_over_traci_and_libsumo_is_refused(net, tmp_path,
                                                                           monkeypatch):
    routes = write_routes(tmp_path, [('a', 0, 'A0A1')])
    monkeypatch.setattr(sumo_session, 'load_libsumo', lambda: None)
    for transport in ('libsumo', 'worker'):       # a worker runs libsumo too
        with pytest.raises(SumoUnavailable,
                           match=rf"field 'transport' = '{transport}': libsumo does not load in "
                                 r'this Python \(transport: traci runs SUMO as a process\): pip '
                                 r"install 'vehicle_sim\[sumo\]'"):
            build_scene(_spec(net, {'routes': routes, 'transport': transport}, tmp_path))
    scene = build_scene(_spec(net, {'routes': routes}, tmp_path))
    try:
        bodies = scene.parts['traffic']
        assert bodies.session.transport == 'traci'
        for _ in range(100):
            scene.world.step()
        (name, *_), = bodies.agents()
        assert bodies.sumo_id(name) == 'a'
    finally:
        scene.world.close()


def test_libsumo_asked_for_twice_in_one_process_is_refused(net, tmp_path):
    routes = write_routes(tmp_path, [('a', 0, 'A0A1')])
    first = build_scene(_spec(net, {'routes': routes}, tmp_path))
    try:
        with pytest.raises(InvalidParameterError,
                           match=r"field 'transport' = 'libsumo': this process runs a SUMO "
                                 r'through libsumo already \(one per process\)'):
            build_scene(_spec(net, {'routes': routes, 'transport': 'libsumo'}, tmp_path))
    finally:
        first.world.close()


@pytest.mark.parametrize('transport', ['auto', 'worker'])
def test_sumo_failing_mid_run_stops_the_world_with_its_message(net, tmp_path, transport):
    # SUMO reads its routes ahead, in steps of 200 s: a bad route departing at 400 s fails
    # when SUMO reads it, at 300 s (after the 300 s departure; through a worker in the step
    # started at 299 s, collected at 300 s)
    routes = write_routes(tmp_path, [('a', 0, 'A0A1'), ('mid', 300, 'A0A1'),
                                     ('late', 400, 'A0A1 NOPE')])
    scene = build_scene(_spec(net, {'routes': routes, 'step': 1.0, 'transport': transport},
                              tmp_path))
    try:
        with pytest.raises(SumoError,
                           match=r"^w\.yaml: traffic: SUMO at t = \d+\.\d+ s: The edge 'NOPE' "
                                 r"within the route for vehicle 'late' is not known"):
            for _ in range(40000):
                scene.world.step()
        assert 299.0 < scene.world.time_s < 302.0
    finally:
        scene.world.close()
    _still_runs(net, tmp_path)


@pytest.mark.parametrize('transport, closed', [('traci', r'Connection closed by SUMO\.'),
                                               ('worker', r'Connection closed by the SUMO '
                                                          r'worker\.')])
def test_a_killed_sumo_process_stops_the_world_with_sumos_words(net, tmp_path, transport,
                                                                closed):
    routes = write_routes(tmp_path, [('a', 0, 'A0A1')])
    scene = build_scene(_spec(net, {'routes': routes, 'transport': transport}, tmp_path))
    try:
        session = scene.parts['traffic'].session
        for _ in range(50):
            scene.world.step()
        session.api._process.kill()
        session.api._process.wait(timeout=60)
        with pytest.raises(SumoError, match=r'^w\.yaml: traffic: SUMO at t = 0\.500 s: '
                                            + closed + r' \(the sumo process '
                                            r'ended with status -9\)$'):
            for _ in range(20):
                scene.world.step()
    finally:
        scene.world.close()
    assert session.closed


def test_our_car_touching_a_sumo_vehicle_is_a_collision_and_stops_it(net, tmp_path):
    # a SUMO car creeping north at 1 m/s from y = 35; ours behind it at full throttle
    path = tmp_path / 'slow.rou.xml'
    path.write_text('<routes>\n  <vType id="slow" maxSpeed="1"/>\n'
                    '  <vehicle id="slow" type="slow" depart="0" departPos="30" '
                    'departSpeed="0"><route edges="A0A1 A1A2"/></vehicle>\n</routes>\n')
    scene = build_scene(_spec(net, {'routes': str(path)}, tmp_path,
                              ego=(1.6, 12.0, math.pi / 2)))
    try:
        bodies = scene.parts['traffic']
        monitor = CollisionMonitor(scene.world, scene.vehicles['ego'].body)
        logic = scene.vehicles['ego'].car.logic
        logic.set_gear(1)
        logic.set_throttle(1.0)
        events = []
        for _ in range(1500):
            scene.world.step()
            events += monitor.fresh
            if events:
                break
        name = bodies.name_of('slow')
        assert [e.other for e in events] == [name]
        logic.set_throttle(0.0)
        logic.set_brake_intensity(1.0)
        (where, _), *_ = scene.world.body_state(bodies.body_of(name))
        for _ in range(300):
            scene.world.step()
        api = bodies.session.api
        assert api.vehicle.getSpeed('slow') == 0.0
        (after, _), *_ = scene.world.body_state(bodies.body_of(name))
        assert after[:2] == pytest.approx(where[:2], abs=0.05)      # it stays, an obstacle
    finally:
        scene.world.close()


def test_sumo_failing_in_its_warmup_stops_the_build_and_leaves_no_sumo_running(net, tmp_path):
    routes = write_routes(tmp_path, [('a', 0, 'A0A1'), ('b', 3, 'A0A1'),
                                     ('late', 6, 'A0A1 NOPE')])
    with pytest.raises(SumoError, match=r"^w\.yaml: traffic: SUMO warming up: The edge 'NOPE' "
                                        r"within the route for vehicle 'late' is not known\. "
                                        r'The route can not be build\.$'):
        build_scene(_spec(net, {'routes': routes, 'warmup': 10.0,
                                'options': ['--route-steps', '1']}, tmp_path))
    assert sumo_session._libsumo_user[0] is None
    _still_runs(net, tmp_path)
