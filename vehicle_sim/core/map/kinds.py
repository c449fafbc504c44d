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
The world file's ``map:`` key: one registry of map kinds, dispatched by ``type``.

A map kind is a :class:`MapKind` row in :data:`MAP_KINDS`: its ``type`` name, the ParamSpec
table of its keys (besides the keys every map has, :data:`COMMON_MAP_SPECS`) and the function
that turns the validated values into its spec. :func:`map_from_dict` validates a world's
``map:`` mapping against the table of its ``type`` and returns that spec; the physics layer
(``physics/map_layer.py``) has a builder registered under the same name, the ROS layer
(``ros/map_interfaces.py``) its topic rows, and a lane map its loader
(``maps/lane_maps.py``); test/test_repo_kind_registries.py checks that they agree. Kinds:
``occupancy_grid``, ``lanelet2`` (core/map/lanelet2_params.py's keys), and the SUMO road networks
``sumo``, ``opendrive`` and ``osm`` (core/map/sumo_net_params.py's keys); the ``roads:`` key of a
world is a lane map without a ``map:`` (core/map/road_segments.py).

Every map spec carries ``type``, ``world_in_map`` (:class:`MapPlacement`: the map -> world
transform, identity unless the world file says otherwise) and ``source`` (where it was
written, quoted in errors). File names are resolved against the world file's folder; nothing
here reads a file.
"""

from dataclasses import dataclass
import math
import os
from typing import Callable, Dict, Tuple

from vehicle_sim.core.geometry.frames import Pose
from vehicle_sim.core.map.grid_rays import (
    compiled_march_installed,
    FAST_EXTRA_HINT,
    RAY_MARCHES,
)
from vehicle_sim.core.map.lanelet2_params import LANELET2_SPECS, Lanelet2MapSpec
from vehicle_sim.core.map.sumo_net_params import (
    NETCONVERT_SPECS,
    OPENDRIVE_INPUT,
    OSM_INPUT,
    SUMO_NET_SPECS,
    SumoNetMapSpec,
)
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.param_spec import ParamSpec, REQUIRED, validate_table
from vehicle_sim.core.specs.registry import register
from vehicle_sim.core.specs.value_text import brief


@dataclass(frozen=True)
class MapPlacement:
    """
    The pose of the ``world`` frame in the ``map`` frame (the map -> world transform).

    :param x_m: x of the world origin in the map frame [m]; likewise ``y_m``.
    :param yaw_rad: yaw of the world frame's x axis in the map frame [rad].
    """

    x_m: float = 0.0
    y_m: float = 0.0
    yaw_rad: float = 0.0

    @property
    def identity(self) -> bool:
        return self.x_m == 0.0 and self.y_m == 0.0 and self.yaw_rad == 0.0

    def to_map(self, x_m: float, y_m: float) -> Tuple[float, float]:
        """Return a world-frame point in the map frame."""
        c, s = math.cos(self.yaw_rad), math.sin(self.yaw_rad)
        return self.x_m + c * x_m - s * y_m, self.y_m + s * x_m + c * y_m

    def to_world(self, x_m: float, y_m: float) -> Tuple[float, float]:
        """Return a map-frame point in the world frame."""
        c, s = math.cos(self.yaw_rad), math.sin(self.yaw_rad)
        dx, dy = x_m - self.x_m, y_m - self.y_m
        return c * dx + s * dy, -s * dx + c * dy


COMMON_MAP_SPECS = (
    ParamSpec('type', 'type', 'str', REQUIRED, '',
              'the map kind, a name of MAP_KINDS: occupancy_grid, lanelet2, sumo, opendrive, '
              'osm'),
    ParamSpec('world_in_map', 'world_in_map', 'pose', Pose(), 'm, rad',
              'pose {x, y, yaw} of the world frame in the map frame (the map -> world '
              'transform on /tf_static); default identity', choices=('x', 'y', 'yaw')),
)

UNKNOWN_CHOICES = ('free', 'occupied')

OCCUPANCY_GRID_SPECS = COMMON_MAP_SPECS + (
    ParamSpec('file', 'file', 'str', REQUIRED, '',
              "the map's YAML file (nav2 map_server's format), relative to the world file"),
    ParamSpec('wall_height', 'wall_height_m', 'float', 1.0, 'm',
              'height of the walls built on occupied cells', gt=0.0, le=100.0),
    ParamSpec('unknown', 'unknown', 'enum', 'free', '',
              'what unknown cells (-1) are: free (no wall) or occupied (a wall)',
              choices=UNKNOWN_CHOICES),
    ParamSpec('ray_march', 'ray_march', 'enum', 'auto', '',
              'how lidar and distance sensors find the walls over the grid: compiled (numba, '
              'the fast extra), numpy, or auto (compiled where numba imports); the same hits',
              choices=RAY_MARCHES),
)


@dataclass(frozen=True)
class OccupancyMapSpec:
    """
    An occupancy-grid map of a world file (``type: occupancy_grid``).

    :param file: the map YAML's path, resolved against the world file's folder.
    :param wall_height_m: height of the walls on occupied cells [m].
    :param unknown: 'free' or 'occupied': what an unknown cell is.
    :param ray_march: which march finds the walls for rays (core/map/grid_rays.py's
        RAY_MARCHES).
    """

    type: str
    world_in_map: MapPlacement
    file: str
    wall_height_m: float = 1.0
    unknown: str = 'free'
    source: str = ''
    ray_march: str = 'auto'


def _placement(pose: Pose) -> MapPlacement:
    return MapPlacement(pose.x_m, pose.y_m, pose.yaw_rad)


def _resolved(base_dir, name):
    return os.path.normpath(os.path.join(base_dir, name))


def _occupancy_grid(values, source, base_dir) -> OccupancyMapSpec:
    if values['ray_march'] == 'compiled' and not compiled_march_installed():
        raise InvalidParameterError(
            f"{source}: field 'ray_march' = 'compiled' needs numba, which is not installed: "
            f'{FAST_EXTRA_HINT}')
    return OccupancyMapSpec(values['type'], _placement(values['world_in_map']),
                            _resolved(base_dir, values['file']), values['wall_height_m'],
                            values['unknown'], source, values['ray_march'])


LANELET2_MAP_SPECS = COMMON_MAP_SPECS + tuple(s for s in LANELET2_SPECS if s.key != 'type')


def _lanelet2(values, source, base_dir) -> Lanelet2MapSpec:
    placement = _placement(values['world_in_map'])
    if not placement.identity:
        # The projector and the world's origin put the nodes in the world frame (docs/maps.md).
        raise InvalidParameterError(
            f"{source}: field 'world_in_map' must be the identity for a lanelet2 map (its "
            'projector and the world origin place the nodes in the world frame, which is the '
            "map frame); choose the projector and 'origin' instead")
    return Lanelet2MapSpec(values['type'], _resolved(base_dir, values['file']),
                           values['projector'], values['default_speed_limit_mps'], placement,
                           source)


SUMO_MAP_SPECS = COMMON_MAP_SPECS + SUMO_NET_SPECS
NETCONVERT_MAP_SPECS = COMMON_MAP_SPECS + NETCONVERT_SPECS


def _network_placement(values, source):
    placement = _placement(values['world_in_map'])
    if not placement.identity:
        # A network's x, y are metres of its own plane: the world frame (docs/maps.md).
        raise InvalidParameterError(
            f"{source}: field 'world_in_map' must be the identity for a {values['type']} map "
            "(the network's coordinates are the world frame, which is the map frame)")
    return placement


def _sumo(values, source, base_dir) -> SumoNetMapSpec:
    return SumoNetMapSpec(values['type'], _network_placement(values, source),
                          net=_resolved(base_dir, values['net']), vclass=values['vclass'],
                          source=source)


def _netconvert(netconvert_input):
    option, defaults = netconvert_input

    def make(values, source, base_dir) -> SumoNetMapSpec:
        cache = values['cache']
        return SumoNetMapSpec(values['type'], _network_placement(values, source),
                              file=_resolved(base_dir, values['file']),
                              vclass=values['vclass'], options=tuple(values['options'] or ()),
                              cache=_resolved(base_dir, cache) if cache else '',
                              netconvert_input=option, netconvert_options=defaults,
                              source=source)
    return make


@dataclass(frozen=True)
class MapKind:
    """
    One kind of map: its ``type`` name, its key table and its spec maker.

    :param name: the ``type`` value in world files.
    :param specs: the ParamSpec table of its keys (:data:`COMMON_MAP_SPECS` included).
    :param make: ``make(values, source, base_dir)`` -> the kind's spec (values validated).
    :param doc: one line for docs/maps.md.
    :param lane_map: the map is a lane map: the world's one (no ``roads:`` beside it), read
        before any body by its loader in ``maps/lane_maps.py``'s ``LANE_LOADERS``; its nodes
        lie in the map frame, which is the world frame (``make`` refuses another
        ``world_in_map``), so the lane messages and objects are stamped ``map``.
    """

    name: str
    specs: Tuple[ParamSpec, ...]
    make: Callable
    doc: str = ''
    lane_map: bool = False


MAP_KINDS: Dict[str, MapKind] = {}


def register_map_kind(kind: MapKind) -> MapKind:
    """Add a map kind to :data:`MAP_KINDS` (its name must be new)."""
    return register(MAP_KINDS, kind, 'map kind')


register_map_kind(MapKind('occupancy_grid', OCCUPANCY_GRID_SPECS, _occupancy_grid,
                          'a nav2 map_server map (YAML + PGM/PNG image): walls on occupied '
                          'cells, /map'))
register_map_kind(MapKind('lanelet2', LANELET2_MAP_SPECS, _lanelet2,
                          'a Lanelet2 .osm lane map: road surface and markings, curbstones and '
                          'walls, lane state, /map/lanes', lane_map=True))
register_map_kind(MapKind('sumo', SUMO_MAP_SPECS, _sumo,
                          'a SUMO network (.net.xml): lanes through junctions, signal programs, '
                          'sidewalks and crossings; lane state, /map/lanes', lane_map=True))
register_map_kind(MapKind('opendrive', NETCONVERT_MAP_SPECS, _netconvert(OPENDRIVE_INPUT),
                          'an OpenDRIVE file (.xodr), converted by netconvert into a SUMO '
                          'network', lane_map=True))
register_map_kind(MapKind('osm', NETCONVERT_MAP_SPECS, _netconvert(OSM_INPUT),
                          'an OpenStreetMap extract (.osm), converted by netconvert into a SUMO '
                          'network (sidewalks and crossings guessed)', lane_map=True))


def is_lane_map(map_spec) -> bool:
    """Return whether a world's map spec (None: no map) is a lane map (``MapKind.lane_map``)."""
    return map_spec is not None and MAP_KINDS[map_spec.type].lane_map


def map_from_dict(data, source, base_dir=''):
    """
    Validate a world's ``map:`` mapping against the table of its ``type``.

    :param data: the mapping (None: no map).
    :param source: where it is written ('world.yaml: map'), quoted in errors.
    :param base_dir: folder the map's files are resolved in (the world file's).
    :return: the kind's spec (e.g. :class:`OccupancyMapSpec`), or None.
    :raises InvalidParameterError: naming the source and the field.
    """
    if data is None:
        return None
    if not isinstance(data, dict):
        raise InvalidParameterError(f'{source}: must be a mapping with a "type", got '
                                    f'{brief(data)}')
    kind_name = data.get('type', REQUIRED)
    if not isinstance(kind_name, str) or kind_name not in MAP_KINDS:
        what = 'is required' if kind_name is REQUIRED else f'= {brief(kind_name)}: unknown'
        raise InvalidParameterError(f"{source}: field 'type' {what}; valid: "
                                    + ', '.join(sorted(MAP_KINDS)))
    kind = MAP_KINDS[kind_name]
    values = validate_table(kind.specs, data, source, what='a map')
    return kind.make(values, source, base_dir)
