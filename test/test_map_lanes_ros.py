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
A world with a Lanelet2 map over the wire: /map/lanes, <ns>/lane_state, <ns>/lane_invasion.

The automobile node runs test/lane_helpers.py's map with a car placed on lanelet 2001 at
s = 10 m, in a subprocess, synchronous. The test node subscribes once the node is ready: a late
subscriber, which gets /map/lanes because the topic is transient-local.
"""

from automobile_helpers import automobile_fixtures, stamp_of, wait_for
from lane_helpers import write_world
import pytest

from vehicle_sim.ros import automobile_interfaces as itf
from vehicle_sim.ros.map_interfaces import MAP_LANES
from vehicle_sim.transport.dds.graph import GraphView

pytest.importorskip('lanelet2', reason="lanelet2 is not installed (pip install "
                                       "'vehicle_sim[lanelet2]'; the test extra has it)")
pytestmark = pytest.mark.transport

NAMESPACE = 'laned'


def _laned_world(request):
    world = write_world(request.getfixturevalue('tmp_path_factory').mktemp('lane_world'), [
        {'name': 'Car', 'namespace': 'ego', 'model': 'ToyotaPrius',
         'pose': {'lanelet': 2001, 's': 10.0}}])
    return ['--ros-args', '-r', f'__ns:=/{NAMESPACE}', '-p', f'world:={world}',
            '-p', 'synchronous:=true']


# The car's client: the node is up once /clock comes (/map/lanes was published before).
node, tester, car = automobile_fixtures('lane_tester', _laned_world, ['/clock'],
                                        f'{NAMESPACE}/ego', names=('node', 'tester', 'car'))


def test_a_late_subscriber_gets_map_lanes_with_surface_boundaries_and_centrelines(car):
    received = []
    car.node.create_subscription(MAP_LANES.ros_type, '/map/lanes', received.append,
                                 MAP_LANES.qos)
    assert wait_for(lambda: received, spin=car.node), 'no /map/lanes'
    markers = received[0].markers
    by_ns = {}
    for marker in markers:
        by_ns.setdefault(marker.ns, []).append(marker)
    assert sorted(by_ns) == ['centrelines', 'lane_boundaries', 'road_surface']
    assert len(by_ns['centrelines']) == 6            # five lanelets, 2005 both ways
    assert sorted(m.id for m in by_ns['lane_boundaries']) == list(range(1001, 1009))
    assert {m.header.frame_id for m in markers} == {'map'}
    curb = next(m for m in by_ns['lane_boundaries'] if m.id == 1007)
    assert [(p.x, p.y) for p in curb.points] == [pytest.approx((100.0, 0.0), abs=1e-6),
                                                 pytest.approx((150.0, 0.0), abs=1e-6)]


def test_lane_topics_have_their_types_and_qos(car):
    lane_state = f'/{NAMESPACE}/ego/lane_state'
    lane_invasion = f'/{NAMESPACE}/ego/lane_invasion'
    with GraphView() as graph:
        assert graph.wait_until(lambda: graph.publishers('/map/lanes')
                                and graph.publishers(lane_state)
                                and graph.publishers(lane_invasion), 30.0)
        found = {name: {(e.ros_type, e.reliable, e.transient_local)
                        for e in graph.publishers(name)}
                 for name in ('/map/lanes', lane_state, lane_invasion)}
    assert found == {'/map/lanes': {('visualization_msgs/msg/MarkerArray', True, True)},
                     lane_state: {('vehicle_msgs/msg/LaneState', True, False)},
                     lane_invasion: {('vehicle_msgs/msg/LaneInvasion', True, False)}}


def test_lane_state_names_the_lanelet_at_s_10_with_offset_0_in_frame_map(car):
    received = []
    sub = car.node.create_subscription(itf.LANE_STATE.ros_type, car.name('lane_state'),
                                       received.append, itf.LANE_STATE.qos)
    assert wait_for(lambda: sub.get_publisher_count(), spin=car.node)
    car.wait_node_matched()
    assert car.call('robot/time_step', 100).success
    assert wait_for(lambda: received, spin=car.node)
    state = received[-1]
    assert state.header.frame_id == 'map' and stamp_of(state) > 0.0
    assert (state.on_lane, state.lane_id) == (True, 2001)
    assert state.offset == pytest.approx(0.0, abs=0.01)
    assert state.s == pytest.approx(10.0, abs=0.01)
    assert state.speed_limit == pytest.approx(13.9)


def _set_lane_pose(car, lanelet, s, offset=0.0):
    client = car.client_of_lane_pose = getattr(car, 'client_of_lane_pose', None) or \
        car.node.create_client(itf.SET_LANE_POSE.srv_type, car.name('set_lane_pose'))
    assert client.wait_for_service(30.0)
    request = car.node.srv(itf.SET_LANE_POSE.srv_type).Request()
    request.lanelet, request.s, request.offset = lanelet, s, offset
    return client.call(request, 30.0)


def test_set_lane_pose_puts_the_car_on_a_lane_and_refuses_places_off_it(car):
    states, invasions = [], []
    car.node.create_subscription(itf.LANE_STATE.ros_type, car.name('lane_state'),
                                 states.append, itf.LANE_STATE.qos)
    sub = car.node.create_subscription(itf.LANE_INVASION.ros_type, car.name('lane_invasion'),
                                       invasions.append, itf.LANE_INVASION.qos)
    assert wait_for(lambda: sub.get_publisher_count(), spin=car.node)
    car.wait_node_matched()
    answer = _set_lane_pose(car, 2002, 20.0, 0.5)   # across the dashed line: no crossing
    assert answer.success and 'on lane 2002 at s 20.000 m' in answer.message
    for lanelet, s, offset, reason in ((9999, 10.0, 0.0, '9999'), (2002, 80.0, 0.0, '80'),
                                       (2002, float('nan'), 0.0, 'nan'),
                                       (2002, 10.0, 3.0, 'offset')):
        refused = _set_lane_pose(car, lanelet, s, offset)
        assert not refused.success
        assert 'refused' in refused.message and reason in refused.message.lower()
        assert 'nothing moved' in refused.message
    assert car.call('robot/time_step', 100).success
    assert wait_for(lambda: states and states[-1].lane_id == 2002, spin=car.node)
    assert states[-1].s == pytest.approx(20.0, abs=0.01)
    assert states[-1].offset == pytest.approx(0.5, abs=0.01)
    assert not wait_for(lambda: invasions, timeout_s=1.0, spin=car.node)


def test_a_refused_set_lane_pose_says_where_and_why_once_in_answer_and_log(node, car):
    refused = _set_lane_pose(car, 999, 10.0)
    assert not refused.success
    assert refused.message == ("refused: vehicle 'Car': set_lane_pose: lane 999 is not in the "
                               'map; nothing moved')
    assert wait_for(lambda: 'lane 999 ' in node.text())
    logged = [line for line in node.text().splitlines() if 'lane 999 ' in line]
    assert len(logged) == 1 and logged[0].endswith(f']: {refused.message}'), logged
