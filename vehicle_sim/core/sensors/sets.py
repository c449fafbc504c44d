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
A vehicle's set of sensors: preset sensors, the world's changes, and the rules across them.

Sensor names are unique per vehicle (they name frames); among the mounted (``enabled``) sensors,
Webots device names and topics are unique, and no sensor takes one of the vehicle's own topics.
"""

from dataclasses import dataclass, replace
from typing import Dict, Sequence, Tuple

from vehicle_sim.core.geometry.frames import OPTICAL_QUATERNION
from vehicle_sim.core.sensors.params import sensor_as_dict, sensor_from_dict
from vehicle_sim.core.sensors.sensor_spec import SensorSpec
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.param_spec import fail, REQUIRED
from vehicle_sim.core.specs.value_kinds import register_kind
from vehicle_sim.core.specs.value_text import brief

# Topics of the vehicle that sensors may not take (docs/ros_interface.md).
RESERVED_TOPICS = ('odom', 'joint_states', 'robot_description', 'collision', 'tf', 'tf_static',
                   'clock')
RESERVED_TOPIC_PREFIXES = ('automobile/', 'robot/')


def sensors_from_list(data, source, enabled_default=True) -> Tuple[SensorSpec, ...]:
    """
    Validate a list of new sensors (a preset's ``sensors:``) and their uniqueness rules.

    :param data: a list of mappings, or a tuple of SensorSpec (returned after the checks).
    :raises InvalidParameterError: naming source, entry and field.
    """
    if isinstance(data, (list, tuple)) and all(isinstance(s, SensorSpec) for s in data):
        sensors = tuple(data)
    elif isinstance(data, list):
        sensors = tuple(sensor_from_dict(item, f'{source}[{index}]', enabled_default)
                        for index, item in enumerate(data))
    else:
        raise InvalidParameterError(f'{source}: sensors must be a list of mappings, '
                                    f'got {brief(data)}')
    check_sensor_set(sensors, source)
    return sensors


def _check_sensors_kind(spec, value):
    # raises InvalidParameterError naming the sensor and its field itself
    return sensors_from_list(value, f'field {spec.key!r}', enabled_default=False)


# The ParamSpec kind of a preset's sensor list (``ParamSpec(kind=SENSORS_KIND)``): registered
# here, so the generic core/specs/param_spec.py knows no sensor module.
SENSORS_KIND = register_kind('sensors', 'sensors', _check_sensors_kind)


def merge_sensors(base: Sequence[SensorSpec], entries, source) -> Tuple[SensorSpec, ...]:
    """
    Apply a world entry's ``sensors:`` list to a vehicle's preset sensors.

    An entry whose ``name`` is a preset sensor's name changes that sensor: the keys it gives
    replace the preset's (``pose`` as a whole), and it is mounted (``enabled: true``) unless it
    says otherwise; ``type`` may be left out. An entry with a new name adds a sensor (``type``
    required), mounted by default.

    :param base: the preset's sensors.
    :param entries: the world's list of mappings (None = no change).
    :param source: file and place quoted in errors (``'w.yaml: vehicles[0].sensors'``).
    :return: the preset's sensors (changed ones in place) followed by the new ones.
    :raises InvalidParameterError: naming source, entry and field.
    """
    if entries is None:
        return tuple(base)
    if not isinstance(entries, list):
        raise InvalidParameterError(f'{source}: must be a list of sensor mappings, '
                                    f'got {brief(entries)}')
    result = list(base)
    index_of = {spec.name: i for i, spec in enumerate(result)}
    given = set()
    for index, entry in enumerate(entries):
        where = f'{source}[{index}]'
        if not isinstance(entry, dict):
            raise InvalidParameterError(f'{where}: a sensor must be a mapping, got {brief(entry)}')
        name = entry.get('name', REQUIRED)
        if name is REQUIRED:
            raise InvalidParameterError(f"{where}: field 'name' is required")
        if isinstance(name, str):
            if name in given:
                raise InvalidParameterError(f'{source}: two sensors are named {brief(name)}')
            given.add(name)
        if isinstance(name, str) and name in index_of:
            old = result[index_of[name]]
            if 'type' in entry and entry['type'] != old.sensor_type:
                fail(where, 'type', entry['type'],
                      f'the preset sensor {brief(name)} is a {old.sensor_type}')
            data = sensor_as_dict(old)
            data.update(entry)
            data['enabled'] = entry.get('enabled', True)
            result[index_of[name]] = sensor_from_dict(data, where)
        else:
            spec = sensor_from_dict(entry, where, enabled_default=True)
            index_of[spec.name] = len(result)
            result.append(spec)
    sensors = tuple(result)
    check_sensor_set(sensors, source)
    return sensors


def selected_sensors(value):
    """
    Return a list of sensor names as :func:`enable_sensors` takes it: 'all', names, or None.

    :param value: names, ``['all']``, or none (empty strings are ignored: the node parameter's
        default is ``['']``).
    """
    names = tuple(v for v in value if v)
    if not names:
        return None
    return 'all' if names == ('all',) else names


def enable_sensors(sensors: Sequence[SensorSpec], names, source) -> Tuple[SensorSpec, ...]:
    """
    Mount some of a vehicle's sensors by name (a node parameter, a Driver argument).

    :param names: sensor names, or ``'all'``.
    :raises InvalidParameterError: for an unknown name (the message lists the known ones).
    """
    known = [s.name for s in sensors]
    wanted = set(known) if names == 'all' else set(names)
    unknown = sorted(wanted - set(known))
    if unknown:
        raise InvalidParameterError(f'{source}: unknown sensor(s) {brief(unknown)}; '
                                    f'this vehicle has {", ".join(known) or "none"}')
    result = tuple(replace(s, enabled=True) if s.name in wanted else s for s in sensors)
    check_sensor_set(result, source)
    return result


def check_sensor_set(sensors: Sequence[SensorSpec], source):
    """
    Check the rules across a vehicle's sensors.

    Names are unique; among the mounted sensors, device names and topics are unique and no
    topic is one of the vehicle's own (odom, collision, automobile/...).

    :raises InvalidParameterError: naming source, the two sensors and the clash.
    """
    owners: Dict[Tuple[str, str], str] = {}
    for spec in sensors:
        key = ('name', spec.name)
        if key in owners:
            raise InvalidParameterError(f'{source}: two sensors are named {brief(spec.name)}')
        owners[key] = spec.name
    for spec in sensors:
        if not spec.enabled:
            continue
        for kind, values in (('device name', spec.device_names), ('topic', spec.topics)):
            for value in values:
                relative = value.lstrip('/')
                if kind == 'topic' and (relative in RESERVED_TOPICS or relative.startswith(
                        RESERVED_TOPIC_PREFIXES)):
                    raise InvalidParameterError(
                        f'{source}: sensor {brief(spec.name)}: topic {brief(value)} is one of the '
                        'vehicle\'s own topics; set another "topic"')
                if (kind, value) in owners:
                    raise InvalidParameterError(
                        f'{source}: sensors {brief(owners[(kind, value)])} and '
                        f'{brief(spec.name)} have the same {kind} {brief(value)}; '
                        f'set "{"device" if kind != "topic" else kind}" on one of them')
                owners[(kind, value)] = spec.name


def mounted(sensors: Sequence[SensorSpec]) -> Tuple[SensorSpec, ...]:
    """Return the sensors that are mounted (``enabled``)."""
    return tuple(s for s in sensors if s.enabled)


@dataclass(frozen=True)
class StaticTransform:
    """A fixed transform for /tf_static: ``child`` in ``parent`` (translation [m], quaternion)."""

    parent: str
    child: str
    xyz: Tuple[float, float, float]
    quaternion: Tuple[float, float, float, float]


def static_transforms(sensors: Sequence[SensorSpec], prefix='') -> Tuple[StaticTransform, ...]:
    """
    Return the static transforms of the mounted sensors.

    ``<p>base_link`` -> ``<p><name>`` at the mount pose; a sensor with an image frame (a
    camera: ``<p><name>_optical``) also ``<p><name>`` -> that frame (rpy -pi/2, 0, -pi/2).
    """
    base = f'{prefix}base_link'
    result = []
    for spec in mounted(sensors):
        result.append(StaticTransform(base, spec.frame_id(prefix), spec.pose.xyz,
                                      spec.pose.quaternion))
        optical = spec.optical_frame_id(prefix)
        if optical is not None:
            result.append(StaticTransform(spec.frame_id(prefix), optical, (0.0, 0.0, 0.0),
                                          OPTICAL_QUATERNION))
    return tuple(result)
