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


"""Golden tests of the Intelligent Driver Model and the improved IDM (core/traffic/idm.py)."""

import math

import pytest

from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.traffic.idm import (
    advance,
    desired_gap,
    equilibrium_gap,
    idm_acceleration,
    IdmParams,
    iidm_acceleration,
)

P = IdmParams()       # the documented defaults
DT = 0.01


def follow(leader_speed, v0, gap, v, seconds, leader_acc=lambda t: 0.0, p=P):
    """Simulate a follower behind a leader; return (gaps, follower speeds) per step."""
    s_lead, s_own, v_lead = gap, 0.0, leader_speed
    gaps, speeds = [], []
    for i in range(int(round(seconds / DT))):
        acc = idm_acceleration(v, v0, s_lead - s_own, v - v_lead, p)
        s_own, v = advance(s_own, v, acc, DT)
        s_lead, v_lead = advance(s_lead, v_lead, leader_acc(i * DT), DT)
        gaps.append(s_lead - s_own)
        speeds.append(v)
    return gaps, speeds


@pytest.mark.parametrize('v', [10.0, 20.0, 30.0])
def test_a_follower_settles_at_the_equilibrium_gap(v):
    v0 = 33.3
    expected = (P.min_gap_m + v * P.time_headway_s) / math.sqrt(1.0 - (v / v0) ** 4)
    assert equilibrium_gap(v, v0, P) == pytest.approx(expected, rel=1e-12)
    # start 40 m too far and 5 m/s slower: IDM closes in and settles
    gaps, speeds = follow(v, v0, expected + 40.0, v - 5.0, 300.0)
    assert gaps[-1] == pytest.approx(expected, rel=0.01)
    assert speeds[-1] == pytest.approx(v, rel=0.001)


def test_free_road_acceleration_from_rest_and_later():
    v0 = 30.0
    assert idm_acceleration(0.0, v0, None, 0.0, P) == pytest.approx(P.acceleration_mps2)
    for v in (5.0, 15.0, 25.0, 29.9):
        assert idm_acceleration(v, v0, None, 0.0, P) == pytest.approx(
            P.acceleration_mps2 * (1.0 - (v / v0) ** 4), rel=1e-12)
    # integrated from rest: the speed approaches v0 and never exceeds it
    s, v = 0.0, 0.0
    for _ in range(int(120.0 / DT)):
        s, v = advance(s, v, idm_acceleration(v, v0, None, 0.0, P), DT)
        assert v <= v0
    assert v == pytest.approx(v0, rel=0.005)


def test_an_emergency_stop_of_the_leader_from_30_mps_is_collision_free():
    v0, v = 33.3, 30.0
    gap = equilibrium_gap(v, v0, P)
    # the leader brakes with the physical limit until it stands
    gaps, speeds = follow(v, v0, gap, v, 30.0, leader_acc=lambda t: -P.max_deceleration_mps2)
    assert min(gaps) > 0.0
    assert speeds[-1] == 0.0
    assert gaps[-1] == pytest.approx(P.min_gap_m, abs=0.5)   # stands about s0 behind


def test_desired_gap_grows_with_the_approach_rate_and_never_falls_below_s0():
    assert desired_gap(0.0, 0.0, P) == P.min_gap_m
    assert desired_gap(20.0, -30.0, P) == P.min_gap_m        # the leader pulls away fast
    closing = desired_gap(20.0, 5.0, P)
    assert closing == pytest.approx(
        P.min_gap_m + 20.0 * P.time_headway_s + 20.0 * 5.0 / (2.0 * math.sqrt(1.5 * 2.0)))


def test_the_braking_is_bounded_by_the_physical_limit():
    assert idm_acceleration(30.0, 33.3, 0.5, 30.0, P) == -P.max_deceleration_mps2
    assert idm_acceleration(30.0, 33.3, -1.0, 0.0, P) == -P.max_deceleration_mps2


def test_advance_stops_at_zero_speed_instead_of_reversing():
    s, v = advance(0.0, 1.0, -10.0, 1.0)
    assert v == 0.0
    assert s == pytest.approx(0.05)        # v^2 / (2 b)


