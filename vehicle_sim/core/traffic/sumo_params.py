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
The ``traffic:`` key of the SUMO traffic engine (``engine: sumo``), validated against its tables.

The form::

    traffic:
      engine: sumo
      routes: city.rou.xml          # SUMO routes (vehicles, persons, flows), or a list of them
      demand:                       # and/or random trips, as SUMO's randomTrips.py makes them
        vehicles_per_hour: 600
        pedestrians_per_hour: 120
        classes: {passenger: 8, truck: 1, bus: 1}   # SUMO vehicle classes: weights (or a list)
        duration: 3600              # departures from begin to begin + duration [s]
        seed: 3                     # null: the engine's seed
      step: 0.1                     # SUMO's step length [s], a multiple of the world step
      seed: 7                       # SUMO's --seed
      begin: 0.0                    # SUMO's simulation time when it starts [s]
      warmup: 60.0                  # SUMO runs this long first: the world starts with traffic
      transport: auto               # libsumo in process, or TraCI (a SUMO process)
      options: [--time-to-teleport, '-1']   # further sumo options
      objects_rate: 10.0

The engine runs on the world's SUMO network (the map of kind sumo, opendrive or osm). Files are
resolved against the world file's folder; a missing file is refused here, naming the file and
the field. SUMO's own messages about the files' content (a route on an edge the network lacks)
come when the engine starts (physics/sumo_traffic.py). Each SUMO vehicle class becomes one of
the object classes of core/traffic/objects.py (:func:`object_class`).
"""

from dataclasses import dataclass, replace
import os
from typing import Optional, Tuple

from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.param_spec import ParamSpec, validate_table
from vehicle_sim.core.specs.value_text import brief
from vehicle_sim.core.traffic.params import OBJECTS_RATE

ENGINE = 'sumo'
TRANSPORTS = ('auto', 'libsumo', 'traci', 'worker')
# The object class (core/traffic/objects.py OBJECT_CLASSES) of each SUMO vehicle class
# (https://sumo.dlr.de/docs/Definition_of_Vehicles%2C_Vehicle_Types%2C_and_Routes.html,
# "Abstract Vehicle Class"); a class not listed is a car.
OBJECT_CLASS_OF_VCLASS = {
    'passenger': 'car', 'private': 'car', 'taxi': 'car', 'emergency': 'car',
    'authority': 'car', 'army': 'car', 'vip': 'car', 'hov': 'car', 'evehicle': 'car',
    'truck': 'truck', 'delivery': 'truck',
    'trailer': 'trailer',
    'bus': 'bus', 'coach': 'bus', 'tram': 'bus', 'rail_urban': 'bus',
    'motorcycle': 'motorcycle', 'moped': 'motorcycle',
    'bicycle': 'bicycle', 'scooter': 'bicycle',
    'pedestrian': 'pedestrian',
}
# The vehicle classes a demand may draw (road vehicles SUMO has a default type for).
DEMAND_CLASSES = ('passenger', 'taxi', 'emergency', 'delivery', 'truck', 'trailer', 'bus',
                  'coach', 'motorcycle', 'moped', 'bicycle')
# Departures a demand may ask for in all (randomTrips writes each one): 10^5, some 28 hours of
# 1000 vehicles an hour.
MAX_DEMAND_TRIPS = 100000
# The sumo options the engine sets itself (from these keys and the world): not in ``options``.
OWN_OPTIONS = ('-n', '--net-file', '-r', '--route-files', '--seed', '--step-length', '-b',
               '--begin', '-c', '--configuration-file', '--remote-port', '--error-log',
               '--start', '--quit-on-end', '--no-step-log')


def object_class(vclass: str) -> str:
    """Return the object class (OBJECT_CLASSES) of a SUMO vehicle class; a car by default."""
    return OBJECT_CLASS_OF_VCLASS.get(vclass, 'car')


SUMO_TRAFFIC_SPECS = (
    ParamSpec('engine', 'engine', 'enum', ENGINE, '', 'the traffic engine: sumo (this table)',
              choices=(ENGINE,)),
    ParamSpec('routes', 'routes', 'raw', None, '', 'SUMO route file(s) (vehicles, persons, '
              'flows, their types), a name or a list, relative to the world file; null = the '
              'demand only', optional=True),
    ParamSpec('demand', 'demand', 'raw', None, '', 'random trips over the network, made by '
              "SUMO's randomTrips.py (table below); null = the routes only", optional=True),
    ParamSpec('step', 'step_s', 'float', 0.1, 's', "SUMO's step length: SUMO advances every "
              'step of simulated time (a multiple of the world step)', gt=0.0, le=1.0),
    ParamSpec('seed', 'seed', 'int', 0, '', "SUMO's --seed (its drivers' randomness); the "
              "demand's seed by default", ge=0, le=999999),
    ParamSpec('begin', 'begin_s', 'float', 0.0, 's', "SUMO's time when it starts (SUMO's "
              '--begin)', ge=0.0, le=86400.0 * 7),
    ParamSpec('warmup', 'warmup_s', 'float', 0.0, 's', 'SUMO runs this long (a multiple of '
              'step) when it starts and at each reset, before the world goes on, so that the '
              "world starts with traffic (SUMO's time at the world's start: begin + warmup)",
              ge=0.0, le=3600.0),
    ParamSpec('transport', 'transport', 'enum', 'auto', '', 'how SUMO runs: libsumo (in this '
              'process; one SUMO per process), traci (a sumo process, over a socket; slower), '
              'auto (libsumo when this process has no SUMO running yet, else traci), worker '
              '(libsumo in a process of its own, stepping while the physics runs: our vehicles '
              'reach SUMO one SUMO step later)',
              choices=TRANSPORTS),
    ParamSpec('options', 'options', 'str_list', None, '', 'further sumo command-line options, '
              "e.g. ['--time-to-teleport', '-1'] (not those the engine sets: "
              + ', '.join(OWN_OPTIONS) + '); null = none', optional=True, empty=True),
    replace(OBJECTS_RATE, default=None, optional=True,
            doc='rate of the objects, markers and signals over ROS on simulated time (null: the '
                "node's objects_rate parameter, 10 Hz by default); wins over the parameter"),
)

DEMAND_SPECS = (
    ParamSpec('vehicles_per_hour', 'vehicles_per_hour', 'float', 0.0, '1/h', 'vehicles '
              'departing an hour, spread evenly (randomTrips --period 3600 / this), over the '
              'classes by weight', ge=0.0, le=20000.0),
    ParamSpec('pedestrians_per_hour', 'pedestrians_per_hour', 'float', 0.0, '1/h', 'persons '
              'walking from a random edge to another an hour (randomTrips --pedestrians)',
              ge=0.0, le=20000.0),
    ParamSpec('classes', 'classes', 'raw', None, '', 'the SUMO vehicle classes of the vehicles: '
              'a list (equal shares) or {class: weight}; one of ' + ', '.join(DEMAND_CLASSES)
              + '; null = passenger', optional=True),
    ParamSpec('duration', 'duration_s', 'float', 3600.0, 's', 'departures from begin to begin '
              '+ duration', gt=0.0, le=86400.0),
    ParamSpec('seed', 'seed', 'int', None, '', "randomTrips' --seed (null: the engine's seed, "
              "and each reset's)",
              ge=0, le=999999, optional=True),
    ParamSpec('min_distance', 'min_distance_m', 'float', 0.0, 'm', 'the least straight '
              "distance between a trip's start and end (randomTrips --min-distance)", ge=0.0,
              le=100000.0),
)


@dataclass(frozen=True)
class SumoDemand:
    """A validated ``demand:`` (:data:`DEMAND_SPECS`); ``classes``: ((vClass, weight), ...)."""

    vehicles_per_hour: float = 0.0
    pedestrians_per_hour: float = 0.0
    classes: Tuple[Tuple[str, float], ...] = (('passenger', 1.0),)
    duration_s: float = 3600.0
    seed: Optional[int] = None      # None: the engine's seed (its reset's seed)
    min_distance_m: float = 0.0

    def class_rates(self):
        """Return ((vClass, vehicles per hour), ...) of the classes with a rate > 0."""
        total = sum(weight for _, weight in self.classes)
        return tuple((vclass, self.vehicles_per_hour * weight / total)
                     for vclass, weight in self.classes
                     if weight > 0.0 and self.vehicles_per_hour > 0.0)


@dataclass(frozen=True)
class SumoTrafficSpec:
    """
    A validated ``traffic:`` of the SUMO engine; ``source`` = 'file: traffic' for later errors.

    ``routes`` are paths resolved against the world file's folder.
    """

    routes: Tuple[str, ...] = ()
    demand: Optional[SumoDemand] = None
    step_s: float = 0.1
    seed: int = 0
    begin_s: float = 0.0
    warmup_s: float = 0.0
    transport: str = 'auto'
    options: Tuple[str, ...] = ()
    source: str = 'traffic'
    objects_rate_hz: Optional[float] = None
    engine: str = ENGINE

    @property
    def update_period_s(self):
        """SUMO's step [s] (the name the builtin engine's spec gives its update period)."""
        return self.step_s


def _resolve(path, base_dir):
    path = os.path.expanduser(path)
    return path if os.path.isabs(path) or not base_dir else os.path.join(base_dir, path)


def _file(value, field, source, base_dir):
    if not isinstance(value, str) or not value:
        raise InvalidParameterError(f'{source}: field {field!r} = {brief(value)}: must be a '
                                    'file name')
    path = _resolve(value, base_dir)
    if not os.path.isfile(path):
        raise InvalidParameterError(f'{source}: field {field!r} = {value!r}: no such file '
                                    f'({path})')
    return path


def _classes(value, where):
    if value is None:
        return (('passenger', 1.0),)
    if isinstance(value, list):
        pairs = [(name, 1.0) for name in value]
    elif isinstance(value, dict):
        pairs = list(value.items())
    else:
        raise InvalidParameterError(f"{where}: field 'classes' = {brief(value)}: must be a list "
                                    'of SUMO vehicle classes or {class: weight}')
    if not pairs:
        raise InvalidParameterError(f"{where}: field 'classes' = {brief(value)}: must not be "
                                    'empty')
    names = [name for name, _ in pairs]
    for name, weight in pairs:
        if name not in DEMAND_CLASSES:
            raise InvalidParameterError(f"{where}: field 'classes': {brief(name)}: not a vehicle "
                                        'class a demand draws; valid: '
                                        + ', '.join(DEMAND_CLASSES))
        if isinstance(weight, bool) or not isinstance(weight, (int, float)) or \
                not 0.0 <= weight < float('inf'):
            raise InvalidParameterError(f"{where}: field 'classes': {name}: weight "
                                        f'{brief(weight)} must be a number >= 0')
    if len(set(names)) != len(names):
        raise InvalidParameterError(f"{where}: field 'classes' = {brief(value)}: a class is "
                                    'named twice')
    if sum(weight for _, weight in pairs) <= 0.0:
        raise InvalidParameterError(f"{where}: field 'classes' = {brief(value)}: the weights "
                                    'add up to 0')
    return tuple((name, float(weight)) for name, weight in pairs)


def _demand(data, where):
    values = validate_table(DEMAND_SPECS, data, where, what='demand')
    demand = SumoDemand(values['vehicles_per_hour'], values['pedestrians_per_hour'],
                        _classes(values['classes'], where), values['duration_s'],
                        values['seed'], values['min_distance_m'])
    trips = (demand.vehicles_per_hour + demand.pedestrians_per_hour) * demand.duration_s / 3600
    if trips > MAX_DEMAND_TRIPS:
        raise InvalidParameterError(
            f'{where}: (vehicles_per_hour + pedestrians_per_hour) x duration = {trips:.0f} '
            f'departures: at most {MAX_DEMAND_TRIPS} (shorten the duration or lower the rates)')
    return demand


def sumo_traffic_from_dict(data, source, check_model=None, base_dir=None) -> SumoTrafficSpec:
    """
    Validate a ``traffic:`` mapping of the SUMO engine (``engine: sumo``).

    :param data: the YAML content (``engine`` included).
    :param source: quoted in errors ('world.yaml: traffic').
    :param check_model: unused (SUMO's vehicle types size its bodies).
    :param base_dir: the folder files are resolved in (the world file's); None = as given.
    :raises InvalidParameterError: naming the file and field.
    """
    values = validate_table(SUMO_TRAFFIC_SPECS, data, source, what='traffic')
    routes = values['routes']
    if routes is None:
        routes = ()
    elif isinstance(routes, str):
        routes = (routes,)
    elif not isinstance(routes, list) or not routes:
        raise InvalidParameterError(f"{source}: field 'routes' = {brief(routes)}: must be a file "
                                    'name or a list of them')
    routes = tuple(_file(r, 'routes', source, base_dir) for r in routes)
    demand = values['demand']
    if demand is not None:
        demand = _demand(demand, f'{source}: demand')
    if not routes and demand is None:
        raise InvalidParameterError(f'{source}: the sumo engine needs routes (a SUMO route file) '
                                    'or demand (random trips), or both')
    options = tuple(values['options'] or ())
    for option in options:
        if option.split('=')[0] in OWN_OPTIONS:
            raise InvalidParameterError(
                f"{source}: field 'options': {option!r} is set by the engine (from the keys "
                "routes, seed, step, begin and the world's network): give it there")
    steps = values['warmup_s'] / values['step_s']
    if abs(steps - round(steps)) > 1e-6:
        raise InvalidParameterError(f"{source}: field 'warmup' = {values['warmup_s']:g}: must be "
                                    f"a multiple of step ({values['step_s']:g} s)")
    return SumoTrafficSpec(routes, demand, values['step_s'], values['seed'], values['begin_s'],
                           values['warmup_s'], values['transport'], options, source,
                           values['objects_rate_hz'])


def sumo_traffic_markdown():
    """Return the key tables of the SUMO engine's ``traffic:`` (docs/sumo.md)."""
    from vehicle_sim.core.specs.param_spec import parameter_table_markdown
    return '\n'.join(f'#### {title}\n\n' + parameter_table_markdown(specs, 'field')
                     for title, specs in (('`traffic:` (`engine: sumo`)', SUMO_TRAFFIC_SPECS),
                                          ('`demand:`', DEMAND_SPECS)))
