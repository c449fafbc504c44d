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
Finding and loading the YAML configuration files: car presets, robot presets and worlds.

The one place where presets and worlds are read (the ROS nodes, the Webots facade and the CLI
all come here). Kept outside ``core`` because it reads files with PyYAML; validation itself is
core's (core/car/params.py, core/diffdrive/params.py, core/world/params.py).
"""

import os
from pathlib import Path
from typing import Tuple

from vehicle_sim.core.car.params import car_params_from_dict, CarParams
from vehicle_sim.core.diffdrive.params import robot_params_from_dict, RobotParams
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.value_text import brief
from vehicle_sim.core.world.params import VehicleSpec, world_from_dict, WorldSpec
from vehicle_sim.yaml_files import load_file

__all__ = ['available', 'car_names', 'config_dirs', 'find_config', 'load_car', 'load_robot',
           'load_world', 'parse_world', 'read_yaml', 'robot_names', 'VehicleSpec',
           'world_names', 'world_path', 'WorldSpec']

PACKAGE_NAME = 'vehicle_sim'


def config_dirs():
    """
    Return the folders searched for configuration, most specific first.

    ``VEHICLE_SIM_CONFIG_DIR``, the source tree (editable installs), then ``share/vehicle_sim/
    config`` under the Python prefix and under every ``AMENT_PREFIX_PATH`` entry (ROS installs).
    """
    dirs = []
    if os.environ.get('VEHICLE_SIM_CONFIG_DIR'):
        dirs.append(Path(os.environ['VEHICLE_SIM_CONFIG_DIR']))
    dirs.append(Path(__file__).resolve().parent.parent / 'config')
    import sys
    dirs.append(Path(sys.prefix) / 'share' / PACKAGE_NAME / 'config')
    for prefix in os.environ.get('AMENT_PREFIX_PATH', '').split(os.pathsep):
        if prefix:
            dirs.append(Path(prefix) / 'share' / PACKAGE_NAME / 'config')
    return [d for d in dirs if d.is_dir()]


def find_config(subdir, name, suffix='.yaml'):
    """
    Resolve a configuration file by path or by name inside ``config/<subdir>``.

    :raises InvalidParameterError: when nothing matches; the message lists the known names.
    """
    candidate = Path(name)
    if candidate.suffix in ('.yaml', '.yml') and _is_file(candidate):
        return candidate
    for folder in config_dirs():
        path = folder / subdir / (name + suffix)
        if _is_file(path):
            return path
    what = subdir[:-1] if subdir.endswith('s') else subdir
    if _looks_like_path(name):
        # A path, not a preset name: the list of presets would not help.
        where = '' if candidate.is_absolute() else f' (relative to {os.getcwd()})'
        reason = ('is not a .yaml file' if _is_file(candidate) else
                  'is a folder, not a file' if _is_file(candidate, Path.is_dir) else
                  'does not exist')
        raise InvalidParameterError(f'{what} file {brief(name)} {reason}{where}')
    known = sorted(available(subdir))
    raise InvalidParameterError(
        f'unknown {what} {brief(name)}; '
        f'known: {", ".join(known) or "none"} (or give a path to a .yaml file)')


def _looks_like_path(name):
    return '/' in name or os.sep in name or name.endswith(('.yaml', '.yml'))


def _is_file(path, test=Path.is_file):
    # A name no file system takes (5000 characters, a NUL) names no file: not an OSError.
    try:
        return test(path)
    except (OSError, ValueError):
        return False


def available(subdir):
    """Names of the configuration files in ``config/<subdir>`` (without suffix)."""
    names = set()
    for folder in config_dirs():
        if (folder / subdir).is_dir():
            names.update(p.stem for p in (folder / subdir).glob('*.yaml'))
    return names


def read_yaml(path):
    """
    Read a YAML file within the bounds of vehicle_sim/yaml_files.py.

    :raises InvalidParameterError: one line naming the file (and line) of what is wrong.
    """
    return load_file(path)


def load_car(name_or_path='Car'):
    """
    Load and validate a car preset.

    :param name_or_path: preset name (``'ToyotaPrius'``), a path to a YAML file, or CarParams.
    :return: CarParams; fields the file omits take the Car defaults.
    :raises InvalidParameterError: naming file, field and value on any invalid content.
    """
    if isinstance(name_or_path, CarParams):
        return name_or_path
    path = find_config('cars', str(name_or_path))
    data = read_yaml(path)
    if data is None:
        data = {}
    return car_params_from_dict(data, source=str(path))


def car_names():
    """Names of the car presets shipped in config/cars."""
    return sorted(available('cars'))


def load_robot(name_or_path='caster_robot'):
    """
    Load and validate a robot preset from ``config/robots``.

    :param name_or_path: preset name (``'caster_robot'``), a path to a YAML file, or
        RobotParams (returned as is).
    :return: RobotParams.
    :raises InvalidParameterError: naming file, field and value on any invalid content.
    """
    if isinstance(name_or_path, RobotParams):
        return name_or_path
    path = find_config('robots', str(name_or_path))
    data = read_yaml(path)
    return robot_params_from_dict({} if data is None else data, source=str(path))


def robot_names():
    """Names of the robot presets shipped in config/robots."""
    return sorted(available('robots'))


def world_path(name):
    """Resolve a world name (config/worlds) or a path to a world .yaml."""
    return find_config('worlds', str(name))


def world_names():
    """Names of the worlds shipped in config/worlds."""
    return sorted(available('worlds'))


def _car_sensors(model):
    return load_car(model).sensor_set


def world_from_data(data, source, default_model='Car', vehicles_required=True,
                    base_dir=None) -> WorldSpec:
    """
    Validate a world mapping; car models are resolved in config/cars.

    :param data: the YAML content.
    :param source: file name quoted in errors.
    :param default_model: model of the vehicles that give none.
    :param vehicles_required: refuse a world without vehicles (see world_from_dict).
    :param base_dir: folder the files the world names (its map) are resolved in; None = the
        folder of ``source``.
    :raises InvalidParameterError: naming file, entry and field.
    """
    return world_from_dict(data, source, default_model, _car_sensors, vehicles_required,
                           base_dir)


def load_world(name_or_path, default_model='Car') -> WorldSpec:
    """
    Load and validate a world: origin, vehicles with their sensors, obstacles.

    :param name_or_path: world name (config/worlds) or a path to a world .yaml.
    :param default_model: model of the vehicles that give none.
    :return: WorldSpec.
    :raises InvalidParameterError: naming file, entry and field.
    """
    path = world_path(name_or_path)
    return world_from_data(read_yaml(path), str(path), default_model, base_dir=str(path.parent))


def parse_world(data, source, default_model) -> Tuple[VehicleSpec, ...]:
    """Validate a world mapping and return its vehicles (see :func:`world_from_data`)."""
    return world_from_data(data, source, default_model).vehicles
