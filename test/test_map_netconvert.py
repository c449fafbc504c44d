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
OpenDRIVE files and OpenStreetMap extracts as lane maps, through netconvert (maps/netconvert.py).

The OpenDRIVE file is netgenerate's signalised grid written by netconvert's OpenDRIVE output
(test/sumo_helpers.py); the OSM extract is test/data/sumo/crossing.osm (hand-made: two streets
crossing at a signalised node, a zebra crossing, footways).
"""

from pathlib import Path
import subprocess
import sys

import pytest
import yaml

pytest.importorskip('sumolib', reason="sumolib is not installed (pip install "
                                      "'vehicle_sim[sumo]')")

from sumo_helpers import grid_net, opendrive_of  # noqa: E402

from vehicle_sim.config import load_world  # noqa: E402
from vehicle_sim.core.map.signal_programs import ProgramController  # noqa: E402
from vehicle_sim.core.specs.errors import InvalidParameterError  # noqa: E402
from vehicle_sim.maps import netconvert  # noqa: E402
from vehicle_sim.maps.lane_maps import with_lanes  # noqa: E402
from vehicle_sim.maps.sumo_net import SumoUnavailable  # noqa: E402

OSM = Path(__file__).resolve().parent / 'data' / 'sumo' / 'crossing.osm'


@pytest.fixture(scope='module')
def xodr(tmp_path_factory):
    folder = tmp_path_factory.mktemp('xodr')
    return opendrive_of(grid_net(folder), folder)


@pytest.fixture
def conversions(monkeypatch):
    """Count netconvert's conversions (its runs with an output)."""
    runs = []
    real = subprocess.run

    def counting(command, *args, **kwargs):
        if '-o' in command:
            runs.append(command)
        return real(command, *args, **kwargs)
    monkeypatch.setattr(netconvert.subprocess, 'run', counting)
    return runs


def _world(folder, kind, path, pose=None, **more):
    world = Path(folder) / f'{kind}_world.yaml'
    data = {'vehicles': [{'name': 'Car', 'model': 'ToyotaPrius',
                          'pose': pose or {'x': 0.0, 'y': 0.0}}],
            'map': dict({'type': kind, 'file': str(path), 'cache': str(Path(folder) / 'cache')},
                        **more)}
    world.write_text(yaml.safe_dump(data), encoding='utf-8')
    return world


def _loaded(folder, kind, path, **more):
    return with_lanes(load_world(str(_world(folder, kind, path, **more)), 'ToyotaPrius')).lanes


def _straight_start(graph):
    """Return the id of the longest lane that is not a junction's."""
    best = None
    for lane in graph.lanes.values():
        if lane.name.startswith(':') or lane.length_m < 30.0:
            continue
        if best is None or lane.length_m > best.length_m:
            best = lane
    return best.id


def _drive_10_s(world):
    """
    Drive the car 10 s at 25 km/h, steering back onto the lane it is on.

    :return: (the lane ids it was on, step by step; the steps it was on no lane).
    """
    from vehicle_sim.webots import Driver
    with Driver(world_file=str(world)) as driver:
        driver.setCruisingSpeed(25.0)                # km/h
        steps = int(round(10.0 / (driver.getBasicTimeStep() / 1000.0)))
        lanes, off = [], 0
        for _ in range(steps):
            state = driver.getLaneState()
            if not state.on_lane:
                off += 1
            else:
                lanes.append(state.lane_id)
                steer = 0.4 * state.offset_m + 1.2 * state.heading_error_rad  # + = right
                driver.setSteeringAngle(max(-0.5, min(0.5, steer)))
            driver.step()
        return lanes, off


# -------------------------------------------------------------------------------- OpenDRIVE

def test_an_opendrive_file_is_converted_and_cached(tmp_path, xodr, conversions):
    graph = _loaded(tmp_path, 'opendrive', xodr)
    assert len(conversions) == 1 and conversions[0][1:3] == ['--opendrive-files', xodr]
    assert len(graph.lanes) > 100 and graph.rules.conflicts
    cached = sorted((tmp_path / 'cache').glob('*.net.xml'))
    assert len(cached) == 1 and not list((tmp_path / 'cache').glob('*.part'))
    again = _loaded(tmp_path, 'opendrive', xodr)
    assert len(conversions) == 1                        # the cache, no second run
    assert sorted(lane.name for lane in again.lanes.values()) == sorted(
        lane.name for lane in graph.lanes.values())
    _loaded(tmp_path, 'opendrive', xodr, options=['--no-turnarounds', 'true'])
    assert len(conversions) == 2                        # other options: converted anew
    assert conversions[1][-4:-2] == ['--no-turnarounds', 'true']
    assert len(list((tmp_path / 'cache').glob('*.net.xml'))) == 2


