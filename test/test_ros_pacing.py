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
The automobile node says when it falls behind real time.

Code: ros/automobile_node.py, core/world/pacing.py. The node runs in this process in real-time
mode, but the test steps it itself with a fake wall clock injected into its pacing: each step
"takes" a chosen wall time, so the achieved factor is exact and no test waits on the real clock.
"""

import pytest

pytestmark = pytest.mark.transport


class FakeClock:
    """A wall clock advancing ``per_call_s`` each time it is read."""

    def __init__(self, per_call_s):
        self.now_s = 100.0
        self.per_call_s = per_call_s

    def __call__(self):
        self.now_s += self.per_call_s
        return self.now_s


def run_node(name, clock, steps, **parameters):
    from vehicle_sim.ros.automobile_node import AutomobileNode
    app = AutomobileNode(['x', '--ros-args', '-r', f'__ns:=/{name}'], transport='dds',
                         parameter_overrides={'real_time_factor': 1.0, **parameters},
                         wall_clock=clock)
    try:
        app.step(steps)
        return app.achieved_real_time_factor
    finally:
        app.close()


def warnings_of(capsys):
    return [line for line in capsys.readouterr().err.splitlines() if 'behind real time' in line]


def test_a_node_three_times_slower_than_real_time_warns_with_the_achieved_factor(capsys):
    factor = run_node('slow_node', FakeClock(0.03), 250)     # 10 ms steps taking 30 ms
    assert factor == pytest.approx(1.0 / 3.0, rel=1e-9)
    found = warnings_of(capsys)
    assert found, 'no warning'
    assert '[WARN]' in found[0]
    assert ('behind real time: 0.33x achieved over the last 1.0 s of wall time, '
            'real_time_factor 1 asked' in found[0])
    # throttled: 7 windows fell behind, far fewer warnings (one per 5 s of real wall time)
    assert len(found) < 7


def test_a_node_keeping_up_does_not_warn(capsys):
    factor = run_node('keeping_up', FakeClock(0.01), 250)
    assert factor == pytest.approx(1.0, rel=1e-9)
    assert warnings_of(capsys) == []


def test_a_synchronous_node_measures_the_factor_but_never_warns(capsys):
    factor = run_node('synchronous_node', FakeClock(0.03), 250, synchronous=True)
    assert factor == pytest.approx(1.0 / 3.0, rel=1e-9)
    assert warnings_of(capsys) == []
