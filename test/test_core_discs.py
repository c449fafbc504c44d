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

"""Discs moved apart where they overlap (core/geometry/discs.py: SUMO's persons' cylinders)."""

import itertools
import math
import random

import pytest

from vehicle_sim.core.geometry.discs import separate_discs, TOUCH_M

R = 0.239                         # SUMO's default pedestrian: a cylinder 0.478 m across


def _closest(centres, radii, velocities=None, horizon_s=0.0, samples=50):
    """Return the least gap between two discs [m] (negative: overlap), sampled in time."""
    velocities = velocities or [(0.0, 0.0)] * len(centres)
    worst = math.inf
    for k in range(samples + 1):
        t = horizon_s * k / samples
        at = [(x + vx * t, y + vy * t) for (x, y), (vx, vy) in zip(centres, velocities)]
        for i, j in itertools.combinations(range(len(at)), 2):
            worst = min(worst, math.dist(at[i], at[j]) - radii[i] - radii[j])
    return worst


def test_discs_that_do_not_overlap_keep_their_centres():
    centres = [(0.0, 0.0), (0.478, 0.0), (5.0, 5.0), (5.0, 5.6)]
    assert separate_discs(centres, [R] * 4) == centres
    assert separate_discs([(1.0, 2.0)], [R]) == [(1.0, 2.0)]
    assert separate_discs([], []) == []


def test_two_overlapping_discs_are_pushed_apart_evenly_along_the_line_between_them():
    a, b = separate_discs([(1.0, 1.0), (1.0 + 0.3 * 0.6, 1.0 + 0.3 * 0.8)], [R, R])
    shift = 0.5 * (2 * R - 0.3)
    assert a == pytest.approx((1.0 - shift * 0.6, 1.0 - shift * 0.8))
    assert b == pytest.approx((1.18 + shift * 0.6, 1.24 + shift * 0.8))
    assert math.dist(a, b) == pytest.approx(2 * R)
    # two on the same point: along x
    assert separate_discs([(0.0, 0.0), (0.0, 0.0)], [R, R]) == [(-R, 0.0), (R, 0.0)]


def test_a_queue_closer_than_its_width_gets_longer_by_the_sum_of_its_overlaps():
    # SUMO's persons in line 0.455 m apart (centre to centre) against cylinders 0.478 m across
    centres = [(0.455 * k, 3.0) for k in range(12)]
    moved = separate_discs(centres, [R] * 12)
    gaps = [b[0] - a[0] for a, b in zip(moved, moved[1:])]
    assert min(gaps) >= 2 * R - TOUCH_M and max(gaps) < 2 * R + 1e-3
    assert all(y == 3.0 for _, y in moved)
    assert moved[-1][0] - moved[0][0] == pytest.approx(11 * 2 * R, abs=11 * TOUCH_M)
    assert moved[0][0] + moved[-1][0] == pytest.approx(11 * 0.455, abs=1e-3)   # both ends


def test_a_crowd_is_left_without_overlaps_and_the_same_input_gives_the_same_output():
    rng = random.Random(7)
    centres = [(rng.uniform(0.0, 3.0), rng.uniform(0.0, 2.0)) for _ in range(30)]
    radii = [rng.uniform(0.2, 0.3) for _ in centres]
    assert _closest(centres, radii) < -0.1
    moved = separate_discs(centres, radii)
    assert _closest(moved, radii) > -TOUCH_M
    assert separate_discs(centres, radii) == moved


def test_discs_moving_on_do_not_overlap_until_the_horizon():
    # a person walking at 1.3 m/s up to one standing 0.6 m ahead: apart now, 0.008 m into it
    # 0.1 s on; pushed apart at their closest approach, they touch then
    centres, velocities = [(0.0, 0.0), (0.6, 0.0)], [(1.3, 0.0), (0.0, 0.0)]
    assert _closest(centres, [R, R], velocities, 0.1) == pytest.approx(-0.008)
    moved = separate_discs(centres, [R, R], velocities, 0.1)
    assert [c for xy in moved for c in xy] == pytest.approx([-0.004, 0.0, 0.604, 0.0])
    assert _closest(moved, [R, R], velocities, 0.1) > -TOUCH_M
    # moving apart: their closest is now, and they do not overlap then
    assert separate_discs([(0.0, 0.0), (0.5, 0.0)], [R, R], [(-1.0, 0.0), (1.0, 0.0)],
                          0.1) == [(0.0, 0.0), (0.5, 0.0)]
    # two passing side by side closer than their width, each pushed off the other's path
    centres, velocities = [(0.0, 0.0), (0.5, 0.3)], [(1.3, 0.0), (-1.3, 0.0)]
    moved = separate_discs(centres, [R, R], velocities, 0.1)
    assert _closest(moved, [R, R], velocities, 0.1, samples=1000) > -TOUCH_M


@pytest.mark.parametrize('args, message', [
    (([(0.0, 0.0)], [R, R]), '1 centres but 2 radii'),
    (([(0.0, 0.0)], [R], [(0.0, 0.0)] * 2, 0.1), '1 centres but 1 radii and 2 velocities'),
    (([(0.0, 0.0)], [R], [(0.0, 0.0)], -0.1), 'horizon_s -0.1'),
    (([(0.0, 0.0)], [R], [(0.0, 0.0)], math.nan), 'horizon_s nan'),
])
def test_sizes_that_do_not_match_and_a_bad_horizon_are_refused(args, message):
    with pytest.raises(ValueError, match=message):
        separate_discs(*args)