def test_bad_parameters_are_refused_naming_the_field():
    with pytest.raises(InvalidParameterError, match=r"w\.yaml: traffic: idm: field "
                                                    r"'time_headway' = -1"):
        IdmParams.from_dict({'time_headway': -1.0}, 'w.yaml: traffic: idm')
    with pytest.raises(InvalidParameterError, match="unknown field 'headway'"):
        IdmParams.from_dict({'headway': 1.0}, 'w.yaml: traffic: idm')


# ---------------------------------------------------------------------------- the improved IDM
# Treiber and Kesting, "Traffic Flow Dynamics" (2013): the IIDM (module docstring).


@pytest.mark.parametrize('v, v0', [(20.0, 3.0), (6.0, 3.0), (30.0, 25.0), (8.0, 0.0)])
def test_iidm_above_the_desired_speed_slows_down_at_most_at_b(v, v0):
    # IDM asks a(1 - (v/v0)^4) there: -2960 m/s^2 from 20 to 3 m/s (cut at the physical limit)
    expected = -P.deceleration_mps2 * (1.0 - (v0 / v) ** (1.5 * 4.0 / 2.0))
    assert iidm_acceleration(v, v0, None, 0.0, P) == pytest.approx(expected, rel=1e-12)
    assert -P.deceleration_mps2 <= expected < 0.0
    if v0 > 0.0:
        assert idm_acceleration(v, v0, None, 0.0, P) < expected
    # far behind a leader (z < 1) the free-road term alone
    assert iidm_acceleration(v, v0, 1e4, 0.0, P) == pytest.approx(expected, rel=1e-12)


def test_iidm_below_the_desired_speed_is_idm_on_a_free_road():
    for v in (0.0, 5.0, 15.0, 29.9, 30.0):
        assert iidm_acceleration(v, 30.0, None, 0.0, P) == pytest.approx(
            idm_acceleration(v, 30.0, None, 0.0, P), rel=1e-12, abs=1e-12)
    assert iidm_acceleration(0.0, 0.0, None, 0.0, P) == 0.0     # standing, asked to stand


def test_iidm_interaction_term_as_treiber_and_kesting_combine_it():
    v, v0 = 10.0, 20.0
    free = P.acceleration_mps2 * (1.0 - (v / v0) ** 4)
    s_star = desired_gap(v, 2.0, P)
    for gap in (0.5 * s_star, s_star, 2.0 * s_star):
        z = s_star / gap
        expected = (P.acceleration_mps2 * (1.0 - z * z) if z >= 1.0
                    else free * (1.0 - z ** (2.0 * P.acceleration_mps2 / free)))
        assert iidm_acceleration(v, v0, gap, 2.0, P) == pytest.approx(
            max(expected, -P.max_deceleration_mps2), rel=1e-12)
    # above v0 and close: the free-road braking plus the interaction's
    v, v0 = 20.0, 10.0
    free = -P.deceleration_mps2 * (1.0 - (v0 / v) ** 3.0)
    gap = 0.8 * desired_gap(v, 0.0, P)
    assert iidm_acceleration(v, v0, gap, 0.0, P) == pytest.approx(
        free + P.acceleration_mps2 * (1.0 - 1.25 ** 2), rel=1e-12)
    assert iidm_acceleration(v, v0, 0.0, 0.0, P) == -P.max_deceleration_mps2


@pytest.mark.parametrize('v', [10.0, 20.0])
def test_an_iidm_follower_keeps_s0_plus_vt_behind_a_leader_and_stops_s0_behind_a_stop(v):
    v0, s, own = 33.3, 0.0, v - 5.0
    lead_s, lead_v = P.min_gap_m + v * P.time_headway_s + 40.0, v
    for _ in range(int(300.0 / DT)):
        acc = iidm_acceleration(own, v0, lead_s - s, own - lead_v, P)
        s, own = advance(s, own, acc, DT)
        lead_s, lead_v = advance(lead_s, lead_v, 0.0, DT)
    assert lead_s - s == pytest.approx(P.min_gap_m + v * P.time_headway_s, rel=0.01)
    for _ in range(int(60.0 / DT)):       # the leader brakes hard to a stop
        acc = iidm_acceleration(own, v0, lead_s - s, own - lead_v, P)
        s, own = advance(s, own, acc, DT)
        lead_s, lead_v = advance(lead_s, lead_v, -P.max_deceleration_mps2, DT)
        assert lead_s - s > 0.0
    assert own == 0.0
    assert lead_s - s == pytest.approx(P.min_gap_m, abs=0.5)
