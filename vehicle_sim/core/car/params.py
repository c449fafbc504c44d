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
The car's parameter table (Webots' Car PROTO fields), the CarParams value object and its checks.

Field names in car presets are the Webots PROTO field names (Car.proto, AckermannVehicle.proto,
VehicleWheel.proto); defaults are the Car.proto R2022b defaults. Body physics fields (mass, centre
of mass, inertia, collision boxes) are ours: Webots' abstract Car has no body physics, see
docs/physics.md. The rows are :mod:`.param_spec` ParamSpec rows, validated like every other table.
"""

from dataclasses import dataclass, field
import math
from typing import Optional, Tuple

from vehicle_sim.core.sensors.sets import SENSORS_KIND
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.param_spec import fail, ParamSpec, table_defaults, validate_table
from vehicle_sim.core.specs.value_kinds import CollisionBox

CAR_TYPES = ('traction', 'propulsion', '4x4')
ENGINE_TYPES = ('combustion', 'electric', 'parallel hybrid', 'power-split hybrid')

# Webots VehicleWheel: Physics {} with density 1000 kg/m^3 when no mass is given.
WHEEL_DENSITY_KG_M3 = 1000.0


CAR_PARAM_SPECS = (
    ParamSpec('model', 'model', 'str', 'Car', doc='preset name'),
    ParamSpec('type', 'car_type', 'enum', 'traction', choices=CAR_TYPES,
              doc='driven wheels: traction = front, propulsion = rear, 4x4 = all'),
    ParamSpec('engineType', 'engine_type', 'enum', 'combustion', choices=ENGINE_TYPES,
              doc='engine model (driver library §2.1)'),
    ParamSpec('trackFront', 'track_front_m', 'float', 1.7, 'm', 'front track', gt=0.0),
    ParamSpec('trackRear', 'track_rear_m', 'float', 1.7, 'm', 'rear track', gt=0.0),
    ParamSpec('wheelbase', 'wheelbase_m', 'float', 4.0, 'm', 'front-to-rear axle distance',
              gt=0.0),
    ParamSpec('minSteeringAngle', 'min_steering_angle_rad', 'float', -1.0, 'rad',
              'steering limit (negative = left)', le=0.0, gt=-math.pi / 2),
    ParamSpec('maxSteeringAngle', 'max_steering_angle_rad', 'float', 1.0, 'rad',
              'steering limit (positive = right)', ge=0.0, le=math.pi / 2),
    ParamSpec('maxSteeringTorque', 'max_steering_torque_nm', 'float', 10000.0, 'N*m',
              'torque of each steering motor', ge=0.0),
    ParamSpec('suspensionFrontSpringConstant', 'suspension_front_spring_n_per_m', 'float',
              100000.0, 'N/m', 'front suspension spring', gt=0.0),
    ParamSpec('suspensionFrontDampingConstant', 'suspension_front_damping_ns_per_m', 'float',
              4000.0, 'N*s/m', 'front suspension damper', ge=0.0),
    ParamSpec('suspensionRearSpringConstant', 'suspension_rear_spring_n_per_m', 'float',
              100000.0, 'N/m', 'rear suspension spring', gt=0.0),
    ParamSpec('suspensionRearDampingConstant', 'suspension_rear_damping_ns_per_m', 'float',
              4000.0, 'N*s/m', 'rear suspension damper', ge=0.0),
    ParamSpec('wheelsDampingConstant', 'wheels_damping_nms_per_rad', 'float', 5.0, 'N*m*s/rad',
              'viscous damping of every wheel joint', gt=0.0),
    ParamSpec('brakeCoefficient', 'brake_coefficient_nm', 'float', 700.0, 'N*m',
              'braking torque per wheel at full brake', gt=0.0),
    ParamSpec('time0To100', 'time_0_to_100_s', 'float', 10.0, 's',
              'time from 0 to 100 km/h; sets the SPEED-mode wheel acceleration', gt=0.0),
    ParamSpec('maxVelocity', 'max_velocity_mps', 'float', 50.0, 'm/s',
              'top speed of the driven wheels (tyre surface)', gt=0.0),
    ParamSpec('engineMaxTorque', 'engine_max_torque_nm', 'float', 250.0, 'N*m',
              'electric motor torque limit', gt=0.0),
    ParamSpec('engineMaxPower', 'engine_max_power_w', 'float', 50000.0, 'W',
              'electric motor power limit', gt=0.0),
    ParamSpec('engineMinRPM', 'engine_min_rpm', 'float', 1000.0, 'rpm',
              'combustion engine idle speed', gt=0.0),
    ParamSpec('engineMaxRPM', 'engine_max_rpm', 'float', 4500.0, 'rpm',
              'engine speed at which torque is cut', gt=0.0),
    ParamSpec('engineFunctionCoefficients', 'engine_function_coefficients', 'floats',
              (150.0, 0.1, 0.0), 'N*m, N*m/rpm, N*m/rpm^2',
              'combustion torque a + b*rpm + c*rpm^2', length=3),
    ParamSpec('gearRatio', 'gear_ratio', 'float_list', (-12.0, 10.0, 6.5, 4.5, 3.5, 2.75), '',
              'reverse ratio (negative) then forward ratios'),
    ParamSpec('hybridPowerSplitRatio', 'hybrid_power_split_ratio', 'float', 0.25, '',
              'share of the combustion engine power sent to the generator', ge=0.0, le=1.0),
    ParamSpec('hybridPowerSplitRPM', 'hybrid_power_split_rpm', 'float', 3000.0, 'rpm',
              'fixed combustion engine speed of a power-split hybrid', gt=0.0),
    ParamSpec('engineSoundRpmReference', 'engine_sound_rpm_reference', 'float', 1000.0, 'rpm',
              'rpm of the engine sound sample (kept for completeness; no sound)', gt=0.0),
    ParamSpec('frontTireRadius', 'front_tire_radius_m', 'float', 0.4, 'm', 'front tyre radius',
              gt=0.0),
    ParamSpec('rearTireRadius', 'rear_tire_radius_m', 'float', 0.4, 'm', 'rear tyre radius',
              gt=0.0),
    ParamSpec('frontTireWidth', 'front_tire_width_m', 'float', 0.3, 'm',
              'front tyre thickness (VehicleWheel.thickness)', gt=0.0),
    ParamSpec('rearTireWidth', 'rear_tire_width_m', 'float', 0.3, 'm',
              'rear tyre thickness (VehicleWheel.thickness)', gt=0.0),
    ParamSpec('frontWheelMass', 'front_wheel_mass_kg', 'float', None, 'kg',
              'mass of each front wheel; null = density 1000 kg/m^3 (Webots)', gt=0.0,
              optional=True),
    ParamSpec('rearWheelMass', 'rear_wheel_mass_kg', 'float', None, 'kg',
              'mass of each rear wheel; null = density 1000 kg/m^3 (Webots)', gt=0.0,
              optional=True),
    ParamSpec('mass', 'mass_kg', 'float', 1500.0, 'kg', 'body mass without the wheels', gt=0.0),
    ParamSpec('centerOfMass', 'center_of_mass_m', 'vec3', (2.0, 0.0, 0.2), 'm',
              'body centre of mass in the vehicle frame (FLU, origin at the rear-axle centre)'),
    ParamSpec('inertiaMatrix', 'inertia_kgm2', 'inertia', None, 'kg*m^2',
              'body inertia [Ixx, Iyy, Izz, Ixy, Ixz, Iyz] about the centre of mass; '
              'null = from the collision boxes', optional=True),
    ParamSpec('collisionBoxes', 'collision_boxes', 'boxes',
              ({'size': (5.0, 1.7, 1.0), 'position': (2.0, 0.0, 0.5), 'pitch': 0.0},), 'm',
              'chassis collision boxes: size [l, w, h], position [x, y, z], pitch [rad]'),
    ParamSpec('sensors', 'sensors', SENSORS_KIND, None, '',
              'sensors of the car, each off unless "enabled: true" (docs/sensors.md); null = '
              'the default set (lidar, camera, gnss, imu)', optional=True),
)

SPEC_BY_KEY = {spec.key: spec for spec in CAR_PARAM_SPECS}


@dataclass(frozen=True)
class CarParams:
    """Validated car parameters (SI units; field meaning in CAR_PARAM_SPECS)."""

    model: str
    car_type: str
    engine_type: str
    track_front_m: float
    track_rear_m: float
    wheelbase_m: float
    min_steering_angle_rad: float
    max_steering_angle_rad: float
    max_steering_torque_nm: float
    suspension_front_spring_n_per_m: float
    suspension_front_damping_ns_per_m: float
    suspension_rear_spring_n_per_m: float
    suspension_rear_damping_ns_per_m: float
    wheels_damping_nms_per_rad: float
    brake_coefficient_nm: float
    time_0_to_100_s: float
    max_velocity_mps: float
    engine_max_torque_nm: float
    engine_max_power_w: float
    engine_min_rpm: float
    engine_max_rpm: float
    engine_function_coefficients: Tuple[float, float, float]
    gear_ratio: Tuple[float, ...]
    hybrid_power_split_ratio: float
    hybrid_power_split_rpm: float
    engine_sound_rpm_reference: float
    front_tire_radius_m: float
    rear_tire_radius_m: float
    front_tire_width_m: float
    rear_tire_width_m: float
    front_wheel_mass_kg: Optional[float]
    rear_wheel_mass_kg: Optional[float]
    mass_kg: float
    center_of_mass_m: Tuple[float, float, float]
    inertia_kgm2: Optional[Tuple[float, ...]]
    collision_boxes: Tuple[CollisionBox, ...] = field(default=())
    sensors: Optional[Tuple] = None

    @property
    def sensor_set(self):
        """The car's sensors: the preset's ``sensors``, or the default set (all unmounted)."""
        if self.sensors is not None:
            return self.sensors
        from vehicle_sim.core.sensors.defaults import default_car_sensors
        return default_car_sensors(self)

    @property
    def gear_number(self):
        """Webots getGearNumber(): number of gear ratios including the reverse one."""
        return len(self.gear_ratio)

    @property
    def driven_wheels(self):
        """Indices (FR, FL, RR, RL order) of the driven wheels."""
        return {'traction': (0, 1), 'propulsion': (2, 3), '4x4': (0, 1, 2, 3)}[self.car_type]

    def wheel_mass_kg(self, front):
        """Mass of one wheel; Webots' density rule when the preset gives none."""
        given = self.front_wheel_mass_kg if front else self.rear_wheel_mass_kg
        if given is not None:
            return given
        radius = self.front_tire_radius_m if front else self.rear_tire_radius_m
        width = self.front_tire_width_m if front else self.rear_tire_width_m
        return WHEEL_DENSITY_KG_M3 * math.pi * radius ** 2 * width

    def replace(self, **changes):
        """Return a validated copy with some attributes changed (attribute names)."""
        data = {spec.key: _to_plain(getattr(self, spec.attr)) for spec in CAR_PARAM_SPECS}
        by_attr = {spec.attr: spec.key for spec in CAR_PARAM_SPECS}
        for attr, value in changes.items():
            if attr not in by_attr:
                raise InvalidParameterError(f'CarParams has no attribute {attr!r}')
            data[by_attr[attr]] = _to_plain(value)
        return car_params_from_dict(data, source='CarParams.replace')