def test_another_content_of_the_same_file_is_converted_anew(tmp_path, xodr, conversions):
    copy = tmp_path / 'town.xodr'
    copy.write_text(Path(xodr).read_text(encoding='utf-8'), encoding='utf-8')
    _loaded(tmp_path, 'opendrive', copy)
    copy.write_text(Path(xodr).read_text(encoding='utf-8') + '\n', encoding='utf-8')
    _loaded(tmp_path, 'opendrive', copy)
    assert len(conversions) == 2


def test_a_car_placed_on_an_opendrive_lane_drives_10_s_on_the_lanes(tmp_path, xodr):
    graph = _loaded(tmp_path, 'opendrive', xodr)
    lane_id = _straight_start(graph)          # 20 m before a junction: through it
    world = _world(tmp_path, 'opendrive', xodr, pose={
        'lanelet': lane_id, 's': graph.lanes[lane_id].length_m - 20.0})
    lanes, off = _drive_10_s(world)
    assert off == 0
    assert lanes[0] == lane_id and len(set(lanes)) >= 2     # on through its successors
    for before, after in zip(lanes, lanes[1:]):
        assert after == before or after in graph.lanes[before].successors


@pytest.mark.parametrize('kind, suffix, text, says', [
    ('opendrive', '.xodr', 'garbage', 'invalid document structure'),
    ('opendrive', '.xodr', '<OpenDRIVE><header/></OpenDRIVE>', 'No nodes loaded'),
    ('osm', '.osm', '<osm version="0.6"><node id="1" lat="a" lon="b"/></osm>',
     "Attribute 'lon' in definition of node '1' Invalid Number Format"),
])
def test_a_file_netconvert_refuses_gives_its_message_naming_the_file(tmp_path, kind, suffix,
                                                                      text, says):
    bad = tmp_path / f'broken{suffix}'
    bad.write_text(text, encoding='utf-8')
    with pytest.raises(InvalidParameterError) as refused:
        _loaded(tmp_path, kind, bad)
    message = str(refused.value)
    assert message.startswith(f'{tmp_path / kind}_world.yaml: map.file: {bad}: netconvert '
                              'cannot convert it: Error: ')
    assert says in message
    assert not list((tmp_path / 'cache').glob('*'))          # nothing cached


def test_a_missing_file_and_an_output_option_are_refused_naming_the_key(tmp_path, xodr):
    with pytest.raises(InvalidParameterError, match=r'map.file: .*absent.xodr: no such file'):
        _loaded(tmp_path, 'opendrive', tmp_path / 'absent.xodr')
    with pytest.raises(InvalidParameterError, match=r"map: field 'options': '-o' sets "
                                                    r"netconvert's output"):
        _loaded(tmp_path, 'opendrive', xodr, options=['-o', 'elsewhere.net.xml'])


def test_without_the_sumo_extra_the_error_names_it(tmp_path, xodr, monkeypatch):
    monkeypatch.setitem(sys.modules, 'sumo', None)       # import sumo -> ImportError
    with pytest.raises(SumoUnavailable, match=r"pip install 'vehicle_sim\[sumo\]'"):
        _loaded(tmp_path, 'opendrive', xodr)
    monkeypatch.setitem(sys.modules, 'sumolib', None)
    net = grid_net(tmp_path)
    world = tmp_path / 'net_world.yaml'
    world.write_text(yaml.safe_dump({'vehicles': [{'name': 'Car'}],
                                     'map': {'type': 'sumo', 'net': net}}), encoding='utf-8')
    with pytest.raises(SumoUnavailable, match=r"sumolib package: pip install "
                                              r"'vehicle_sim\[sumo\]'"):
        with_lanes(load_world(str(world), 'ToyotaPrius'))


def test_the_default_cache_is_the_xdg_cache(tmp_path, monkeypatch):
    monkeypatch.setenv('XDG_CACHE_HOME', str(tmp_path / 'xdg'))
    assert netconvert.default_cache() == str(tmp_path / 'xdg' / 'vehicle_sim' / 'netconvert')


