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
The keys of the SUMO road network lane maps: ``sumo``, ``opendrive`` and ``osm``.

- ``map: {type: sumo, net: city.net.xml}``: a SUMO network, read with sumolib
  (``vehicle_sim/maps/sumo_net.py``);
- ``map: {type: opendrive, file: town.xodr}`` and ``map: {type: osm, file: area.osm}``: an
  OpenDRIVE file or an OpenStreetMap extract, converted into a SUMO network by the
  ``netconvert`` of the ``eclipse-sumo`` package (``vehicle_sim/maps/netconvert.py``) with
  :data:`NETCONVERT_INPUTS`' options and the world's ``options:``, cached, then read as a SUMO
  network.

Only the tables, the options and the spec live here (ROS-free, file-free). The network's
coordinates are the world frame (the ``map`` frame, as a lanelet2 map's): ``world_in_map`` must
stay the identity.
"""

from dataclasses import dataclass
from typing import Any, Tuple

from vehicle_sim.core.specs.param_spec import ParamSpec, REQUIRED

# SUMO's vehicle classes (its "abstract vehicle classes", sumolib.net's SUMO_VEHICLE_CLASSES
# less the pedestrian): the lanes of the ``vclass`` key are the lanes the traffic drives.
VEHICLE_CLASSES = ('private', 'emergency', 'authority', 'army', 'vip', 'passenger', 'hov',
                   'taxi', 'bus', 'coach', 'delivery', 'truck', 'trailer', 'tram', 'rail_urban',
                   'rail', 'rail_electric', 'rail_fast', 'motorcycle', 'moped', 'bicycle',
                   'evehicle', 'ship', 'container', 'cable_car', 'subway', 'aircraft',
                   'wheelchair', 'scooter', 'drone', 'custom1', 'custom2')

SUMO_COMMON_SPECS = (
    ParamSpec('vclass', 'vclass', 'enum', 'passenger', choices=VEHICLE_CLASSES,
              doc="the SUMO vehicle class whose lanes are the traffic's lanes (subtype road); "
                  'the other road-like lanes are lanes of their subtype (bicycle_lane, '
                  'bus_lane, ...)'),
)

SUMO_NET_SPECS = (
    ParamSpec('net', 'net', 'str', REQUIRED,
              doc='the SUMO network (.net.xml, also gzipped), relative to the world file'),
) + SUMO_COMMON_SPECS

NETCONVERT_SPECS = (
    ParamSpec('file', 'file', 'str', REQUIRED,
              doc='the file netconvert converts, relative to the world file'),
    ParamSpec('options', 'options', 'str_list', None, optional=True,
              doc="more netconvert options, after the map's own (e.g. ['--no-turnarounds', "
                  "'true']); a value is its own entry"),
    ParamSpec('cache', 'cache', 'str', '', empty=True,
              doc="the folder of converted networks, relative to the world file; '' = "
                  '$XDG_CACHE_HOME/vehicle_sim/netconvert (~/.cache/...)'),
) + SUMO_COMMON_SPECS

# netconvert's input option and its default options, by input format (the map kinds opendrive
# and osm, core/map/kinds.py): sidewalks and crossings guessed from OSM's ways, and traffic
# lights where OSM has them (joined at a junction); OpenDRIVE files have their own.
OPENDRIVE_INPUT = ('--opendrive-files', (
    '--opendrive.internal-shapes', 'true',
))
OSM_INPUT = ('--osm-files', (
    '--geometry.remove', 'true', '--ramps.guess', 'true', '--junctions.join', 'true',
    '--tls.guess-signals', 'true', '--tls.discard-simple', 'true', '--tls.join', 'true',
    '--sidewalks.guess', 'true', '--crossings.guess', 'true',
    '--osm.sidewalks', 'true', '--osm.crossings', 'true',
))
# Every conversion: internal lanes (the connections through junctions), no warnings' flood.
NETCONVERT_ALWAYS = ('--no-internal-links', 'false', '--no-warnings', 'true')


@dataclass(frozen=True)
class SumoNetMapSpec:
    """
    A validated ``map:`` of a SUMO network kind (sumo, opendrive, osm).

    :param type: the kind.
    :param world_in_map: the identity MapPlacement.
    :param net: the ``.net.xml`` file (kind sumo), resolved; '' for a converted one.
    :param file: the file netconvert converts (opendrive, osm), resolved; '' for sumo.
    :param vclass: the SUMO vehicle class of the traffic's lanes.
    :param options: the world's extra netconvert options.
    :param cache: the cache folder, resolved ('' = the XDG default).
    :param netconvert_input: netconvert's input option for ``file`` ('' for sumo).
    :param netconvert_options: the kind's own netconvert options (before ``options``).
    :param source: where it was written, quoted in errors.
    """

    type: str
    world_in_map: Any
    net: str = ''
    file: str = ''
    vclass: str = 'passenger'
    options: Tuple[str, ...] = ()
    cache: str = ''
    netconvert_input: str = ''
    netconvert_options: Tuple[str, ...] = ()
    source: str = ''

    @property
    def field(self) -> str:
        """The key that names its file ('net' or 'file'), for errors."""
        return 'net' if self.net else 'file'
