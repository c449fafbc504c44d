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

"""The ``ackermann_to_differential`` bridge's parameter table (ParamSpec rows) and BridgeParams."""

from dataclasses import dataclass

from vehicle_sim.core.bridge.ackermann_mapping import KINEMATIC_MODES
from vehicle_sim.core.commands.watchdog import (
    DEFAULT_TIMEOUT_ACTION,
    DEFAULT_TIMEOUT_S,
    TIMEOUT_ACTIONS,
)
from vehicle_sim.core.specs.param_spec import ParamSpec, validate_table

BRIDGE_PARAM_SPECS = (
    ParamSpec('wheel_base', 'wheel_base_m', 'float', 0.5, 'm',
              '(pseudo) wheel base of the bicycle model Autoware assumes; near wheel_tread',
              gt=0.0),
    ParamSpec('wheel_tread', 'wheel_tread_m', 'float', 0.5, 'm',
              'distance between the left and right wheel contact points', gt=0.0),
    ParamSpec('wheel_radius', 'wheel_radius_m', 'float', 0.1, 'm',
              'drive wheel radius (m/s <-> rad/s)', gt=0.0),
    ParamSpec('max_wheel_speed_mps', 'max_wheel_speed_mps', 'float', 1.0, 'm/s',
              'largest tyre-surface speed; both wheels scale together (0 disables)', ge=0.0),
    ParamSpec('max_accel_mps2', 'max_accel_mps2', 'float', 1.0, 'm/s^2',
              'largest increase rate of |v| (0 disables)', ge=0.0),
    ParamSpec('max_decel_mps2', 'max_decel_mps2', 'float', 2.0, 'm/s^2',
              'largest decrease rate of |v| (0 disables)', ge=0.0),
    ParamSpec('max_angular_accel_radps2', 'max_angular_accel_radps2', 'float', 0.0, 'rad/s^2',
              'largest change rate of |yaw rate|; non-zero trades path fidelity for smoothness '
              '(0 disables)', ge=0.0),
    ParamSpec('mode', 'mode', 'enum', 'kinematic', choices=KINEMATIC_MODES,
              doc="kinematic: yaw rate v*tan(steer)/wheel_base; literal: the snippet of "
                  "Autoware's note (steering angle used as yaw rate), compatibility only"),
    ParamSpec('turn_in_place', 'turn_in_place', 'bool', False,
              doc='rotate in place when |v| < turn_in_place_speed_threshold_mps and steer != 0'),
    ParamSpec('turn_in_place_speed_threshold_mps', 'turn_in_place_speed_threshold_mps', 'float',
              0.05, 'm/s', 'commanded |v| below which turn-in-place applies', gt=0.0),
    ParamSpec('turn_in_place_gain_per_s', 'turn_in_place_gain_per_s', 'float', 1.0, '1/s',
              'in-place yaw rate per rad of steering', gt=0.0),
    ParamSpec('turn_in_place_max_yaw_rate_radps', 'turn_in_place_max_yaw_rate_radps', 'float',
              0.5, 'rad/s', 'largest in-place yaw rate', gt=0.0),
    ParamSpec('command_timeout_s', 'command_timeout_s', 'float', DEFAULT_TIMEOUT_S, 's',
              'age of the last accepted command (receipt, node clock) after which '
              'timeout_action applies (0 disables)', ge=0.0),
    ParamSpec('timeout_action', 'timeout_action', 'enum', DEFAULT_TIMEOUT_ACTION,
              choices=TIMEOUT_ACTIONS,
              doc='brake: publish zero wheel speeds; coast: publish nothing; hold: repeat the '
                  'last command'),
)



@dataclass(frozen=True)
class BridgeParams:
    """Validated bridge parameters (SI units; meaning in BRIDGE_PARAM_SPECS)."""

    wheel_base_m: float
    wheel_tread_m: float
    wheel_radius_m: float
    max_wheel_speed_mps: float
    max_accel_mps2: float
    max_decel_mps2: float
    max_angular_accel_radps2: float
    mode: str
    turn_in_place: bool
    turn_in_place_speed_threshold_mps: float
    turn_in_place_gain_per_s: float
    turn_in_place_max_yaw_rate_radps: float
    command_timeout_s: float
    timeout_action: str


def default_bridge_dict():
    """Return the bridge defaults keyed by parameter name."""
    return {spec.key: spec.default for spec in BRIDGE_PARAM_SPECS}


def bridge_params_from_dict(data=None, source='bridge parameters'):
    """
    Validate bridge parameters (ROS names, see BRIDGE_PARAM_SPECS) and build BridgeParams.

    :param data: mapping of parameter names to values; missing names take their default.
    :param source: origin quoted in error messages (file or node name).
    :return: BridgeParams.
    :raises InvalidParameterError: naming the parameter, its value and the allowed range, for an
        unknown name, a wrong type or an out-of-range value (nothing is clamped).
    """
    values = validate_table(BRIDGE_PARAM_SPECS, {} if data is None else data, source,
                            default_bridge_dict(), 'bridge parameters', 'parameter')
    return BridgeParams(**values)


DEFAULT_BRIDGE_PARAMS = bridge_params_from_dict(source='bridge defaults')