# -------------------------------------------------------------------------------------- OSM

def test_an_osm_extract_has_sidewalks_crossings_and_a_signal(tmp_path):
    graph = _loaded(tmp_path, 'osm', OSM)
    kinds = {}
    for area in graph.rules.areas:
        kinds.setdefault(area.kind, []).append(area)
    assert len(kinds['crosswalk']) == 5         # four guessed at the junction, the zebra
    assert len(kinds['walkway']) > 10           # sidewalks guessed, walking areas, footways
    assert all(area.lanes for area in kinds['crosswalk'])
    names = {lane.name.split('_')[0] for lane in graph.lanes.values()}
    assert {'100#0', '-100#0', '101#2', '-101#2'} <= names      # the streets, both ways
    assert not any(name.startswith(('102', '103')) for name in names)   # footways: no lanes
    (program,) = graph.rules.programs
    assert program.tls_id == '1' and graph.rules.groups
    assert graph.source.startswith(f'{tmp_path}/osm_world.yaml: map.file: {OSM} (converted '
                                   f'by netconvert into {tmp_path}/cache/')
    north = graph.lane_named('101#2_1')                # _0: its sidewalk
    assert north.speed_limit_mps == pytest.approx(50 / 3.6, abs=0.01)


def test_an_osm_world_runs_its_signal_and_a_car_drives_10_s_on_it(tmp_path):
    from vehicle_sim.physics.scene import build_scene
    graph = _loaded(tmp_path, 'osm', OSM)
    world = _world(tmp_path, 'osm', OSM, pose={'lane': '101#0_1', 's': 70.0})
    scene = build_scene(load_world(str(world), 'ToyotaPrius'))
    try:
        assert isinstance(scene.parts['signals'].controller, ProgramController)
    finally:
        scene.world.close()
    lanes, off = _drive_10_s(world)
    assert off == 0
    assert graph.lanes[lanes[0]].name == '101#0_1' and len(set(lanes)) >= 2
    for before, after in zip(lanes, lanes[1:]):
        assert after == before or after in graph.lanes[before].successors


# ------------------------------------------------------------------------------ at the node

@pytest.mark.transport
@pytest.mark.parametrize('kind, name, text, says', [
    ('opendrive', 'town.xodr', 'garbage', 'netconvert cannot convert it: Error: invalid '
                                          'document structure'),
    ('sumo', 'city.net.xml', '<net><edge', 'not a SUMO network that sumolib can read'),
])
def test_a_bad_network_stops_the_node_at_start_naming_the_file(tmp_path, kind, name, text,
                                                               says):
    from automobile_helpers import NodeProcess
    bad = tmp_path / name
    bad.write_text(text, encoding='utf-8')
    world = tmp_path / 'bad_world.yaml'
    key = 'net' if kind == 'sumo' else 'file'
    world_map = {'type': kind, key: name}
    if kind != 'sumo':
        world_map['cache'] = str(tmp_path / 'cache')
    world.write_text(yaml.safe_dump({'vehicles': [{'name': 'car'}], 'map': world_map}),
                     encoding='utf-8')
    process = NodeProcess('--ros-args', '-r', '__ns:=/bad_network', '-p', f'world:={world}')
    try:
        status = process.wait()
    finally:
        process.stop()
    output = process.text()
    assert status == 2, output
    assert 'ready' not in output and 'Traceback' not in output, output
    assert f'{world}: map.{key}: {bad}: {says}' in output, output


def test_the_cache_key_changes_with_netconverts_version_and_the_options(tmp_path, xodr):
    from vehicle_sim.core.map.kinds import map_from_dict
    spec = map_from_dict({'type': 'opendrive', 'file': xodr}, 'w.yaml: map')
    other = map_from_dict({'type': 'opendrive', 'file': xodr, 'options': ['--a', 'b']},
                          'w.yaml: map')
    version = netconvert.netconvert_version()
    assert version.startswith('Eclipse SUMO netconvert ')
    keys = {netconvert.cache_key(spec, version), netconvert.cache_key(spec, version + '.1'),
            netconvert.cache_key(other, version)}
    assert len(keys) == 3 and netconvert.cache_key(spec, version) in keys
