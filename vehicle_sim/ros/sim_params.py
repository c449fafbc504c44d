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
The automobile node's parameters, declared once (one ParamSpec table).

:data:`AUTOMOBILE_PARAMETERS` is a core ParamSpec table; the node declares it through
``ros/node_support.py``, and ``config/automobile.yaml`` and the table in
``docs/ros_interface.md`` are generated from it (tests check both). Bad values are rejected with a
reason naming the parameter, its value and the valid range; nothing is clamped.
"""

from dataclasses import dataclass
from typing import Tuple

from vehicle_sim.config import (  # noqa: F401 (re-exported)
    car_names,
    find_config,
    load_car,
    load_world,
    parse_world,
    VehicleSpec,
    world_path,
    WorldSpec,
)
from vehicle_sim.core.geometry.geodesy import GeodeticOrigin
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.param_spec import ParamSpec, table_defaults
from vehicle_sim.core.specs.simulation import FRICTION, TIME_STEP_MS
from vehicle_sim.core.traffic.params import OBJECTS_RATE
from vehicle_sim.ros import node_support
from vehicle_sim.ros.endpoints import CMD_VEL_STAMPED_PARAMETER, CMD_VEL_TIMEOUT_PARAMETER
from vehicle_sim.ros.sensor_interfaces import SENSORS_PARAMETER


def _config_file(subdir):
    def check(value):
        if value == '' and subdir == 'worlds':
            return None
        try:
            find_config(subdir, value)
        except InvalidParameterError as error:
            return str(error)
        return None
    return check


AUTOMOBILE_PARAMETERS: Tuple[ParamSpec, ...] = (
    ParamSpec('car_model', kind='str', default='Car',
              doc='car preset name (config/cars) or path to a preset .yaml; model of the default '
                  'vehicle and of world entries that give none', check=_config_file('cars')),
    ParamSpec('world', kind='str', default='', empty=True,
              doc="world name (config/worlds) or path to a world .yaml; '' = one car 'Car' "
                  'with no namespace at the initial pose', check=_config_file('worlds')),
    ParamSpec('initial_x', kind='float', default=0.0, unit='m',
              doc='initial x of the default vehicle in the world frame'),
    ParamSpec('initial_y', kind='float', default=0.0, unit='m',
              doc='initial y of the default vehicle in the world frame'),
    ParamSpec('initial_yaw', kind='float', default=0.0, unit='rad',
              doc='initial yaw of the default vehicle (REP 103, + = left)'),
    TIME_STEP_MS,
    ParamSpec('publish_period_ms', kind='int', default=0, unit='ms', ge=0, le=60000,
              doc='period of the topics (/clock excepted); 0 = each basic step; a multiple of '
                  'time_step_ms'),
    ParamSpec('real_time_factor', kind='float', default=1.0, unit='1', ge=0.0,
              doc='simulated time per wall time: 1 = real time, 0 = as fast as possible '
                  '(ignored when synchronous)'),
    ParamSpec('synchronous', kind='bool', default=False,
              doc='advance the world only on robot/time_step calls (Webots --synchronize)'),
    OBJECTS_RATE,
    FRICTION,
    SENSORS_PARAMETER,
    CMD_VEL_STAMPED_PARAMETER,
    CMD_VEL_TIMEOUT_PARAMETER,
    ParamSpec('initialpose_vehicle', kind='str', default='', empty=True,
              doc="name of the vehicle that /initialpose (RViz 2D Pose Estimate) teleports; "
                  "'' = the first vehicle of the world"),
    ParamSpec('gui', kind='bool', default=False,
              doc="open PyBullet's window, a chase camera following the first vehicle (needs "
                  'an X display; docs/drive.md)'),
    ParamSpec('foxglove', kind='int', default=0, unit='', ge=0, le=65535,
              doc='TCP port of a Foxglove WebSocket server showing the node live (topics, 3D '
                  "scene, services, parameters; the 'foxglove' extra; docs/foxglove.md); "
                  '0 = none'),
    ParamSpec('foxglove_host', kind='str', default='127.0.0.1',
              doc='address the Foxglove server listens on; beyond loopback anyone who reaches '
                  'it can call the services (the protocol has no authentication)'),
)


def defaults():
    """
    Return {name: default} of every parameter (plus use_sim_time, declared by the port).

    Values as a parameter file holds them (lists for the string arrays).
    """
    return {key: list(value) if isinstance(value, tuple) else value for key, value in
            table_defaults(AUTOMOBILE_PARAMETERS + (node_support.USE_SIM_TIME,)).items()}


def parameter_names() -> Tuple[str, ...]:
    """Return the node's parameter names (use_sim_time included)."""
    return tuple(spec.key for spec in AUTOMOBILE_PARAMETERS + (node_support.USE_SIM_TIME,))


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
    sensors: Tuple[str, ...] = ('',)
    cmd_vel_stamped: bool = False
    cmd_vel_timeout_s: float = CMD_VEL_TIMEOUT_PARAMETER.default
    initialpose_vehicle: str = ''
    gui: bool = False
    foxglove: int = 0
    foxglove_host: str = '127.0.0.1'
    objects_rate_hz: float = OBJECTS_RATE.default

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
    :raises TransportError: an override is refused (naming parameter, value and range).
    """
    settings = SimSettings(**node_support.declare_parameters(node, AUTOMOBILE_PARAMETERS))
    if settings.publish_period_ms % settings.time_step_ms:
        raise InvalidParameterError(
            f'publish_period_ms = {settings.publish_period_ms} must be 0 or a multiple of '
            f'time_step_ms = {settings.time_step_ms}')
    return settings


def params_file_text(node_name='automobile') -> str:
    """Return config/automobile.yaml: every parameter with its default and description."""
    return node_support.params_file_text(node_name, AUTOMOBILE_PARAMETERS)


def parameter_table_markdown() -> str:
    """Return the Markdown table of the parameters (docs/ros_interface.md)."""
    return node_support.node_parameter_table(AUTOMOBILE_PARAMETERS)


def world_spec(settings: SimSettings) -> WorldSpec:
    """
    Return the world to simulate: origin, vehicles (with their sensors) and obstacles.

    :param settings: the node settings; ``world == ''`` gives the default car (its preset's
        sensors, none mounted) at the initial pose, no obstacles, origin at 0 deg, 0 deg, 0 m.
    :raises InvalidParameterError: for an invalid world file (naming file, entry and field).
    """
    if not settings.world:
        model = settings.car_model
        car = VehicleSpec('Car', '', model, settings.initial_x, settings.initial_y,
                          settings.initial_yaw, load_car(model).sensor_set)
        return WorldSpec(GeodeticOrigin(), (car,), ())
    return load_world(settings.world, settings.car_model)


def initialpose_index(settings: SimSettings, scene: WorldSpec) -> int:
    """
    Return the index of the vehicle /initialpose teleports (parameter initialpose_vehicle).

    :raises InvalidParameterError: for a name that is not a vehicle of the world.
    """
    name = settings.initialpose_vehicle
    if not name:
        return 0
    names = [vehicle.name for vehicle in scene.vehicles]
    if name not in names:
        raise InvalidParameterError(
            f'initialpose_vehicle = {name!r}: not a vehicle of the world; vehicles: '
            f'{", ".join(names)}')
    return names.index(name)


def world_vehicles(settings: SimSettings) -> Tuple[VehicleSpec, ...]:
    """Return the vehicles to simulate (see :func:`world_spec`)."""
    return world_spec(settings).vehicles
