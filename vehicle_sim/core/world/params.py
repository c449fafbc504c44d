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
World files: geodetic origin, vehicles (with their sensors) and obstacles, validated.

The form (every key optional except ``vehicles``)::

    origin: {latitude: 48.0, longitude: 11.0, altitude: 500.0}
    vehicles:
      - {name: Car, namespace: '', model: ToyotaPrius, pose: {x: 0.0, y: 0.0, yaw: 0.0},
         sensors: [...]}
    obstacles:
      - {name: wall, shape: box, size: [1.0, 6.0, 2.0], position: [20.0, 0.0, 1.0], yaw: 0.0}
    roads:        # lanes from road segments: core/map/road_segments.py
      - {lanes: 2, segments: [{type: straight, length: 200.0}]}
    map: {type: occupancy_grid, file: maps/track.yaml}
    traffic: {vehicles: 20, seed: 1}   # vehicles on the lanes: core/traffic/params.py
    signals: {green: 20.0}             # the traffic lights' plan: core/map/signal_params.py


Each mapping is checked against a ParamSpec table (core/specs/param_spec.py), so an unknown key, a
wrong type, a NaN or an impossible value is refused with the file, the entry and the field. Reading
the file and resolving car models are config.py's (this module touches no file).
"""

from dataclasses import dataclass, field, replace
import os
from typing import Callable, Dict, Optional, Sequence, Tuple, Union

from vehicle_sim.core.car.kinematic_models import vehicle_model_from, VehicleModelParams
from vehicle_sim.core.geometry.frames import Pose
from vehicle_sim.core.geometry.geodesy import GeodeticOrigin
from vehicle_sim.core.map.kinds import is_lane_map, map_from_dict
from vehicle_sim.core.map.lane_placement import is_lane_pose, lane_pose_values
from vehicle_sim.core.map.road_segments import roads_from_list, RoadSpec
from vehicle_sim.core.map.signal_params import signals_from_dict, SignalSpec
from vehicle_sim.core.sensors.sensor_spec import SensorSpec
from vehicle_sim.core.sensors.sets import merge_sensors
from vehicle_sim.core.specs.errors import InvalidParameterError, InvalidPoseError
from vehicle_sim.core.specs.param_spec import (
    parameter_table_markdown,
    ParamSpec,
    REQUIRED,
    validate_table,
)
from vehicle_sim.core.specs.registry import register
from vehicle_sim.core.specs.value_text import brief
from vehicle_sim.core.traffic import sumo_folder
from vehicle_sim.core.traffic.engines import traffic_spec_from_dict
from vehicle_sim.core.traffic.params import TrafficSpec
from vehicle_sim.core.traffic.sumo_params import SumoTrafficSpec
from vehicle_sim.core.world.placement import check_in_world

WORLD_KEYS = ('origin', 'vehicles', 'obstacles', 'roads', 'map', 'traffic', 'signals')

ORIGIN_SPECS = (
    ParamSpec('latitude', 'latitude_deg', 'float', 0.0, 'deg', 'WGS-84 latitude of the world '
              'origin', ge=-90.0, le=90.0),
    ParamSpec('longitude', 'longitude_deg', 'float', 0.0, 'deg', 'longitude of the world origin',
              ge=-180.0, le=180.0),
    ParamSpec('altitude', 'altitude_m', 'float', 0.0, 'm',
              'height of the world origin above the WGS-84 ellipsoid'),
)

@dataclass(frozen=True)
class ObstacleShape:
    """
    One obstacle shape of world files: its name, default colour, size keys and extents.

    :param name: the ``shape`` value in world files.
    :param color_rgba: its default colour (so that the kinds tell apart in camera images).
    :param size_specs: the ParamSpec rows of its size keys.
    :param extents: ``extents(values)`` -> its full extent [x, y, z] [m] from the validated
        values (``ObstacleSpec.size_m``).
    """

    name: str
    color_rgba: Tuple[float, float, float, float]
    size_specs: Tuple[ParamSpec, ...]
    extents: Callable

    @property
    def specs(self) -> Tuple[ParamSpec, ...]:
        """The ParamSpec table of an obstacle of this shape: the common keys, then its size."""
        return _obstacle_common(self.name, self.color_rgba) + self.size_specs


# The core registration of obstacle shapes: shape name -> ObstacleShape. Each layer registers
# its part under these names (core/geometry/footprint.py OBSTACLE_FOOTPRINTS,
# physics/obstacles.py OBSTACLE_GEOMETRY, foxglove/scene.py PRIMITIVE_OF_SHAPE,
# ros/traffic_messages.py OBJECT_SHAPE_OF_OBSTACLE); test/test_repo_kind_registries.py checks
# that they agree.
OBSTACLE_SHAPES: Dict[str, ObstacleShape] = {}


def register_obstacle_shape(shape: ObstacleShape) -> ObstacleShape:
    """Add an obstacle shape to :data:`OBSTACLE_SHAPES` (its name must be new)."""
    return register(OBSTACLE_SHAPES, shape, 'obstacle shape')


def _obstacle_common(shape, color_rgba):
    return (
        ParamSpec('name', 'name', 'ros_name', REQUIRED,
                  doc='unique name; the "other" of collision events'),
        ParamSpec('shape', 'shape', 'enum', shape, choices=(shape,),
                  doc='the shape (its size keys: the table of its name below)'),
        ParamSpec('position', 'position_m', 'floats', REQUIRED, 'm',
                  'centre of the shape in the world [x, y, z]', length=3),
        ParamSpec('roll', 'roll_rad', 'float', 0.0, 'rad', 'rotation about x'),
        ParamSpec('pitch', 'pitch_rad', 'float', 0.0, 'rad', 'rotation about y'),
        ParamSpec('yaw', 'yaw_rad', 'float', 0.0, 'rad', 'rotation about z (+ = left)'),
        ParamSpec('mass', 'mass_kg', 'float', 0.0, 'kg', '0 = static (fixed in the world)',
                  ge=0.0),
        ParamSpec('color', 'color_rgba', 'rgba', color_rgba, '',
                  '[red, green, blue, alpha] in [0, 1]'),
    )


def _round_extents(values):
    # a cylinder's or sphere's bounding extents: its diameter across, its height (or diameter)
    diameter = 2.0 * values['radius_m']
    return (diameter, diameter, values.get('height_m') or diameter)


_COMMON_KEYS = ('name', 'shape', 'position', 'roll', 'pitch', 'yaw', 'mass', 'color')
_RADIUS = ParamSpec('radius', 'radius_m', 'float', REQUIRED, 'm', 'radius', gt=0.0)

register_obstacle_shape(ObstacleShape(
    'box', (0.75, 0.3, 0.2, 1.0),                       # brick red
    (ParamSpec('size', 'size_m', 'vec3', REQUIRED, 'm', 'extents [x, y, z]', gt=0.0),),
    lambda values: values['size_m']))
register_obstacle_shape(ObstacleShape(
    'cylinder', (0.95, 0.6, 0.1, 1.0),                  # orange, like a traffic pole
    (_RADIUS, ParamSpec('height', 'height_m', 'float', REQUIRED, 'm', 'length along its z axis',
                        gt=0.0)),
    _round_extents))
register_obstacle_shape(ObstacleShape(
    'sphere', (0.2, 0.4, 0.85, 1.0),                    # blue
    (_RADIUS,), _round_extents))


def obstacles_markdown():
    """Return the key tables of the obstacles in docs/sensors.md: common keys, then per shape."""
    shown = {'color': {'default': 'per shape'},
             'shape': {'default': REQUIRED, 'choices': tuple(OBSTACLE_SHAPES)}}
    common = tuple(replace(spec, **shown[spec.key]) if spec.key in shown else spec
                   for spec in next(iter(OBSTACLE_SHAPES.values())).specs[:len(_COMMON_KEYS)])
    parts = ['#### Keys of every obstacle\n\n', parameter_table_markdown(common, 'key')]
    for name, shape in OBSTACLE_SHAPES.items():
        parts.append(f'\n#### `{name}` (default `color`: {list(shape.color_rgba)})\n\n'
                     + parameter_table_markdown(shape.specs, 'key',
                                                skip=tuple(s.key for s in common)))
    return ''.join(parts)


@dataclass(frozen=True)
class ObstacleSpec:
    """
    One obstacle: a box, a cylinder (axis along its z) or a sphere.

    ``size_m`` is the full extent along the obstacle's own x, y, z axes for every shape.
    """

    name: str
    shape: str
    position_m: Tuple[float, float, float]
    roll_rad: float
    pitch_rad: float
    yaw_rad: float
    mass_kg: float
    color_rgba: Tuple[float, float, float, float]
    size_m: Tuple[float, float, float]
    radius_m: Optional[float] = None
    height_m: Optional[float] = None

    @property
    def pose(self) -> Pose:
        x, y, z = self.position_m
        return Pose(x, y, z, self.roll_rad, self.pitch_rad, self.yaw_rad)

    @property
    def static(self):
        return self.mass_kg == 0.0


# The fields of an ObstacleSpec (a shape's further size keys are folded into size_m).
_OBSTACLE_FIELDS = frozenset(ObstacleSpec.__dataclass_fields__)


def obstacle_from_dict(data, source) -> ObstacleSpec:
    """
    Validate one obstacle mapping.

    :raises InvalidParameterError: naming source, field and value.
    """
    if not isinstance(data, dict):
        raise InvalidParameterError(f'{source}: an obstacle must be a mapping, got {brief(data)}')
    shape = data.get('shape', REQUIRED)
    if shape is REQUIRED or not isinstance(shape, str) or shape not in OBSTACLE_SHAPES:
        what = 'is required' if shape is REQUIRED else f'= {brief(shape)}: unknown shape'
        raise InvalidParameterError(f"{source}: field 'shape' {what}; valid: "
                                    + ', '.join(OBSTACLE_SHAPES))
    kind = OBSTACLE_SHAPES[shape]
    specs = kind.specs
    values = validate_table(specs, data, source, {s.key: s.default for s in specs},
                            'an obstacle')
    _check_in_world(source, 'position', *values['position_m'][:2])
    values['size_m'] = tuple(kind.extents(values))
    return ObstacleSpec(**{key: value for key, value in values.items()
                           if key in _OBSTACLE_FIELDS})


def _check_in_world(source, key, x_m, y_m):
    try:
        check_in_world(x_m, y_m, key)
    except InvalidPoseError as error:
        raise InvalidParameterError(f'{source}: field {key!r}: {error}') from None


def obstacles_from_list(data, source) -> Tuple[ObstacleSpec, ...]:
    """
    Validate a world's ``obstacles:`` list (names unique).

    :raises InvalidParameterError: naming source, entry and field.
    """
    if data is None:
        return ()
    if not isinstance(data, list):
        raise InvalidParameterError(f'{source}: must be a list of obstacles, got {brief(data)}')
    obstacles = tuple(obstacle_from_dict(item, f'{source}[{i}]') for i, item in enumerate(data))
    twice = used_twice(o.name for o in obstacles)
    if twice:
        raise InvalidParameterError(f'{source}: two obstacles are named {brief(twice[0])}')
    return obstacles


def used_twice(names):
    """Return the names that occur more than once, sorted."""
    seen, twice = set(), set()
    for name in names:
        (twice if name in seen else seen).add(name)
    return sorted(twice)


def origin_from_dict(data, source) -> GeodeticOrigin:
    """Validate a world's ``origin:`` (None = latitude 0, longitude 0, altitude 0)."""
    if data is None:
        return GeodeticOrigin()
    values = validate_table(ORIGIN_SPECS, data, source, {s.key: s.default for s in ORIGIN_SPECS},
                            'the origin')
    return GeodeticOrigin(**values)


