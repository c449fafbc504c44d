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
The ``driver`` section of a scenario file: what drives the vehicle under test.

One of three kinds (``DRIVER_KINDS``): timed Webots setter ``commands``, a Webots-API
``controller`` script, or ``processes`` served over ROS (with lockstep ``sync`` topics).
:mod:`.schema` validates the rest of the file and calls :func:`driver_from_data`.

A command may also force a traffic light group of the world's lane map into a state
(``signal: {group, state}``, :data:`SIGNAL_COMMAND_SPECS`): ``state`` one of red, yellow, green,
off (held until another command for the group), or ``plan`` (the group follows its plan again).
The group must be one of the world's lane map (checked when the file is loaded).
"""

from dataclasses import dataclass
import os
import shlex
from typing import Any, Optional, Tuple

from vehicle_sim.core.map.lane_rules import SIGNAL_STATES
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.param_spec import ParamSpec, REQUIRED, validate_table
from vehicle_sim.core.specs.value_text import brief
from vehicle_sim.scenarios.yaml_lines import line_of
from vehicle_sim.webots.api_table import CAR_API, DRIVER_API

DRIVER_KINDS = ('commands', 'controller', 'processes')
# The longest a scenario may run (simulated) and wait (wall clock): a file cannot keep the runner
# busy for ever.
MAX_DURATION_S = 86400.0
MAX_WAIT_S = 3600.0
# The keys of a driver.sync entry: a topic, its type and the messages per sync period.
SYNC_KEYS = frozenset(('topic', 'type', 'count'))

DRIVER_SPECS = (
    ParamSpec('commands', 'commands', 'raw', None, optional=True,
              doc='[{t: s, <setter>: value, ...}, ...] in time order (Webots driver setters)'),
    ParamSpec('controller', 'controller', 'str', None, optional=True,
              doc='Webots-API controller script (.py, relative to the scenario file), run in '
                  "the runner's process"),
    ParamSpec('args', 'args', 'raw', (), doc="the controller's sys.argv[1:] (strings)",
              check=lambda v: None if isinstance(v, (list, tuple)) and all(
                  isinstance(a, str) for a in v) else 'must be a list of strings'),
    ParamSpec('processes', 'processes', 'raw', None, optional=True,
              doc='command lines started as subprocesses (ROS 2 nodes, built-ins; the '
                  "program 'python' is the runner's interpreter); the simulation is served "
                  'over ROS with /clock'),
    ParamSpec('real_time_factor', 'real_time_factor', 'float', 1.0, '',
              'processes: simulated seconds per wall-clock second; 0 = as fast as possible; '
              f'duration / real_time_factor at most {MAX_DURATION_S:g} s', ge=0.0),
    ParamSpec('sync', 'sync', 'raw', (), doc='processes: lockstep topics [{topic, type, '
              'count}, ...]: after every sync_period the runner waits until each has count '
              "(default 1) new messages (the controller's answers to that /clock), and the "
              'served robots have taken them'),
    ParamSpec('sync_period', 'sync_period_s', 'float', 0.0, 's', 'processes: simulated time '
              'between lockstep waits; 0 = every basic step', ge=0.0),
    ParamSpec('sync_timeout', 'sync_timeout_s', 'float', 5.0, 's', 'processes: longest '
              'lockstep wait (wall clock); a longer one ends the run with an error', gt=0.0,
              le=MAX_WAIT_S),
    ParamSpec('clock_subscribers', 'clock_subscribers', 'int', -1, '',
              'processes: time starts once /clock has this many subscribers (and the runner '
              'has matched a publisher of each sync topic); -1 = one per process', ge=-1),
    ParamSpec('startup_timeout', 'startup_timeout_s', 'float', 60.0, 's',
              'processes: how long to wait for them (wall clock)', gt=0.0, le=MAX_WAIT_S),
)

# Webots driver-level setters a command may hold: the snake_case names of the 2023 Python
# wrapper (api_table ``prop``), applied through the strict core setter.
COMMAND_ROWS = {row.prop: row for row in DRIVER_API + CAR_API
                if row.setter is not None and row.prop is not None}
# The command key that forces a traffic light group, its keys (one table: the loader, the
# runner and docs/scenarios.md read it) and the states it takes ('plan': back to the plan).
SIGNAL_COMMAND = 'signal'
SIGNAL_COMMAND_STATES = SIGNAL_STATES + ('plan',)
SIGNAL_COMMAND_SPECS = (
    ParamSpec('group', 'group', 'int', REQUIRED, '',
              "the traffic light group id (the map's; roads: docs/signals.md)"),
    ParamSpec('state', 'state', 'enum', REQUIRED, '',
              'held from this step until another command for the group; plan: the group '
              'follows its plan again', choices=SIGNAL_COMMAND_STATES),
)


@dataclass(frozen=True)
class Command:
    """Setters applied at time ``t_s``: ((core setter, value, Webots name), ...)."""

    t_s: float
    setters: Tuple[Tuple[str, Any, str], ...]
    line: Optional[int] = None
    signals: Tuple[Tuple[int, str], ...] = ()     # (group id, state) forced at ``t_s``


@dataclass(frozen=True)
class DriverSpec:
    """What drives the vehicle under test: ``kind`` is one of DRIVER_KINDS."""

    kind: str
    commands: Tuple[Command, ...] = ()
    controller: Optional[str] = None
    args: Tuple[str, ...] = ()
    processes: Tuple[Tuple[str, ...], ...] = ()
    real_time_factor: float = 1.0
    clock_subscribers: int = -1
    startup_timeout_s: float = 60.0
    sync: Tuple[Tuple[str, str, int], ...] = ()   # (topic, type, messages per sync period)
    sync_period_s: float = 0.0
    sync_timeout_s: float = 5.0


def driver_from_data(ctx, value, drives_car, world=None):
    """
    Validate a scenario's ``driver`` mapping into a :class:`DriverSpec`.

    :param ctx: the scenario file's context (``fail``, ``validated``, ``relative``, ``lines``,
        ``folder``), as :mod:`.schema` makes it.
    :param value: the ``driver`` value of the file.
    :param drives_car: whether the vehicle under test is a car (commands and controllers drive
        cars; a robot takes processes).
    :param world: the scenario's WorldSpec (its lane map names the groups of signal commands).
    :raises ScenarioError: naming the file, the line and the key.
    """
    path = ('driver',)
    values = ctx.validated(DRIVER_SPECS, value, path, 'the driver')
    given = [kind for kind in DRIVER_KINDS if values[kind] is not None]
    if len(given) != 1:
        raise ctx.fail(path, f'driver: give exactly one of {", ".join(DRIVER_KINDS)} '
                             f'(got {", ".join(given) or "none"})')
    kind = given[0]
    if kind == 'commands':
        if not drives_car:
            raise ctx.fail(path + ('commands',), 'commands drive a car (Webots driver '
                                                 'setters); a robot takes processes')
        return DriverSpec(kind, commands=_commands(ctx, values['commands'], world))
    if kind == 'controller':
        if not drives_car:
            raise ctx.fail(path + ('controller',), 'a Webots controller drives a car')
        script = ctx.relative(values['controller'])
        if not os.path.isfile(script):
            raise ctx.fail(path + ('controller',), f'controller {brief(values["controller"])}: no '
                                                   f'such file (relative to {ctx.folder})')
        return DriverSpec(kind, controller=script, args=tuple(values['args']))
    return DriverSpec(kind, processes=_processes(ctx, values['processes']),
                      real_time_factor=values['real_time_factor'],
                      clock_subscribers=values['clock_subscribers'],
                      startup_timeout_s=values['startup_timeout_s'],
                      sync=_sync(ctx, values['sync']), sync_period_s=values['sync_period_s'],
                      sync_timeout_s=values['sync_timeout_s'])


def _sync(ctx, value):
    path = ('driver', 'sync')
    if not isinstance(value, (list, tuple)):
        raise ctx.fail(path, 'sync must be a list of {topic, type, count}')
    topics = []
    for index, entry in enumerate(value):
        if not (isinstance(entry, dict) and {'topic', 'type'} <= set(entry) <= SYNC_KEYS
                and all(isinstance(entry[k], str) and entry[k] for k in ('topic', 'type'))):
            raise ctx.fail(path + (index,), f'sync entry {brief(entry)}: must be {{topic: /name, '
                                            'type: pkg/msg/Type, count: messages (optional, 1)}')
        count = entry.get('count', 1)
        if isinstance(count, bool) or not isinstance(count, int) or count < 1:
            raise ctx.fail(path + (index, 'count'), f'sync count = {brief(count)}: must be an '
                                                    'integer >= 1 (messages per sync period)')
        topics.append((entry['topic'], entry['type'], count))
    return tuple(topics)


def _commands(ctx, value, world):
    path = ('driver', 'commands')
    if not isinstance(value, list) or not value:
        raise ctx.fail(path, 'commands must be a non-empty list of {t: s, <setter>: value}')
    commands, last_t, groups = [], 0.0, _GroupCheck(ctx, world)
    for index, entry in enumerate(value):
        where = path + (index,)
        if not isinstance(entry, dict) or 't' not in entry:
            raise ctx.fail(where, f'command {brief(entry)}: must be a mapping with t (s) and '
                                  'setters')
        t_s = entry['t']
        if isinstance(t_s, bool) or not isinstance(t_s, (int, float)) or not 0 <= t_s < 1e12:
            raise ctx.fail(where + ('t',), f't = {brief(t_s)}: must be a finite time >= 0 s')
        if t_s < last_t:
            raise ctx.fail(where + ('t',), f't = {brief(t_s)}: commands must be in time order '
                                           f'(previous t = {brief(last_t)})')
        last_t = t_s
        setters, signals = [], []
        for key, item in entry.items():
            if key == 't':
                continue
            if key == SIGNAL_COMMAND:
                signals.append(_signal(ctx, where + (key,), item, groups))
                continue
            row = COMMAND_ROWS.get(key)
            if row is None:
                raise ctx.fail(where + (key,), f'unknown setter {brief(key)}; valid: '
                                               + ', '.join(sorted(COMMAND_ROWS))
                                               + f' (and {SIGNAL_COMMAND})')
            setters.append((row.core_setter, _command_value(ctx, where + (key,), row, item),
                            row.setter))
        if not setters and not signals:
            raise ctx.fail(where, 'a command needs at least one setter besides t')
        commands.append(Command(float(t_s), tuple(setters), line_of(ctx.lines, where),
                                tuple(signals)))
    return tuple(commands)


class _GroupCheck:
    """The traffic light groups of the scenario's world, its lane map loaded when first asked."""

    def __init__(self, ctx, world):
        self.ctx, self.world, self.rules = ctx, world, None

    def check(self, path, group_id):
        if self.rules is None:
            from vehicle_sim.maps.lane_maps import load_lane_graph
            graph = None if self.world is None else load_lane_graph(self.world)
            if graph is None:
                raise self.ctx.fail(path, f'signal.group = {brief(group_id)}: the world has no '
                                          'lane map (roads: or a Lanelet2 map) with traffic '
                                          'lights')
            self.rules = graph.rules
        try:
            self.rules.group(group_id)
        except InvalidParameterError as error:
            raise self.ctx.fail(path, f'signal.group = {brief(group_id)}: {error}') from None


