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
The scenario file format: validated into a :class:`ScenarioSpec`, errors naming ``file:line``.

Top-level keys (docs/scenarios.md has the tables, generated from the ParamSpec rows here)::

    name: stop_before_wall
    world: obstacle_course          # a world name/path, or an inline world mapping
    robots: [{name: diff_robot, model: caster_robot, pose: {x: 0, y: 0, yaw: 0}}]
    vehicle: Car                    # the vehicle under test (default: the first one)
    duration: 12.0
    seed: 0
    actors: [{vehicle: car2, waypoints: [[0, 6], [40, 6]], speed: 5.0}]
    driver: {controller: ../examples/lidar_stop_controller.py}
    criteria: [{kind: no_collision}, {kind: max_speed, limit: 6.0}]

The world keeps the schema of the node's ``world`` parameter (core/world/params.py); criteria
are checked by :mod:`.criteria` (its ``CRITERIA`` registry gives each kind's table); the
``driver`` section is :mod:`.driver_schema`'s.
"""

from dataclasses import dataclass, field
from pathlib import Path
from typing import Dict, Optional, Tuple

from vehicle_sim import config
from vehicle_sim.core.sensors.sets import enable_sensors, selected_sensors
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.param_spec import ParamSpec, REQUIRED, validate_table
from vehicle_sim.core.specs.simulation import TIME_STEP_MS
from vehicle_sim.core.specs.value_text import brief
from vehicle_sim.core.world.params import RobotSpec, used_twice, WorldSpec
from vehicle_sim.scenarios.criteria import criteria_from_list, CriterionSpec
from vehicle_sim.scenarios.driver_schema import (
    COMMAND_ROWS,
    driver_from_data,
    DRIVER_KINDS,
    DRIVER_SPECS,
    DriverSpec,
    MAX_DURATION_S,
    SIGNAL_COMMAND,
    SIGNAL_COMMAND_SPECS,
)
import vehicle_sim.scenarios.lane_criteria  # noqa: F401  (registers the lane criteria)
import vehicle_sim.scenarios.overtake_criterion  # noqa: F401  (registers overtake)
import vehicle_sim.scenarios.rule_criteria  # noqa: F401  (registers the traffic rule ones)
from vehicle_sim.scenarios.yaml_lines import error_at, line_of, load_with_lines, ScenarioError

SCENARIO_SPECS = (
    ParamSpec('name', 'name', 'str', '', doc="test name; '' = the file name without .yaml",
              empty=True),
    ParamSpec('description', 'description', 'str', '', empty=True, doc='free text'),
    ParamSpec('world', 'world', 'raw', REQUIRED, doc='world name (config/worlds), path to a '
              'world .yaml (relative to the scenario file), or an inline world mapping'),
    ParamSpec('robots', 'robots', 'raw', None, optional=True,
              doc='differential-drive robots added to the world (table below)'),
    ParamSpec('vehicle', 'vehicle', 'str', None, optional=True,
              doc='name of the vehicle under test; null = the first vehicle of the world '
                  '(the first robot when the world has no car)'),
    ParamSpec('duration', 'duration_s', 'float', REQUIRED, 's', 'simulated time the scenario '
              'runs', gt=0.0, le=MAX_DURATION_S),
    ParamSpec('seed', 'seed', 'int', 0, doc='seed of the sensor noise and of the '
              'controller (random, numpy, VEHICLE_SIM_SEED); --seed overrides it', ge=0),
    TIME_STEP_MS,
    ParamSpec('actors', 'actors', 'raw', None, optional=True,
              doc='scripted vehicles following waypoints (table below)'),
    ParamSpec('driver', 'driver', 'raw', REQUIRED,
              doc='what drives the vehicle under test: exactly one of ' +
                  ', '.join(DRIVER_KINDS)),
    ParamSpec('criteria', 'criteria', 'raw', REQUIRED, doc='pass criteria (table below)'),
)

ROBOT_SPECS = (
    ParamSpec('name', 'name', 'ros_name', REQUIRED,
              doc='robot name (its node name when served: /<name>/differential_command)'),
    ParamSpec('model', 'model', 'str', 'caster_robot', doc='robot preset (config/robots)'),
    ParamSpec('pose', 'pose', 'pose', None, 'm, rad', 'spawn pose {x, y, yaw}',
              choices=('x', 'y', 'yaw'), optional=True),
    ParamSpec('sensors', 'sensors', 'raw', None, optional=True,
              doc="names of the preset's sensors to mount, or 'all' (docs/sensors.md); "
                  'published by the robot node (/<name>/scan, /<name>/imu): the scenario '
                  'must be served (processes or a topic criterion)'),
)

ACTOR_SPECS = (
    ParamSpec('vehicle', 'vehicle', 'str', REQUIRED,
              doc='name of a world vehicle or robot (not the vehicle under test)'),
    ParamSpec('waypoints', 'waypoints', 'raw', REQUIRED, 'm, m/s',
              doc='[[x, y], ...] or [[x, y, speed], ...]: the speed towards that point'),
    ParamSpec('speed', 'speed_mps', 'float', 5.0, 'm/s', 'speed of waypoints that give none',
              ge=0.0),
    ParamSpec('lookahead', 'lookahead_m', 'float', 0.0, 'm',
              'pure-pursuit look-ahead; 0 = max(2 wheelbases, 1 s of travel)', ge=0.0),
    ParamSpec('loop', 'loop', 'bool', False, doc='back to the first waypoint after the last '
              '(else stop there)'),
    ParamSpec('speed_control', 'speed_control', 'enum', 'idm',
              choices=('idm', 'waypoints'), doc="idm: at most the waypoints' speeds, slower as "
              'the improved Intelligent Driver Model (docs/traffic.md) asks behind whatever '
              "drives ahead within the actor's width (traffic, other vehicles); waypoints: "
              "exactly the waypoints' speeds, whatever is ahead"),
)

@dataclass(frozen=True)
class Waypoint:
    """A point to drive to [m] and the speed on the way to it [m/s]."""

    x_m: float
    y_m: float
    speed_mps: float


@dataclass(frozen=True)
class ActorSpec:
    """A scripted vehicle: which one, its waypoints, look-ahead and whether it loops."""

    vehicle: str
    waypoints: Tuple[Waypoint, ...]
    lookahead_m: float
    loop: bool
    line: Optional[int] = None
    speed_control: str = 'idm'


@dataclass(frozen=True)
class ScenarioSpec:
    """A validated scenario file."""

    name: str
    description: str
    source: str
    world: WorldSpec
    world_file: Optional[str]
    world_data: Optional[dict]
    robots: Tuple[RobotSpec, ...]
    vehicle: str
    duration_s: float
    seed: int
    time_step_ms: int
    actors: Tuple[ActorSpec, ...]
    driver: DriverSpec
    criteria: Tuple[CriterionSpec, ...]
    lines: Dict = field(default_factory=dict, compare=False, repr=False)

    @property
    def car_names(self):
        return tuple(v.name for v in self.world.vehicles)

    @property
    def robot_names(self):
        return tuple(r.name for r in self.robots)

    @property
    def served(self):
        """Tell whether the scenario runs served over ROS (processes, or a topic criterion)."""
        return self.driver.kind == 'processes' or any(c.kind == 'topic' for c in self.criteria)

    def with_seed(self, seed):
        """Return this scenario with another seed."""
        from dataclasses import replace
        return replace(self, seed=int(seed))


def load_scenario(path) -> ScenarioSpec:
    """
    Read and validate a scenario file.

    :param path: the .yaml file.
    :return: ScenarioSpec.
    :raises ScenarioError: ``file:line: what is wrong`` for any invalid content.
    """
    source = str(path)
    try:
        content = Path(path).read_bytes()
    except OSError as error:
        raise ScenarioError(source, None, f'cannot read: {error.strerror or error}') from None
    data, lines = load_with_lines(content, source)
    return scenario_from_data(data, lines, source)


class _Context:
    """The file, its lines and its folder, for errors and relative paths."""

    def __init__(self, source, lines):
        self.source = source
        self.lines = lines
        self.folder = Path(source).resolve().parent

    def fail(self, path, message):
        return ScenarioError(self.source, line_of(self.lines, path), message)

    def validated(self, specs, data, path, what):
        where = '.'.join(str(p) for p in path) or 'scenario'
        try:
            return validate_table(specs, data, where, what=what)
        except InvalidParameterError as error:
            raise error_at(self.source, self.lines, path, error) from None

    def relative(self, name):
        candidate = self.folder / name
        return str(candidate) if candidate.is_file() else name


def scenario_from_data(data, lines, source) -> ScenarioSpec:
    """
    Validate scenario data (see :func:`load_scenario`).

    :param data: the parsed YAML.
    :param lines: {path: line} from :func:`~.yaml_lines.load_with_lines`.
    :param source: file name for errors and relative paths.
    """
    ctx = _Context(source, lines)
    if not isinstance(data, dict):
        raise ctx.fail((), 'a scenario must be a mapping with world, duration, driver and '
                           'criteria')
    values = ctx.validated(SCENARIO_SPECS, data, (), 'a scenario')
    robots = _robots(ctx, values['robots'])
    world, world_file = _world(ctx, values['world'], cars_optional=bool(robots))
    world_data = values['world'] if world_file is None else None
    cars = tuple(v.name for v in world.vehicles)
    names = cars + tuple(r.name for r in robots)
    duplicates = used_twice(names)
    if duplicates:
        raise ctx.fail(('robots',), f'vehicle name(s) used twice: {brief(duplicates)}')
    vehicle = values['vehicle'] or names[0]
    if vehicle not in names:
        raise ctx.fail(('vehicle',), f'vehicle {brief(vehicle)}: not in the world; vehicles: '
                                     f'{", ".join(names)}')
    actors = _actors(ctx, values['actors'], names, vehicle)
    driver = driver_from_data(ctx, values['driver'], vehicle in cars, world)
    paced = driver.kind == 'processes' and driver.real_time_factor > 0.0
    if paced and values['duration_s'] / driver.real_time_factor > MAX_DURATION_S:
        raise ctx.fail(('driver', 'real_time_factor'),
                       f'real_time_factor = {driver.real_time_factor:g}: the '
                       f'{values["duration_s"]:g} s would take '
                       f'{values["duration_s"] / driver.real_time_factor:g} s of wall clock; '
                       f'at most {MAX_DURATION_S:g} s')
    criteria = criteria_from_list(ctx, data.get('criteria'), names, vehicle)
    name = values['name'] or Path(source).stem
    spec = ScenarioSpec(name, values['description'], source, world, world_file, world_data,
                        robots, vehicle,
                        values['duration_s'], values['seed'], values['time_step_ms'], actors,
                        driver, criteria, lines)
    for index, robot in enumerate(robots):
        if robot.sensors and not spec.served:
            raise ctx.fail(('robots', index, 'sensors'),
                           f'robot {brief(robot.name)}: its sensors are published over ROS by its '
                           'node, and this scenario runs without ROS; add the process that '
                           'reads them (driver.processes) or a topic criterion')
    return spec


def _world(ctx, value, cars_optional):
    # A world name or file, or an inline world: a world file's mapping, read by the same
    # parser; without cars when the scenario's vehicles are all robots.
    path = ('world',)
    try:
        if isinstance(value, str):
            file = ctx.relative(value)
            return config.load_world(file), str(config.world_path(file))
        if isinstance(value, dict):
            return config.world_from_data(value, f'{ctx.source}: world',
                                          vehicles_required=not cars_optional,
                                          base_dir=str(ctx.folder)), None
    except InvalidParameterError as error:
        raise error_at(ctx.source, ctx.lines, path, error) from None
    raise ctx.fail(path, f'world = {brief(value)}: give a world name, a path to a world .yaml or '
                         'an inline world mapping')


def _robots(ctx, value):
    if value is None:
        return ()
    if not isinstance(value, list):
        raise ctx.fail(('robots',), 'robots must be a list of {name, model, pose}')
    robots = []
    for index, entry in enumerate(value):
        path = ('robots', index)
        values = ctx.validated(ROBOT_SPECS, entry, path, 'a robot')
        try:
            config.load_robot(values['model'])
        except InvalidParameterError as error:
            raise ctx.fail(path + ('model',), str(error)) from None
        pose = values['pose']
        x_m, y_m, yaw_rad = (pose.x_m, pose.y_m, pose.yaw_rad) if pose else (0.0, 0.0, 0.0)
        sensors = _robot_sensors(ctx, values['sensors'], values['model'], path + ('sensors',))
        robots.append(RobotSpec(values['name'], values['model'], x_m, y_m, yaw_rad, sensors))
    return tuple(robots)


def _robot_sensors(ctx, value, model, path):
    # None, 'all' or a list of names of the preset's sensors (the diff_robot node's parameter).
    if value is None:
        return ()
    names = ('all',) if value == 'all' else value
    if not (isinstance(names, (list, tuple)) and names
            and all(isinstance(n, str) and n for n in names)):
        raise ctx.fail(path, f"sensors {brief(value)}: a list of sensor names, or 'all'")
    try:
        enable_sensors(config.load_robot(model).sensor_set, selected_sensors(names),
                       f'robot model {brief(model)}')
    except InvalidParameterError as error:
        raise ctx.fail(path, str(error)) from None
    return tuple(names)


def _actors(ctx, value, names, vehicle):
    if value is None:
        return ()
    if not isinstance(value, list):
        raise ctx.fail(('actors',), 'actors must be a list of {vehicle, waypoints, speed}')
    actors, taken = [], set()
    for index, entry in enumerate(value):
        path = ('actors', index)
        values = ctx.validated(ACTOR_SPECS, entry, path, 'an actor')
        name = values['vehicle']
        if name not in names:
            raise ctx.fail(path + ('vehicle',), f'vehicle {brief(name)}: not in the world; '
                                                f'vehicles: {", ".join(names)}')
        if name == vehicle:
            raise ctx.fail(path + ('vehicle',), f'vehicle {brief(name)} is the vehicle under test '
                                                '(the driver drives it)')
        if name in taken:
            raise ctx.fail(path + ('vehicle',), f'vehicle {brief(name)} has two actors')
        taken.add(name)
        points = _waypoints(ctx, values['waypoints'], path + ('waypoints',),
                            values['speed_mps'])
        actors.append(ActorSpec(name, points, values['lookahead_m'], values['loop'],
                                line_of(ctx.lines, path), values['speed_control']))
    return tuple(actors)


def _waypoints(ctx, value, path, speed_mps):
    if not isinstance(value, list) or not value:
        raise ctx.fail(path, 'waypoints must be a non-empty list of [x, y] or [x, y, speed]')
    points = []
    for index, point in enumerate(value):
        ok = isinstance(point, list) and len(point) in (2, 3) and all(
            isinstance(v, (int, float)) and not isinstance(v, bool) and abs(v) < float('inf')
            for v in point)
        if not ok or (len(point) == 3 and point[2] < 0):
            raise ctx.fail(path + (index,), f'waypoint {brief(point)}: must be [x, y] or '
                                            '[x, y, speed >= 0] (finite numbers)')
        points.append(Waypoint(float(point[0]), float(point[1]),
                               float(point[2]) if len(point) == 3 else speed_mps))
    return tuple(points)


def schema_markdown():
    """Return the key tables of docs/scenarios.md (the file format), generated from the specs."""
    from vehicle_sim.core.specs.param_spec import parameter_table_markdown
    from vehicle_sim.scenarios.criteria import common_specs, CRITERIA
    parts = ['#### Top level\n\n', parameter_table_markdown(SCENARIO_SPECS, 'key'),
             '\n#### `robots` entries\n\n', parameter_table_markdown(ROBOT_SPECS, 'key'),
             '\n#### `actors` entries\n\n', parameter_table_markdown(ACTOR_SPECS, 'key'),
             '\n#### `driver`\n\n', parameter_table_markdown(DRIVER_SPECS, 'key'),
             '\n#### `driver.commands` setters (besides `t` [s])\n\n',
             '| key | Webots setter | value | unit | description |\n|---|---|---|---|---|\n']
    for key, row in sorted(COMMAND_ROWS.items()):
        parts.append(f'| `{key}` | `{row.setter}` | {row.kind} | {row.unit} | {row.doc} |\n')
    parts.append(f'| `{SIGNAL_COMMAND}` | - | mapping |  | forces a traffic light group of the '
                 "world's lane map: {"
                 + ', '.join(spec.key for spec in SIGNAL_COMMAND_SPECS) + '} (below) |\n')
    parts += [f'\n#### `driver.commands` `{SIGNAL_COMMAND}` keys\n\n',
              parameter_table_markdown(SIGNAL_COMMAND_SPECS, 'key')]
    parts += ['\n#### Keys of every criterion\n\n',
              parameter_table_markdown(common_specs(), 'key')]
    for kind, cls in sorted(CRITERIA.items()):     # not import order: one order everywhere
        table = (parameter_table_markdown(cls.SPECS, 'key') if cls.SPECS
                 else 'No keys of its own.\n')
        unit = cls.UNIT or "the field's unit"
        parts.append(f'\n#### `{kind}` (measured value in {unit})\n\n{cls.__doc__.strip()}\n\n'
                     + table)
    return ''.join(parts)
