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
The CLI's graph view looks like an rmw_cyclonedds participant to the nodes it reads.

rmw_cyclonedds parses the ``typehash=`` USER_DATA of every reader it discovers and logs
``Failed to parse type hash`` for one without it, so the view's ``ros_discovery_info`` reader
carries the same USER_DATA as the transport's own endpoints.
"""

from cyclonedds.qos import Policy
import pytest

from vehicle_sim.transport import dds
from vehicle_sim.transport.dds.graph import DISCOVERY_TOPIC, GraphView

pytestmark = pytest.mark.transport

# rmw_dds_common/msg/ParticipantEntitiesInfo on a real Jazzy graph (test_msgs_vehicle_msgs_py).
INFO_USER_DATA = (b'typehash=RIHS01_91a0593bacdcc50ea9bdcf849a938b128412cc1ea821245c663bcd26f83c29'
                  b'5e;')
WAIT_S = 30.0


@pytest.fixture
def view():
    graph = GraphView()
    try:
        yield graph
    finally:
        graph.close()


def test_graph_discovery_reader_carries_the_type_hash_user_data(view):
    qos = view._info_reader.get_qos()
    assert qos[Policy.Userdata].data == INFO_USER_DATA
    assert INFO_USER_DATA == dds.endpoint_user_data('rmw_dds_common/msg/ParticipantEntitiesInfo')


def test_graph_discovery_reader_is_announced_with_its_type_hash(view):
    # What another participant (an rclpy node's rmw) discovers of the view's reader.
    guid = view._info_reader.guid.bytes
    with GraphView() as other:
        def announced():
            endpoint = other._endpoints.get(guid)
            return endpoint is not None and endpoint

        assert other.wait_until(announced, WAIT_S)
        endpoint = announced()
        assert (endpoint.dds_topic, endpoint.is_writer) == (DISCOVERY_TOPIC, False)
        assert endpoint.user_data == INFO_USER_DATA.decode()