def _to_plain(value):
    if isinstance(value, tuple) and value and isinstance(value[0], CollisionBox):
        return [{'size': list(b.size_m), 'position': list(b.position_m), 'pitch': b.pitch_rad}
                for b in value]
    return value


def default_car_dict():
    """Return the Car defaults as a preset dictionary (Webots field names)."""
    return table_defaults(CAR_PARAM_SPECS)


def _check_relations(source, values):
    gears = values['gear_ratio']
    if len(gears) < 2:
        fail(source, 'gearRatio', list(gears), 'needs the reverse ratio and >= 1 forward ratio')
    if gears[0] >= 0.0:
        fail(source, 'gearRatio', list(gears), 'the first (reverse) ratio must be negative')
    if min(gears[1:]) <= 0.0:
        fail(source, 'gearRatio', list(gears), 'forward ratios must be positive')
    if values['engine_max_rpm'] <= values['engine_min_rpm']:
        fail(source, 'engineMaxRPM', values['engine_max_rpm'],
              f'must be > engineMinRPM ({values["engine_min_rpm"]:g})')
    if values['min_steering_angle_rad'] >= values['max_steering_angle_rad']:
        fail(source, 'minSteeringAngle', values['min_steering_angle_rad'],
              'must be < maxSteeringAngle')
    inertia = values['inertia_kgm2']
    if inertia is not None:
        ixx, iyy, izz, ixy, ixz, iyz = inertia
        det2 = ixx * iyy - ixy * ixy
        det3 = (ixx * (iyy * izz - iyz * iyz) - ixy * (ixy * izz - iyz * ixz)
                + ixz * (ixy * iyz - iyy * ixz))
        if ixx <= 0.0 or det2 <= 0.0 or det3 <= 0.0:
            fail(source, 'inertiaMatrix', list(inertia), 'must be positive definite')


def car_params_from_dict(data, source='<dict>', base=None):
    """
    Validate a preset dictionary and build CarParams.

    :param data: mapping of Webots field names to values; missing fields take ``base``.
    :param source: file name (or other origin) quoted in error messages.
    :param base: defaults to complete ``data`` with; the Car defaults when None.
    :return: CarParams.
    :raises InvalidParameterError: naming the source, field and value, for an unknown field, a
        wrong type or an impossible value.
    """
    values = validate_table(CAR_PARAM_SPECS, data, source,
                            default_car_dict() if base is None else base, 'a car preset')
    _check_relations(source, values)
    return CarParams(**values)


DEFAULT_CAR = car_params_from_dict({}, source='Car defaults')