def _signal(ctx, path, value, groups):
    try:
        values = validate_table(SIGNAL_COMMAND_SPECS, value, SIGNAL_COMMAND,
                                what='a signal command {group, state}')
    except InvalidParameterError as error:
        raise ctx.fail(path, str(error)) from None
    groups.check(path + ('group',), values['group'])
    return values['group'], values['state']


def _command_value(ctx, path, row, value):
    # The type only: ranges depend on the car and are the core setter's (checked at run start).
    number = isinstance(value, (int, float)) and not isinstance(value, bool)
    if row.kind == 'bool' and isinstance(value, bool):
        return value
    if row.kind in ('int', 'enum') and number and float(value).is_integer():
        return int(value)
    if row.kind == 'float' and number and abs(value) < float('inf'):
        return float(value)
    want = {'bool': 'true or false', 'int': 'an integer', 'enum': 'an integer',
            'float': 'a finite number'}[row.kind]
    raise ctx.fail(path, f'{path[-1]} = {brief(value)}: must be {want} ({row.setter}, '
                         f'{row.unit or "no unit"})')


def _processes(ctx, value):
    path = ('driver', 'processes')
    if isinstance(value, str):
        value = [value]
    if not isinstance(value, list) or not value:
        raise ctx.fail(path, 'processes must be a command line or a list of them')
    commands = []
    for index, entry in enumerate(value):
        if isinstance(entry, str):
            argv = shlex.split(entry)
        elif isinstance(entry, list) and all(isinstance(a, str) for a in entry):
            argv = list(entry)
        else:
            argv = []
        if not argv:
            raise ctx.fail(path + (index,), f'process {brief(entry)}: a command line (a string or '
                                            'a list of strings)')
        commands.append(tuple(argv))
    return tuple(commands)
