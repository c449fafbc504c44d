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
The action layouts of a policy: what each entry of its action Box means, and what it sets.

One table, :data:`LAYOUTS`, for the Gym environment (gym/controls.py calls the setters on the
vehicle in process) and the policy node (ros/policy_actions.py calls the automobile node's
services of the same names): the entry names and units, the Box's bounds from the vehicle's
limits, the check of an action against the Box, and the rule that turns a physical action into
the vehicle's driver setters with their values, in the driver's units (:data:`SETTERS`).

Every layout is a continuous Box in physical units; an action outside the Box, of the wrong
shape or not finite is refused with a ValueError naming the entry (a value past a bound by float
rounding only is the bound). Nothing is clipped.

- ``speed_steering`` (car): [steering angle [rad], + = left (REP 103); cruising speed [m/s],
  negative = reverse] -> ``set_steering_angle`` (+ RIGHT: the sign flips),
  ``set_cruising_speed`` (km/h). The car's speed controller (Webots' cruising speed) tracks the
  speed.
- ``braking_speed_steering`` (car): the entries of ``speed_steering``; a speed more than 1 m/s
  slower than the car's forward speed when the action is applied is reached with the brakes
  instead (core/car/speed_braking.py), as a driver brakes out of cruise control:
  ``set_steering_angle``, ``set_throttle`` 0 (TORQUE mode) and ``set_brake_intensity``; else
  ``set_steering_angle``, ``set_brake_intensity`` 0 and ``set_cruising_speed`` (whose ramp
  starts at the wheels' speeds, driver.c).
- ``guarded_speed_steering`` (car): the entries of ``speed_steering``; the speed asked is
  min(the action's, the headway guard's speed for the vehicles ahead in the car's lane,
  core/learning/headway_guard.py, from the objects table the policy reads), then the rule of
  ``braking_speed_steering``: the policy chooses the lane and the speed, the guard keeps it from
  running into the car ahead (an adaptive cruise control). Needs the objects table.
- ``lane_speed`` (car): [lateral offset [m] asked from the centreline of the lane the car is on,
  + = left; cruising speed [m/s], forward only]: a lane-keeping law steers toward the offset
  (core/car/lane_keeping.py: from the car's lane state and speed, within the steering bounds),
  the speed as ``braking_speed_steering``. An offset of one lane's width asks for the next
  lane; once the car is over the line, its lane state is the new lane's, and an offset of 0
  keeps it there (highway-env's lane-change meta-actions as one continuous entry). Needs a
  world with lanes.
- ``throttle_steering`` (car): [steering angle [rad], + = left; throttle [0, 1]; brake [0, 1]]
  -> ``set_steering_angle``, ``set_throttle``, ``set_brake_intensity`` (Webots' engine model).
- ``twist`` (robot): [forward speed [m/s]; yaw rate [rad/s], + = left] ->
  ``set_wheel_velocities``: v -+ w t / 2 over the wheel radius; where one wheel would exceed
  max_wheel_speed both are scaled by one factor (the turning radius is kept, core diff_drive
  limit_wheel_speeds).

Setters are called in the order given (a brake sent before the throttle that leaves cruise
control would reach a car still cruising).
"""

from dataclasses import dataclass
import math
from typing import Callable, Optional, Tuple

import numpy as np

from vehicle_sim.core.car.lane_keeping import lane_keeping_steering
from vehicle_sim.core.car.speed_braking import brake_for_speed
from vehicle_sim.core.diffdrive.kinematics import wheel_speeds_from_twist
from vehicle_sim.core.diffdrive.speed_limiter import limit_wheel_speeds
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.units import kmh_to_mps, mps_to_kmh, ros_steering_to_webots

CAR = 'car'
ROBOT = 'robot'

# Relative float rounding taken as the bound (float32 epsilon is 1.2e-7; a rescaled bound is a
# few of them off).
ROUNDING_TOLERANCE = 1.0e-6
# The car's default largest speed action [m/s] (72 km/h) when the top speed is higher.
DEFAULT_MAX_SPEED_MPS = 20.0
# The default largest reverse speed action [m/s].
DEFAULT_MAX_REVERSE_MPS = 5.0
# The largest lateral offset a lane_speed action asks for either way [m]: one lane of up to 4 m.
MAX_LANE_OFFSET_M = 4.0
# The name of a steering angle entry (a layout without one steers by core's lane-keeping law).
STEERING_ENTRY = 'steering_angle'

SET_STEERING = 'set_steering_angle'
SET_CRUISING_SPEED = 'set_cruising_speed'
SET_THROTTLE = 'set_throttle'
SET_BRAKE = 'set_brake_intensity'
SET_WHEEL_VELOCITIES = 'set_wheel_velocities'

# The driver setters a layout calls -> (the vehicle, the unit of the value). A car's are Webots'
# driver functions (wbu_driver_set_*: the automobile node's services of the same names), in
# Webots' units; a robot's takes (left, right).
SETTERS = {
    SET_STEERING: (CAR, 'rad'),          # + = right (Webots)
    SET_CRUISING_SPEED: (CAR, 'km/h'),   # negative = reverse
    SET_THROTTLE: (CAR, '1'),            # [0, 1], TORQUE mode
    SET_BRAKE: (CAR, '1'),               # [0, 1]
    SET_WHEEL_VELOCITIES: (ROBOT, 'rad/s'),  # (left, right), + = forward
}


@dataclass(frozen=True)
class Reading:
    """
    What a layout's rule reads of the vehicle when an action is applied.

    :ivar forward_mps: the car's forward speed [m/s] (its odometry's).
    :ivar lane_offset_m: its lateral offset from its lane's centreline, + = left [m] (its lane
        state's; 0 off every lane).
    :ivar heading_error_rad: its yaw minus the lane's direction [rad] (its lane state's).
    :ivar steering_bounds: the steering angles allowed (low, high) [rad], + = left: the
        law's limits for ``lane_speed`` (which refuses None); unused by the others.
    :ivar guard_speed_mps: the headway guard's speed [m/s] (core/learning/headway_guard.py;
        infinity: no vehicle ahead): ``guarded_speed_steering`` asks for no more.
    """

    forward_mps: float = 0.0
    lane_offset_m: float = 0.0
    heading_error_rad: float = 0.0
    steering_bounds: Optional[Tuple[float, float]] = None
    guard_speed_mps: float = math.inf


@dataclass(frozen=True)
class ActionLayout:
    """
    One action layout: its entries, the setters it calls and the rules of both.

    :ivar name: the layout's name (the Gym environment's ``control``).
    :ivar vehicle: :data:`CAR` or :data:`ROBOT`, the vehicle it drives.
    :ivar names: the entries' names.
    :ivar units: the entries' units.
    :ivar setters: the setters it may call (keys of :data:`SETTERS`).
    :ivar halt: the action that brakes the vehicle to a stand.
    :ivar reads_speed: whether its setters depend on the car's forward speed.
    :ivar reads_lane: whether they depend on the car's lane state (a world with lanes).
    :ivar reads_objects: whether they depend on the objects table (the headway guard's speed).
    """

    name: str
    vehicle: str
    names: Tuple[str, ...]
    units: Tuple[str, ...]
    setters: Tuple[str, ...]
    halt: Tuple[float, ...]
    reads_speed: bool
    reads_lane: bool
    _bounds: Callable
    _values: Callable
    reads_objects: bool = False

    def bounds(self, limits, max_speed_mps=None, max_reverse_mps=DEFAULT_MAX_REVERSE_MPS,
               max_steering_rad=None):
        """
        Return the Box's (low, high) [the entries' units] for a vehicle.

        :param limits: a car's driver logic (its steering limits, + = right, and top speed) or
            a robot's parameters (wheel tread, radius, largest wheel speed).
        :param max_speed_mps: a car's largest speed action (None: min(top speed, 20 m/s)).
        :param max_reverse_mps: a car's largest reverse speed action.
        :param max_steering_rad: a car's largest steering action either way (None: its limits).
        :raises InvalidParameterError: a steering bound beyond the car's limit.
        """
        return self._bounds(limits, max_speed_mps, max_reverse_mps, max_steering_rad)

    def values(self, action, reading=Reading(), limits=None):
        """
        Return [(setter, value in its unit)] of a checked physical action, in call order.

        :param reading: the vehicle's :class:`Reading` when the action is applied (its speed
            read when :attr:`reads_speed`, its lane state and steering bounds when
            :attr:`reads_lane`, the guard's speed when :attr:`reads_objects`).
        :param limits: a robot's parameters (twist); unused for a car.
        """
        return self._values(action, reading, limits)


def check_shape(action, low, names):
    """
    Return the action as an array, or raise ValueError for a shape other than the Box's.

    :param low: the Box's low bounds (their shape is the action's).
    """
    values = np.asarray(action)
    if values.shape != np.shape(low):
        raise ValueError(f'action of shape {values.shape}: expected {np.shape(low)} '
                         f'({", ".join(names)})')
    return values


def check_action(action, low, high, names, units, hint=''):
    """
    Return the action as float64, or raise ValueError naming the first bad entry.

    Bounds are those of the Box (float32), compared in float64. A value past a bound by float
    rounding only (ROUNDING_TOLERANCE of the bound: what RescaleAction's arithmetic gives for -1
    and 1) is taken as the bound.

    :param hint: appended to an out-of-bounds message.
    """
    values = np.array(check_shape(action, low, names), dtype=np.float64)
    for i, value in enumerate(values):
        lo, hi = float(low[i]), float(high[i])
        if not lo <= value <= hi:      # NaN fails too
            if lo - ROUNDING_TOLERANCE * max(1.0, abs(lo)) <= value < lo:
                values[i] = lo
            elif hi < value <= hi + ROUNDING_TOLERANCE * max(1.0, abs(hi)):
                values[i] = hi
            else:
                raise ValueError(f'action[{i}] ({names[i]}) = {float(value)!r} {units[i]}: '
                                 f'outside [{lo:g}, {hi:g}]{hint}')
    return values


def steering_bounds(logic, max_steering_rad=None):
    """
    Return the steering action's (low, high) [rad], + = left (REP 103).

    :param logic: the car's driver logic (its Webots steering limits, + = right).
    :param max_steering_rad: None: the car's limits; else (-it, it), which must lie within them.
    :raises InvalidParameterError: for a bound beyond the car's steering limit.
    """
    # REP 103 (+ left) = -(Webots, + right): the bounds swap.
    low, high = -logic.max_steering_angle_rad, -logic.min_steering_angle_rad
    if max_steering_rad is None:
        return low, high
    limit = min(-low, high)
    if max_steering_rad > limit:
        raise InvalidParameterError(
            f"option max_steering = {max_steering_rad!r} rad: more than the car's steering "
            f'limit ({limit:g} rad); give at most that, or null for the limits')
    return -max_steering_rad, max_steering_rad


def _speed_bounds(logic, max_speed_mps, max_reverse_mps, max_steering_rad):
    top = kmh_to_mps(logic.max_cruising_speed_kmh) if logic.max_cruising_speed_kmh > 0 else \
        DEFAULT_MAX_SPEED_MPS
    if max_speed_mps is None:
        max_speed_mps = min(top, DEFAULT_MAX_SPEED_MPS)
    right, left = steering_bounds(logic, max_steering_rad)
    return (right, -max_reverse_mps), (left, max_speed_mps)


def _lane_speed_bounds(logic, max_speed_mps, _max_reverse_mps, max_steering_rad):
    # forward only: the law steers a car driving forward
    (_, _), (_, top) = _speed_bounds(logic, max_speed_mps, 0.0, max_steering_rad)
    return (-MAX_LANE_OFFSET_M, 0.0), (MAX_LANE_OFFSET_M, top)


def _throttle_bounds(logic, _max_speed_mps, _max_reverse_mps, max_steering_rad):
    right, left = steering_bounds(logic, max_steering_rad)
    return (right, 0.0, 0.0), (left, 1.0, 1.0)


def _twist_bounds(params, _max_speed_mps, _max_reverse_mps, _max_steering_rad):
    top = params.max_wheel_speed_mps
    return (-top, -2.0 * top / params.wheel_tread_m), (top, 2.0 * top / params.wheel_tread_m)


def _speed_steering(a, _reading, _limits):
    return [(SET_STEERING, ros_steering_to_webots(float(a[0]))),
            (SET_CRUISING_SPEED, mps_to_kmh(float(a[1])))]


def _braking_speed_steering(a, reading, _limits):
    return _brake_or_cruise(ros_steering_to_webots(float(a[0])), float(a[1]),
                            reading.forward_mps)


def _guarded_speed_steering(a, reading, _limits):
    speed = float(a[1])
    if speed > 0.0:
        # never below 0: a guard's speed is no reverse gear
        speed = min(speed, max(reading.guard_speed_mps, 0.0))
    return _brake_or_cruise(ros_steering_to_webots(float(a[0])), speed, reading.forward_mps)


def _lane_speed(a, reading, _limits):
    if reading.steering_bounds is None:
        raise ValueError('lane_speed steers within the steering bounds of its environment: '
                         'none given')
    low, high = reading.steering_bounds
    steering = lane_keeping_steering(float(a[0]), reading.lane_offset_m,
                                     reading.heading_error_rad, reading.forward_mps, low, high)
    return _brake_or_cruise(ros_steering_to_webots(steering), float(a[1]), reading.forward_mps)


def _brake_or_cruise(steering, speed, forward_mps):
    # brake out of cruise control for a speed well below the car's, else cruise
    brake = brake_for_speed(forward_mps, speed)
    if brake > 0.0:
        return [(SET_STEERING, steering), (SET_THROTTLE, 0.0), (SET_BRAKE, brake)]
    return [(SET_STEERING, steering), (SET_BRAKE, 0.0), (SET_CRUISING_SPEED, mps_to_kmh(speed))]


def _throttle_steering(a, _reading, _limits):
    return [(SET_STEERING, ros_steering_to_webots(float(a[0]))), (SET_THROTTLE, float(a[1])),
            (SET_BRAKE, float(a[2]))]


def _twist(a, _reading, params):
    left, right = wheel_speeds_from_twist(float(a[0]), float(a[1]), params.wheel_tread_m)
    left, right = limit_wheel_speeds(left, right, params.max_wheel_speed_mps)
    # rounding may put a scaled wheel a hair above the limit: the body refuses that
    limit = params.max_wheel_speed_radps
    radius = params.wheel_radius_m
    return [(SET_WHEEL_VELOCITIES, (min(max(left / radius, -limit), limit),
                                    min(max(right / radius, -limit), limit)))]


_STEERING_SPEED = ((STEERING_ENTRY, 'speed'), ('rad', 'm/s'))
_BRAKING_SETTERS = (SET_STEERING, SET_CRUISING_SPEED, SET_THROTTLE, SET_BRAKE)

LAYOUTS = {layout.name: layout for layout in (
    ActionLayout('speed_steering', CAR, *_STEERING_SPEED, (SET_STEERING, SET_CRUISING_SPEED),
                 (0.0, 0.0), False, False, _speed_bounds, _speed_steering),
    ActionLayout('braking_speed_steering', CAR, *_STEERING_SPEED, _BRAKING_SETTERS, (0.0, 0.0),
                 True, False, _speed_bounds, _braking_speed_steering),
    ActionLayout('guarded_speed_steering', CAR, *_STEERING_SPEED, _BRAKING_SETTERS, (0.0, 0.0),
                 True, True, _speed_bounds, _guarded_speed_steering, reads_objects=True),
    ActionLayout('lane_speed', CAR, ('lane_offset', 'speed'), ('m', 'm/s'), _BRAKING_SETTERS,
                 (0.0, 0.0), True, True, _lane_speed_bounds, _lane_speed),
    ActionLayout('throttle_steering', CAR, (STEERING_ENTRY, 'throttle', 'brake'),
                 ('rad', '', ''), (SET_STEERING, SET_THROTTLE, SET_BRAKE), (0.0, 0.0, 1.0),
                 False, False, _throttle_bounds, _throttle_steering),
    ActionLayout('twist', ROBOT, ('speed', 'yaw_rate'), ('m/s', 'rad/s'),
                 (SET_WHEEL_VELOCITIES,), (0.0, 0.0), False, False, _twist_bounds, _twist),
)}
# The layout a vehicle gets for ``control: auto``.
DEFAULT_LAYOUT = {CAR: 'speed_steering', ROBOT: 'twist'}


def layouts_of(vehicle):
    """Return the names of the layouts that drive a vehicle (:data:`CAR` or :data:`ROBOT`)."""
    return tuple(name for name, layout in LAYOUTS.items() if layout.vehicle == vehicle)


def layout_for(name, vehicle, vehicle_name='the ego'):
    """
    Return the ActionLayout called ``name`` ('auto': the vehicle's default) for a vehicle.

    :param vehicle: :data:`CAR` or :data:`ROBOT`.
    :raises ValueError: a layout that does not drive that vehicle, or none of that name.
    """
    if name == 'auto':
        name = DEFAULT_LAYOUT[vehicle]
    layout = LAYOUTS.get(name)
    if layout is None or layout.vehicle != vehicle:
        raise ValueError(f'control {name!r} does not fit the ego {vehicle_name!r}, a '
                         f'{vehicle}; valid: {", ".join(layouts_of(vehicle))}')
    return layout
