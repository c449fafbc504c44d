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
A sensor type is registered once per layer under its core name, and checked across the layers.

The core registration (``SENSOR_TYPES``, core/sensors/params.py) names the types; physics
(``SENSOR_CLASSES``), ROS (``SENSOR_ROWS``) and Webots (``DEVICE_API``) register their part
under those names, each checked by ``check_layer`` when imported. Every physics class has the
one constructor shape ``cls(world, body, spec, plane)``.
"""

import ast
from dataclasses import dataclass, fields, replace
import inspect
from pathlib import Path

import pytest

from vehicle_sim.config import load_car, load_world
from vehicle_sim.core.sensors import params as sensor_params
from vehicle_sim.core.sensors.lidar_spec import LidarSpec
from vehicle_sim.core.sensors.params import (
    check_layer,
    sensor_as_dict,
    sensor_from_dict,
    SENSOR_TYPES,
)
from vehicle_sim.core.sensors.sets import check_sensor_set, static_transforms
from vehicle_sim.physics import World
from vehicle_sim.physics.sensor_urdf import sensor_links_urdf
from vehicle_sim.physics.sensors import Sensor, SENSOR_CLASSES, SensorSuite
from vehicle_sim.physics.sensors.distance import RayDistanceSensor
from vehicle_sim.physics.simulated_car import SimulatedCar
from vehicle_sim.ros import messages as m
from vehicle_sim.ros.sensor_interfaces import SENSOR_ROWS, sensor_rows
from vehicle_sim.webots import devices
from vehicle_sim.webots.api_table import DEVICE_API, DeviceRow
from vehicle_sim.webots.devices import Device, DEVICE_CLASSES

PACKAGE = Path(__file__).resolve().parent.parent / 'vehicle_sim'

LAYERS = {
    'physics': lambda: set(SENSOR_CLASSES),
    'ros': lambda: set(SENSOR_ROWS),
    'webots': lambda: {row.sensor_type for row in DEVICE_API},
}

# The registrations, the core type modules (core/sensors/<type>_spec.py: each table's ``type``)
# and the preset data that mounts sensors by type (configuration, as a YAML file would): the
# only modules that write a sensor type name.
REGISTRATION_FILES = {
    'core/sensors/params.py', 'core/sensors/defaults.py', 'physics/sensors/suite.py',
    'ros/sensor_interfaces.py', 'webots/api_table.py', 'core/sensors/*_spec.py',
}


@pytest.mark.parametrize('layer', sorted(LAYERS))
def test_every_layer_registers_exactly_the_core_sensor_types(layer):
    assert LAYERS[layer]() == set(SENSOR_TYPES)
    check_layer(layer, LAYERS[layer]())


@pytest.mark.parametrize('layer', sorted(LAYERS))
def test_a_core_type_missing_from_a_layer_is_refused_by_its_check(layer, monkeypatch):
    sonar = replace(SENSOR_TYPES['distance'])     # a type the core would add next
    monkeypatch.setitem(sensor_params.SENSOR_TYPES, 'sonar', sonar)
    with pytest.raises(RuntimeError, match=r'sensor types missing: sonar; unknown: none'):
        check_layer(layer, LAYERS[layer]())


def test_a_layer_type_unknown_to_the_core_is_refused():
    with pytest.raises(RuntimeError, match=r'missing: none; unknown: sonar'):
        check_layer('physics', set(SENSOR_TYPES) | {'sonar'})


@pytest.mark.parametrize('sensor_type', sorted(SENSOR_TYPES))
def test_every_physics_class_has_the_one_constructor_shape(sensor_type):
    cls = SENSOR_CLASSES[sensor_type]
    assert issubclass(cls, Sensor)
    parameters = list(inspect.signature(cls).parameters.values())
    assert [p.name for p in parameters] == ['world', 'body', 'spec', 'plane']
    assert parameters[3].default is None


def test_only_the_imu_tracks_motion():
    assert {name for name, cls in SENSOR_CLASSES.items() if cls.tracks_motion} == {'imu'}


def test_every_webots_device_row_resolves_to_a_device_class():
    for row in DEVICE_API:
        assert issubclass(DEVICE_CLASSES[row.device_class], Device)
        assert DEVICE_CLASSES[row.device_class].__name__ == row.device_class


def _string_literals(path):
    for node in ast.walk(ast.parse(path.read_text(encoding='utf-8'))):
        if isinstance(node, ast.Constant) and isinstance(node.value, str):
            yield node.lineno, node.value


def test_sensor_type_names_are_written_only_in_the_registrations():
    found = [f'{path.relative_to(PACKAGE)}:{line}: {text!r}'
             for path in sorted(PACKAGE.rglob('*.py'))
             if not any(path.relative_to(PACKAGE).match(name) for name in REGISTRATION_FILES)
             for line, text in _string_literals(path) if text in SENSOR_TYPES]
    assert found == []


def _core_imports(path):
    # every import of a vehicle_sim.core module, at module level or inside a function
    for node in ast.walk(ast.parse(path.read_text(encoding='utf-8'))):
        if isinstance(node, ast.ImportFrom):
            if (node.module or '').startswith('vehicle_sim.core.'):
                yield node.module
        elif isinstance(node, ast.Import):
            yield from (a.name for a in node.names if a.name.startswith('vehicle_sim.core.'))


def test_the_generic_spec_module_imports_no_sensor_module():
    imports = set(_core_imports(PACKAGE / 'core' / 'specs' / 'param_spec.py'))
    assert not {m for m in imports if 'sensor' in m}


@dataclass(frozen=True)
class _ImagingLidar(LidarSpec):
    """A lidar that also has an image frame (a new type would be its own SensorSpec)."""

    def optical_frame_id(self, prefix=''):
        return f'{prefix}{self.name}_image'


def test_an_image_frame_comes_from_the_spec_contract_not_from_the_camera_type():
    lidar = sensor_from_dict({'type': 'lidar', 'name': 'l'}, 'test')
    imaging = _ImagingLidar(**{f.name: getattr(lidar, f.name) for f in fields(lidar)})
    assert [t.child for t in static_transforms((lidar,), 'car/')] == ['car/l']
    assert [(t.parent, t.child) for t in static_transforms((imaging,), 'car/')] == [
        ('car/base_link', 'car/l'), ('car/l', 'car/l_image')]
    assert 'car/l_image_joint' in sensor_links_urdf((imaging,), 'car/')
    assert 'car/l_image_joint' not in sensor_links_urdf((lidar,), 'car/')


def test_a_new_type_registered_in_each_layer_works_with_no_other_change(monkeypatch):
    # A 'radar' that reuses the distance sensor's parts: only the four registrations change.
    specs = tuple(replace(spec, default='radar', choices=('radar',)) if spec.key == 'type'
                  else spec for spec in SENSOR_TYPES['distance'].specs)
    monkeypatch.setitem(sensor_params.SENSOR_TYPES, 'radar',
                        replace(SENSOR_TYPES['distance'], specs=specs))
    monkeypatch.setitem(SENSOR_CLASSES, 'radar', RayDistanceSensor)
    monkeypatch.setitem(SENSOR_ROWS, 'radar', SENSOR_ROWS['distance'])
    monkeypatch.setattr(devices, 'DEVICE_API',
                        DEVICE_API + (DeviceRow('DistanceSensor', 'radar', 'device', 'getRadar'),))
    spec = sensor_from_dict({'type': 'radar', 'name': 'front', 'pose': {'x': 4.6, 'z': 0.9},
                             'max_range': 20.0}, 'test')
    assert (spec.sensor_type, sensor_as_dict(spec)['type']) == ('radar', 'radar')
    assert check_sensor_set((spec,), 'test') is None
    assert [t.child for t in static_transforms((spec,))] == ['front']
    assert [(row.name, row.ros_type) for row in sensor_rows((spec,))] == [('front', m.RANGE)]
    world = World()
    try:
        for obstacle in load_world('obstacle_course').obstacles:   # a wall's face at x = 19.5 m
            world.add_obstacle(obstacle)
        car = SimulatedCar(world, load_car('Car'), (0.0, 0.0, 0.0))
        suite = SensorSuite(world, car.body, (spec,))
        world.step()
        assert suite.sample('front').range_m == pytest.approx(19.5 - 4.6, abs=1e-3)
        device, = devices.devices_of(suite).values()
        assert type(device) is devices.DistanceSensor
    finally:
        world.close()
