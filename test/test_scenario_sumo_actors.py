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
A scenario actor in a world with the SUMO engine has the route of its waypoints in SUMO.

On the SUMO engine's test grid (sumo_helpers.one_lane_grid_net: B0B1 runs north along x = 101.6
into junction B1 at (100, 100), B1A1 west from it along y = 101.6) an actor drives north on
B0B1 and turns left at B1 onto B1A1, along waypoints; SUMO's car ``f`` departs behind it on B0B1
and goes straight on through B1. SUMO's vehicle for the actor (``vehicle_sim.lead``) has the
route B0B1 B1A1 from the start (its next link at B1 is the left turn), read back from libsumo at
every step until it is through the junction; ``f`` follows it and goes on without a warning
from SUMO (no emergency braking, no teleport). The edges a path passes
(core/traffic/lane_paths.py ``edges_along``) on the grid's lane graph.
"""

import math
import re

import pytest
import yaml

pytest.importorskip('libsumo', reason="needs the 'sumo' extra")

from sumo_helpers import one_lane_grid_net, write_routes  # noqa: E402

from vehicle_sim.config import world_from_data  # noqa: E402
from vehicle_sim.core.traffic.lane_paths import edges_along  # noqa: E402
from vehicle_sim.maps.lane_maps import with_lanes  # noqa: E402
from vehicle_sim.scenarios.runner import run_scenario  # noqa: E402

OURS = 'vehicle_sim.lead'
CENTRE, RADIUS = 92.8, 8.8       # the left turn at B1: from (101.6, 92.8) to (92.8, 101.6)


def _left_turn():
    # north on B0B1, round the corner's arc at 3 m/s, west on B1A1
    points = [[101.6, 80.0, 6.0], [101.6, 92.8, 3.0]]
    for k in range(1, 8):
        angle = k / 8 * math.pi / 2
        points.append([CENTRE + RADIUS * math.cos(angle), CENTRE + RADIUS * math.sin(angle),
                       3.0])
    return points + [[92.8, 101.6, 3.0], [80.0, 101.6, 5.0], [30.0, 101.6, 6.0]]


@pytest.fixture(scope='module')
def net(tmp_path_factory):
    return one_lane_grid_net(tmp_path_factory.mktemp('grid'))


def _scenario(net, folder):
    routes = write_routes(folder, [('f', 2.0, 'B0B1 B1B2')])
    path = folder / 'turn_left.yaml'
    path.write_text(yaml.safe_dump({
        'name': 'turn_left',
        'world': {'vehicles': [
            {'name': 'ego', 'namespace': 'ego', 'model': 'Car',
             'pose': {'x': -30.0, 'y': -30.0, 'yaw': 0.0}},          # off every road
            {'name': 'lead', 'namespace': 'lead', 'model': 'Car',
             'pose': {'lane': 'B0B1_1', 's': 30.0}}],
            'map': {'type': 'sumo', 'net': net},
            'traffic': {'engine': 'sumo', 'routes': routes, 'transport': 'libsumo'}},
        'vehicle': 'ego',
        'duration': 26.0,
        'actors': [{'vehicle': 'lead', 'waypoints': _left_turn()}],
        'driver': {'commands': [{'t': 0.0, 'brake_intensity': 1.0}]},
        'criteria': [{'kind': 'max_speed', 'vehicle': 'lead', 'limit': 8.0}]}),
        encoding='utf-8')
    return path


def test_an_actors_waypoints_are_its_route_in_sumo(net, tmp_path, capfd):
    import libsumo
    seen = []                    # (t, actor's edge, its route, its next links, f's edge)

    def look(time_s, _):
        ids = libsumo.vehicle.getIDList()
        if OURS in ids and round(time_s * 100) % 10 == 0:
            vehicle = libsumo.vehicle
            seen.append((time_s, vehicle.getRoadID(OURS), vehicle.getRoute(OURS),
                         [(link[0], link[6]) for link in vehicle.getNextLinks(OURS)],
                         vehicle.getRoadID('f') if 'f' in ids else None))

    capfd.readouterr()
    result = run_scenario(_scenario(net, tmp_path), progress=look)
    warnings = capfd.readouterr().err
    assert result.passed, [(c.name, c.detail) for c in result.criteria]
    # from the start to the end of the turn: SUMO's route is the waypoints' edges, its next
    # link at B1 the left turn onto B1A1
    approach = [s for s in seen if s[1] == 'B0B1']
    assert approach and approach[0][0] < 0.25          # from SUMO's 2nd step on
    assert {s[2] for s in approach} == {('B0B1', 'B1A1')}
    assert {tuple(s[3]) for s in approach} == {(('B1A1_1', 'l'),)}
    inside = [s for s in seen if s[1].startswith(':B1_')]
    assert inside and {s[2] for s in inside} == {('B0B1', 'B1A1')}
    assert seen[-1][1] == 'B1A1'                                 # the actor turned
    # SUMO's car behind it went straight on through B1, unconfused
    assert 'B1B2' in {s[4] for s in seen}
    assert not re.search(r"Vehicle 'f'|[Tt]eleport", warnings), warnings


def test_the_edges_a_path_passes(net, tmp_path):
    data = {'vehicles': [{'name': 'ego', 'model': 'Car', 'pose': {'x': 0.0, 'y': 0.0}}],
            'map': {'type': 'sumo', 'net': net}}
    graph = with_lanes(world_from_data(data, 'w.yaml', base_dir=str(tmp_path))).lanes
    turn = [(101.6, 40.0)] + [tuple(p[:2]) for p in _left_turn()]
    assert edges_along(graph, turn) == ('B0B1', 'B1A1')
    # the same road the other way: the lanes heading the path's way
    assert edges_along(graph, [(98.4, 80.0), (98.4, 20.0)]) == ('B1B0',)
    # straight through two junctions: the edges on either side of each
    assert edges_along(graph, [(101.6, 20.0), (101.6, 180.0)]) == ('B0B1', 'B1B2')
    assert edges_along(graph, [(101.6, 20.0)]) == ('B0B1',)           # one point: its edge
    assert edges_along(graph, [(-50.0, -50.0), (-50.0, -10.0)]) == ()  # on no lane