VEHICLE_SPECS = (
    ParamSpec('name', 'name', 'str', None, optional=True,
              doc="robot name; null = 'vehicle<index>'"),
    ParamSpec('namespace', 'namespace', 'namespace', '', doc="ROS namespace; '' = none"),
    ParamSpec('model', 'model', 'str', None, optional=True,
              doc='car preset; null = the car_model parameter'),
    ParamSpec('pose', 'pose', 'pose', Pose(), 'm, rad', 'spawn pose of base_link {x, y, yaw}, '
              'or on a lane {lanelet or lane, s, offset} (docs/maps.md)',
              choices=('x', 'y', 'yaw')),
    ParamSpec('sensors', 'sensors', 'raw', None, '',
              "changes to the preset's sensors and new ones (docs/sensors.md)", optional=True),
    ParamSpec('route', 'route', 'raw', (), '', 'the lanes (ids or names) it will drive on after '
              'the one it starts on, in order: the SUMO engine gives SUMO its route '
              '(docs/sumo_engine.md); [] = none', check=lambda v: None if isinstance(
                  v, (list, tuple)) and all(isinstance(lane, (int, str)) and not isinstance(
                      lane, bool) and lane != '' for lane in v) else
              'must be a list of lane ids or names'),
    ParamSpec('vehicle_model', 'vehicle_model', 'raw', None, '',
              "null = the full physics car; a simple_planning_simulator model (a name, or a "
              "mapping with 'type' and its parameters) moving the car kinematically "
              '(docs/physics.md)', optional=True),
)


