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
The Intelligent Driver Model (Treiber, Hennecke and Helbing, 2000): a traffic vehicle's speed.

A vehicle of speed ``v`` whose desired speed is ``v0`` (its lane's limit times its speed factor)
follows a leader at the bumper-to-bumper gap ``s``, closing in at ``dv = v - v_leader``::

    s*(v, dv) = s0 + max(0, v T + v dv / (2 sqrt(a b)))
    dv/dt     = a (1 - (v / v0)^delta - (s* / s)^2)

with the time headway ``T``, the minimum gap ``s0``, the comfortable acceleration ``a``, the
comfortable deceleration ``b`` and the exponent ``delta`` = 4. On a free road the last term is
absent. The result is bounded below by the physical ``max_deceleration`` (IDM itself brakes
harder than ``b`` only in an emergency). Behind a leader at constant speed ``v`` the follower
settles at the equilibrium gap ``s_e(v) = (s0 + v T) / sqrt(1 - (v / v0)^delta)``.

:func:`advance` integrates one step ballistically (the speed never goes below 0), as the
traffic simulators built on the model do.
"""

import math

from vehicle_sim.core.specs.param_spec import ParamSpec, table_dataclass

IDM_SPECS = (
    ParamSpec('time_headway', 'time_headway_s', 'float', 1.5, 's',
              'desired time gap T to the leader', gt=0.0, le=10.0),
    ParamSpec('min_gap', 'min_gap_m', 'float', 2.0, 'm',
              'minimum bumper-to-bumper gap s0 when stopped', gt=0.0, le=50.0),
    ParamSpec('acceleration', 'acceleration_mps2', 'float', 1.5, 'm/s^2',
              'comfortable (maximum) acceleration a', gt=0.0, le=10.0),
    ParamSpec('deceleration', 'deceleration_mps2', 'float', 2.0, 'm/s^2',
              'comfortable deceleration b', gt=0.0, le=10.0),
    ParamSpec('exponent', 'exponent', 'float', 4.0, '',
              'acceleration exponent delta', gt=0.0, le=10.0),
    ParamSpec('max_deceleration', 'max_deceleration_mps2', 'float', 9.0, 'm/s^2',
              'physical braking limit (emergency braking)', gt=0.0, le=15.0),
)


@table_dataclass(IDM_SPECS)
class IdmParams:
    """
    Validated IDM parameters: a field per row of :data:`IDM_SPECS` (units, ranges, defaults).

    ``IdmParams.from_dict(data, source)`` validates a mapping of the table's keys.
    """


def desired_gap(v_mps, dv_mps, p: IdmParams):
    """Return the IDM's desired gap s*(v, dv) [m] (``dv`` = own speed - leader's speed)."""
    dynamic = v_mps * p.time_headway_s + v_mps * dv_mps / (
        2.0 * math.sqrt(p.acceleration_mps2 * p.deceleration_mps2))
    return p.min_gap_m + max(0.0, dynamic)


def idm_acceleration(v_mps, v0_mps, gap_m, dv_mps, p: IdmParams):
    """
    Return the IDM acceleration [m/s^2], bounded below by ``max_deceleration``.

    :param v_mps: own speed (>= 0).
    :param v0_mps: desired speed (> 0).
    :param gap_m: bumper-to-bumper gap to the leader; None = free road.
    :param dv_mps: own speed minus the leader's (ignored on a free road).
    :param p: IdmParams.
    """
    acc = p.acceleration_mps2 * (1.0 - (v_mps / v0_mps) ** p.exponent)
    if gap_m is not None:
        if gap_m <= 0.0:
            return -p.max_deceleration_mps2
        ratio = desired_gap(v_mps, dv_mps, p) / gap_m
        acc -= p.acceleration_mps2 * ratio * ratio
    return max(acc, -p.max_deceleration_mps2)


def equilibrium_gap(v_mps, v0_mps, p: IdmParams):
    """Return the steady gap [m] behind a leader at constant ``v_mps`` < ``v0_mps``."""
    return (p.min_gap_m + v_mps * p.time_headway_s) / math.sqrt(
        1.0 - (v_mps / v0_mps) ** p.exponent)


def advance(s_m, v_mps, acc_mps2, dt_s):
    """
    Return (s, v) after ``dt_s`` at constant acceleration, stopping at v = 0 (no reversing).

    :param s_m: position along the path [m].
    :param v_mps: speed [m/s].
    :param acc_mps2: acceleration [m/s^2].
    :param dt_s: time step [s].
    """
    v_new = v_mps + acc_mps2 * dt_s
    if v_new >= 0.0:
        return s_m + (v_mps + 0.5 * acc_mps2 * dt_s) * dt_s, v_new
    return s_m - 0.5 * v_mps * v_mps / acc_mps2, 0.0      # stops within the step


def acceleration_function(p: IdmParams):
    """
    Return ``acceleration(v, v0, gap, v_leader)``: :func:`idm_acceleration` bound to ``p``.

    The same numbers as :func:`idm_acceleration` (``gap`` None: a free road; ``dv`` = ``v -
    v_leader``), with the parameters read once: the traffic manager calls it for every vehicle
    at every update.
    """
    a, time_headway, s0 = p.acceleration_mps2, p.time_headway_s, p.min_gap_m
    two_sqrt_ab = 2.0 * math.sqrt(p.acceleration_mps2 * p.deceleration_mps2)
    delta, floor = p.exponent, -p.max_deceleration_mps2

    def acceleration(v_mps, v0_mps, gap_m, leader_mps):
        acc = a * (1.0 - (v_mps / v0_mps) ** delta)
        if gap_m is not None:
            if gap_m <= 0.0:
                return floor
            dynamic = v_mps * time_headway + v_mps * (v_mps - leader_mps) / two_sqrt_ab
            ratio = (s0 + (dynamic if dynamic > 0.0 else 0.0)) / gap_m
            acc -= a * ratio * ratio
        return acc if acc > floor else floor
    return acceleration
