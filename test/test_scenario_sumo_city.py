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
The shipped SUMO city: its world, its two scenarios, and a Webots project's SUMO folder run as is.

``config/worlds/city_sumo.yaml`` builds with SUMO's vehicles and pedestrians moving in it;
``scenarios/red_light.yaml`` (the car stops behind SUMO's cars queued at B1's red light) and
``scenarios/pedestrian_crossing.yaml`` (the car yields to SUMO's pedestrian on B1's crossing)
pass, and fail without their brake, through the scenario runner; a world with ``sumo_folder:``
runs a folder laid out as Webots' SUMO interface reads it (docs/sumo.md).
"""

import os
from pathlib import Path
import subprocess
import sys

from conftest import peer_env
import pytest
import yaml

pytest.importorskip('libsumo', reason="needs the 'sumo' extra")

from sumo_helpers import grid_net, write_routes  # noqa: E402

from vehicle_sim.config import load_world, world_from_data  # noqa: E402
from vehicle_sim.core.specs.errors import InvalidParameterError  # noqa: E402
from vehicle_sim.physics.scene import build_scene  # noqa: E402
from vehicle_sim.scenarios.runner import run_scenario  # noqa: E402

REPO = Path(__file__).resolve().parent.parent
SCENARIOS = REPO / 'scenarios'
RED_LIGHT = SCENARIOS / 'red_light.yaml'
PEDESTRIAN_CROSSING = SCENARIOS / 'pedestrian_crossing.yaml'
STOP_LINE_X = 149.6      # the end of lane A1B1_1 (eastbound, y = 155.2): B1's stop line


@pytest.fixture(autouse=True)
def _cache(tmp_path_factory, monkeypatch):
    # the demand's trips are made in the test's folder, not in the user's cache
    monkeypatch.setenv('VEHICLE_SIM_CACHE', str(tmp_path_factory.getbasetemp() / 'cache'))


def _variant(tmp_path, source, change):
    # the scenario with a change, written beside copies of its route file and the map
    data = yaml.safe_load(source.read_text(encoding='utf-8'))
    change(data)
    data['world']['map']['net'] = str(REPO / 'config' / 'maps' / 'city_sumo.net.xml')
    routes = SCENARIOS / data['world']['traffic']['routes']
    (tmp_path / routes.name).write_text(routes.read_text(encoding='utf-8'), encoding='utf-8')
    path = tmp_path / source.name
    path.write_text(yaml.safe_dump(data), encoding='utf-8')
    return path


def _no_brake(data):
    data['driver']['commands'] = data['driver']['commands'][:1]


# ------------------------------------------------------------------------------- the world

def test_the_city_world_has_sumo_vehicles_and_pedestrians_moving_on_its_lanes():
    spec = load_world('city_sumo')
    scene = build_scene(spec)
    try:
        # placed 20 m into lane A1B1_1 (eastbound, y = 155.2, from x = 70.4)
        placed = scene.spec.vehicles[0]
        assert (placed.x_m, placed.y_m, placed.yaw_rad) == (
            pytest.approx(90.4), pytest.approx(155.2), pytest.approx(0.0))
        assert len(scene.lanes.rules.programs) == 16
        traffic = scene.parts['traffic']
        # its 60 s warmup: the city has traffic when the world starts
        assert len(traffic.agents()) >= 10
        world = scene.world
        seen, moved = {}, set()
        for _ in range(60):                       # 60 s, sampled every second
            for _ in range(100):
                world.step()
            for name, x, y, *_ in traffic.agents():
                sumo_id = traffic.sumo_id(name)
                if sumo_id in seen and seen[sumo_id] != (x, y):
                    moved.add(sumo_id)
                seen[sumo_id] = (x, y)
        classes = {o.object_class for o in traffic.objects()}
        assert 'car' in classes and 'pedestrian' in classes
        # the demand's vehicles and persons (randomTrips ids: veh*, ped*) move
        assert len(moved) >= 10
        assert any('ped' in name for name in moved)
    finally:
        scene.world.close()


# ---------------------------------------------------------------------------- red light

def test_the_car_stops_behind_the_queue_at_the_red_light():
    result = run_scenario(RED_LIGHT)
    assert result.passed and result.error is None
    light = result.criterion('traffic_light')
    assert light.value == 0
    # B1's program holds the west arm red: the car came closest to that red line, its
    # straight-on group's (B1's link 13)
    assert 'closest to a red line: ' in light.detail
    assert 'before line 20000094 (group 30000094)' in light.detail
    gap = result.criterion('min_gap')
    # behind SUMO's third queued car (sumo_2), 3.5 m from its rear
    assert 2.0 < gap.value < 5.0 and 'to sumo_2' in gap.detail
    track = result.tracks['Car']
    front = track.x_m[-1] + track.outline.x_max_m
    assert front < STOP_LINE_X - 15.0 and abs(track.y_m[-1] - 155.2) < 0.2


def test_without_the_brake_the_car_runs_into_the_queue(tmp_path):
    result = run_scenario(_variant(tmp_path, RED_LIGHT, _no_brake))
    assert not result.passed
    collision = result.criterion('no_collision')
    # into the rear of the queue's last car, well before the stop line
    assert collision.others[0] == 'sumo_2' and 6.0 < collision.at_s < 10.0
    assert collision.points_m[0][0] < STOP_LINE_X - 15.0
    assert result.criterion('min_gap').value <= 0.0
    # it hit the queue before the line: the light itself was not run
    assert result.criterion('traffic_light').value == 0


def test_the_installed_command_runs_the_red_light_scenario(tmp_path):
    # what a user types: exit 0, every criterion printed
    command = os.path.join(os.path.dirname(sys.executable), 'vehicle-sim')
    done = subprocess.run([command, 'scenario', str(RED_LIGHT), '--junit',
                           str(tmp_path / 'red_light.xml')],
                          env=dict(peer_env(), VEHICLE_SIM_CACHE=str(tmp_path / 'cache')),
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stdout + done.stderr
    assert '  PASS  traffic_light: 0 crossings' in done.stdout
    assert '  PASS  min_gap: 3.' in done.stdout and 'PASS: 3/3 criteria passed' in done.stdout
    assert 'testsuite' in (tmp_path / 'red_light.xml').read_text(encoding='utf-8')


# ----------------------------------------------------------------------- pedestrian crossing

def test_the_car_yields_to_the_pedestrian_on_the_crossing_and_drives_on():
    result = run_scenario(PEDESTRIAN_CROSSING)
    assert result.passed and result.error is None
    gap = result.criterion('min_gap')
    # the only SUMO agent is the pedestrian (sumo_0): the car stopped 4 m before it
    assert 3.0 < gap.value < 5.0 and 'to sumo_0' in gap.detail
    assert result.criterion('no_collision').value == 0
    goal = result.criterion('reach_goal')
    assert 15.0 < goal.value < 30.0                 # past B1 once the pedestrian has crossed


def test_without_the_brake_the_car_hits_the_pedestrian(tmp_path):
    result = run_scenario(_variant(tmp_path, PEDESTRIAN_CROSSING, _no_brake))
    assert not result.passed
    collision = result.criterion('no_collision')
    # the pedestrian, on the crossing just beyond the stop line
    assert collision.others[0] == 'sumo_0' and 9.0 < collision.at_s < 12.0
    assert STOP_LINE_X - 3.0 < collision.points_m[0][0] < STOP_LINE_X + 5.0
    assert result.criterion('min_gap').value <= 0.0


# ------------------------------------------------------------------- a Webots SUMO folder

SUMOCFG = ('<configuration>\n    <input>\n        <net-file value="sumo.net.xml"/>\n'
           '        <route-files value="sumo.rou.xml"/>\n    </input>\n</configuration>\n')


def _webots_project(tmp_path):
    # my_world.wbt's folder: my_world_net/ with the files Webots' SUMO interface reads
    folder = tmp_path / 'my_world_net'
    folder.mkdir()
    grid_net(folder, 'sumo.net.xml')
    write_routes(folder, [('east', 0, 'A0B0 B0C0'), ('north', 0, 'C0C1 C1C2'),
                          ('west', 1, 'C2B2 B2A2')], name='sumo.rou.xml')
    (folder / 'sumo.sumocfg').write_text(SUMOCFG, encoding='utf-8')
    return folder


def _folder_world(tmp_path, **extra):
    data = {'vehicles': [{'name': 'Car', 'model': 'ToyotaPrius',
                          'pose': {'lane': 'A1B1_1', 's': 10.0}}],
            'sumo_folder': 'my_world_net', **extra}
    return world_from_data(data, str(tmp_path / 'my_world.yaml'))


def test_a_webots_sumo_folder_runs_as_it_is(tmp_path):
    folder = _webots_project(tmp_path)
    spec = _folder_world(tmp_path, traffic={'seed': 3})
    assert spec.map.type == 'sumo' and spec.map.net == str(folder / 'sumo.net.xml')
    assert spec.traffic.seed == 3
    scene = build_scene(spec)
    try:
        traffic = scene.parts['traffic']
        for _ in range(800):                      # 8 s
            scene.world.step()
        found = {traffic.sumo_id(name): (x, y) for name, x, y, *_ in traffic.agents()}
        # the three vehicles of sumo.rou.xml, driven along their routes' first edges (the grid's
        # junctions 100 m apart, A0 at the origin: A0B0 east along y ~ 0, C0C1 north along
        # x ~ 200, C2B2 west along y ~ 200)
        assert set(found) == {'east', 'north', 'west'}
        assert 20.0 < found['east'][0] < 200.0 and abs(found['east'][1]) < 10.0
        assert abs(found['north'][0] - 200.0) < 10.0 and 20.0 < found['north'][1] < 200.0
        assert abs(found['west'][1] - 200.0) < 10.0 and 0.0 < found['west'][0] < 180.0
    finally:
        scene.world.close()


def test_a_sumo_folder_beside_a_map_or_routes_is_refused(tmp_path):
    _webots_project(tmp_path)
    with pytest.raises(InvalidParameterError, match=r'sumo_folder: the folder gives the map'):
        _folder_world(tmp_path, map={'type': 'sumo', 'net': 'my_world_net/sumo.net.xml'})
    with pytest.raises(InvalidParameterError, match=r'sumo_folder: the folder gives the routes'):
        _folder_world(tmp_path, traffic={'routes': 'other.rou.xml'})
    with pytest.raises(InvalidParameterError, match=r"runs on the engine sumo, not 'builtin'"):
        _folder_world(tmp_path, traffic={'engine': 'builtin', 'vehicles': 3})
    with pytest.raises(InvalidParameterError, match=r"'.*elsewhere_net' is not a folder"):
        world_from_data({'vehicles': [{'name': 'Car'}], 'sumo_folder': 'elsewhere_net'},
                        str(tmp_path / 'my_world.yaml'))

