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
Autoware vehicle-interface codes and their validation, ROS-free.

The constants of ``autoware_vehicle_msgs`` (autoware_msgs 1.9.0): GearCommand and GearReport
share their values, as do the turn-indicator, hazard-light and control-mode commands and
reports. The bridge (``core/bridge/controller.py``) and the autoware_automobile node accept and
refuse the same commands through the ``check_*`` functions here.
"""

from vehicle_sim.core.specs.errors import InvalidCommandError

# GearCommand / GearReport (DRIVE_2..DRIVE_18 are 3..19).
GEAR_NONE, GEAR_NEUTRAL, GEAR_DRIVE = 0, 1, 2
GEAR_REVERSE, GEAR_REVERSE_2, GEAR_PARK, GEAR_LOW, GEAR_LOW_2 = 20, 21, 22, 23, 24
REVERSE_GEARS = (GEAR_REVERSE, GEAR_REVERSE_2)
STOP_GEARS = (GEAR_NEUTRAL, GEAR_PARK)
VALID_GEARS = frozenset(range(GEAR_NONE, GEAR_LOW_2 + 1))

# TurnIndicatorsCommand / HazardLightsCommand (and their reports, NO_COMMAND excepted).
NO_COMMAND, DISABLE, ENABLE_LEFT, ENABLE_RIGHT = 0, 1, 2, 3
HAZARD_ENABLE = 2
TURN_INDICATORS_COMMANDS = (NO_COMMAND, DISABLE, ENABLE_LEFT, ENABLE_RIGHT)
HAZARD_LIGHTS_COMMANDS = (NO_COMMAND, DISABLE, HAZARD_ENABLE)

# ControlModeCommand / ControlModeReport: the two modes a simulated vehicle supports.
MODE_AUTONOMOUS, MODE_MANUAL = 1, 4
SUPPORTED_CONTROL_MODES = (MODE_AUTONOMOUS, MODE_MANUAL)


def check_gear(gear):
    """
    Return a GearCommand value, or refuse an undefined one.

    :raises InvalidCommandError: naming the value when it is not a GearCommand constant.
    """
    if gear not in VALID_GEARS:
        raise InvalidCommandError(f'gear command {gear!r}: not a GearCommand constant')
    return gear


def check_turn_indicators(command):
    """
    Return a TurnIndicatorsCommand value, or refuse an undefined one.

    :raises InvalidCommandError: naming the value when it is undefined.
    """
    if command not in TURN_INDICATORS_COMMANDS:
        raise InvalidCommandError(f'turn indicators command {command!r}: undefined')
    return command


def check_hazard_lights(command):
    """
    Return a HazardLightsCommand value, or refuse an undefined one.

    :raises InvalidCommandError: naming the value when it is undefined.
    """
    if command not in HAZARD_LIGHTS_COMMANDS:
        raise InvalidCommandError(f'hazard lights command {command!r}: undefined')
    return command


def is_supported_control_mode(mode):
    """Return True for AUTONOMOUS and MANUAL, the modes a ControlModeCommand may request."""
    return mode in SUPPORTED_CONTROL_MODES


def control_mode_refusal(mode):
    """Return None for a supported control mode, else why a request for ``mode`` is refused."""
    if is_supported_control_mode(mode):
        return None
    return f'mode={mode!r} refused: only AUTONOMOUS (1) and MANUAL (4) are supported'
