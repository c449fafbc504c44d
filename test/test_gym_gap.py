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
The ``gap`` reward term (core/learning/gap.py): time headway, time to collision, side gap.

Its value against its formula on constructed situations (boxes placed around a rotated ego),
and in Drive-v0 on a car driving towards a parked box; off by default.
"""

import math

import numpy as np
import pytest

from vehicle_sim.core.geometry.footprint import Outline
from vehicle_sim.core.learning.gap import Box, gap_fractions, gap_term, GapWeights
from vehicle_sim.core.specs.errors import InvalidParameterError

# A car-sized ego: base_link at the rear axle, 3.5 m to its front, 1 m to its rear, 1.8 m wide.
OUTLINE = Outline(-1.0, 3.5, -0.9, 0.9)
EGO = (10.0, -5.0, 0.4)             # x, y, yaw in the world: the boxes are placed around it


def around(dx, dy, heading=0.0, speed=0.0, length=4.0, width=2.0):
    """Return a Box at (dx, dy) in the ego's frame, heading ``heading`` relative to it."""
    x, y, yaw = EGO
    c, s = math.cos(yaw), math.sin(yaw)
    return Box(x + c * dx - s * dy, y + s * dx + c * dy, yaw + heading, speed, length, width)


def fractions(others, speed, **weights):
    return gap_fractions(GapWeights(**weights), OUTLINE, *EGO, speed, others)


def test_a_slower_car_ahead_in_the_path_gives_headway_and_ttc_fractions():
    # centre 20 m ahead, 0.5 m left: bumper gap 20 - 2 - 3.5 = 14.5 m; ego 30 m/s, car 25 m/s
    headway, ttc, side = fractions([around(20.0, 0.5, speed=25.0)], 30.0, headway_s=1.0,
                                   ttc_s=3.0)
    assert headway == pytest.approx(1.0 - 14.5 / 30.0)          # headway 0.483 s of 1 s
    assert ttc == pytest.approx(1.0 - (14.5 / 5.0) / 3.0)       # ttc 2.9 s of 3 s
    assert side == 0.0
    # beyond the thresholds: nothing
    assert fractions([around(20.0, 0.5, speed=25.0)], 30.0, headway_s=0.4, ttc_s=2.5) == \
        (0.0, 0.0, 0.0)


def test_an_oncoming_car_closes_at_both_speeds_and_a_faster_one_ahead_not_at_all():
    # heading pi: its velocity along the ego's x is -20 m/s, closing 30 + 20 = 50 m/s
    _, ttc, _ = fractions([around(40.0, 0.0, heading=math.pi, speed=20.0)], 30.0, ttc_s=3.0)
    assert ttc == pytest.approx(1.0 - (40.0 - 2.0 - 3.5) / 50.0 / 3.0)
    headway, ttc, _ = fractions([around(20.0, 0.0, speed=35.0)], 30.0, headway_s=1.0)
    assert ttc == 0.0 and headway == pytest.approx(1.0 - 14.5 / 30.0)
    # at rest, no headway and nothing closes in
    assert fractions([around(20.0, 0.0, speed=0.0)], 0.0) == (0.0, 0.0, 0.0)


def test_the_margin_decides_what_is_in_the_path():
    # a car 3.75 m to the right (the next lane): clearance 3.75 - 1 - 0.9 = 1.85 m
    car = around(10.0, -3.75, speed=10.0)
    assert fractions([car], 30.0, gap_margin_m=1.0) == (0.0, 0.0, 0.0)
    headway, ttc, _ = fractions([car], 30.0, gap_margin_m=2.0)
    assert headway == pytest.approx(1.0 - 4.5 / 30.0)
    assert ttc == pytest.approx(1.0 - 4.5 / 20.0 / 3.0)
    # behind the ego (even in its lane, closing in): not in the path
    assert fractions([around(-10.0, 0.0, speed=40.0)], 30.0) == (0.0, 0.0, 0.0)


def test_a_car_beside_gives_the_side_fraction_of_its_clearance():
    # overlapping along x, centre 2.3 m left, 2 m wide: clearance 2.3 - 1 - 0.9 = 0.4 m
    _, _, side = fractions([around(1.0, 2.3)], 30.0, gap_margin_m=1.0)
    assert side == pytest.approx(0.6)
    _, _, side = fractions([around(1.0, -2.3), around(3.0, 3.0)], 30.0, gap_margin_m=0.5)
    assert side == pytest.approx(1.0 - 0.4 / 0.5)                # the nearer of the two
    # turned across the ego (heading pi/2): its length lies along y, 4 m: clearance 2.3 - 2
    # - 0.9 < 0, touching: the fraction is 1
    _, _, side = fractions([around(1.0, 2.3, heading=math.pi / 2)], 30.0)
    assert side == 1.0


