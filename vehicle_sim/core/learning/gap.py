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
The ``gap`` reward term: the room the ego leaves to the road users around it.

Geometry, in the ego's base_link frame (x forward, y left): the ego is its footprint rectangle
(core/geometry/footprint.py ``Outline``), each other road user a box of its length and width
around its centre, taken as the rectangle around it along the ego's axes (its half extents
``|cos h| l/2 + |sin h| w/2`` along x, ``|sin h| l/2 + |cos h| w/2`` along y, h its heading
relative to the ego's). Between the ego and a box:

- the *longitudinal gap* [m]: bumper to bumper along x (ahead: the box's rear minus the ego's
  front; behind: the ego's rear minus the box's front), <= 0 when they overlap along x;
- the *clearance* [m]: side to side along y, <= 0 when they overlap along y.

A box is *beside* the ego when they overlap along x, and *in the ego's path* when it is not
beside, its centre is ahead of the ego's front and its clearance is below ``gap_margin``. Each
box in the path, with its longitudinal gap g (clipped at 0), gives

- the time headway ``g / v`` (v the ego's forward speed; none when v <= 0),
- the time to collision ``g / (v - v_o)`` (v_o the box's velocity along the ego's x; none
  when it does not close in).

The term, per env step of duration dt [s] (each fraction in 0 .. 1, the largest over the
boxes):

    gap = -dt * ( headway_penalty  * max(0, 1 - headway / headway_s)
                + ttc_penalty      * max(0, 1 - ttc / ttc_s)
                + side_gap_penalty * max(0, 1 - clearance / gap_margin) [boxes beside] )

Numpy-free; :func:`gap_fractions` and :func:`gap_term` are what the Gym environment calls
(gym/ego.py) on the state at the end of each env step.
"""

from dataclasses import dataclass
import math
from typing import Iterable, Tuple

from vehicle_sim.core.specs.errors import InvalidParameterError


@dataclass(frozen=True)
class GapWeights:
    """
    Weights and thresholds of the ``gap`` term (see the module text).

    :param headway_penalty: subtracted per second at zero time headway [1/s], >= 0.
    :param headway_s: time headway below which the penalty starts [s], > 0.
    :param ttc_penalty: subtracted per second at zero time to collision [1/s], >= 0.
    :param ttc_s: time to collision below which the penalty starts [s], > 0.
    :param side_gap_penalty: subtracted per second touching a box beside [1/s], >= 0.
    :param gap_margin_m: clearance below which a box is in the path and a box beside is
        penalised [m], > 0.
    """

    headway_penalty: float = 0.0
    headway_s: float = 1.0
    ttc_penalty: float = 0.0
    ttc_s: float = 3.0
    side_gap_penalty: float = 0.0
    gap_margin_m: float = 1.0

    def __post_init__(self):
        for name in ('headway_penalty', 'ttc_penalty', 'side_gap_penalty'):
            value = getattr(self, name)
            if not math.isfinite(value) or value < 0.0:
                raise InvalidParameterError(f'{name} = {value!r}: must be finite and >= 0 '
                                            '(it is subtracted)')
        for name in ('headway_s', 'ttc_s', 'gap_margin_m'):
            value = getattr(self, name)
            if not math.isfinite(value) or value <= 0.0:
                raise InvalidParameterError(f'{name} = {value!r}: must be finite and > 0')

    @property
    def enabled(self) -> bool:
        """True when any of its penalties is not 0 (the term is then computed and reported)."""
        return bool(self.headway_penalty or self.ttc_penalty or self.side_gap_penalty)


@dataclass(frozen=True)
class Box:
    """
    Another road user (world frame).

    :param x_m: its centre x [m]; ``y_m`` its y.
    :param yaw_rad: its heading [rad].
    :param speed_mps: its speed along its heading [m/s] (0 at rest).
    :param length_m: its length [m]; ``width_m`` its width.
    """

    x_m: float
    y_m: float
    yaw_rad: float
    speed_mps: float
    length_m: float
    width_m: float


def gap_fractions(weights: GapWeights, outline, ego_x_m: float, ego_y_m: float,
                  ego_yaw_rad: float, ego_forward_mps: float,
                  others: Iterable[Box]) -> Tuple[float, float, float]:
    """
    Return the (headway, ttc, side) fractions, each 0 .. 1 (the module text's max(0, ...)).

    :param outline: the ego's footprint in base_link (x_min_m, x_max_m, y_min_m, y_max_m).
    :param ego_x_m: its base_link x in the boxes' frame [m]; ``ego_y_m`` its y.
    :param ego_yaw_rad: its heading [rad]; ``ego_forward_mps`` its speed along it [m/s].
    """
    c, s = math.cos(ego_yaw_rad), math.sin(ego_yaw_rad)
    margin = weights.gap_margin_m
    v = ego_forward_mps
    headway = ttc = side = 0.0
    for other in others:
        dx_w, dy_w = other.x_m - ego_x_m, other.y_m - ego_y_m
        dx, dy = c * dx_w + s * dy_w, -s * dx_w + c * dy_w
        h = other.yaw_rad - ego_yaw_rad
        ch, sh = abs(math.cos(h)), abs(math.sin(h))
        half_x = 0.5 * (ch * other.length_m + sh * other.width_m)
        half_y = 0.5 * (sh * other.length_m + ch * other.width_m)
        clearance = (dy - half_y - outline.y_max_m) if dy >= 0.0 \
            else (outline.y_min_m - dy - half_y)
        ahead = dx - half_x - outline.x_max_m
        behind = outline.x_min_m - dx - half_x
        if ahead < 0.0 and behind < 0.0:          # beside: overlapping along x
            side = max(side, min(1.0, 1.0 - clearance / margin))
            continue
        if dx <= outline.x_max_m or clearance >= margin:
            continue                                # behind, or out of the path
        gap = max(0.0, ahead)
        if v > 0.0:
            headway = max(headway, 1.0 - gap / (v * weights.headway_s))
        closing = v - other.speed_mps * math.cos(h)
        if closing > 0.0:
            ttc = max(ttc, 1.0 - gap / (closing * weights.ttc_s))
    return max(0.0, headway), max(0.0, ttc), max(0.0, side)


def gap_term(weights: GapWeights, fractions: Tuple[float, float, float], step_s: float) -> float:
    """Return the weighted ``gap`` term of one step (0 or negative) from its fractions."""
    headway, ttc, side = fractions
    penalty = (weights.headway_penalty * headway + weights.ttc_penalty * ttc
               + weights.side_gap_penalty * side) * float(step_s)
    return -penalty if penalty else 0.0
