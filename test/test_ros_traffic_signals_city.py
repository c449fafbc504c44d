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
The signals' topic and the lane state on the shipped config/worlds/city_block_signals.yaml.

The automobile node runs the world in this process (synchronous, embedded DDS) with its own
signals part (physics/signal_part.py); a client node reads
/perception/traffic_light_recognition/traffic_signals (its 20 groups under their ids and the
controller's colours; a state forced between the 10 Hz instants published at that step) and the
car's lane_state (the ring intersection's stop line, group and state ahead). Its own module: the
topic is global, so no other node of this process may publish it meanwhile.
"""

from automobile_helpers import client_node, wait_for
import pytest

from vehicle_sim.ros.traffic_interfaces import TRAFFIC_SIGNALS
from vehicle_sim.transport.qos import QosProfile, TRANSIENT_LOCAL

pytestmark = pytest.mark.transport

# A late-joining subscription keeping every message of a burst of steps.
KEEP_ALL = QosProfile(depth=1000, durability=TRANSIENT_LOCAL)
COLOUR = {'red': 1, 'yellow': 2, 'green': 3}


def seconds(stamp):
    return stamp.sec + stamp.nanosec * 1e-9


@pytest.fixture(scope='module')
def city():
    from vehicle_sim.ros.automobile_node import AutomobileNode
    node = AutomobileNode(['x', '--ros-args', '-r', '__ns:=/signals_city'], transport='dds',
                          parameter_overrides={'synchronous': True,
                                               'world': 'city_block_signals'})
    yield node
    node.close()


def test_city_block_signals_publishes_its_groups_and_a_forced_change_at_once(city):
    controller = city.scene.parts['signals'].controller
    groups = [g.id for g in city.scene.lanes.rules.groups]
    assert len(groups) == 20 and 4000100101 in groups      # docs/signals.md's ids
    received = []
    with client_node('city_signals_listener') as client:
        sub = client.create_subscription(TRAFFIC_SIGNALS.ros_type, TRAFFIC_SIGNALS.name,
                                         received.append, KEEP_ALL)
        assert wait_for(lambda: sub.get_publisher_count(), spin=client)
        assert wait_for(lambda: received, spin=client)          # the latched start
        first = received[-1]
        assert [g.traffic_light_group_id for g in first.traffic_light_groups] == groups
        assert [g.elements[0].color for g in first.traffic_light_groups] == [
            COLOUR[controller.state(g)] for g in groups]
        assert {len(g.elements) for g in first.traffic_light_groups} == {1}   # lamp circles
        city.step(13)                     # 0.13 s: one message at 0.1 s
        controller.force(4000100101, 'yellow')
        time_s = city.step(1)             # off the 10 Hz instants: published for the change
        assert wait_for(lambda: seconds(received[-1].stamp) == pytest.approx(time_s),
                        spin=client)
        controller.release()
    assert [round(seconds(m.stamp), 3) for m in received[1:]] == [0.1, 0.14]
    last = {g.traffic_light_group_id: g.elements[0].color
            for g in received[-1].traffic_light_groups}
    assert last[4000100101] == 2                            # AMBER
    assert last == {g: COLOUR[state] for g, state in controller.states().items()} | {
        4000100101: 2}


def test_city_block_signals_lane_state_names_the_ring_intersections_line(city):
    from vehicle_sim.ros import automobile_interfaces as itf
    controller = city.scene.parts['signals'].controller
    received = []
    with client_node('city_lane_listener') as client:
        sub = client.create_subscription(itf.LANE_STATE.ros_type, '/signals_city/lane_state',
                                         received.append, itf.LANE_STATE.qos)
        assert wait_for(lambda: sub.get_publisher_count(), spin=client)
        time_s = city.step(1)
        assert wait_for(lambda: received and seconds(received[-1].header.stamp)
                        == pytest.approx(time_s), spin=client)
    state = received[-1]
    # the car at x = -60 on the ring's south side heading east; the line at the entry of the
    # intersection at x = -6 (docs/signals.md: line 3000000000 + lane, group 4000000000 + ...)
    assert (state.lane_id, state.stop_line_ahead, state.stop_line_id, state.stop_line_kind,
            state.traffic_light_group_id) == (
        100001, True, 3000100001, 'traffic_light', 4000100101)
    assert state.stop_line_distance == pytest.approx(54.0, abs=0.05)
    assert state.signal_state == controller.state(4000100101)
