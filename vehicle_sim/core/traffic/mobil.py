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
MOBIL, "minimizing overall braking induced by lane changes" (Kesting, Treiber and Helbing, 2007).

A vehicle ``c`` considers a change to a neighbouring lane. With ``n`` its new follower (behind it
in the target lane) and ``o`` its old follower (behind it now), and the accelerations ``a`` now
and ``ã`` after the change (all from the longitudinal model, IDM here):

- safety: the new follower would not brake harder than ``b_safe``: ``ã_n >= -b_safe``; nor the
  vehicle itself: ``ã_c >= -b_safe``;
- incentive: ``ã_c - a_c + p ((ã_n - a_n) + (ã_o - a_o)) > Δa_th``, with the politeness ``p``
  and the threshold ``Δa_th``.

The change happens when both hold (the incentive strictly greater than the threshold). A side
without a follower contributes 0 to the incentive and nothing to the safety criterion.
"""

from dataclasses import dataclass

from vehicle_sim.core.specs.param_spec import ParamSpec, table_dataclass

MOBIL_SPECS = (
    ParamSpec('politeness', 'politeness', 'float', 0.2, '',
              "weight p of the followers' acceleration changes", ge=0.0, le=1.0),
    ParamSpec('threshold', 'threshold_mps2', 'float', 0.2, 'm/s^2',
              'acceleration gain needed to change lanes, delta a_th', ge=0.0, le=5.0),
    ParamSpec('safe_braking', 'safe_braking_mps2', 'float', 4.0, 'm/s^2',
              'the hardest braking b_safe a change may impose', gt=0.0, le=9.0),
)


@table_dataclass(MOBIL_SPECS)
class MobilParams:
    """
    Validated MOBIL parameters: a field per row of :data:`MOBIL_SPECS`.

    ``MobilParams.from_dict(data, source)`` validates a mapping of the table's keys.
    """


@dataclass(frozen=True)
class LaneChangeAccelerations:
    """
    The accelerations [m/s^2] MOBIL weighs, now (``*_now``) and after the change (``*_after``).

    ``new_follower_*`` / ``old_follower_*`` are None where there is no such vehicle.
    """

    own_now: float
    own_after: float
    new_follower_now: float = None
    new_follower_after: float = None
    old_follower_now: float = None
    old_follower_after: float = None


def incentive(acc: LaneChangeAccelerations, p: MobilParams):
    """Return MOBIL's incentive [m/s^2]: own gain plus ``politeness`` times the followers'."""
    gain = acc.own_after - acc.own_now
    others = 0.0
    if acc.new_follower_now is not None:
        others += acc.new_follower_after - acc.new_follower_now
    if acc.old_follower_now is not None:
        others += acc.old_follower_after - acc.old_follower_now
    return gain + p.politeness * others


def is_safe(acc: LaneChangeAccelerations, p: MobilParams):
    """Return whether neither the vehicle nor its new follower would brake harder than b_safe."""
    if acc.own_after < -p.safe_braking_mps2:
        return False
    return acc.new_follower_after is None or acc.new_follower_after >= -p.safe_braking_mps2


def should_change(acc: LaneChangeAccelerations, p: MobilParams):
    """Return whether MOBIL changes lanes: safe, and the incentive above the threshold."""
    return is_safe(acc, p) and incentive(acc, p) > p.threshold_mps2