@dataclass(frozen=True)
class VehicleSpec:
    """
    One vehicle of a world: its name, namespace, car preset, spawn pose (REP 103) and sensors.

    ``sensors`` holds every sensor of the vehicle (the preset's, changed by the world, and the
    world's new ones); those with ``enabled`` are mounted.
    """

    name: str
    namespace: str
    model: str
    x_m: float = 0.0
    y_m: float = 0.0
    yaw_rad: float = 0.0
    sensors: Tuple[SensorSpec, ...] = ()
    # placed on a lane: (lane id, or its name: str, s [m], offset [m]); x, y, yaw are set from
    # the world's lane map when the scene is built (core/map/lane_placement.py); None = placed
    # by x, y, yaw.
    lane_pose: Optional[Tuple[Union[int, str], float, float]] = None
    # the lanes (ids or names) it will drive on after its first, in order: its route (the SUMO
    # engine's, physics/sumo_ours.py); () = none
    route: Tuple[Union[int, str], ...] = ()
    # None = the full physics car; else VehicleModelParams (core/car/kinematic_models.py)
    vehicle_model: Optional[VehicleModelParams] = None


@dataclass(frozen=True)
class WorldSpec:
    """
    A validated world: origin, vehicles, obstacles, roads, map, traffic; ``source`` = its file.

    ``roads`` are its road segments (core/map/road_segments.py); ``map`` is its map layer's spec
    (core/map/kinds.py: e.g. an OccupancyMapSpec), or None; ``traffic`` its traffic: the spec
    of its engine (core/traffic/engines.py; the builtin engine's TrafficSpec of
    core/traffic/params.py), or None; ``signals`` the plan of its traffic lights
    (core/map/signal_params.py), or None (the default plan where the lane map has any).
    ``lanes`` is its lane map (a core LaneGraph from a lane map or the roads) once loaded
    (vehicle_sim/maps/lane_maps.py, by the scene builder), with the vehicles placed by lane;
    None before that or without one.
    """

    origin: GeodeticOrigin
    vehicles: Tuple[VehicleSpec, ...]
    obstacles: Tuple[ObstacleSpec, ...]
    source: str = ''
    roads: Tuple[RoadSpec, ...] = ()
    map: Optional[object] = None
    traffic: Optional[TrafficSpec] = None      # or another engine's spec (engines.py)
    lanes: Optional[object] = field(default=None, compare=False, repr=False)
    signals: Optional[SignalSpec] = None


