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
Differential-drive robot parameters: one table of ParamSpec rows, RobotParams and validation.

Presets live in ``config/robots/*.yaml`` with these keys (SI units, suffix-free like the car
presets; the unit is in the table). Two drive layouts: ``caster`` (two driven wheels on one
axle and a passive ball caster) and ``skid_steer`` (four driven wheels, left pair and right pair
commanded together). Frames: REP 103, ``base_link`` on the ground below the centre of the
driven axle (caster) or of the wheel rectangle (skid steer).
"""

from dataclasses import dataclass
from typing import Optional, Tuple

from vehicle_sim.core.sensors.sets import SENSORS_KIND
from vehicle_sim.core.specs.param_spec import fail, ParamSpec, validate_table

DRIVE_TYPES = ('caster', 'skid_steer')

ROBOT_PARAM_SPECS = (
    ParamSpec('model', 'model', 'str', 'caster_robot', doc='preset name'),
    ParamSpec('drive', 'drive', 'enum', 'caster', choices=DRIVE_TYPES,
              doc='caster: 2 driven wheels + ball caster; skid_steer: 4 driven wheels'),
    ParamSpec('wheel_tread', 'wheel_tread_m', 'float', 0.4, 'm',
              'distance between the left and right wheel contact points', gt=0.0),
    ParamSpec('wheel_base', 'wheel_base_m', 'float', 0.0, 'm',
              'front-to-rear axle distance (skid_steer; must be 0 for caster)', ge=0.0),
    ParamSpec('wheel_radius', 'wheel_radius_m', 'float', 0.1, 'm', 'driven wheel radius',
              gt=0.0),
    ParamSpec('wheel_width', 'wheel_width_m', 'float', 0.04, 'm', 'driven wheel width', gt=0.0),
    ParamSpec('wheel_mass', 'wheel_mass_kg', 'float', 0.5, 'kg', 'mass of each driven wheel',
              gt=0.0),
    ParamSpec('mass', 'mass_kg', 'float', 10.0, 'kg', 'body mass without the wheels', gt=0.0),
    ParamSpec('body_size', 'body_size_m', 'vec3', (0.5, 0.3, 0.1), 'm',
              'body box [length, width, height]; centred on the axle height', gt=0.0),
    ParamSpec('body_offset', 'body_offset_m', 'float', -0.1, 'm',
              'x of the body box centre relative to base_link (negative = behind the axle)'),
    ParamSpec('max_wheel_speed', 'max_wheel_speed_radps', 'float', 15.0, 'rad/s',
              'largest wheel angular speed accepted by set_wheel_velocities', gt=0.0),
    ParamSpec('wheel_motor_torque', 'wheel_motor_torque_nm', 'float', 20.0, 'N*m',
              'torque limit of each wheel velocity motor', gt=0.0),
    ParamSpec('wheel_friction', 'wheel_friction', 'float', 1.0, '',
              'tyre friction coefficient (multiplied with the ground friction)', gt=0.0),
    ParamSpec('caster_radius', 'caster_radius_m', 'float', 0.05, 'm',
              'ball caster radius (caster drive only)', gt=0.0),
    ParamSpec('caster_offset', 'caster_offset_m', 'float', -0.3, 'm',
              'x of the caster contact relative to base_link (caster drive only; != 0)'),
    ParamSpec('sensors', 'sensors', SENSORS_KIND, None, '',
              'sensors of the robot, each off unless "enabled: true" (docs/sensors.md); null = '
              'the default set (lidar, imu)', optional=True),
)



@dataclass(frozen=True)
class RobotParams:
    """Validated robot parameters (SI units; meaning in ROBOT_PARAM_SPECS)."""

    model: str
    drive: str
    wheel_tread_m: float
    wheel_base_m: float
    wheel_radius_m: float
    wheel_width_m: float
    wheel_mass_kg: float
    mass_kg: float
    body_size_m: Tuple[float, float, float]
    body_offset_m: float
    max_wheel_speed_radps: float
    wheel_motor_torque_nm: float
    wheel_friction: float
    caster_radius_m: float
    caster_offset_m: float
    sensors: Optional[Tuple] = None

    @property
    def sensor_set(self):
        """The robot's sensors: the preset's ``sensors``, or the default set (all unmounted)."""
        if self.sensors is not None:
            return self.sensors
        from vehicle_sim.core.sensors.defaults import default_robot_sensors
        return default_robot_sensors(self)

    @property
    def wheel_names(self):
        """Wheel name stems, left side first then right (e.g. ``left``, ``rear_right``)."""
        if self.drive == 'caster':
            return ('left', 'right')
        return ('front_left', 'rear_left', 'front_right', 'rear_right')

    @property
    def wheel_joints(self):
        """Driven wheel joint names (URDF), left side first."""
        return tuple(f'{name}_wheel_joint' for name in self.wheel_names)

    @property
    def max_wheel_speed_mps(self):
        """Largest tyre-surface speed [m/s] (max wheel speed × radius)."""
        return self.max_wheel_speed_radps * self.wheel_radius_m


def default_robot_dict():
    """Return the robot defaults keyed by preset field name."""
    return {spec.key: spec.default for spec in ROBOT_PARAM_SPECS}


def _check_relations(source, values):
    length, width, height = values['body_size_m']
    radius = values['wheel_radius_m']
    if height / 2.0 >= radius:
        fail(source, 'body_size', list(values['body_size_m']),
              f'body height / 2 must be < wheel_radius ({radius:g} m) or the body drags')
    if width >= values['wheel_tread_m'] - values['wheel_width_m']:
        fail(source, 'body_size', list(values['body_size_m']),
              'body width must be < wheel_tread - wheel_width (wheels outside the body)')
    if values['drive'] == 'caster':
        if values['wheel_base_m'] != 0.0:
            fail(source, 'wheel_base', values['wheel_base_m'],
                  'must be 0 for a caster robot (it has one axle)')
        if values['caster_offset_m'] == 0.0:
            fail(source, 'caster_offset', 0.0, 'must be != 0 (the caster cannot sit on the axle)')
        if values['caster_radius_m'] >= radius:
            fail(source, 'caster_radius', values['caster_radius_m'],
                  f'must be < wheel_radius ({radius:g} m)')
        if abs(values['caster_offset_m']) <= radius:
            fail(source, 'caster_offset', values['caster_offset_m'],
                  f'|offset| must be > wheel_radius ({radius:g} m)')
    elif values['wheel_base_m'] <= 2.0 * radius:
        fail(source, 'wheel_base', values['wheel_base_m'],
              f'must be > 2 x wheel_radius ({2.0 * radius:g} m) for a skid-steer robot')


def robot_params_from_dict(data, source='<dict>'):
    """
    Validate a robot preset dictionary and build RobotParams.

    :param data: mapping of preset field names to values; missing fields take the defaults.
    :param source: file name (or other origin) quoted in error messages.
    :return: RobotParams.
    :raises InvalidParameterError: naming the source, field and value, for an unknown field, a
        wrong type or an impossible value (nothing is clamped).
    """
    values = validate_table(ROBOT_PARAM_SPECS, data, source, default_robot_dict(),
                            'a robot preset')
    _check_relations(source, values)
    return RobotParams(**values)


DEFAULT_ROBOT = robot_params_from_dict({}, source='robot defaults')
