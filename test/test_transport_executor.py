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
The embedded transport's executor: which callbacks one ``spin_once`` runs, and shutdown.

Two nodes of this process share its participant; a sample written by one reaches the other's
readers by Cyclone's local delivery before ``publish`` returns, so one ``spin_once`` sees it.
"""

from automobile_helpers import wait_for
import pytest

from vehicle_sim.transport.dds import DdsNode
from vehicle_sim.transport.dds.endpoints import TAKE_BATCH
from vehicle_sim.transport.qos import QosProfile

pytestmark = pytest.mark.transport

STRING = 'std_msgs/msg/String'
# Deep enough to keep every sample of the batch test.
DEEP = QosProfile(depth=4 * TAKE_BATCH)
# Generous bound for one spin that has work waiting [s].
SPIN_S = 5.0


@pytest.fixture
def pair(request):
    """Yield a (writer node, reader node) pair under a namespace of this test."""
    ns = '/exec_' + request.node.name[:40].replace('[', '_').replace(']', '_')
    nodes = [DdsNode('writer', ns), DdsNode('reader', ns)]
    yield nodes
    for node in reversed(nodes):
        node.shutdown()


def _matched(publishers):
    return wait_for(lambda: all(p.get_subscription_count() for p in publishers))


def test_one_spin_serves_every_reader_that_has_data(pair):
    writer, reader = pair
    got = []
    topics = ['a', 'b', 'c']
    for topic in topics:
        reader.create_subscription(STRING, topic, lambda m, t=topic: got.append((t, m.data)))
    publishers = [writer.create_publisher(STRING, topic) for topic in topics]
    assert _matched(publishers)
    for topic, publisher in zip(topics, publishers):
        publisher.publish(writer.msg(STRING)(data=topic * 2))
    reader.spin_once(SPIN_S)
    assert sorted(got) == [('a', 'aa'), ('b', 'bb'), ('c', 'cc')]


def test_readers_that_fired_together_run_in_creation_order_whatever_fired_last(pair):
    writer, reader = pair
    got = []
    topics = ['a', 'b', 'c']
    for topic in topics:
        reader.create_subscription(STRING, topic, lambda m, t=topic: got.append(t))
    publishers = dict(zip(topics, (writer.create_publisher(STRING, t) for t in topics)))
    assert _matched(publishers.values())
    for alone in ('c', 'b'):   # the executor now looks at c and b first
        publishers[alone].publish(writer.msg(STRING)(data=alone))
        reader.spin_once(SPIN_S)
    assert got == ['c', 'b']
    for topic in ('c', 'a', 'b'):
        publishers[topic].publish(writer.msg(STRING)(data=topic))
    reader.spin_once(SPIN_S)
    assert got == ['c', 'b', 'a', 'b', 'c']


def test_samples_beyond_one_take_batch_are_served_by_the_next_spin(pair):
    writer, reader = pair
    got = []
    reader.create_subscription(STRING, 'burst', lambda m: got.append(int(m.data)), DEEP)
    publisher = writer.create_publisher(STRING, 'burst', DEEP)
    assert _matched([publisher])
    count = TAKE_BATCH + 44
    for index in range(count):
        publisher.publish(writer.msg(STRING)(data=str(index)))
    reader.spin_once(SPIN_S)
    assert got == list(range(TAKE_BATCH))
    reader.spin_once(SPIN_S)   # the reader is still readable: the wait returns at once
    assert got == list(range(count))


def test_a_callback_that_shuts_the_node_down_ends_the_spin(pair):
    writer, reader = pair
    got = []

    def first(msg):
        got.append(('first', msg.data))
        reader.shutdown()

    reader.create_subscription(STRING, 'first', first)
    reader.create_subscription(STRING, 'second', lambda m: got.append(('second', m.data)))
    publishers = [writer.create_publisher(STRING, t) for t in ('first', 'second')]
    assert _matched(publishers)
    for publisher in publishers:
        publisher.publish(writer.msg(STRING)(data='x'))
    reader.spin_once(SPIN_S)
    assert got == [('first', 'x')]
    assert not reader.ok()
    reader.spin_once(SPIN_S)   # returns at once: nothing is served any more
    reader.request_shutdown()  # its guard condition is gone: still no error
    assert got == [('first', 'x')]


def test_a_node_that_shuts_down_leaves_at_once_and_the_other_node_serves_on(pair):
    writer, reader = pair
    got = []
    reader.create_subscription(STRING, 'left', got.append)
    writer.create_subscription(STRING, 'echo', got.append)
    publisher = writer.create_publisher(STRING, 'left')
    echo = writer.create_publisher(STRING, 'echo')
    assert _matched([publisher, echo])
    reader.shutdown()   # not the last node: its endpoints are deleted one by one
    assert publisher.get_subscription_count() == 0
    echo.publish(writer.msg(STRING)(data='still here'))
    writer.spin_once(SPIN_S)
    assert [m.data for m in got] == ['still here']


def test_a_timer_fires_from_spin_once_and_not_after_cancel(pair):
    _, node = pair
    fired = []
    timer = node.create_timer(0.01, lambda: fired.append(len(fired)))
    assert wait_for(lambda: fired, spin=node)
    timer.cancel()
    node.spin_once(0.0)   # a cancelled timer is dropped at the next spin
    count = len(fired)
    for _ in range(5):
        node.spin_once(0.02)
    assert len(fired) == count
