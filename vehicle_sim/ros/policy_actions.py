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
A policy's action written as the automobile node's drive commands.

The policy's action is in its card's ``action_range`` (RescaleAction's [-1, 1]); it is mapped
back to the environment's physical action Box with RescaleAction's own affine map (float32, as
gymnasium computes it), checked against that Box as the environment checks it, and turned into
the car's Webots-level setters with their values by core's table of the action layouts
(``vehicle_sim/core/learning/actions.py``: the rule the environment applies in process,
gym/controls.py), each sent as the automobile node's service of the same name
(``automobile/<setter>``, docs/ros_interface.md), in its unit:

- ``speed_steering`` [steering angle [rad], + left; speed [m/s]] ->
  ``automobile/set_steering_angle`` (rad, + RIGHT: the sign flips) and
  ``automobile/set_cruising_speed`` (km/h: m/s x 3.6);
- ``braking_speed_steering`` [the same entries]: for a speed more than 1 m/s below the car's
  forward speed (its odometry's at the tick; core/car/speed_braking.py)
  ``automobile/set_steering_angle``, ``automobile/set_throttle`` 0 and
  ``automobile/set_brake_intensity``; else ``set_steering_angle``, ``set_brake_intensity`` 0 and
  ``set_cruising_speed``;
- ``lane_speed`` [lateral offset in the lane [m], + left; speed [m/s]]: the steering angle of
  core's lane-keeping law (core/car/lane_keeping.py) from the car's lane state
  (``<ns>/lane_state`` at the tick) and forward speed, within the steering bounds of the
  environment (its card's ``max_steering``), then the setters of ``braking_speed_steering``;
- ``guarded_speed_steering`` [the same entries]: the speed min(the action's, core's headway
  guard's for the vehicles ahead in the car's lane, core/learning/headway_guard.py), the guard
  reading the objects table built from ``/perception/object_recognition/objects`` at the tick
  (the environment's own function) and the tick's lane state, then the setters of
  ``braking_speed_steering``;
- ``throttle_steering`` [steering angle; throttle; brake] -> ``automobile/set_steering_angle``,
  ``automobile/set_throttle``, ``automobile/set_brake_intensity``.
"""

import math

import numpy as np

from vehicle_sim.core.learning import actions
from vehicle_sim.core.learning.headway_guard import guard_speed
from vehicle_sim.core.specs.errors import InvalidParameterError

# The layouts the node offers: core's layouts of a car (a robot's drives no automobile node).
LAYOUTS = {name: actions.LAYOUTS[name] for name in actions.layouts_of(actions.CAR)}


def service_of(setter):
    """Return the automobile node's service of a car's setter (core's SETTERS)."""
    return 'automobile/' + setter


class ActionWriter:
    """
    A policy's action -> the drive commands of the car.

    :param control: the action layout (a key of :data:`LAYOUTS`).
    :param low: the environment's physical action Box low bounds (its ``unwrapped`` space).
    :param high: its high bounds.
    :param action_range: (low, high) the policy's actions were rescaled to (its card's).
    :param steering_bounds: the environment's steering angles allowed (low, high) [rad],
        + = left: ``lane_speed``'s law keeps within them (required for it).
    :param objects_spec: the ObjectsTableSpec of the environment's objects table (its range
        and speed scale): ``guarded_speed_steering``'s guard reads the table (required for it).
    :raises InvalidParameterError: an unknown layout, bounds of the wrong length,
        ``lane_speed`` without steering bounds, or ``guarded_speed_steering`` without a table.
    """

    def __init__(self, control, low, high, action_range=(-1.0, 1.0), steering_bounds=None,
                 objects_spec=None):
        if control not in LAYOUTS:
            raise InvalidParameterError(
                f'control {control!r}: the automobile node is driven by '
                f'{", ".join(LAYOUTS)} (a robot policy, twist, drives no car)')
        self.control = control
        self.layout = LAYOUTS[control]
        if steering_bounds is None:
            # a layout without a steering entry that reads the lane state steers by core's
            # lane-keeping law (lane_speed), within the environment's steering bounds
            if self.layout.reads_lane and actions.STEERING_ENTRY not in self.layout.names:
                raise InvalidParameterError(
                    f'control {control!r} steers by a law within the steering bounds of its '
                    "environment: none given (the card's environment gives them)")
            self.steering_bounds = None
        else:
            self.steering_bounds = (float(steering_bounds[0]), float(steering_bounds[1]))
        if self.layout.reads_objects and objects_spec is None:
            raise InvalidParameterError(
                f"control {control!r} reads the objects table (its headway guard): the "
                "environment has none (its option 'objects')")
        self.objects_spec = objects_spec
        self.names, self.units = self.layout.names, self.layout.units
        self.low = np.asarray(low, dtype=np.float32)
        self.high = np.asarray(high, dtype=np.float32)
        if self.low.shape != (len(self.names),) or self.high.shape != self.low.shape:
            raise InvalidParameterError(
                f'control {control!r}: bounds of shape {self.low.shape} and '
                f'{self.high.shape}; expected ({len(self.names)},) ({", ".join(self.names)})')
        new_min = np.full(self.low.shape, action_range[0], dtype=np.float32)
        new_max = np.full(self.low.shape, action_range[1], dtype=np.float32)
        # gymnasium.wrappers.utils.rescale_box: y = gradient x + intercept (x physical)
        diff = self.high.astype(np.float64) - self.low.astype(np.float64)
        self._gradient = ((new_max - new_min) / diff).astype(np.float32)
        self._intercept = (self._gradient * -self.low + new_min).astype(np.float32)

    @property
    def services(self):
        """The services this layout may call."""
        return tuple(service_of(setter) for setter in self.layout.setters)

    def physical(self, action):
        """
        Return the physical action (float64) of a policy's action, checked against the Box.

        :raises ValueError: naming the entry: a wrong shape, NaN, or a value outside the Box.
        """
        action = actions.check_shape(np.asarray(action, dtype=np.float32), self.low, self.names)
        values = ((action - self._intercept) / self._gradient).astype(np.float64)
        return actions.check_action(values, self.low, self.high, self.names, self.units)

    def reading(self, forward_mps=0.0, lane_state=None, objects_table=None):
        """
        Return core's Reading of the car when an action is taken.

        :param forward_mps: the car's forward speed (its odometry's): braking_speed_steering,
            guarded_speed_steering and lane_speed brake or cruise by it.
        :param lane_state: its vehicle_msgs/LaneState (lane_speed steers by its offset and
            heading error, guarded_speed_steering's guard finds the car's lane by them), or
            None.
        :param objects_table: the objects table around the car then (the environment's
            layout, :attr:`objects_spec`'s), for guarded_speed_steering's guard; or None.
        """
        if lane_state is None:
            if self.layout.reads_lane:
                raise ValueError(f'control {self.control!r} reads the lane state: no '
                                 'lane_state message')
            return actions.Reading(float(forward_mps), steering_bounds=self.steering_bounds)
        offset, heading = float(lane_state.offset), float(lane_state.heading_error)
        guard = math.inf
        if self.layout.reads_objects:
            if objects_table is None:
                raise ValueError(f'control {self.control!r} reads the objects table: none '
                                 'given')
            spec = self.objects_spec
            guard = guard_speed(objects_table, spec.range_m, spec.speed_scale_mps,
                                float(forward_mps), offset, heading)
        return actions.Reading(float(forward_mps), offset, heading, self.steering_bounds, guard)

    def setters(self, values, forward_mps=0.0, lane_state=None, objects_table=None):
        """
        Return [(service, value in its unit)] of a physical action, in call order.

        :param forward_mps: the car's forward speed (its odometry's) when the action is taken.
        :param lane_state: its vehicle_msgs/LaneState then (lane_speed,
            guarded_speed_steering), or None.
        :param objects_table: the objects table then (guarded_speed_steering), or None.
        """
        reading = self.reading(forward_mps, lane_state, objects_table)
        return [(service_of(setter), float(value)) for setter, value
                in self.layout.values(values, reading)]

    def commands(self, action, forward_mps=0.0, lane_state=None, objects_table=None):
        """Return [(service, value in its unit)] for a policy's action, in call order."""
        return self.setters(self.physical(action), forward_mps, lane_state, objects_table)
