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
The action layouts of the Gym environment applied to its vehicle in process.

The layouts (their entries, units, bounds, check and the setters each calls with their values)
are core's table, ``vehicle_sim/core/learning/actions.py`` (docs/gym.md, Actions); the policy
node sends the same setters as the automobile node's services (ros/policy_actions.py). Here a
:class:`Control` calls them on the car's driver logic or the robot's wheels. Nothing is clipped
beyond float rounding at a bound: wrap the environment in ``gymnasium.wrappers.ClipAction`` to
clip a policy's samples, or ``RescaleAction`` for [-1, 1].
"""

import math

import numpy as np

from vehicle_sim.core.learning.actions import (
    CAR,
    check_action,
    layout_for,
    LAYOUTS,
    Reading,
    ROBOT,
    steering_bounds,
)
from vehicle_sim.core.learning.headway_guard import guard_speed
from vehicle_sim.core.specs.errors import InvalidParameterError

# A car's setters (core learning/actions.py SETTERS) -> its driver logic's methods.
CAR_SETTERS = {
    'set_steering_angle': 'set_steering_angle',
    'set_cruising_speed': 'set_cruising_speed_kmh',
    'set_throttle': 'set_throttle',
    'set_brake_intensity': 'set_brake_intensity',
}
# A robot's setters -> its body's methods (the value: their arguments).
ROBOT_SETTERS = {
    'set_wheel_velocities': 'set_wheel_velocities',
}
# The layouts the environment offers (every layout of core's table).
CONTROLS = tuple(LAYOUTS)
CLIP_HINT = ' (the action space; gymnasium.wrappers.ClipAction clips)'


class Control:
    """
    One action layout on a vehicle: ``names``, ``units``, ``low``, ``high`` and ``apply``.

    :param layout: core's ActionLayout.
    :param limits: the car's driver logic, or the robot's parameters (its bounds).
    """

    def __init__(self, layout, limits, max_speed_mps=None, max_reverse_mps=5.0,
                 max_steering_rad=None):
        self.layout = layout
        self.names = layout.names
        self.units = layout.units
        low, high = layout.bounds(limits, max_speed_mps, max_reverse_mps, max_steering_rad)
        self.low = np.asarray(low, dtype=np.float32)
        self.high = np.asarray(high, dtype=np.float32)
        self._limits = limits

    def check(self, action):
        """
        Return the action as float64, or raise ValueError naming the first bad entry.

        A value past a bound by float rounding only is taken as the bound (core's
        check_action).
        """
        return check_action(action, self.low, self.high, self.names, self.units, CLIP_HINT)

    def apply(self, action):
        """Command the vehicle (a checked action)."""
        for setter, value in self.layout.values(action, self._reading(), self._limits):
            self._setters[setter](value)

    def _reading(self):
        return Reading()

    def stop(self):
        """Command the vehicle to stand still (the state after a reset)."""

    def halt(self):
        """Brake the vehicle to a stand (an agent that left a multi-agent episode)."""
        self.apply(self.layout.halt)


class CarControl(Control):
    """
    A car's layout: the setters are its driver logic's (Webots' driver API).

    :param lanes: the car's VehicleLanes (its lane state, updated once per env step), or None
        in a world without lanes; a layout that reads the lane state needs them.
    :param objects: the ego's objects part (gym/objects.py: its spec and the table of the last
        observation), or None; a layout that reads the objects table needs it.
    """

    def __init__(self, layout, car, max_speed_mps=None, max_reverse_mps=5.0,
                 max_steering_rad=None, lanes=None, objects=None):
        super().__init__(layout, car.logic, max_speed_mps, max_reverse_mps, max_steering_rad)
        self.logic = car.logic
        self.body = car.body
        self.lanes = lanes
        self.objects = objects
        # the steering angles allowed, + = left: the Box's, or the lane-keeping law's limits
        self.steering_bounds = steering_bounds(car.logic, max_steering_rad)
        self._setters = {setter: getattr(car.logic, method)
                         for setter, method in CAR_SETTERS.items()}

    def _reading(self):
        layout = self.layout
        forward = self.body.body_twist()[0][0] if layout.reads_speed else 0.0
        if not layout.reads_lane:
            return Reading(forward)
        state = self.lanes.state
        guard = math.inf
        if layout.reads_objects:
            spec = self.objects.spec
            # the table the policy saw: the last observation's, at this same time
            guard = guard_speed(self.objects.last_table(), spec.range_m, spec.speed_scale_mps,
                                forward, state.offset_m, state.heading_error_rad)
        return Reading(forward, state.offset_m, state.heading_error_rad, self.steering_bounds,
                       guard)


class RobotControl(Control):
    """A robot's layout: the setter is its wheels'."""

    def __init__(self, layout, robot):
        super().__init__(layout, robot.params)
        self.robot = robot
        self._setters = {setter: (lambda values, method=getattr(robot, method): method(*values))
                         for setter, method in ROBOT_SETTERS.items()}

    def stop(self):
        self.robot.set_wheel_velocities(0.0, 0.0)


def make_control(name, vehicle, max_speed_mps=None, max_reverse_mps=5.0,
                 max_steering_rad=None, lanes=None, objects=None):
    """
    Return the Control of a layout for the ego.

    :param name: 'auto' or a layout of core's table: 'speed_steering',
        'braking_speed_steering', 'guarded_speed_steering', 'lane_speed', 'throttle_steering'
        or 'twist'.
    :param vehicle: the ego's SceneVehicle (``car`` is None for a robot).
    :param max_steering_rad: a car's largest steering action either way (None: its limits).
    :param lanes: the ego's VehicleLanes, None in a world without lanes.
    :param objects: the ego's objects part (gym/objects.py), None without the option
        ``objects``.
    :raises ValueError: for a car layout on a robot or the robot layout on a car.
    :raises InvalidParameterError: a layout that reads the lane state in a world without lanes,
        or the objects table without the option ``objects``.
    """
    layout = layout_for(name, CAR if vehicle.car is not None else ROBOT, vehicle.name)
    if layout.reads_lane and lanes is None:
        raise InvalidParameterError(
            f'control {layout.name!r} reads the lane state: the world has no lanes '
            '(roads: or a lane map); give a control with a steering entry')
    if layout.reads_objects and objects is None:
        raise InvalidParameterError(
            f"control {layout.name!r} reads the objects table (its headway guard): give the "
            "option 'objects' (true, or its count, range and speed_scale)")
    if layout.vehicle == CAR:
        return CarControl(layout, vehicle.car, max_speed_mps, max_reverse_mps, max_steering_rad,
                          lanes, objects)
    if max_steering_rad is not None:
        raise InvalidParameterError(
            f'option max_steering = {max_steering_rad!r} rad: the ego {vehicle.name!r} is a '
            'robot (twist actions have no steering angle); give null')
    return RobotControl(layout, vehicle.body)
