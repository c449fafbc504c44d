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
Sensor configuration: the registry of the sensor types, and a sensor mapping's validation.

Each type's ParamSpec table, spec (a SensorSpec subclass) and cross-field check live in a module
of its own (core/sensors/lidar_spec.py, inertial_spec.py, distance_spec.py, camera_spec.py,
range_finder_spec.py, radar_spec.py; the common keys and the SensorSpec contract:
sensor_spec.py); :data:`SENSOR_TYPES` registers them under their type names.

A vehicle's sensors come from its preset (``sensors:`` of a car or robot preset, or the default
set of core/sensors/defaults.py, all off) and its world entry (``vehicles[i].sensors``). Every
entry is validated by :func:`vehicle_sim.core.specs.param_spec.validate_table` against the table
of its
``type``, so a negative range, a zero resolution, an unknown key or type, a NaN or a bad name is
refused with the file and the field in the message. Keys and defaults are listed in
docs/sensors.md, which a test checks against these tables.

The rules across a vehicle's sensors (unique names, devices and topics; merging a world entry
into a preset) are in core/sensors/sets.py.
"""

from dataclasses import dataclass, fields
from typing import Dict, Tuple

from vehicle_sim.core.geometry.frames import Pose
from vehicle_sim.core.sensors.camera_spec import CAMERA_SPECS, CameraSpec, check_camera
from vehicle_sim.core.sensors.distance_spec import check_distance, DISTANCE_SPECS, DistanceSpec
from vehicle_sim.core.sensors.inertial_spec import GNSS_SPECS, GnssSpec, IMU_SPECS, ImuSpec
from vehicle_sim.core.sensors.lidar_spec import check_lidar, LIDAR_SPECS, LidarSpec
from vehicle_sim.core.sensors.radar_spec import check_radar, RADAR_SPECS, RadarSpec
from vehicle_sim.core.sensors.range_finder_spec import (
    check_range_finder,
    RANGE_FINDER_SPECS,
    RangeFinderSpec,
)
from vehicle_sim.core.sensors.sensor_spec import common_specs, SensorSpec
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.param_spec import (
    parameter_table_markdown,
    ParamSpec,
    REQUIRED,
    validate_table,
)
from vehicle_sim.core.specs.value_text import brief


@dataclass(frozen=True)
class SensorType:
    """One registry row: the spec class, its ParamSpec table and its cross-field check."""

    spec_class: type
    specs: Tuple[ParamSpec, ...]
    check: object


# The core registration of the sensor types, in docs order: the one list of type names. Each
# other layer registers its part under these names (physics class, ROS rows, Webots devices);
# check_layer refuses a layer that misses one (docs/sensors.md, "Adding a sensor type").
SENSOR_TYPES: Dict[str, SensorType] = {
    'lidar': SensorType(LidarSpec, LIDAR_SPECS, check_lidar),
    'imu': SensorType(ImuSpec, IMU_SPECS, None),
    'gnss': SensorType(GnssSpec, GNSS_SPECS, None),
    'distance': SensorType(DistanceSpec, DISTANCE_SPECS, check_distance),
    'camera': SensorType(CameraSpec, CAMERA_SPECS, check_camera),
    'range_finder': SensorType(RangeFinderSpec, RANGE_FINDER_SPECS, check_range_finder),
    'radar': SensorType(RadarSpec, RADAR_SPECS, check_radar),
}


def check_layer(layer, registered):
    """
    Refuse a layer's sensor registration that misses a core sensor type or names an unknown one.

    :param layer: what registers (quoted in the error), e.g. 'physics SENSOR_CLASSES'.
    :param registered: the sensor type names the layer registers.
    :raises RuntimeError: naming the missing and the unknown types.
    """
    names = set(registered)
    missing = [name for name in SENSOR_TYPES if name not in names]
    unknown = sorted(names - set(SENSOR_TYPES))
    if missing or unknown:
        raise RuntimeError(f'{layer}: sensor types missing: {", ".join(missing) or "none"}; '
                           f'unknown: {", ".join(unknown) or "none"} (registered in '
                           f'core/sensors/params.py SENSOR_TYPES: {", ".join(SENSOR_TYPES)})')


def sensor_from_dict(data, source, enabled_default=True) -> SensorSpec:
    """
    Validate one sensor mapping.

    :param data: the mapping (keys of the type's table; ``type`` and ``name`` required).
    :param source: file and place quoted in errors (``'w.yaml: vehicles[0].sensors[1]'``).
    :param enabled_default: ``enabled`` when the mapping does not say (presets: False).
    :return: the type's SensorSpec subclass.
    :raises InvalidParameterError: naming source, field and value.
    """
    if not isinstance(data, dict):
        raise InvalidParameterError(f'{source}: a sensor must be a mapping, got {brief(data)}')
    sensor_type = data.get('type', REQUIRED)
    if sensor_type is REQUIRED:
        raise InvalidParameterError(f"{source}: field 'type' is required; one of "
                                    + ', '.join(SENSOR_TYPES))
    row = SENSOR_TYPES.get(sensor_type) if isinstance(sensor_type, str) else None
    if row is None:
        raise InvalidParameterError(f"{source}: field 'type' = {brief(sensor_type)}: unknown "
                                    f'sensor type; valid: {", ".join(SENSOR_TYPES)}')
    defaults = {spec.key: spec.default for spec in row.specs}
    defaults['enabled'] = enabled_default
    values = validate_table(row.specs, data, source, defaults, 'a sensor')
    if values['device'] is None:
        values['device'] = values['name']
    if row.check is not None:
        row.check(source, values)
    return row.spec_class(**values)


def sensor_as_dict(sensor: SensorSpec) -> Dict:
    """Return the configuration mapping of a sensor (keys as in the file)."""
    return {spec.key: _plain(getattr(sensor, spec.attr))
            for spec in SENSOR_TYPES[sensor.sensor_type].specs}


def _plain(value):
    if isinstance(value, Pose):
        return value.as_dict()
    if isinstance(value, tuple):
        return [_plain(v) for v in value]
    return value


COMMON_KEYS = tuple(spec.key for spec in common_specs('any', 1.0))


def sensors_markdown():
    """Return the key tables of docs/sensors.md: the common keys, then each type's own."""
    common = common_specs('required', 'see the type', tuple(SENSOR_TYPES))
    parts = ['#### Keys of every sensor\n\n', parameter_table_markdown(common, 'key')]
    for name, row in SENSOR_TYPES.items():
        rate = next(spec.default for spec in row.specs if spec.key == 'rate_hz')
        parts.append(f'\n#### `{name}` (default `rate_hz`: {rate:g} Hz)\n\n'
                     + parameter_table_markdown(row.specs, 'key', skip=COMMON_KEYS))
    return ''.join(parts)


def spec_field_names(sensor_type) -> Tuple[str, ...]:
    """Return the keys of a sensor type's table, in table order (docs, tests)."""
    return tuple(spec.key for spec in SENSOR_TYPES[sensor_type].specs)


assert all(len(fields(row.spec_class)) == len(row.specs) for row in SENSOR_TYPES.values())
