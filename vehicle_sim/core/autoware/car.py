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
Autoware vehicle commands -> a Webots car (CarLogic), and the car's state -> Autoware reports.

ROS-free mapping behind the ``autoware_automobile`` node (docs/end_to_end.md, "The
autoware_automobile node"). Units and signs change only through ``core/specs/units.py``: Autoware
speaks m/s and a steering tire angle with + = left (REP 103); the Webots car takes km/h and a
steering angle with + = right.

- The steering tire angle of Autoware's bicycle model is the Webots driver's (centre) steering
  angle, the angle of the virtual wheel between the two front wheels; the Ackermann geometry then
  turns the inner wheel more. So δ_webots = ros_steering_to_webots(δ_tire), nothing else.
- Gears (the velocity's sign is ignored, the gear gives the direction, as with a real vehicle
  interface): DRIVE -> cruising speed +|v|; REVERSE -> cruising speed −|v| (steering kept: the car
  backs along the commanded circle); PARK -> cruising speed 0 and brake 1 (full); NEUTRAL -> no
  drive: TORQUE mode with throttle 0 and Webots gear 0, the car coasts. The Webots gear register
  follows (DRIVE 1, REVERSE −1, PARK/NEUTRAL 0), so the gear report is read back from the car.
- No silent clamping: a steering angle beyond the car's limits or a speed above its top speed is
  rejected (InvalidCommandError naming value and limits) and nothing changes.
"""

from dataclasses import dataclass
import math

from vehicle_sim.core.autoware.codes import (
    DISABLE,
    ENABLE_LEFT,
    ENABLE_RIGHT,
    GEAR_DRIVE,
    GEAR_NEUTRAL,
    GEAR_PARK,
    GEAR_REVERSE,
    REVERSE_GEARS,
)
from vehicle_sim.core.car.signals import Indicator
from vehicle_sim.core.car.speed_braking import full_stop
from vehicle_sim.core.commands.watchdog import (
    CommandWatchdog,
    DEFAULT_TIMEOUT_ACTION,
    DEFAULT_TIMEOUT_S,
)
from vehicle_sim.core.specs.errors import InvalidCommandError
from vehicle_sim.core.specs.units import (
    kmh_to_mps,
    mps_to_kmh,
    ros_steering_to_webots,
    webots_steering_to_ros,
)

# Gear actions (what a gear does to the car); the node maps Autoware GearCommand values to them.
DRIVE, REVERSE, PARK, NEUTRAL = 'drive', 'reverse', 'park', 'neutral'
GEAR_ACTIONS = (DRIVE, REVERSE, PARK, NEUTRAL)
# Webots gear register per action (driver library: −1 reverse, 0 neutral, 1 first gear).
WEBOTS_GEAR = {DRIVE: 1, REVERSE: -1, PARK: 0, NEUTRAL: 0}
PARK_BRAKE_INTENSITY = 1.0
# Indicator sides (Autoware ENABLE_LEFT/ENABLE_RIGHT/DISABLE <-> Webots LEFT/RIGHT/OFF).
INDICATOR_OFF, INDICATOR_LEFT, INDICATOR_RIGHT = 'off', 'left', 'right'
_TO_WEBOTS_INDICATOR = {INDICATOR_OFF: Indicator.OFF, INDICATOR_LEFT: Indicator.LEFT,
                        INDICATOR_RIGHT: Indicator.RIGHT}
_FROM_WEBOTS_INDICATOR = {int(v): k for k, v in _TO_WEBOTS_INDICATOR.items()}

# Autoware GearCommand -> gear action; every other defined gear (DRIVE_2.., LOW, LOW_2) drives
# forward. GearReport of each action (read back from the car).
_GEAR_ACTION = {GEAR_NEUTRAL: NEUTRAL, GEAR_PARK: PARK}
_GEAR_ACTION.update({gear: REVERSE for gear in REVERSE_GEARS})
GEAR_REPORT = {DRIVE: GEAR_DRIVE, REVERSE: GEAR_REVERSE, PARK: GEAR_PARK, NEUTRAL: GEAR_NEUTRAL}
# Autoware TurnIndicatorsCommand (NO_COMMAND excepted) <-> indicator side; the report uses the
# same values.
INDICATOR_OF_COMMAND = {DISABLE: INDICATOR_OFF, ENABLE_LEFT: INDICATOR_LEFT,
                        ENABLE_RIGHT: INDICATOR_RIGHT}
INDICATOR_REPORT = {side: value for value, side in INDICATOR_OF_COMMAND.items()}


def gear_action_of_command(gear):
    """Return the gear action of a defined GearCommand value other than NONE."""
    return _GEAR_ACTION.get(gear, DRIVE)


@dataclass(frozen=True)
class CarLimits:
    """The car's command limits in Webots units and signs (km/h, rad + = right)."""

    min_steering_rad: float
    max_steering_rad: float
    max_speed_kmh: float
    wheelbase_m: float

    @classmethod
    def from_logic(cls, logic):
        """Read the limits of a CarLogic."""
        return cls(logic.min_steering_angle_rad, logic.max_steering_angle_rad,
                   logic.max_cruising_speed_kmh, logic.wheelbase_m)

    @property
    def autoware_steering_range_rad(self):
        """(lowest, highest) steering tire angle accepted [rad], + = left."""
        return (webots_steering_to_ros(self.max_steering_rad),
                webots_steering_to_ros(self.min_steering_rad))


@dataclass(frozen=True)
class CarCommand:
    """
    What the mapping sets on the CarLogic (Webots units and signs).

    :param cruising_speed_kmh: cruising speed [km/h], negative = reverse (unused when coast).
    :param steering_angle_rad: driver steering angle [rad], + = right.
    :param brake_intensity: brake in [0, 1].
    :param webots_gear: gear register (−1, 0, 1).
    :param coast: True: TORQUE mode with throttle 0 (neutral), no cruising speed.
    """

    cruising_speed_kmh: float
    steering_angle_rad: float
    brake_intensity: float
    webots_gear: int
    coast: bool = False


def _finite(name, value, unit):
    if isinstance(value, bool) or not isinstance(value, (int, float)) or \
            not math.isfinite(value):
        raise InvalidCommandError(f'{name} = {value!r} {unit}: must be a finite number')
    return float(value)


def car_command(speed_mps, steering_tire_rad, action, limits):
    """
    Map one Autoware command to a CarCommand, or reject it.

    :param speed_mps: longitudinal velocity [m/s]; its sign is ignored (the gear decides).
    :param steering_tire_rad: steering tire angle [rad], + = left.
    :param action: one of GEAR_ACTIONS.
    :param limits: CarLimits.
    :return: CarCommand.
    :raises InvalidCommandError: non-finite values, a steering angle beyond the car's limits, a
        speed above its top speed, or an unknown action (the message names value and range).
    """
    speed_mps = _finite('velocity', speed_mps, 'm/s')
    steering_tire_rad = _finite('steering_tire_angle', steering_tire_rad, 'rad')
    if action not in GEAR_ACTIONS:
        raise InvalidCommandError(f'gear action {action!r}: must be one of {GEAR_ACTIONS}')
    steering_rad = ros_steering_to_webots(steering_tire_rad)
    if not limits.min_steering_rad <= steering_rad <= limits.max_steering_rad:
        low, high = limits.autoware_steering_range_rad
        raise InvalidCommandError(
            f"steering_tire_angle = {steering_tire_rad!r} rad (+ left) is outside the car's "
            f'steering limits [{low:g}, {high:g}] rad; not clamped')
    speed_kmh = mps_to_kmh(abs(speed_mps))
    if speed_kmh > limits.max_speed_kmh:
        raise InvalidCommandError(
            f"velocity = {speed_mps!r} m/s is above the car's top speed "
            f'{kmh_to_mps(limits.max_speed_kmh):g} m/s; not clamped')
    gear = WEBOTS_GEAR[action]
    if action == DRIVE:
        return CarCommand(speed_kmh, steering_rad, 0.0, gear)
    if action == REVERSE:
        return CarCommand(-speed_kmh, steering_rad, 0.0, gear)
    if action == PARK:
        return CarCommand(0.0, steering_rad, PARK_BRAKE_INTENSITY, gear)
    return CarCommand(0.0, steering_rad, 0.0, gear, coast=True)


def apply_car_command(logic, command):
    """
    Set a CarCommand on a CarLogic (values already validated by car_command).

    :param logic: CarLogic.
    :param command: CarCommand.
    """
    logic.set_steering_angle(command.steering_angle_rad)
    logic.set_gear(command.webots_gear)
    if command.coast:
        logic.set_throttle(0.0)
    else:
        logic.set_cruising_speed_kmh(command.cruising_speed_kmh)
    logic.set_brake_intensity(command.brake_intensity)


def gear_action_of_car(logic):
    """
    Read the gear action back from the car (for GearReport).

    Webots gear −1 -> REVERSE, >= 1 -> DRIVE; gear 0 with the parking brake applied -> PARK,
    otherwise NEUTRAL.
    """
    gear = logic.selected_gear
    if gear < 0:
        return REVERSE
    if gear > 0:
        return DRIVE
    return PARK if logic.brake_intensity >= PARK_BRAKE_INTENSITY else NEUTRAL


def indicator_of_car(logic):
    """Return the car's indicator as INDICATOR_OFF/LEFT/RIGHT."""
    return _FROM_WEBOTS_INDICATOR[int(logic.indicator)]


def set_car_indicator(logic, side):
    """Set the car's indicator from INDICATOR_OFF/LEFT/RIGHT."""
    if side not in _TO_WEBOTS_INDICATOR:
        raise InvalidCommandError(f'indicator {side!r}: must be one of '
                                  f'{sorted(_TO_WEBOTS_INDICATOR)}')
    logic.set_indicator(int(_TO_WEBOTS_INDICATOR[side]))


@dataclass(frozen=True)
class CarReport:
    """The car's state for the Autoware reports (SI, REP 103)."""

    speed_mps: float
    heading_rate_radps: float
    steering_tire_rad: float
    gear_action: str
    indicator: str
    hazard: bool


def car_report(logic):
    """
    Build the Autoware view of the car from its own (non ground-truth) data.

    Speed: the car's current speed (driven-wheel estimate, km/h -> m/s). Steering: the measured
    steering angle (mean of the two front wheels, Webots sign -> + left). Heading rate: the
    bicycle model on those two, v·tan δ / L (the car has no yaw sensor).

    :param logic: CarLogic (after at least one step for measured values).
    :return: CarReport.
    """
    speed_mps = kmh_to_mps(logic.current_speed_kmh)
    steering = webots_steering_to_ros(logic.steering_angle_rad)
    return CarReport(speed_mps, speed_mps * math.tan(steering) / logic.wheelbase_m, steering,
                     gear_action_of_car(logic), indicator_of_car(logic),
                     bool(logic.hazard_flashers))


class AutowareCar:
    """
    The autoware_automobile node's state, ROS-free (``now_s`` passed in): gear, autonomy, watchdog.

    Commands are validated before anything changes. In MANUAL the car is left to its
    /automobile services (one stop is applied when switching). The watchdog (receipt time,
    accepted commands only) acts once per staleness: brake = a safety stop (core/car/
    speed_braking.py's full_stop: cruising speed 0, the throttle released and full brake, so
    that the car slows at its full-brake deceleration, not at its cruise control's ramp), coast =
    NEUTRAL behaviour, hold = nothing.
    """

    def __init__(self, logic, timeout_s=DEFAULT_TIMEOUT_S, timeout_action=DEFAULT_TIMEOUT_ACTION):
        """
        Wrap a car.

        :param logic: CarLogic to drive.
        :param timeout_s: command timeout [s] (0 disables).
        :param timeout_action: 'brake', 'coast' or 'hold'.
        """
        self.logic = logic
        self.limits = CarLimits.from_logic(logic)
        self.watchdog = CommandWatchdog(timeout_s, timeout_action)
        self.action = DRIVE
        self.autonomous = True
        self.target = None          # last accepted (speed [m/s], steering tire angle [rad])
        self.timed_out = False
        logic.set_gear(WEBOTS_GEAR[DRIVE])

    def command(self, speed_mps, steering_tire_rad, now_s):
        """
        Accept one Autoware command at receipt time ``now_s``.

        :return: the CarCommand applied, or None in MANUAL.
        :raises InvalidCommandError: see car_command; nothing changes then.
        """
        command = car_command(speed_mps, steering_tire_rad, self.action, self.limits)
        self.watchdog.feed(now_s)
        self.target = (float(speed_mps), float(steering_tire_rad))
        self.timed_out = False
        if not self.autonomous:
            return None
        apply_car_command(self.logic, command)
        return command

    def set_gear_action(self, action):
        """Select DRIVE/REVERSE/PARK/NEUTRAL; applied at once with the last command (or 0)."""
        if action not in GEAR_ACTIONS:
            raise InvalidCommandError(f'gear action {action!r}: must be one of {GEAR_ACTIONS}')
        self.action = action
        if self.autonomous:
            self._apply_target(0.0 if self.timed_out else None)

    def set_autonomous(self, autonomous):
        """Switch AUTONOMOUS (True) / MANUAL (False); entering MANUAL stops the car once."""
        if self.autonomous and not autonomous:
            self._apply_target(0.0)
        self.autonomous = bool(autonomous)

    def reset(self):
        """
        Start again after the car's logic was reset (the vehicle's reset, /sim/reset).

        As when built: gear action DRIVE (the car in its first forward gear), no command, the
        watchdog idle until the next command. AUTONOMOUS or MANUAL stays as last requested:
        the control mode is the operator's choice, not the car's state.
        """
        self.action = DRIVE
        self.target = None
        self.timed_out = False
        self.watchdog.reset()
        self.logic.set_gear(WEBOTS_GEAR[DRIVE])

    def tick(self, now_s):
        """Run the watchdog at ``now_s``; return True when it acted on this call."""
        if not self.autonomous or self.timed_out or self.target is None or \
                not self.watchdog.is_stale(now_s):
            return False
        self.timed_out = True
        action = self.watchdog.action
        if action == 'hold':
            return False
        steering = ros_steering_to_webots(self.target[1])
        if action == 'brake':
            self.logic.set_steering_angle(steering)
            self.logic.set_gear(WEBOTS_GEAR[self.action])
            full_stop(self.logic)
        else:
            apply_car_command(self.logic, CarCommand(0.0, steering, 0.0, 0, coast=True))
        return True

    def _apply_target(self, speed_mps=None):
        speed, steering = self.target if self.target is not None else (0.0, None)
        if speed_mps is not None:
            speed = speed_mps
        if steering is None:
            steering = webots_steering_to_ros(self.logic.commanded_steering_angle_rad)
        apply_car_command(self.logic, car_command(speed, steering, self.action, self.limits))

