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
The signals' topic of the automobile node over the wire (ros/traffic_interfaces.py).

The node runs test/signal_helpers.py's road in this process (synchronous, embedded DDS), its
'signals' scene part made by hand; a client node subscribes to
/perception/traffic_light_recognition/traffic_signals. Every message holds every group of the
map with the colour the world's SignalController gives it at the message's stamp; messages
come every 0.1 s of simulated time and at each step a group changes state; a subscriber that
comes late gets the current states (transient local). test_ros_traffic_signals_city.py: the
same on the shipped signalised world.
"""

from automobile_helpers import client_node, wait_for
import pytest
from signal_helpers import with_hand_signals, write_world

from vehicle_sim.ros.traffic_interfaces import (
    QOS_SIGNALS,
    TRAFFIC_LIGHT_MARKERS,
    TRAFFIC_SIGNALS,
)
from vehicle_sim.transport.qos import QosProfile, TRANSIENT_LOCAL

pytestmark = pytest.mark.transport

# A late-joining subscription keeping every message of a burst of steps.
KEEP_ALL = QosProfile(depth=1000, durability=TRANSIENT_LOCAL)
COLOUR = {'red': 1, 'yellow': 2, 'green': 3}


@pytest.fixture(scope='module')
def app(tmp_path_factory):
    from vehicle_sim.ros import automobile_node
    with pytest.MonkeyPatch.context() as patch:
        with_hand_signals(patch, automobile_node)
        path = write_world(tmp_path_factory.mktemp('signals'))
        node = automobile_node.AutomobileNode(
            ['x', '--ros-args', '-r', '__ns:=/signals_test'], transport='dds',
            parameter_overrides={'synchronous': True, 'world': str(path)})
    yield node
    node.close()


def seconds(stamp):
    return stamp.sec + stamp.nanosec * 1e-9


def test_the_row_is_wired_with_its_type_and_qos(app):
    publishers = app._signals.outputs.publishers
    assert tuple(publishers) == (TRAFFIC_SIGNALS, TRAFFIC_LIGHT_MARKERS)    # the lamps' too
    assert TRAFFIC_SIGNALS.ros_type == 'autoware_perception_msgs/msg/TrafficLightGroupArray'
    assert (QOS_SIGNALS.reliability, QOS_SIGNALS.durability, QOS_SIGNALS.depth) == \
        ('reliable', 'transient_local', 1)


def test_messages_carry_the_controllers_states_every_0_1_s_and_at_each_change(app):
    controller = app.scene.parts['signals'].controller
    received = []
    with client_node('signals_listener') as client:
        sub = client.create_subscription(TRAFFIC_SIGNALS.ros_type, TRAFFIC_SIGNALS.name,
                                         received.append, KEEP_ALL)
        assert wait_for(lambda: sub.get_publisher_count(), spin=client)
        # the state published before the subscriber existed (transient local): the start's
        assert wait_for(lambda: received, spin=client)
        start_s = seconds(received[0].stamp)
        assert start_s == app.world.time_s
        expected = {round(start_s * 1000): controller.states()}
        for _ in range(230):                    # 2.3 s: a whole cycle of both phases
            before = controller.states()
            app.step(1)
            states = controller.states()
            step_ms = round(app.world.time_s * 1000)
            if states != before or (step_ms - round(start_s * 1000)) % 100 == 0:
                expected[step_ms] = states
        assert wait_for(lambda: len(received) >= len(expected), spin=client)
    by_time = {round(seconds(m.stamp) * 1000): m for m in received}
    assert sorted(by_time) == sorted(expected)
    # the plan's changes between the 10 Hz instants (its others, at 1.6, 1.8 and 2.1 s, fall
    # on them): 7001 yellow at 0.55 s, red at 0.75 s; 7002 green at 1.05 s
    assert start_s == 0.0
    assert [t for t in expected if t % 100] == [550, 750, 1050]
    seen = set()
    for time_ms, message in by_time.items():
        states = expected[time_ms]
        groups = {g.traffic_light_group_id: g for g in message.traffic_light_groups}
        assert list(groups) == [7001, 7002]              # the map's ids, in its order
        for group_id, group in groups.items():
            colours = {e.color for e in group.elements}
            assert colours == {COLOUR[states[group_id]]}, (time_ms, group_id)
            assert {(e.status, e.confidence) for e in group.elements} == {(2, 1.0)}  # SOLID_ON
            assert list(group.predictions) == []
            seen.add((group_id, states[group_id]))
        shapes = [e.shape for e in groups[7001].elements]
        assert shapes == ([1, 2] if states[7001] == 'green' else [1])   # circle, left arrow
    assert seen == {(g, s) for g in (7001, 7002) for s in ('red', 'yellow', 'green')}


def test_a_world_without_signal_groups_has_no_signals_topic(tmp_path):
    from vehicle_sim.ros.automobile_node import AutomobileNode
    node = AutomobileNode(['x', '--ros-args', '-r', '__ns:=/no_signals'], transport='dds',
                          parameter_overrides={'synchronous': True,
                                               'world': str(write_world(tmp_path))})
    try:
        assert node.scene.parts.get('signals') is None and node._signals is None
    finally:
        node.close()


def test_the_cars_lane_state_names_the_next_stop_line_and_its_signal(app):
    from vehicle_sim.ros import automobile_interfaces as itf
    controller = app.scene.parts['signals'].controller
    received = []
    with client_node('lane_state_listener') as client:
        sub = client.create_subscription(itf.LANE_STATE.ros_type,
                                         '/signals_test/lane_state', received.append,
                                         itf.LANE_STATE.qos)
        assert wait_for(lambda: sub.get_publisher_count(), spin=client)
        controller.force(7001, 'red')
        try:
            stepped_to_s = app.step(10)
            assert wait_for(lambda: received and seconds(received[-1].header.stamp)
                            == pytest.approx(stepped_to_s), spin=client)
        finally:
            controller.release()
    state = received[-1]
    assert (state.on_lane, state.lane_id) == (True, 100001)
    assert (state.stop_line_ahead, state.stop_line_id, state.stop_line_kind,
            state.traffic_light_group_id, state.signal_state) == (
        True, 9001, 'traffic_light', 7001, 'red')
    assert state.stop_line_distance == pytest.approx(50.0 - state.s, abs=1e-9)
    assert state.stop_line_distance == pytest.approx(30.0, abs=0.05)    # the car at x = 20
