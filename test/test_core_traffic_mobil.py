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


"""MOBIL's incentive and safety criteria on hand-computed cases (core/traffic/mobil.py)."""

import pytest

from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.traffic.idm import idm_acceleration, IdmParams
from vehicle_sim.core.traffic.mobil import (
    incentive,
    is_safe,
    LaneChangeAccelerations,
    MobilParams,
    should_change,
)

P = MobilParams(politeness=0.5, threshold_mps2=0.2, safe_braking_mps2=4.0)


def test_the_incentive_is_own_gain_plus_politeness_times_the_followers_gains():
    acc = LaneChangeAccelerations(own_now=-1.0, own_after=0.5,
                                  new_follower_now=0.3, new_follower_after=-0.7,
                                  old_follower_now=-0.4, old_follower_after=0.2)
    # 1.5 + 0.5 * ((-1.0) + 0.6) = 1.5 - 0.2 = 1.3
    assert incentive(acc, P) == pytest.approx(1.3)
    assert should_change(acc, P)


def test_a_change_happens_exactly_when_the_incentive_exceeds_the_threshold():
    # binary fractions, so that the sums are exact: gain g, no followers
    for gain, expected in ((0.125, False), (0.25, False), (0.375, True)):
        p = MobilParams(politeness=0.5, threshold_mps2=0.25, safe_braking_mps2=4.0)
        acc = LaneChangeAccelerations(own_now=-0.5, own_after=-0.5 + gain)
        assert incentive(acc, p) == gain
        assert should_change(acc, p) is expected      # 0.25 == threshold: no change
    # with followers: 1.0 - 0.5 * 1.5 = 0.25 (equal, no change); 1.0 - 0.5 * 1.25 > 0.25
    p = MobilParams(politeness=0.5, threshold_mps2=0.25, safe_braking_mps2=4.0)
    equal = LaneChangeAccelerations(0.0, 1.0, 0.0, -1.5)
    assert incentive(equal, p) == 0.25 and not should_change(equal, p)
    above = LaneChangeAccelerations(0.0, 1.0, 0.0, -1.25)
    assert should_change(above, p)


def test_never_when_the_new_follower_would_brake_harder_than_b_safe():
    big_gain = dict(own_now=-3.0, own_after=1.0)      # incentive far above the threshold
    at_limit = LaneChangeAccelerations(**big_gain, new_follower_now=0.0,
                                       new_follower_after=-4.0)
    beyond = LaneChangeAccelerations(**big_gain, new_follower_now=0.0,
                                     new_follower_after=-4.001)
    assert is_safe(at_limit, P) and should_change(at_limit, P)
    assert not is_safe(beyond, P) and not should_change(beyond, P)
    # politeness 0 does not make an unsafe change safe
    selfish = MobilParams(politeness=0.0, threshold_mps2=0.0, safe_braking_mps2=4.0)
    assert not should_change(beyond, selfish)


def test_nor_when_the_vehicle_itself_would_have_to_brake_harder_than_b_safe():
    acc = LaneChangeAccelerations(own_now=-8.0, own_after=-5.0)
    assert incentive(acc, P) == 3.0
    assert not should_change(acc, P)


def test_a_case_from_idm_accelerations():
    # c at 25 m/s stuck 30 m behind a 20 m/s truck; the left lane: its leader 80 m ahead at
    # 30 m/s and a follower 40 m behind at 25 m/s; no old follower
    idm, v0 = IdmParams(), 33.3
    own_now = idm_acceleration(25.0, v0, 30.0, 5.0, idm)
    own_after = idm_acceleration(25.0, v0, 80.0, -5.0, idm)
    n_now = idm_acceleration(25.0, v0, 40.0 + 80.0 + 4.5, -5.0, idm)   # behind the leader
    n_after = idm_acceleration(25.0, v0, 40.0, 0.0, idm)
    acc = LaneChangeAccelerations(own_now, own_after, n_now, n_after)
    assert own_now < -1.0 < own_after      # braking behind the truck, not after the change
    assert n_after > -P.safe_braking_mps2
    assert should_change(acc, P)
    # the same with the follower only 8 m behind: it would brake too hard
    n_close = idm_acceleration(25.0, v0, 8.0, 0.0, idm)
    assert n_close < -P.safe_braking_mps2
    assert not should_change(LaneChangeAccelerations(own_now, own_after, n_now, n_close), P)


def test_bad_parameters_are_refused_naming_the_field():
    with pytest.raises(InvalidParameterError, match="field 'politeness' = 1.5"):
        MobilParams.from_dict({'politeness': 1.5}, 'w.yaml: traffic: mobil')
