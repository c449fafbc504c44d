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

:func:`iidm_acceleration` is the improved IDM (IIDM) of Treiber and Kesting ("Traffic Flow
Dynamics", 2013), with the same parameters. Above its desired speed (a lower limit ahead) IDM's
free-road term ``a (1 - (v / v0)^delta)`` asks a huge deceleration (at 20 m/s for 3 m/s,
1.5 (1 - 6.7^4) = -2960 m/s^2, bounded only by ``max_deceleration``): a driver slows down
comfortably instead. The IIDM's free-road acceleration is::

    a_free(v) = a (1 - (v / v0)^delta)              v <= v0
    a_free(v) = -b (1 - (v0 / v)^(a delta / b))     v > v0   (at most b)

and with ``z = s*(v, dv) / s`` behind a leader::

    v <= v0:  a (1 - z^2) for z >= 1,   a_free (1 - z^(2 a / a_free)) for z < 1
    v > v0:   a_free + a (1 - z^2) for z >= 1,   a_free for z < 1

so that a follower keeps ``s0 + v T`` behind a leader at its desired speed, and the free-road
term never brakes harder than ``b``. It is bounded below by ``max_deceleration`` too. Scenario
actors drive with it (scenarios/actors.py); the traffic keeps the IDM (``idm`` of the traffic
models, core/traffic/models.py).
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


def iidm_free_acceleration(v_mps, v0_mps, p: IdmParams):
    """
    Return the IIDM's free-road acceleration a_free(v) [m/s^2] (at most ``b`` braking).

    :param v_mps: own speed (>= 0).
    :param v0_mps: desired speed (>= 0; 0 asks a stop, at ``b``: the limit v0 -> 0).
    :param p: IdmParams.
    """
    if v_mps > v0_mps:
        return -p.deceleration_mps2 * (1.0 - (v0_mps / v_mps) ** (
            p.acceleration_mps2 * p.exponent / p.deceleration_mps2))
    if v0_mps <= 0.0:
        return 0.0              # standing, asked to stand
    return p.acceleration_mps2 * (1.0 - (v_mps / v0_mps) ** p.exponent)


def iidm_acceleration(v_mps, v0_mps, gap_m, dv_mps, p: IdmParams):
    """
    Return the improved IDM's acceleration [m/s^2], bounded below by ``max_deceleration``.

    The same arguments as :func:`idm_acceleration` (the module docstring gives the model).

    :param v_mps: own speed (>= 0).
    :param v0_mps: desired speed (>= 0; 0 asks a stop).
    :param gap_m: bumper-to-bumper gap to the leader; None = free road.
    :param dv_mps: own speed minus the leader's (ignored on a free road).
    :param p: IdmParams.
    """
    free = iidm_free_acceleration(v_mps, v0_mps, p)
    if gap_m is None:
        return max(free, -p.max_deceleration_mps2)
    if gap_m <= 0.0:
        return -p.max_deceleration_mps2
    z = desired_gap(v_mps, dv_mps, p) / gap_m
    a = p.acceleration_mps2
    if v_mps <= v0_mps:
        if z >= 1.0:
            acc = a * (1.0 - z * z)
        elif free > 0.0:
            acc = free * (1.0 - z ** (2.0 * a / free))
        else:
            acc = 0.0            # at v0 with room ahead: z^(2a/a_free) -> 0 as a_free -> 0
    else:
        acc = free + a * (1.0 - z * z) if z >= 1.0 else free
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
