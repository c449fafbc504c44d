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

"""The real-time factor a simulation achieves (core/world/pacing.py), with injected times."""

import math

import pytest

from vehicle_sim.core.world.pacing import RealTimeMeter


def drive(meter, steps, step_s, wall_per_step_s, wall_s=0.0, sim_s=0.0):
    """Feed ``steps`` steps of ``step_s`` taking ``wall_per_step_s`` each; return the closings."""
    closed = []
    for _ in range(steps):
        wall_s += wall_per_step_s
        sim_s += step_s
        closed.append(meter.update(wall_s, sim_s))
    return closed, wall_s, sim_s


def test_a_node_three_times_slower_than_real_time_reads_a_third_and_is_behind():
    meter = RealTimeMeter(1.0)
    closed, _, _ = drive(meter, 100, 0.01, 0.03)
    # windows of >= 1 s wall: 34 steps of 30 ms (1.02 s) for 0.34 s simulated
    assert meter.factor == pytest.approx(1.0 / 3.0, rel=1e-9)
    assert meter.window_wall_s == pytest.approx(1.02)
    assert meter.behind
    assert closed.count(True) == 2       # two windows closed in 3 s, each reported once


def test_a_node_keeping_up_is_not_behind_and_reads_the_target():
    meter = RealTimeMeter(2.0)
    closed, _, _ = drive(meter, 500, 0.01, 0.005)
    assert meter.factor == pytest.approx(2.0, rel=1e-9)
    assert not meter.behind and not any(closed)


def test_within_the_tolerance_is_not_behind_and_below_it_is():
    # 10 % tolerance: 0.95 x the target is jitter, 0.85 x is behind
    for wall_per_step_s, behind in ((0.01 / 0.95, False), (0.01 / 0.85, True)):
        meter = RealTimeMeter(1.0)
        drive(meter, 300, 0.01, wall_per_step_s)
        assert meter.behind is behind


def test_target_0_measures_but_is_never_behind():
    meter = RealTimeMeter(0.0)
    closed, _, _ = drive(meter, 300, 0.01, 0.05)
    assert meter.factor == pytest.approx(0.2, rel=1e-9)
    assert not meter.behind and not any(closed)


def test_no_factor_before_a_whole_window_and_restart_forgets_the_held_time():
    meter = RealTimeMeter(1.0)
    _, wall_s, sim_s = drive(meter, 50, 0.01, 0.01)      # 0.5 s: no window closed yet
    assert meter.factor is None and not meter.behind
    meter.restart()                                       # paused 10 s of wall time
    wall_s += 10.0
    drive(meter, 150, 0.01, 0.01, wall_s, sim_s)
    assert meter.factor == pytest.approx(1.0, rel=1e-9)   # the pause is not counted


def test_simulated_time_going_back_starts_a_new_window():
    meter = RealTimeMeter(1.0)
    meter.update(0.0, 5.0)
    assert meter.update(0.5, 0.0) is False               # a new world at 0 s
    assert meter.update(1.5, 1.0) is False
    assert meter.factor == pytest.approx(1.0)


@pytest.mark.parametrize('kwargs', [{'target': -1.0}, {'target': math.nan},
                                    {'target': 1.0, 'window_s': 0.0},
                                    {'target': 1.0, 'tolerance': 1.0}])
def test_out_of_range_settings_are_refused_naming_them(kwargs):
    with pytest.raises(ValueError, match=f'{list(kwargs)[-1]} = '):
        RealTimeMeter(**kwargs)