def test_the_worst_box_of_each_fraction_counts():
    near = around(8.0, 0.0, speed=30.0)     # gap 2.5 m: headway 1 - 2.5/30, no closing
    closing = around(40.0, 0.3, speed=10.0)  # gap 34.5 m at 20 m/s: ttc 1.725 s
    headway, ttc, _ = fractions([closing, near], 30.0, headway_s=1.0, ttc_s=3.0)
    assert headway == pytest.approx(1.0 - 2.5 / 30.0)
    assert ttc == pytest.approx(1.0 - 34.5 / 20.0 / 3.0)


def test_the_term_weights_the_fractions_over_the_step():
    weights = GapWeights(headway_penalty=2.0, ttc_penalty=3.0, side_gap_penalty=5.0)
    assert gap_term(weights, (0.5, 0.25, 0.1), 0.2) == pytest.approx(
        -(2.0 * 0.5 + 3.0 * 0.25 + 5.0 * 0.1) * 0.2)
    assert gap_term(weights, (0.0, 0.0, 0.0), 0.2) == 0.0
    assert not GapWeights().enabled and GapWeights(ttc_penalty=0.1).enabled


@pytest.mark.parametrize('key, value', [('headway_penalty', -1.0), ('ttc_penalty', math.nan),
                                        ('side_gap_penalty', -0.1), ('headway_s', 0.0),
                                        ('ttc_s', -2.0), ('gap_margin_m', math.inf)])
def test_bad_weights_are_refused_naming_them(key, value):
    with pytest.raises(InvalidParameterError, match=key):
        GapWeights(**{key: value})


# ---------------------------------------------------------------- in Drive-v0

PARKED = {'vehicles': [{'name': 'Car', 'model': 'ToyotaPrius',
                        'pose': {'x': 0.0, 'y': 0.0, 'yaw': 0.0}}],
          'obstacles': [{'name': 'parked_car', 'shape': 'box', 'size': [4.5, 1.8, 1.5],
                         'position': [15.0, 0.4, 0.75]}]}


def test_drive_v0_reports_the_gap_term_of_its_state(make):
    pytest.importorskip('gymnasium', reason="needs the 'gym' extra (gymnasium)")
    import vehicle_sim.gym  # noqa: F401
    env = make(world=PARKED, action_repeat=20, headway_penalty=2.0, headway_s=10.0,
               ttc_penalty=3.0, ttc_s=10.0, side_gap_penalty=5.0)
    _, info = env.reset(seed=0)
    assert info['reward_terms']['gap'] == 0.0
    agent = env.unwrapped.sim.agent
    outline = agent.body.outline
    for _ in range(5):
        _, reward, _, _, info = env.step(np.array([0.0, 8.0], dtype=np.float32))
        x, y, yaw = agent.state()
        speed = agent.body.forward_speed_mps()
        # the box in the car's frame (yaw stays near 0: its extents along the car's axes)
        dx = math.cos(yaw) * (15.0 - x) + math.sin(yaw) * (0.4 - y)
        gap = dx - 2.25 - outline.x_max_m
        fraction = max(0.0, 1.0 - gap / (speed * 10.0))   # headway and ttc: at rest, closing
        expected = -(2.0 * fraction + 3.0 * fraction) * 0.2  # at the car's speed
        assert info['reward_terms']['gap'] == pytest.approx(expected, rel=1e-3)
        assert reward == pytest.approx(sum(info['reward_terms'].values()))
    assert speed > 2.0 and info['reward_terms']['gap'] < -0.1


def test_the_gap_term_is_off_by_default(make):
    pytest.importorskip('gymnasium', reason="needs the 'gym' extra (gymnasium)")
    import vehicle_sim.gym  # noqa: F401
    env = make(world=PARKED, action_repeat=20)
    env.reset(seed=0)
    _, _, _, _, info = env.step(np.array([0.0, 8.0], dtype=np.float32))
    assert 'gap' not in info['reward_terms']
    with pytest.raises(InvalidParameterError, match='ttc_s'):
        make(world=PARKED, ttc_s=0.0)