@dataclass(frozen=True)
class RobotSpec:
    """A differential-drive robot placed in a world: name, preset and spawn pose (REP 103)."""

    name: str
    model: str
    x_m: float = 0.0
    y_m: float = 0.0
    yaw_rad: float = 0.0
    sensors: Tuple[str, ...] = ()     # names to mount, ('all',) for every one; () none


ModelResolver = Callable[[str], Sequence[SensorSpec]]


def world_from_dict(data, source, default_model, preset_sensors: ModelResolver,
                    vehicles_required=True, base_dir=None) -> WorldSpec:
    """
    Validate a world mapping.

    :param data: the YAML content.
    :param source: file name quoted in errors.
    :param default_model: model of the vehicles that give none.
    :param preset_sensors: model name -> the preset's sensors; raises InvalidParameterError
        for an unknown model (config.py reads the preset).
    :param vehicles_required: refuse a world without vehicles (False: a scenario whose
        vehicles are all robots gives only the origin and the obstacles).
    :param base_dir: folder the files a world names (its map) are resolved in; None = the
        folder of ``source``.
    :return: WorldSpec.
    :raises InvalidParameterError: naming file, entry and field.
    """
    if not isinstance(data, dict):
        raise InvalidParameterError(f'{source}: a world must be a mapping with "vehicles"')
    base_dir = os.path.dirname(source) if base_dir is None else base_dir
    if data.get(sumo_folder.KEY) is not None:     # a Webots SUMO folder: its map and traffic
        data = sumo_folder.with_sumo_folder(data, f'{source}: {sumo_folder.KEY}', base_dir)
    unknown = sorted(set(data) - set(WORLD_KEYS) - {sumo_folder.KEY})
    if unknown:
        raise InvalidParameterError(f'{source}: unknown key(s) {brief(unknown)}; valid: '
                                    + ', '.join(WORLD_KEYS + (sumo_folder.KEY,)))
    entries = data.get('vehicles')
    if not entries and not vehicles_required:
        entries = []
    elif not isinstance(entries, list) or not entries:
        raise InvalidParameterError(f'{source}: needs a non-empty list "vehicles"')
    origin = origin_from_dict(data.get('origin'), f'{source}: origin')
    vehicles = tuple(_vehicle(entry, f'{source}: vehicles[{index}]', index, default_model,
                              preset_sensors) for index, entry in enumerate(entries))
    # Names are how getDevice, /initialpose and scenarios find a vehicle: unique in the world,
    # whatever the namespaces.
    twice = used_twice(v.name for v in vehicles)
    if twice:
        raise InvalidParameterError(f'{source}: vehicle name(s) used twice: {brief(twice)}')
    namespaces = [v.namespace for v in vehicles]
    if len(set(namespaces)) != len(namespaces):
        raise InvalidParameterError(f'{source}: two vehicles share a namespace: '
                                    f'{brief(namespaces)}')
    obstacles = obstacles_from_list(data.get('obstacles'), f'{source}: obstacles')
    taken = {v.name for v in vehicles} & {o.name for o in obstacles}
    if taken:
        raise InvalidParameterError(f'{source}: obstacle and vehicle share a name: '
                                    f'{brief(sorted(taken))}')
    roads = data.get('roads')
    roads = () if roads is None else roads_from_list(roads, f'{source}: roads')
    world_map = map_from_dict(data.get('map'), f'{source}: map', base_dir)
    if roads and is_lane_map(world_map):
        raise InvalidParameterError(f'{source}: has both roads: and a {world_map.type} map: a '
                                    'world has one lane map; keep one of them')
    traffic = data.get('traffic')
    if traffic is not None:
        traffic = traffic_spec_from_dict(traffic, f'{source}: traffic', preset_sensors, base_dir)
    routed = [(index, v.route) for index, v in enumerate(vehicles) if v.route]
    if routed and not isinstance(traffic, SumoTrafficSpec):
        index, route = routed[0]
        raise InvalidParameterError(
            f"{source}: vehicles[{index}]: field 'route' = {brief(list(route))}: a route is "
            'given to the sumo traffic engine (traffic: {engine: sumo}); this world has '
            + ('no traffic' if traffic is None else 'another engine'))
    signals = data.get('signals')
    if signals is not None:
        signals = signals_from_dict(signals, f'{source}: signals')
    return WorldSpec(origin, vehicles, obstacles, source, roads=roads, map=world_map,
                     traffic=traffic, signals=signals)


