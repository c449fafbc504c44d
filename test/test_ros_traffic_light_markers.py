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
The lamps for RViz over the wire: /sim/traffic_lights/markers on city_block_signals.yaml.

The automobile node runs the shipped world in this process (synchronous, embedded DDS); a client
reads /sim/traffic_lights/markers (a sphere per bulb in its group's colour, published at the
start and at each change, transient local) and /map/lanes (the lights' housings and poles, the
stop lines). Its own module: the topics are global, so no other node of this process may
publish them meanwhile.
"""

from automobile_helpers import client_node, wait_for
import pytest

from vehicle_sim.core.map.signal_lamps import DARK_LAMP_COLOR, LAMP_COLORS
from vehicle_sim.ros.map_interfaces import MAP_LANES
from vehicle_sim.ros.traffic_interfaces import TRAFFIC_LIGHT_MARKERS
from vehicle_sim.transport.qos import QosProfile, TRANSIENT_LOCAL

pytestmark = pytest.mark.transport

KEEP_ALL = QosProfile(depth=1000, durability=TRANSIENT_LOCAL)
GROUP = 4000100101          # the ring's southern intersection, the approach from the west


@pytest.fixture(scope='module')
def city():
    from vehicle_sim.ros.automobile_node import AutomobileNode
    node = AutomobileNode(['x', '--ros-args', '-r', '__ns:=/lamps_city'], transport='dds',
                          parameter_overrides={'synchronous': True,
                                               'world': 'city_block_signals'})
    yield node
    node.close()


def _colours(message, lamps, group):
    """Return {bulb colour: (r, g, b)} of one group's bulbs in a markers message."""
    (bulbs,) = message.markers
    return {lamp.bulb.color: (c.r, c.g, c.b)
            for lamp, c in zip(lamps, bulbs.colors) if lamp.group_id == group}


def test_the_lamps_markers_show_each_group_state_and_change_only_with_it(city):
    controller = city.scene.parts['signals'].controller
    lamps = city.scene.parts['signal_lamps'].lamps
    received, maps = [], []
    with client_node('lamps_listener') as client:
        client.create_subscription(TRAFFIC_LIGHT_MARKERS.ros_type, TRAFFIC_LIGHT_MARKERS.name,
                                   received.append, KEEP_ALL)
        client.create_subscription(MAP_LANES.ros_type, MAP_LANES.name, maps.append,
                                   MAP_LANES.qos)
        city.step(1)
        assert wait_for(lambda: received and maps, spin=client)
        first = received[-1]
        (bulbs,) = first.markers
        assert (bulbs.ns, bulbs.header.frame_id, len(bulbs.points)) == (
            'traffic_light_bulbs', 'world', 60)
        state = controller.state(GROUP)
        for colour, rgb in _colours(first, lamps, GROUP).items():
            want = LAMP_COLORS[colour] if colour == state else DARK_LAMP_COLOR
            assert rgb == pytest.approx(want[:3], abs=1e-6)
        count = len(received)
        city.step(50)                       # 0.5 s of the plan: no group changes
        controller.force(GROUP, 'red')
        time_s = city.step(1)
        assert wait_for(lambda: len(received) > count, spin=client)
        controller.release()
    assert len(received) == count + 1                   # the change, nothing in between
    last = received[-1]
    assert last.markers[0].header.stamp.sec + last.markers[0].header.stamp.nanosec * 1e-9 == \
        pytest.approx(time_s)
    assert _colours(last, lamps, GROUP)['red'] == pytest.approx(LAMP_COLORS['red'][:3], abs=1e-6)
    namespaces = {(m.ns, m.id) for m in maps[-1].markers}
    assert {('traffic_lights', 0), ('traffic_lights', 1)} <= namespaces
    assert len([n for n in namespaces if n[0] == 'stop_lines']) == 20
