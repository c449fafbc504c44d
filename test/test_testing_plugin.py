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
The pytest plugin ``vehicle_sim.testing``: the user example runs and passes in a fresh pytest.

The child pytest gets a ROS_DOMAIN_ID of its own (102..201, outside conftest's 1..101) so that
its simulations cannot meet the peers of this run.
"""

import os
import subprocess
import sys

from conftest import peer_env, REPO_ROOT, sleeper_process
import pytest

EXAMPLE = os.path.join(REPO_ROOT, 'examples', 'test_user_example.py')
# Generous bound for a child pytest starting three simulations.
CHILD_TIMEOUT_S = 240.0

pytestmark = pytest.mark.transport


def test_user_example_passes_with_the_plugin():
    env = peer_env()
    env['ROS_DOMAIN_ID'] = str(102 + os.getpid() % 100)
    result = subprocess.run(
        [sys.executable, '-m', 'pytest', EXAMPLE, '-q',
         '-p', 'no:cacheprovider'],
        cwd=REPO_ROOT, env=env, capture_output=True, text=True, timeout=CHILD_TIMEOUT_S)
    assert result.returncode == 0, result.stdout[-4000:] + result.stderr[-2000:]
    assert '3 passed' in result.stdout


def test_stamp_helpers_read_header_and_clock_stamps():
    from vehicle_msgs_py import message_type
    from vehicle_sim.testing import stamp_ns, stamp_s
    clock = message_type('rosgraph_msgs/msg/Clock')()
    clock.clock.sec, clock.clock.nanosec = 2, 500_000_000
    value = message_type('vehicle_msgs/msg/Float64Stamped')()
    value.header.stamp.sec = 3
    assert stamp_ns(clock) == 2_500_000_000
    assert stamp_s(value) == 3.0


def test_automobile_sim_stops_its_node_process_when_its_client_node_fails(monkeypatch):
    import types

    from vehicle_sim import testing
    started = []

    def popen(*_args, **_kwargs):
        started.append(sleeper_process())
        return started[-1]

    class FailingClient:
        def __init__(self, *_args, **_kwargs):
            raise OSError('the client node could not start')

    monkeypatch.setattr(testing, 'subprocess', types.SimpleNamespace(
        Popen=popen, STDOUT=subprocess.STDOUT, TimeoutExpired=subprocess.TimeoutExpired))
    monkeypatch.setattr(testing, 'AutomobileClient', FailingClient)
    with pytest.raises(RuntimeError, match='did not start'):
        testing.AutomobileSim()
    (proc,) = started
    assert proc.poll() is not None
