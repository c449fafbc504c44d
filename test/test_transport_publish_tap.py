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
The port's publish tap and call_soon on the embedded transport.

A tap receives the very bytes the DDS writer writes (no second encoding), widens the reader gate
while a sink wants the topic, and hears of the node's services; ``call_soon`` runs a callback
from another thread on the node's thread at its next spin.
"""

import struct
import threading

from automobile_helpers import wait_for
import pytest

from vehicle_sim.transport.dds import DdsNode
from vehicle_sim.transport.errors import TransportError
from vehicle_sim.transport.publish_tap import PublishTap
from vehicle_sim.transport.qos import QOS_LATCHED, TRANSIENT_LOCAL, VOLATILE

TOPIC = '/tap/value'
FLOAT64 = 'std_msgs/msg/Float64'


class Sink:
    def __init__(self, open_=True):
        self.open = open_
        self.data = []

    def write(self, data):
        self.data.append(bytes(data))


class Tap(PublishTap):
    def __init__(self, sink):
        self.sink = sink
        self.topics = []
        self.services = []

    def topic(self, topic_name, ros_type, qos):
        self.topics.append((topic_name, ros_type, qos.durability))
        return self.sink

    def service(self, service_name, srv_type, callback):
        self.services.append((service_name, srv_type, callback))


@pytest.fixture
def nodes():
    made = [DdsNode('tap_publisher'), DdsNode('tap_reader')]
    try:
        yield made
    finally:
        for node in made:
            node.shutdown()


def test_tap_gets_the_bytes_a_dds_reader_receives(nodes):
    publisher_node, reader_node = nodes
    sink = Sink()
    publisher_node.add_publish_tap(Tap(sink))
    publisher = publisher_node.create_publisher(FLOAT64, TOPIC)
    received = []
    reader_node.create_subscription(FLOAT64, TOPIC, received.append, raw=True)
    assert wait_for(lambda: publisher.get_subscription_count() > 0)
    message = publisher_node.msg(FLOAT64)(data=2.5)
    publisher.publish(message)
    publisher.publish_serialized(bytes(sink.data[0]))
    assert wait_for(lambda: len(received) >= 2, spin=reader_node)
    # publish(msg): serialized once, the same bytes to DDS and to the tap (XCDR1 little endian,
    # 4-byte header, the float64 2.5).
    assert sink.data[0] == b'\x00\x01\x00\x00' + struct.pack('<d', 2.5)
    assert [bytes(r) for r in received] == sink.data == [sink.data[0]] * 2


def test_tap_sink_opens_the_reader_gate_without_a_dds_reader(nodes):
    publisher_node, _ = nodes
    sink = Sink(open_=False)
    publisher_node.add_publish_tap(Tap(sink))
    publisher = publisher_node.create_publisher(FLOAT64, '/tap/nobody')
    assert publisher.reader_gate.open is False       # no DDS reader, the sink does not want it
    sink.open = True
    assert publisher.reader_gate.open is True
    publisher.publish(publisher_node.msg(FLOAT64)(data=1.0))
    assert len(sink.data) == 1


def test_a_topic_only_a_sink_wants_costs_no_dds_write_until_a_reader_comes(nodes):
    publisher_node, reader_node = nodes
    sink = Sink()
    publisher_node.add_publish_tap(Tap(sink))
    publisher = publisher_node.create_publisher(FLOAT64, '/tap/later')
    message = publisher_node.msg(FLOAT64)(data=3.0)
    publisher.publish(message)
    # no DDS reader: the sink has it, the transport wrote nothing (it would go nowhere)
    assert len(sink.data) == 1 and publisher.publish_serialized.count[0] == 0
    received = []
    reader_node.create_subscription(FLOAT64, '/tap/later', received.append, raw=True)
    assert wait_for(lambda: publisher.get_subscription_count() > 0)
    publisher.publish(message)
    assert wait_for(lambda: received, spin=reader_node)
    assert publisher.publish_serialized.count[0] == 1 and len(sink.data) == 2
    # a latched topic is written whatever its readers: a later one gets it from the history
    latched = publisher_node.create_publisher(FLOAT64, '/tap/kept', QOS_LATCHED)
    latched.publish(message)
    assert latched.publish_serialized.count[0] == 1


def test_publish_of_another_type_is_refused_before_the_tap_sees_it(nodes):
    publisher_node, _ = nodes
    sink = Sink()
    publisher_node.add_publish_tap(Tap(sink))
    publisher = publisher_node.create_publisher(FLOAT64, TOPIC)
    with pytest.raises(TransportError, match='takes std_msgs/msg/Float64, got String'):
        publisher.publish(publisher_node.msg('std_msgs/msg/String')(data='x'))
    assert sink.data == []


def test_tap_hears_of_services_and_latched_topics(nodes):
    publisher_node, _ = nodes
    tap = Tap(Sink())
    publisher_node.add_publish_tap(tap)
    publisher_node.create_publisher(FLOAT64, '/tap/latched', QOS_LATCHED)

    def callback(request, response):
        return response
    publisher_node.create_service('std_srvs/srv/Trigger', 'poke', callback)
    # The node's own publishers, created with it, are tapped when the tap is attached.
    assert tap.topics == [('/rosout', 'rcl_interfaces/msg/Log', TRANSIENT_LOCAL),
                          ('/parameter_events', 'rcl_interfaces/msg/ParameterEvent',
                           VOLATILE),
                          ('/tap/latched', FLOAT64, TRANSIENT_LOCAL)]
    assert tap.services == [('/poke', 'std_srvs/srv/Trigger', callback)]


def test_a_tap_attached_later_gets_the_node_log(nodes):
    node, _ = nodes
    sink = Sink()
    node.add_publish_tap(Tap(sink))
    node.get_logger().info('hello tap')
    (data,) = sink.data
    assert node.deserialize('rcl_interfaces/msg/Log', data).msg == 'hello tap'


def test_call_soon_runs_on_the_spinning_thread(nodes):
    node, _ = nodes
    ran_on = []
    done = threading.Event()

    def work():
        ran_on.append(threading.get_ident())
        done.set()
    caller = threading.Thread(target=node.call_soon, args=(work,))
    caller.start()
    caller.join()
    assert ran_on == []             # nothing runs until the node spins
    node.serve_pending()
    assert done.is_set() and ran_on == [threading.get_ident()]


def test_function_taps_and_a_live_view_tap_share_a_publisher(nodes):
    node, _ = nodes
    recorded = []
    node.tap_publishers(lambda topic, ros_type, qos: recorded.append if topic == TOPIC else None)
    watched = Sink(open_=False)
    node.add_publish_tap(Tap(watched))
    publisher = node.create_publisher(FLOAT64, TOPIC)
    assert publisher.reader_gate.open is True       # the recorder takes every message
    publisher.publish(node.msg(FLOAT64)(data=4.0))
    assert recorded == [b'\x00\x01\x00\x00' + struct.pack('<d', 4.0)]
    assert watched.data == []                        # nobody watching
    watched.open = True
    publisher.publish(node.msg(FLOAT64)(data=5.0))
    assert recorded[1] == watched.data[0] == b'\x00\x01\x00\x00' + struct.pack('<d', 5.0)
