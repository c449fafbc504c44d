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
The one table of the Webots driver and car library API.

Each row names the Webots Python method(s), the CarLogic member behind them, the value kind,
how the facade treats odd input (docs/deviations.md, facade column), and what the round-trip test
needs
(valid sample values, settling steps and a tolerance where the getter reports a measured value).
The facade's methods and snake_case properties are generated from these rows, and the tests
iterate them, so a name cannot diverge (the lesson of the Webots wrapper slips).
"""

from dataclasses import dataclass
from typing import Callable, Optional, Tuple

from vehicle_sim.core.car.signals import MIN_INDICATOR_PERIOD_S


@dataclass(frozen=True)
class ApiRow:
    """One Webots setter/getter pair (either may be absent)."""

    setter: Optional[str]
    getter: Optional[str]
    core_setter: Optional[str]
    core_getter: Optional[str]
    kind: str                      # 'float', 'int', 'bool', 'enum'
    owner: str = 'driver'          # 'driver' (Driver and Car) or 'car' (Car only)
    prop: Optional[str] = None     # snake_case property of the 2023 Python wrapper
    limits: Optional[Callable] = None  # logic -> (low, high) of the sensible values
    # Outside the limits, with a warning: 'clamp' (Webots clamps), 'ignore' (nothing changes) or
    # 'store' (passed on as given: Webots stores it and only its motors saturate).
    out_of_range: str = 'clamp'
    enum_values: Tuple[int, ...] = ()
    samples: Tuple = ()            # valid values for the round-trip test
    settle_steps: int = 0          # steps before the getter reports a set value
    tolerance: float = 0.0         # absolute tolerance of the round trip
    speed_mode_zero: bool = False  # getter warns and returns 0 in SPEED mode (Webots)
    aliases: Tuple[str, ...] = ()  # deprecated Webots names: (setter alias, getter alias)
    unit: str = ''
    doc: str = ''


def _steering_limits(logic):
    return logic.min_steering_angle_rad, logic.max_steering_angle_rad


def _cruise_limits(logic):
    top = logic.max_cruising_speed_kmh
    return -top, top


def _gear_limits(logic):
    return -1, logic.gear_number - 1


def _unit_interval(logic):
    return 0.0, 1.0


def _indicator_periods(logic):
    return MIN_INDICATOR_PERIOD_S, float('inf')


DRIVER_API = (
    # The measured steering angle is the mean of the two Ackermann wheel angles, which differs
    # from the commanded centre angle by the Ackermann asymmetry (< 0.01 rad for |δ| <= 0.3
    # on every preset); the steering motors need ~1 s to settle (P = 10 1/s).
    ApiRow('setSteeringAngle', 'getSteeringAngle', 'set_steering_angle', 'steering_angle_rad',
           'float', prop='steering_angle', limits=_steering_limits, samples=(0.3, -0.2, 0.0),
           settle_steps=150, tolerance=0.01, unit='rad',
           doc='steering angle, positive = right'),
    # Beyond the top speed Webots stores the value (the getter returns it) and the wheel motors
    # saturate at maxVelocity / r with a warning (WbMotor); so do we.
    ApiRow('setCruisingSpeed', 'getTargetCruisingSpeed', 'set_cruising_speed_kmh',
           'target_cruising_speed_kmh', 'float', prop='cruising_speed', limits=_cruise_limits,
           out_of_range='store', samples=(30.0, -10.0, 0.0), unit='km/h',
           doc='cruise control target speed'),
    ApiRow('setThrottle', 'getThrottle', 'set_throttle', 'throttle', 'float', prop='throttle',
           limits=_unit_interval, samples=(0.5, 1.0, 0.0), doc='throttle in [0, 1]'),
    ApiRow('setBrakeIntensity', 'getBrakeIntensity', 'set_brake_intensity', 'brake_intensity',
           'float', prop='brake_intensity', limits=_unit_interval, samples=(0.7, 0.0),
           aliases=('setBrake', 'getBrake'), doc='brake intensity in [0, 1]'),
    ApiRow('setIndicator', 'getIndicator', 'set_indicator', 'indicator', 'enum',
           prop='indicator', out_of_range='ignore', enum_values=(0, 1, 2), samples=(1, 2, 0),
           doc='INDICATOR_OFF, INDICATOR_RIGHT or INDICATOR_LEFT'),
    ApiRow('setHazardFlashers', 'getHazardFlashers', 'set_hazard_flashers', 'hazard_flashers',
           'bool', prop='hazard_flashers', samples=(True, False)),
    ApiRow('setDippedBeams', 'getDippedBeams', 'set_dipped_beams', 'dipped_beams', 'bool',
           prop='dipped_beams', samples=(True, False)),
    ApiRow('setAntifogLights', 'getAntifogLights', 'set_antifog_lights', 'antifog_lights',
           'bool', prop='antifog_lights', samples=(True, False)),
    ApiRow('setGear', 'getGear', 'set_gear', 'gear', 'int', prop='gear', limits=_gear_limits,
           samples=(1, 2, -1, 0), speed_mode_zero=True,
           doc='-1 reverse, 0 neutral, 1..getGearNumber()-1 forward'),
    ApiRow('setWiperMode', 'getWiperMode', 'set_wiper_mode', 'wiper_mode', 'enum',
           prop='wiper_mode', out_of_range='ignore', enum_values=(0, 1, 2, 3),
           samples=(1, 2, 3, 0), aliases=('setWipersMode', 'getWipersMode'),
           doc='DOWN, SLOW, NORMAL or FAST'),
    ApiRow(None, 'getCurrentSpeed', None, 'current_speed_kmh', 'float', prop='current_speed',
           unit='km/h', doc='speed estimated from the driven wheels'),
    ApiRow(None, 'getRpm', None, 'rpm', 'float', prop='rpm', speed_mode_zero=True,
           unit='rpm', doc='engine speed'),
    ApiRow(None, 'getGearNumber', None, 'gear_number', 'int', prop='gear_number',
           doc='number of gear ratios including reverse'),
    ApiRow(None, 'getControlMode', None, 'control_mode', 'int', prop='control_mode',
           doc='SPEED, TORQUE, or None before the first command (Webots Python)'),
)

CAR_API = (
    ApiRow('setIndicatorPeriod', 'getIndicatorPeriod', 'set_indicator_period_s',
           'indicator_period_s', 'float', owner='car', prop='indicator_period',
           limits=_indicator_periods, out_of_range='ignore', samples=(0.5, 0.34, 1e-3),
           unit='s',
           doc='duration of one on (or off) phase of the indicators'),
    ApiRow('setRightSteeringAngle', 'getRightSteeringAngle', 'set_right_steering_angle',
           'right_steering_angle_rad', 'float', owner='car', prop='right_steering_angle',
           limits=_steering_limits, samples=(0.2, -0.1, 0.0), settle_steps=150,
           tolerance=1e-3, unit='rad'),
    ApiRow('setLeftSteeringAngle', 'getLeftSteeringAngle', 'set_left_steering_angle',
           'left_steering_angle_rad', 'float', owner='car', prop='left_steering_angle',
           limits=_steering_limits, samples=(0.2, -0.1, 0.0), settle_steps=150,
           tolerance=1e-3, unit='rad'),
    ApiRow('enableLimitedSlipDifferential', None, 'enable_limited_slip_differential',
           'limited_slip_differential', 'bool', owner='car', samples=(False, True)),
    ApiRow('enableIndicatorAutoDisabling', None, 'enable_indicator_auto_disabling',
           'indicator_auto_disabling', 'bool', owner='car', samples=(False, True)),
    ApiRow(None, 'getType', None, 'car_type', 'int', owner='car', prop='type'),
    ApiRow(None, 'getEngineType', None, 'engine_type', 'int', owner='car', prop='engine_type'),
    ApiRow(None, 'getBackwardsLights', None, 'backwards_lights', 'bool', owner='car',
           prop='backwards_lights'),
    ApiRow(None, 'getBrakeLights', None, 'brake_lights', 'bool', owner='car',
           prop='brake_lights'),
    ApiRow(None, 'getTrackFront', None, 'track_front_m', 'float', owner='car',
           prop='track_front', unit='m'),
    ApiRow(None, 'getTrackRear', None, 'track_rear_m', 'float', owner='car',
           prop='track_rear', unit='m'),
    ApiRow(None, 'getWheelbase', None, 'wheelbase_m', 'float', owner='car', prop='wheelbase',
           unit='m'),
    ApiRow(None, 'getFrontWheelRadius', None, 'front_wheel_radius_m', 'float', owner='car',
           prop='front_wheel_radius', unit='m'),
    ApiRow(None, 'getRearWheelRadius', None, 'rear_wheel_radius_m', 'float', owner='car',
           prop='rear_wheel_radius', unit='m'),
)

# Indexed getters (wheel index 0..3): Webots name -> CarLogic method.
CAR_WHEEL_API = (
    ('getWheelEncoder', 'wheel_encoder_rad'),
    ('getWheelSpeed', 'wheel_speed_radps'),
)

API = DRIVER_API + CAR_API



@dataclass(frozen=True)
class DeviceRow:
    """
    One Webots device class that a sensor provides (``Driver.getDevice(name)``).

    ``name_attr`` is the SensorSpec attribute holding its device name (an IMU provides three
    devices); ``robot_getter`` is Webots' deprecated ``Robot.get<Device>(name)``; ``spec_getters``
    are (Webots getter, SensorSpec attribute, type) rows of the values a device reports from its
    configuration.
    """

    device_class: str
    sensor_type: str
    name_attr: str
    robot_getter: str
    spec_getters: Tuple[Tuple[str, str, type], ...] = ()


# The Webots registration: every device class of webots/devices.py under the core sensor type
# it serves (one or more rows per type).
DEVICE_API = (
    DeviceRow('Lidar', 'lidar', 'device', 'getLidar', (
        ('getHorizontalResolution', 'horizontal_resolution', int),
        ('getNumberOfLayers', 'layers', int),
        ('getFov', 'fov_rad', float),
        ('getVerticalFov', 'vertical_fov_rad', float),
        ('getMinRange', 'min_range_m', float),
        ('getMaxRange', 'max_range_m', float))),
    DeviceRow('Camera', 'camera', 'device', 'getCamera', (
        ('getWidth', 'width', int),
        ('getHeight', 'height', int),
        ('getFov', 'fov_rad', float),
        ('getNear', 'near_m', float))),
    DeviceRow('GPS', 'gnss', 'device', 'getGPS'),
    DeviceRow('InertialUnit', 'imu', 'device', 'getInertialUnit'),
    DeviceRow('Gyro', 'imu', 'gyro_device', 'getGyro'),
    DeviceRow('Accelerometer', 'imu', 'accelerometer_device', 'getAccelerometer'),
    DeviceRow('DistanceSensor', 'distance', 'device', 'getDistanceSensor', (
        ('getAperture', 'aperture_rad', float),)),
    DeviceRow('RangeFinder', 'range_finder', 'device', 'getRangeFinder', (
        ('getWidth', 'width', int),
        ('getHeight', 'height', int),
        ('getFov', 'fov_rad', float),
        ('getMinRange', 'min_range_m', float),
        ('getMaxRange', 'max_range_m', float))),
    DeviceRow('Radar', 'radar', 'device', 'getRadar', (
        ('getMinRange', 'min_range_m', float),
        ('getMaxRange', 'max_range_m', float),
        ('getHorizontalFov', 'horizontal_fov_rad', float),
        ('getVerticalFov', 'vertical_fov_rad', float))),
)

# Robot / Supervisor functions that exist in Webots but not here (no other devices are
# simulated; the sensor devices of DEVICE_API are, through getDevice): a device getter that a
# DEVICE_API row serves drops out of this list by itself.
UNSUPPORTED_ROBOT_API = tuple(name for name in (
    'getKeyboard', 'getJoystick',
    'getMouse', 'getSelf', 'getRoot', 'getFromDef', 'getFromId', 'getFromDevice',
    'getDisplay',
    'getRangeFinder', 'getSpeaker', 'getLED', 'getMotor', 'getPositionSensor', 'getBrake',
    'getCompass', 'getRadar', 'getReceiver',
    'getEmitter', 'simulationSetMode', 'simulationReset', 'simulationQuit', 'worldReload',
    'wwiSendText', 'wwiReceiveText', 'getCustomData', 'setCustomData', 'getUrdf',
    'batterySensorEnable', 'waitForUserInputEvent', 'exportImage',
) if name not in {row.robot_getter for row in DEVICE_API})
