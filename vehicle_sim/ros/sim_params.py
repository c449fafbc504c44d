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
The automobile node's parameters, declared once (STYLE rule 6).

``config/automobile.yaml``, the node's declarations and ``docs/ros_interface.md`` derive from
:data:`AUTOMOBILE_PARAMETERS`. Bad values are rejected with a reason naming the parameter, its
value and the valid range; nothing is clamped.
"""

from dataclasses import dataclass
import math
from typing import Any, Callable, Optional, Tuple

from vehicle_sim.config import (  # noqa: F401 (re-exported)
    car_names,
    find_config,
    load_world,
    parse_world,
    VehicleSpec,
    world_path,
)
from vehicle_sim.core.errors import InvalidParameterError
from vehicle_sim.physics import DEFAULT_FRICTION


@dataclass(frozen=True)
class ParamSpec:
    """
    One node parameter.

    :param name: parameter name.
    :param default: default value (its Python type is the ROS parameter type).
    :param unit: unit, '' when none.
    :param doc: description shown by ``ros2 param describe``.
    :param check: ``check(value)`` returns None or the reason the value is refused.
    :param read_only: fixed once the node runs (the world is built from it).
    """

    name: str
    default: Any
    unit: str
    doc: str
    check: Optional[Callable[[Any], Optional[str]]] = None
    read_only: bool = True

    def validator(self, value):
        """Return None when ``value`` is valid, else a reason naming parameter and value."""
        if self.check is None:
            return None
        reason = self.check(value)
        return None if reason is None else f'{self.name} = {value!r}: {reason}'

    @property
    def description(self) -> str:
        unit = f' [{self.unit}]' if self.unit else ''
        return self.doc + unit


def _finite(value):
    return None if math.isfinite(value) else 'must be a finite number'


def _at_least(low, strict=False):
    def check(value):
        if not math.isfinite(value):
            return 'must be a finite number'
        if value < low or (strict and value == low):
            return f'must be {">" if strict else ">="} {low}'
        return None
    return check


def _int_range(low, high):
    def check(value):
        return None if low <= value <= high else f'must be in {low}..{high}'
    return check


def _car_model(value):
    try:
        find_config('cars', value)
    except InvalidParameterError:
        return f'unknown car model; known: {", ".join(car_names())} (or a path to a .yaml file)'
    return None


def _world(value):
    if value == '':
        return None
    try:
        find_config('worlds', value)
    except InvalidParameterError as error:
        return str(error)
    return None


AUTOMOBILE_PARAMETERS: Tuple[ParamSpec, ...] = (
    ParamSpec('car_model', 'Car', '',
              'car preset name (config/cars) or path to a preset .yaml; model of the default '
              'vehicle and of world entries that give none', _car_model),
    ParamSpec('world', '', '',
              "world name (config/worlds) or path to a world .yaml; '' = one car 'Car' "
              'with no namespace at the initial pose', _world),
    ParamSpec('initial_x', 0.0, 'm', 'initial x of the default vehicle in the world frame',
              _finite),
    ParamSpec('initial_y', 0.0, 'm', 'initial y of the default vehicle in the world frame',
              _finite),
    ParamSpec('initial_yaw', 0.0, 'rad', 'initial yaw of the default vehicle (REP 103, + = left)',
              _finite),
    ParamSpec('time_step_ms', 10, 'ms', 'basic time step of the world (Webots basicTimeStep)',
              _int_range(1, 1000)),
    ParamSpec('publish_period_ms', 0, 'ms',
              'period of the topics (/clock excepted); 0 = each basic step; a multiple of '
              'time_step_ms', _int_range(0, 60000)),
    ParamSpec('real_time_factor', 1.0, '1',
              'simulated time per wall time: 1 = real time, 0 = as fast as possible '
              '(ignored when synchronous)', _at_least(0.0)),
    ParamSpec('synchronous', False, '',
              'advance the world only on robot/time_step calls (Webots --synchronize)'),
    ParamSpec('friction', DEFAULT_FRICTION, '1', 'tyre-road friction coefficient of the ground',
              _at_least(0.0, strict=True)),
)


def defaults():
    """Return {name: default} of every parameter (plus use_sim_time, declared by the port)."""
    values = {spec.name: spec.default for spec in AUTOMOBILE_PARAMETERS}
    values['use_sim_time'] = False
    return values


@dataclass(frozen=True)
class SimSettings:
    """The validated parameter values the node runs with."""

    car_model: str
    world: str
    initial_x: float
    initial_y: float
    initial_yaw: float
    time_step_ms: int
    publish_period_ms: int
    real_time_factor: float
    synchronous: bool
    friction: float

    @property
    def time_step_s(self) -> float:
        return self.time_step_ms * 1e-3

    @property
    def publish_every_steps(self) -> int:
        """Basic steps per publish period (1 = each step)."""
        if self.publish_period_ms == 0:
            return 1
        return self.publish_period_ms // self.time_step_ms


def declare_parameters(node) -> SimSettings:
    """
    Declare every parameter on a node and return the validated settings.

    :param node: a transport NodePort.
    :raises InvalidParameterError: a value is refused (also for the cross-parameter rule
        publish_period_ms % time_step_ms == 0).
    """
    values = {}
    for spec in AUTOMOBILE_PARAMETERS:
        values[spec.name] = node.declare_parameter(
            spec.name, spec.default, description=spec.description, validator=spec.validator,
            read_only=spec.read_only)
    settings = SimSettings(**values)
    if settings.publish_period_ms % settings.time_step_ms:
        raise InvalidParameterError(
            f'publish_period_ms = {settings.publish_period_ms} must be 0 or a multiple of '
            f'time_step_ms = {settings.time_step_ms}')
    return settings


def params_file_text(node_name='automobile') -> str:
    """Return config/automobile.yaml: every parameter with its default and description."""
    lines = [f'{node_name}:', '  ros__parameters:']
    for spec in AUTOMOBILE_PARAMETERS:
        lines.append(f'    # {spec.description}')
        lines.append(f'    {spec.name}: {_yaml_value(spec.default)}')
    lines.append('    # use /clock as the node clock (ROS standard)')
    lines.append('    use_sim_time: false')
    return '\n'.join(lines) + '\n'


def _yaml_value(value):
    if isinstance(value, bool):
        return 'true' if value else 'false'
    if isinstance(value, str):
        return f"'{value}'"
    return repr(value)


def parameter_table_markdown() -> str:
    """Return the Markdown table of the parameters (docs/ros_interface.md)."""
    lines = ['| parameter | default | unit | description |', '|---|---|---|---|']
    for spec in AUTOMOBILE_PARAMETERS:
        lines.append(f'| `{spec.name}` | `{_yaml_value(spec.default)}` | {spec.unit} | '
                     f'{spec.doc} |')
    lines.append('| `use_sim_time` | `false` |  | use /clock as the node clock (ROS standard) |')
    return '\n'.join(lines) + '\n'


def world_vehicles(settings: SimSettings) -> Tuple[VehicleSpec, ...]:
    """
    Return the vehicles to simulate.

    :param settings: the node settings; ``world == ''`` gives the default car.
    :raises InvalidParameterError: for an invalid world file.
    """
    if not settings.world:
        return (VehicleSpec('Car', '', settings.car_model, settings.initial_x,
                            settings.initial_y, settings.initial_yaw),)
    return load_world(settings.world, settings.car_model).vehicles
