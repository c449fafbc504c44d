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
The suite's own waits: a loaded machine makes them slower, never wrong.

A node matches a test's new subscription later than the test does, the later the more loaded
the machine; ``wait_matched`` must not return before the node has (the node process frozen
with SIGSTOP is the extreme case). The wall-clock budgets no event can replace scale with
``VEHICLE_SIM_TEST_TIME_FACTOR`` (test/conftest.py), pytest-timeout's limit with them.
"""

import os
import signal
from types import SimpleNamespace

import automobile_helpers
from automobile_helpers import client_node, NodeProcess, stamp_of, VehicleClient
import conftest
import pytest

from vehicle_sim.transport.errors import ServiceTimeoutError

NAMESPACE = 'test_waits'


@pytest.fixture(scope='module')
def node():
    with NodeProcess('--ros-args', '-r', f'__ns:=/{NAMESPACE}', '-p',
                     'synchronous:=true') as process:
        yield process


def test_wait_matched_returns_only_once_the_node_has_matched_the_subscription(node, monkeypatch):
    with client_node('test_waits_tester') as tester:
        car = VehicleClient(tester, NAMESPACE)
        car.wait_matched(['/clock'])
        os.kill(node.proc.pid, signal.SIGSTOP)
        try:
            # This side matches the node's odom publisher at once; the frozen node cannot
            # match the subscription, so the wait cannot end (within a short bound here).
            monkeypatch.setattr(automobile_helpers, 'WAIT_S', 2.0)
            with pytest.raises(ServiceTimeoutError):
                car.wait_matched(['odom'])
        finally:
            os.kill(node.proc.pid, signal.SIGCONT)
        monkeypatch.undo()
        try:
            car.wait_matched(['odom'])
        except ServiceTimeoutError as error:      # the node's own account, for the next reader
            pytest.fail(f'{error}\nnode output:\n{node.text()[-4000:]}')
        odom = car.step_and_read('odom', 20)
        assert stamp_of(odom) == car.time_s() == pytest.approx(0.02, abs=1e-9)


@pytest.mark.parametrize('text', ['abc', '0.5', 'nan', 'inf', ''])
def test_a_time_factor_that_is_not_a_number_from_1_is_refused_naming_it(text):
    with pytest.raises(pytest.UsageError, match=f"VEHICLE_SIM_TEST_TIME_FACTOR = '{text}': "
                                                'must be a number >= 1'):
        conftest.time_factor(text)


def test_the_time_factor_scales_the_budgets_and_pytest_timeouts_limit(monkeypatch, request):
    assert conftest.time_factor('2.5') == 2.5
    monkeypatch.setattr(conftest, 'TIME_FACTOR', 2.5)
    assert conftest.scaled_s(8.0) == 20.0
    marked = pytest.mark.timeout(7).mark

    class Item:
        def __init__(self, marker):
            self.markers = [marker] if marker is not None else []

        def get_closest_marker(self, name):
            return self.markers[0] if self.markers else None

        def add_marker(self, marker, append=True):
            self.markers.insert(len(self.markers) if append else 0, marker.mark)

    items = [Item(None), Item(marked)]
    config = SimpleNamespace(pluginmanager=request.config.pluginmanager,
                             getoption=lambda name, default=None: None,
                             getini=lambda name: '300')
    monkeypatch.delenv('PYTEST_TIMEOUT', raising=False)
    conftest.pytest_collection_modifyitems(config, items)
    assert [item.get_closest_marker('timeout').args[0] for item in items] == [750.0, 17.5]
