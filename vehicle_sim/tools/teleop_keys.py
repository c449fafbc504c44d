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
Keyboard teleop without ROS: terminal bytes -> keys -> the (v, ω) to send (docs/drive.md).

A terminal reports key presses, never releases; a held key repeats (after ~0.25-0.5 s, then
~30 times a second). So a key counts as held while its events keep arriving: within
:data:`HOLD_S` of the last one. Terminals repeat only the last key pressed, so holding ↑ and then
also ← repeats only ←; the drive direction therefore stays in force while any driving key keeps
arriving, and the steering key only while its own events do.

- ↑/W: speed up forwards, ↓/S: backwards (|v| ramps at ``accel_mps2`` up to ``max_speed_mps``);
  no ↑/↓ (and no key at all): v = 0 at once, so the vehicle stops when the keys are released.
- ←/A, →/D: turn left/right. Robot: ω = ±``max_yaw_rate_radps`` (it turns in place at v = 0).
  Car: ω = ±``curvature_per_m``·v, a turn of fixed radius (δ = atan(κ·L)); nothing at v = 0,
  where a car cannot turn.
- space: stop now (v = ω = 0, every held key forgotten). q (or Ctrl-C): quit.

Time is passed in (``now_s``, wall clock [s]), so tests need no sleep.
"""

from dataclasses import dataclass
import math
from typing import List, Optional, Tuple

# A key counts as held this long after its last event [s] (terminal auto-repeat comes in time).
HOLD_S = 0.6
UP, DOWN, LEFT, RIGHT, BRAKE, QUIT = 'up', 'down', 'left', 'right', 'brake', 'quit'

_PLAIN = {'w': UP, 's': DOWN, 'a': LEFT, 'd': RIGHT, ' ': BRAKE, 'q': QUIT, '\x03': QUIT}
# ESC [ X (normal cursor mode) and ESC O X (application cursor mode).
_ARROWS = {'A': UP, 'B': DOWN, 'C': RIGHT, 'D': LEFT}
_ESC = '\x1b'


class KeyDecoder:
    """
    Turn the bytes read from a terminal in cbreak mode into key names.

    An escape sequence split over two reads is completed by the next one; other bytes are
    ignored.
    """

    def __init__(self):
        self._pending = ''

    def feed(self, data: bytes) -> List[str]:
        """Return the keys in ``data`` (UP, DOWN, LEFT, RIGHT, BRAKE, QUIT), in order."""
        text = self._pending + data.decode('latin-1')
        self._pending = ''
        keys = []
        i = 0
        while i < len(text):
            if text[i] != _ESC:
                key = _PLAIN.get(text[i].lower())
                if key is not None:
                    keys.append(key)
                i += 1
                continue
            end = _sequence_end(text, i)
            if end is None:                  # incomplete: wait for the next read
                self._pending = text[i:]
                break
            if end > i + 2 and text[end - 1] in _ARROWS:
                keys.append(_ARROWS[text[end - 1]])   # modifiers (ESC [ 1 ; 5 A) ignored
            i = end
        return keys


def _sequence_end(text, i):
    # End index of the escape sequence at text[i] == ESC; None when it is incomplete. ESC O X
    # is three characters; ESC [ (CSI) runs to its final byte (0x40..0x7e); any other character
    # after ESC ends it (a lone Escape key).
    if i + 1 >= len(text):
        return None
    kind = text[i + 1]
    if kind == 'O':
        return i + 3 if i + 2 < len(text) else None
    if kind != '[':
        return i + 1
    for j in range(i + 2, len(text)):
        if '\x40' <= text[j] <= '\x7e':
            return j + 1
    return None


@dataclass(frozen=True)
class TeleopLimits:
    """
    What the keys command.

    :param max_speed_mps: |v| reached by holding ↑ or ↓ [m/s].
    :param accel_mps2: rate at which |v| rises while ↑ or ↓ is held [m/s²].
    :param max_yaw_rate_radps: robot: yaw rate of ← and → [rad/s].
    :param curvature_per_m: car: path curvature of ← and → [1/m] (ω = κ·v).
    :param robot: True: a differential robot (turns in place); False: a car.
    """

    max_speed_mps: float = 2.0
    accel_mps2: float = 1.0
    max_yaw_rate_radps: float = 1.0
    curvature_per_m: float = 0.15
    robot: bool = False

    def __post_init__(self):
        """Refuse limits that are not finite numbers > 0."""
        for name in ('max_speed_mps', 'accel_mps2', 'max_yaw_rate_radps', 'curvature_per_m'):
            value = getattr(self, name)
            if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0.0):
                raise ValueError(f'{name} = {value!r}: must be a finite number > 0')


class TeleopState:
    """The keys held and the (v, ω) command they give; ``now_s`` is passed in."""

    def __init__(self, limits: TeleopLimits = TeleopLimits(), hold_s: float = HOLD_S):
        self.limits = limits
        self.hold_s = hold_s
        self.speed_mps = 0.0
        self.quit = False
        self._direction = 0            # +1 forward, −1 backward, 0 none
        self._turn = 0                 # +1 left, −1 right, 0 none
        self._last_key_s: Optional[float] = None
        self._last_turn_s: Optional[float] = None
        self._last_update_s: Optional[float] = None

    def press(self, key: str, now_s: float) -> None:
        """Record one key event at ``now_s`` [s]."""
        if key == QUIT:
            self.quit = True
            return
        if key == BRAKE:
            self._direction = self._turn = 0
            self._last_key_s = self._last_turn_s = None
            self.speed_mps = 0.0
            return
        self._last_key_s = now_s
        if key in (UP, DOWN):
            direction = 1 if key == UP else -1
            if direction != self._direction and self.speed_mps * direction < 0.0:
                self.speed_mps = 0.0   # reversing the keys stops first
            self._direction = direction
        elif key in (LEFT, RIGHT):
            self._turn = 1 if key == LEFT else -1
            self._last_turn_s = now_s

    def _held(self, last_s, now_s):
        return last_s is not None and now_s - last_s <= self.hold_s

    def command(self, now_s: float) -> Tuple[float, float]:
        """
        Return the (v [m/s], ω [rad/s, + left]) to send at ``now_s``, ramping v since last call.

        With no key held it is (0, 0).
        """
        limits = self.limits
        dt_s = 0.0 if self._last_update_s is None else max(0.0, now_s - self._last_update_s)
        self._last_update_s = now_s
        if not self._held(self._last_key_s, now_s):
            self._direction = 0
        if not self._held(self._last_turn_s, now_s):
            self._turn = 0
        if self._direction == 0:
            self.speed_mps = 0.0
        else:
            target = self._direction * limits.max_speed_mps
            step = limits.accel_mps2 * dt_s
            self.speed_mps = min(self.speed_mps + step, target) if target > 0.0 else \
                max(self.speed_mps - step, target)
        if limits.robot:
            yaw_rate = self._turn * limits.max_yaw_rate_radps
        else:
            yaw_rate = self._turn * limits.curvature_per_m * self.speed_mps
        return self.speed_mps, yaw_rate


def status_line(command: Tuple[float, float], speed_mps: Optional[float],
                steering: Optional[float], robot: bool) -> str:
    """
    Return the one-line status: commanded and measured speed and steering.

    :param command: the (v [m/s], ω [rad/s]) sent.
    :param speed_mps: measured speed [m/s] (None: nothing received yet).
    :param steering: measured steering: car: steering angle [rad, + left]; robot: yaw rate
        [rad/s]; None: nothing received yet.
    :param robot: True for a robot.
    """
    def value(number, unit):
        return '--' if number is None else f'{number:+.2f} {unit}'
    turn = 'yaw rate' if robot else 'steering'
    turn_unit = 'rad/s' if robot else 'rad'
    return (f'cmd v {command[0]:+.2f} m/s  ω {command[1]:+.2f} rad/s | measured v '
            f'{value(speed_mps, "m/s")}  {turn} {value(steering, turn_unit)}  '
            '(arrows/WASD, space stops, q quits)')
