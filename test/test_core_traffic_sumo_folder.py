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

"""A Webots project's SUMO folder is read as Webots' SUMO interface reads it (sumo_folder.py)."""

import pytest

from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.traffic.sumo_folder import read_sumo_folder, with_sumo_folder

CONFIG = ('<?xml version="1.0" encoding="UTF-8"?>\n<configuration>\n  <input>\n'
          '    <net-file value="{net}"/>\n    <route-files value="{routes}"/>\n  </input>\n'
          '  <time><begin value="0"/></time>\n</configuration>\n')


def _folder(tmp_path, files, config=None, name='sumo.sumocfg'):
    folder = tmp_path / 'my_world_net'
    folder.mkdir()
    for file in files:
        (folder / file).write_text('<net/>', encoding='utf-8')
    if config is not None:
        (folder / name).write_text(CONFIG.format(**config), encoding='utf-8')
    return folder


def test_the_sumocfg_names_the_network_and_the_routes(tmp_path):
    folder = _folder(tmp_path, ['sumo.net.xml', 'sumo.rou.xml', 'sumo.flow.rou.xml'],
                     {'net': 'sumo.net.xml', 'routes': 'sumo.rou.xml,sumo.flow.rou.xml'})
    found = read_sumo_folder(str(folder))
    assert found.net == str(folder / 'sumo.net.xml')
    assert found.routes == (str(folder / 'sumo.rou.xml'), str(folder / 'sumo.flow.rou.xml'))
    assert found.config == str(folder / 'sumo.sumocfg')


def test_another_sumocfg_is_read_when_there_is_no_sumo_sumocfg(tmp_path):
    folder = _folder(tmp_path, ['city.net.xml', 'trips.rou.xml'],
                     {'net': 'city.net.xml', 'routes': 'trips.rou.xml'}, name='city.sumocfg')
    found = read_sumo_folder(str(folder))
    assert (found.net, found.routes) == (str(folder / 'city.net.xml'),
                                         (str(folder / 'trips.rou.xml'),))


def test_without_a_sumocfg_the_folder_gives_sumo_net_xml_and_sumo_rou_xml(tmp_path):
    folder = _folder(tmp_path, ['sumo.net.xml', 'sumo.rou.xml'])
    found = read_sumo_folder(str(folder))
    assert (found.net, found.routes, found.config) == (
        str(folder / 'sumo.net.xml'), (str(folder / 'sumo.rou.xml'),), '')
    (folder / 'sumo.rou.xml').unlink()
    assert read_sumo_folder(str(folder)).routes == ()


def test_a_folder_without_its_network_is_refused_naming_the_file_and_netconvert(tmp_path):
    folder = _folder(tmp_path, ['sumo.rou.xml', 'sumo.netccfg'])
    with pytest.raises(InvalidParameterError,
                       match=r'no SUMO network .*sumo\.net\.xml .*netconvert -c sumo\.netccfg'):
        read_sumo_folder(str(folder))


def test_missing_route_files_a_missing_folder_and_a_broken_config_are_refused(tmp_path):
    folder = _folder(tmp_path, ['sumo.net.xml'], {'net': 'sumo.net.xml', 'routes': 'gone.rou.xml'})
    with pytest.raises(InvalidParameterError, match=r'route file\(s\) that do not exist: .*gone'):
        read_sumo_folder(str(folder))
    with pytest.raises(InvalidParameterError, match=r"'.*nowhere_net' is not a folder"):
        read_sumo_folder(str(tmp_path / 'nowhere_net'))
    (folder / 'sumo.sumocfg').write_text('<configuration><input>', encoding='utf-8')
    with pytest.raises(InvalidParameterError, match=r'cannot read .*sumo\.sumocfg'):
        read_sumo_folder(str(folder))


def test_the_world_key_becomes_the_map_and_the_routes_and_refuses_a_non_folder(tmp_path):
    folder = _folder(tmp_path, ['sumo.net.xml', 'sumo.rou.xml'],
                     {'net': 'sumo.net.xml', 'routes': 'sumo.rou.xml'})
    data = {'vehicles': [{'name': 'Car'}], 'sumo_folder': folder.name,
            'traffic': {'seed': 4, 'demand': {'vehicles_per_hour': 60}}}
    expanded = with_sumo_folder(data, 'w.yaml: sumo_folder', str(tmp_path))
    assert expanded == {'vehicles': [{'name': 'Car'}],
                        'map': {'type': 'sumo', 'net': str(folder / 'sumo.net.xml')},
                        'traffic': {'engine': 'sumo', 'seed': 4,
                                    'demand': {'vehicles_per_hour': 60},
                                    'routes': [str(folder / 'sumo.rou.xml')]}}
    assert 'map' not in data                       # the world's mapping is left as it was
    for value in (3, '', ['my_world_net']):
        with pytest.raises(InvalidParameterError,
                           match=r'w\.yaml: sumo_folder: must be a folder name .* not '):
            with_sumo_folder({'sumo_folder': value}, 'w.yaml: sumo_folder', str(tmp_path))
