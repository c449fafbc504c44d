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
A Webots project's SUMO folder (``<world>_net/``), read as Webots' SUMO interface reads it.

Webots' ``SumoInterface`` (its ``sumo_supervisor`` controller) starts SUMO with the folder's
``sumo.sumocfg``, or, when there is none, with the one other ``*.sumocfg`` of the folder (the
first by name when there are several); that configuration names the network (``net-file``) and
the routes (``route-files``), relative to the configuration's folder. A folder without any
``.sumocfg`` is read here as ``sumo.net.xml`` and, when it exists, ``sumo.rou.xml``.

:func:`read_sumo_folder` returns the files; with the world key ``sumo_folder:``
(core/world/params.py), :func:`with_sumo_folder` makes them the world's map (``{type: sumo,
net: ...}``) and its SUMO traffic's ``routes`` (docs/sumo.md, "Webots users"). Webots'
``useNetconvert`` (a network made at start from ``sumo.netccfg``) is not repeated: the folder
needs its ``.net.xml`` (``netconvert -c sumo.netccfg`` makes it, as Webots would). The standard
library only (xml.etree).
"""

from dataclasses import dataclass
import os
from typing import Tuple
import xml.etree.ElementTree as ElementTree

from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.traffic.sumo_params import ENGINE

KEY = 'sumo_folder'          # the world key (core/world/params.py)
CONFIG = 'sumo.sumocfg'
NET = 'sumo.net.xml'
ROUTES = 'sumo.rou.xml'


@dataclass(frozen=True)
class SumoFolder:
    """The files of a Webots SUMO folder: its network, its route files, its configuration."""

    folder: str
    net: str
    routes: Tuple[str, ...] = ()
    config: str = ''           # the .sumocfg read, '' when the folder has none


def _config_of(folder):
    if os.path.isfile(os.path.join(folder, CONFIG)):
        return os.path.join(folder, CONFIG)
    others = sorted(name for name in os.listdir(folder) if name.endswith('.sumocfg'))
    return os.path.join(folder, others[0]) if others else ''


def _values(root, key):
    # <input><net-file value="a.net.xml"/></input>, or the key at the top; a value may list
    # several files, comma- or space-separated (SUMO's file lists)
    found = root.find(f'input/{key}')
    if found is None:
        found = root.find(key)
    if found is None:
        return ()
    return tuple(part for part in found.get('value', '').replace(',', ' ').split() if part)


def _read_config(config, where):
    try:
        root = ElementTree.parse(config).getroot()
    except (ElementTree.ParseError, OSError) as error:
        raise InvalidParameterError(f'{where}: cannot read {config}: {error}') from None
    base = os.path.dirname(config)
    nets = _values(root, 'net-file')
    if len(nets) != 1:
        raise InvalidParameterError(f'{where}: {config} names {len(nets)} net-file(s); a '
                                    'world needs exactly one SUMO network')
    routes = _values(root, 'route-files')
    return (os.path.normpath(os.path.join(base, nets[0])),
            tuple(os.path.normpath(os.path.join(base, r)) for r in routes))


def read_sumo_folder(folder, where='sumo_folder') -> SumoFolder:
    """
    Return the network and route files of a Webots SUMO folder.

    :param folder: the folder (resolved by the caller).
    :param where: quoted in errors.
    :raises InvalidParameterError: naming the folder or the missing file.
    """
    if not os.path.isdir(folder):
        raise InvalidParameterError(f'{where}: {folder!r} is not a folder (a Webots project '
                                    "keeps its SUMO files in '<world>_net/')")
    config = _config_of(folder)
    if config:
        net, routes = _read_config(config, where)
    else:
        net = os.path.join(folder, NET)
        routes = (os.path.join(folder, ROUTES),) if os.path.isfile(
            os.path.join(folder, ROUTES)) else ()
    if not os.path.isfile(net):
        made = (' (Webots makes it with netconvert -c sumo.netccfg: run that once)'
                if os.path.isfile(os.path.join(folder, 'sumo.netccfg')) else '')
        raise InvalidParameterError(f'{where}: no SUMO network {net}{made}')
    missing = [route for route in routes if not os.path.isfile(route)]
    if missing:
        raise InvalidParameterError(f'{where}: {config or folder} names route file(s) that do '
                                    f'not exist: {", ".join(missing)}')
    return SumoFolder(folder, net, routes, config)


def with_sumo_folder(data, where, base_dir):
    """
    Return a world mapping whose ``sumo_folder:`` became its ``map:`` and its SUMO ``traffic:``.

    ``map: {type: sumo, net: <the folder's network>}``; ``traffic:`` the world's (engine sumo by
    default: its step, seed, demand, options stay) with ``routes`` the folder's route files.
    A world that also gives ``map:``, another engine or ``routes:`` is refused: the folder
    gives them.

    :param data: the world mapping, with the key ``sumo_folder`` (a folder, relative to
        ``base_dir``).
    :param where: quoted in errors (the world file and the key).
    :raises InvalidParameterError: naming the key and what is wrong.
    """
    folder = data[KEY]
    if not isinstance(folder, str) or not folder:
        raise InvalidParameterError(f"{where}: must be a folder name (a Webots project's "
                                    f"'<world>_net'), not {folder!r}")
    for key in ('map',):
        if data.get(key) is not None:
            raise InvalidParameterError(f'{where}: the folder gives the map: leave out {key}:')
    traffic = data.get('traffic') or {}
    if not isinstance(traffic, dict):
        raise InvalidParameterError(f'{where}: traffic: must be a mapping beside it')
    if traffic.get('engine', ENGINE) != ENGINE:
        raise InvalidParameterError(f"{where}: the folder's traffic runs on the engine "
                                    f"{ENGINE}, not {traffic.get('engine')!r}")
    if traffic.get('routes') is not None:
        raise InvalidParameterError(f'{where}: the folder gives the routes: leave out '
                                    'traffic.routes (a demand: may add random trips)')
    found = read_sumo_folder(os.path.join(base_dir, folder), where)
    expanded = {key: value for key, value in data.items() if key != KEY}
    expanded['map'] = {'type': 'sumo', 'net': found.net}
    expanded['traffic'] = dict(traffic, engine=ENGINE, routes=list(found.routes) or None)
    return expanded
