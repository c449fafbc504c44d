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


"""A step serves the requests that arrived meanwhile (issue 10: latency under load)."""

from automobile_helpers import wait_for
import pytest

from vehicle_sim.ros.automobile_node import AutomobileNode
from vehicle_sim.transport.dds import DdsNode

pytestmark = pytest.mark.transport


@pytest.fixture
def app_and_client():
    app = AutomobileNode(['t', '--ros-args', '-r', '__ns:=/pending', '-p', 'synchronous:=true'],
                         transport='dds')
    client = DdsNode('pending_client')
    try:
        yield app, client
    finally:
        client.shutdown()
        app.close()


def test_a_request_is_answered_by_a_step_while_the_node_does_not_spin(app_and_client):
    app, node = app_and_client
    client = node.create_client('vehicle_msgs/srv/SetInt', '/pending/automobile/set_gear')
    request = node.srv('vehicle_msgs/srv/SetInt').Request
    assert client.wait_for_service(60.0)
    # A first call with the node spinning: the reply path is matched both ways.
    first = client.call_async(request(value=1))
    assert wait_for(lambda: first.done() or app.node.spin_once(0.01), spin=node)
    assert first.result().success

    # Then the node only steps (as inside a long time_step, or a real-time step timer).
    second = client.call_async(request(value=2))
    steps = 0
    while not second.done() and steps < 6000:
        app.step_once()
        node.spin_once(0.01)
        steps += 1
    assert second.done(), 'the request waited for the next spin of the node'
    assert second.result().success
    assert app.vehicles[''].logic.gear == 2
