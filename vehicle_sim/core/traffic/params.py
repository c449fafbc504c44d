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
The ``traffic:`` key of world files and scenarios, validated against ParamSpec tables.

The form (every key optional)::

    traffic:
      vehicles: 50                 # or density: 8.0 (vehicles per km per lane); not both
      models: [ToyotaPrius, BmwX5] # car presets (config/cars): each vehicle's box and colour
      speed_factor: {mean: 1.0, std: 0.1}
      seed: 7
      spawn: {lanes: [100001, 100002], s_range: [0.0, 500.0], spacing: 30.0}
      model: {car_following: idm, lane_change: mobil}   # core/traffic/models.py (defaults)
      idm: {time_headway: 1.5, min_gap: 2.0}       # each model's parameters under its name
      mobil: {politeness: 0.2}
      objects_rate: 10.0           # Hz of the objects and markers over ROS (null: the node's)
      placed:                                       # individually placed vehicles
        - {model: BmwX5, lanelet: 100001, s: 120.0, speed: 20.0, route: [100101, 100201]}

What needs the lane map (a lane, s on it, a route's lanes, whether the vehicles fit) is checked
when the manager is built on the world's LaneGraph (core/traffic/manager.py), naming the same
file and field.
"""

from dataclasses import dataclass, replace
from typing import Any, Optional, Tuple

from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.param_spec import ParamSpec, REQUIRED, validate_table
from vehicle_sim.core.specs.value_kinds import ParamRefused, register_kind
from vehicle_sim.core.specs.value_text import brief
from vehicle_sim.core.traffic.models import all_models, CAR_FOLLOWING_MODELS, LANE_CHANGE_MODELS


def _check_lane_ids(spec, value):
    if not isinstance(value, (list, tuple)) or not all(
            isinstance(v, int) and not isinstance(v, bool) for v in value):
        raise ParamRefused('must be a list of lane (lanelet) ids (integers)')
    if not value and not spec.empty:
        raise ParamRefused('must not be empty')
    return tuple(value)


LANE_IDS = register_kind('lane_ids', 'int[]', _check_lane_ids)

# The rate of the traffic objects over ROS (PredictedObjects and their markers), declared once:
# the automobile node's parameter ``objects_rate`` (ros/sim_params.py) is this row, a world's
# ``traffic: objects_rate`` is this row made optional. 10 Hz: Autoware's perception publishes
# its objects at 10 Hz, and 60 vehicles with predicted paths each step cost more than the step.
OBJECTS_RATE = ParamSpec(
    'objects_rate', 'objects_rate_hz', 'float', 10.0, 'Hz',
    'rate of /perception/object_recognition/objects, /sim/traffic/markers and '
    '/perception/traffic_light_recognition/traffic_signals (that also at each change) on '
    "simulated time (at the first basic step at or after each k / rate; Autoware's perception: "
    '10 Hz)',
    gt=0.0)

TRAFFIC_SPECS = (
    ParamSpec('engine', 'engine', 'enum', 'builtin', '', 'the traffic engine, a name of '
              'TRAFFIC_ENGINES (core/traffic/engines.py): builtin (this table) or sumo '
              '(docs/sumo.md)', choices=('builtin',)),
    ParamSpec('vehicles', 'vehicles', 'int', None, '', 'number of vehicles spawned at random '
              '(null: from density)', ge=0, le=10000, optional=True),
    ParamSpec('density', 'density_per_km', 'float', None, '1/km', 'vehicles per km per lane of '
              'the spawn lanes (null: from vehicles)', ge=0.0, le=200.0, optional=True),
    ParamSpec('models', 'models', 'str_list', ('Car',), '', 'car presets the random vehicles '
              'are drawn from (their dimensions)'),
    ParamSpec('speed_factor', 'speed_factor', 'raw', None, '', 'desired speed / lane limit: '
              '{mean, std} of a normal distribution cut at 2 std', optional=True),
    # 0 .. 2^31 - 1: every seed a Gym reset draws (gym/drive_sim.py TRAFFIC_SEEDS) can be named
    ParamSpec('seed', 'seed', 'int', 0, '', 'random seed (spawn places, models, factors, '
              'route choices)', ge=0, le=2 ** 31 - 1),
    ParamSpec('spawn', 'spawn', 'raw', None, '', 'where the random vehicles start: {lanes, '
              's_range, spacing}', optional=True),
    ParamSpec('model', 'model', 'raw', None, '', 'the traffic models: {car_following, '
              "lane_change} (table below; each model's parameters under its name)",
              optional=True),
    ParamSpec('lane_change_duration', 'lane_change_duration_s', 'float', 3.0, 's',
              'time a lane change takes (lateral move)', gt=0.5, le=20.0),
    ParamSpec('lane_change_period', 'lane_change_period_s', 'float', 1.0, 's',
              'how often each vehicle considers a lane change', gt=0.0, le=60.0),
    ParamSpec('update_period', 'update_period_s', 'float', 0.1, 's',
              'traffic update period (a multiple of the world step; 0.1 = 10 Hz)', gt=0.0,
              le=1.0),
    ParamSpec('placed', 'placed', 'raw', None, '', 'individually placed vehicles (table below)',
              optional=True),
    replace(OBJECTS_RATE, default=None, optional=True,
            doc='rate of the objects, markers and signals over ROS on simulated time (null: the '
                "node's objects_rate parameter, 10 Hz by default); wins over the parameter"),
)

MODEL_SPECS = (
    ParamSpec('car_following', 'car_following', 'str', 'idm', '', 'the car-following model, a '
              'name of CAR_FOLLOWING_MODELS (core/traffic/models.py)'),
    ParamSpec('lane_change', 'lane_change', 'str', 'mobil', '', 'the lane-change model, a name '
              'of LANE_CHANGE_MODELS (core/traffic/models.py)'),
)


def traffic_specs():
    """Return the table of ``traffic:``: its keys, then a key per registered traffic model."""
    return TRAFFIC_SPECS + tuple(
        ParamSpec(name, name, 'raw', None, '', f'parameters of {model.doc}', optional=True)
        for name, model in all_models().items())


def _model_names(data, source):
    values = validate_table(MODEL_SPECS, data or {}, f'{source}: model', what='traffic models')
    for key, registry in (('car_following', CAR_FOLLOWING_MODELS),
                          ('lane_change', LANE_CHANGE_MODELS)):
        if values[key] not in registry:
            raise InvalidParameterError(f'{source}: model: field {key!r} = '
                                        f'{brief(values[key])}: unknown; valid: '
                                        + ', '.join(registry))
    return values['car_following'], values['lane_change']


SPEED_FACTOR_SPECS = (
    ParamSpec('mean', 'mean', 'float', 1.0, '', 'mean desired speed / lane limit', gt=0.0,
              le=2.0),
    ParamSpec('std', 'std', 'float', 0.1, '', 'standard deviation', ge=0.0, le=0.5),
)

SPAWN_SPECS = (
    ParamSpec('lanes', 'lanes', LANE_IDS, None, '', 'lane (lanelet) ids to spawn on; null = '
              'every lane', optional=True),
    ParamSpec('s_range', 's_range_m', 'floats', None, 'm', '[from, to] arc length on each '
              'spawn lane; null = the whole lane', length=2, optional=True),
    ParamSpec('spacing', 'spacing_m', 'float', 30.0, 'm', 'distance between spawn places '
              '(centre to centre)', gt=0.0, le=1000.0),
)

PLACED_SPECS = (
    ParamSpec('model', 'model', 'str', None, '', "car preset; null = models' first",
              optional=True),
    ParamSpec('lanelet', 'lanelet', 'int', REQUIRED, '', 'the lane (lanelet) id it starts on'),
    ParamSpec('s', 's_m', 'float', 0.0, 'm', 'arc length of its centre along the lane', ge=0.0),
    ParamSpec('speed', 'speed_mps', 'float', None, 'm/s', 'start speed; null = the safe speed '
              'behind its leader, up to its desired speed', ge=0.0, le=100.0, optional=True),
    ParamSpec('speed_factor', 'speed_factor', 'float', 1.0, '', 'desired speed / lane limit',
              gt=0.0, le=2.0),
    ParamSpec('route', 'route', LANE_IDS, (), '', 'the lanes it drives after its first, each a '
              'successor of the one before ([] = random at forks); it does not change lanes',
              empty=True),
    ParamSpec('change_lane', 'change_lane', 'enum', 'none', choices=('none', 'left', 'right'),
              doc='a scripted lane change (a cut-in): to this side, from change_at on, as soon '
                  'as the lane map allows it (no MOBIL: the only change it makes)'),
    ParamSpec('change_at', 'change_at_s', 'float', 0.0, 's', 'simulated time of the scripted '
              'lane change', ge=0.0),
)


@dataclass(frozen=True)
class PlacedVehicle:
    """One individually placed traffic vehicle (:data:`PLACED_SPECS`)."""

    model: str
    lanelet: int
    s_m: float
    speed_mps: Optional[float]
    speed_factor: float
    route: Tuple[int, ...]
    where: str           # 'file: traffic: placed[i]', for the errors the lane map finds
    change_lane: str = 'none'
    change_at_s: float = 0.0


@dataclass(frozen=True)
class TrafficSpec:
    """A validated ``traffic:`` mapping; ``source`` = 'file: traffic' for later errors."""

    vehicles: Optional[int] = 0
    density_per_km: Optional[float] = None
    models: Tuple[str, ...] = ('Car',)
    speed_factor_mean: float = 1.0
    speed_factor_std: float = 0.1
    seed: int = 0
    spawn_lanes: Optional[Tuple[int, ...]] = None
    spawn_s_range_m: Optional[Tuple[float, float]] = None
    spawn_spacing_m: float = 30.0
    car_following: str = 'idm'
    lane_change: str = 'mobil'
    # (model name, its validated parameters) of every registered model (core/traffic/models.py)
    model_params: Tuple[Tuple[str, Any], ...] = ()
    lane_change_duration_s: float = 3.0
    lane_change_period_s: float = 1.0
    update_period_s: float = 0.1
    placed: Tuple[PlacedVehicle, ...] = ()
    source: str = 'traffic'
    objects_rate_hz: Optional[float] = None
    engine: str = 'builtin'          # core/traffic/engines.py

    def params_of(self, model: str):
        """Return the validated parameters of a traffic model (``traffic: <model>:``)."""
        return dict(self.model_params)[model]

    @property
    def idm(self):
        """The IDM's parameters (also what scenario actors follow their leaders with)."""
        return self.params_of('idm')

    @property
    def mobil(self):
        """MOBIL's parameters."""
        return self.params_of('mobil')

    @property
    def all_models(self):
        """Every model named: ``models`` and the placed vehicles' (each once, in order)."""
        return tuple(dict.fromkeys(self.models + tuple(p.model for p in self.placed)))


def traffic_from_dict(data, source, check_model=None, base_dir=None) -> TrafficSpec:
    """
    Validate a ``traffic:`` mapping of the builtin engine (``engine: builtin`` or none).

    A world's ``traffic:`` goes through ``core/traffic/engines.traffic_spec_from_dict``, which
    calls this for the builtin engine.

    :param data: the YAML content.
    :param source: quoted in errors ('world.yaml: traffic').
    :param check_model: ``check_model(name)`` raises InvalidParameterError for an unknown car
        preset (config.py reads presets; None = no check).
    :param base_dir: unused (the builtin engine names no files).
    :raises InvalidParameterError: naming the file and field.
    """
    values = validate_table(traffic_specs(), data, source, what='traffic')
    car_following, lane_change = _model_names(values['model'], source)
    model_params = tuple((name, model.params(values[name], f'{source}: {name}'))
                         for name, model in all_models().items())
    if values['vehicles'] is not None and values['density_per_km'] is not None:
        raise InvalidParameterError(f'{source}: give either vehicles or density, not both '
                                    f'(vehicles = {values["vehicles"]}, density = '
                                    f'{values["density_per_km"]})')
    factor = validate_table(SPEED_FACTOR_SPECS, values['speed_factor'] or {},
                            f'{source}: speed_factor', what='speed_factor')
    if factor['mean'] - 2.0 * factor['std'] <= 0.0:
        raise InvalidParameterError(
            f'{source}: speed_factor: mean - 2 std = {factor["mean"] - 2.0 * factor["std"]:g} '
            f'must be > 0 (every vehicle needs a desired speed > 0)')
    spawn = validate_table(SPAWN_SPECS, values['spawn'] or {}, f'{source}: spawn',
                           what='spawn')
    s_range = spawn['s_range_m']
    if s_range is not None and not 0.0 <= s_range[0] < s_range[1]:
        raise InvalidParameterError(f"{source}: spawn: field 's_range' = {list(s_range)}: "
                                    f'must be [from, to] with 0 <= from < to')
    models = values['models']
    for model in models:
        _check(check_model, model, f"{source}: field 'models'")
    placed = values['placed'] or []
    if not isinstance(placed, list):
        raise InvalidParameterError(f"{source}: field 'placed' = {brief(placed)}: must be a "
                                    f'list of vehicles')
    entries = []
    for index, entry in enumerate(placed):
        where = f'{source}: placed[{index}]'
        if not isinstance(entry, dict):
            raise InvalidParameterError(f'{where} must be a mapping')
        item = validate_table(PLACED_SPECS, entry, where, what='placed vehicle')
        model = item['model'] or models[0]
        _check(check_model, model, f"{where}: field 'model'")
        if item['change_lane'] != 'none' and item['route']:
            raise InvalidParameterError(f"{where}: field 'change_lane' = "
                                        f"{item['change_lane']!r}: a vehicle with a route does "
                                        f'not change lanes (give one or the other)')
        entries.append(PlacedVehicle(model, item['lanelet'], item['s_m'], item['speed_mps'],
                                     item['speed_factor'], item['route'], where,
                                     item['change_lane'], item['change_at_s']))
    vehicles = values['vehicles']
    if vehicles is None and values['density_per_km'] is None:
        vehicles = 0
    return TrafficSpec(
        vehicles, values['density_per_km'], models, factor['mean'], factor['std'],
        values['seed'], spawn['lanes'], s_range, spawn['spacing_m'],
        car_following, lane_change, model_params,
        values['lane_change_duration_s'], values['lane_change_period_s'],
        values['update_period_s'], tuple(entries), source, values['objects_rate_hz'])


def _check(check_model, model, where):
    if check_model is None:
        return
    try:
        check_model(model)
    except InvalidParameterError as error:
        raise InvalidParameterError(f'{where}: unknown model {model!r}: {error}') from None


def traffic_markdown():
    """Return the key tables of ``traffic:`` (and of its sub-mappings) for docs/traffic.md."""
    from vehicle_sim.core.specs.param_spec import parameter_table_markdown
    parts = []
    for title, specs in (('`traffic:`', traffic_specs()),
                         ('`model:`', MODEL_SPECS),
                         ('`speed_factor:`', SPEED_FACTOR_SPECS),
                         ('`spawn:`', SPAWN_SPECS),
                         ('each entry of `placed:`', PLACED_SPECS),
                         *((f'`{name}:` ({model.doc})', model.specs)
                           for name, model in all_models().items())):
        parts.append(f'#### {title}\n\n' + parameter_table_markdown(specs, 'field'))
    return '\n'.join(parts)