def _vehicle(entry, where, index, default_model, preset_sensors):
    if not isinstance(entry, dict):
        raise InvalidParameterError(f'{where} must be a mapping')
    lane_pose = None
    if is_lane_pose(entry.get('pose')):    # on a lane: placed once the lane map is loaded
        lane_pose = lane_pose_values(entry['pose'], f'{where}.pose')
        entry = {key: value for key, value in entry.items() if key != 'pose'}
    values = validate_table(VEHICLE_SPECS, entry, where,
                            {s.key: s.default for s in VEHICLE_SPECS}, 'a vehicle')
    model = values['model'] or default_model
    try:
        base = preset_sensors(model)
    except InvalidParameterError as error:
        raise InvalidParameterError(f"{where}: field 'model': {error}") from None
    sensors = merge_sensors(base, values['sensors'], f'{where}.sensors')
    route = tuple(values['route'])
    vehicle_model = vehicle_model_from(values['vehicle_model'], f'{where}.vehicle_model')
    if lane_pose is not None:
        return VehicleSpec(values['name'] or f'vehicle{index}', values['namespace'], model,
                           sensors=sensors, lane_pose=lane_pose, route=route,
                           vehicle_model=vehicle_model)
    pose = values['pose']
    _check_in_world(where, 'pose', pose.x_m, pose.y_m)
    return VehicleSpec(values['name'] or f'vehicle{index}', values['namespace'], model,
                       pose.x_m, pose.y_m, pose.yaw_rad, sensors, route=route,
                       vehicle_model=vehicle_model)
