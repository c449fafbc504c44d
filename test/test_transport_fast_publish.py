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


"""The publishing fast path: rows with a fast serializer write bytes on the embedded transport."""

import math
from types import SimpleNamespace

from automobile_helpers import wait_for
import pytest

from vehicle_msgs_py import types as msg_types
from vehicle_sim.ros import automobile_interfaces as itf
from vehicle_sim.ros import endpoints
from vehicle_sim.transport import port
from vehicle_sim.transport.dds import DdsNode
from vehicle_sim.transport.errors import TransportError

SPEED = itf.topic('automobile/current_speed')
ROWS = (endpoints.CLOCK, SPEED)


@pytest.fixture
def nodes():
    publisher, subscriber = DdsNode('fast_publisher', '/fast'), DdsNode('fast_reader', '/fast')
    try:
        yield publisher, subscriber
    finally:
        subscriber.shutdown()
        publisher.shutdown()


def _call(sec, nanosec, speed_kmh):
    stamp = msg_types.message_type('builtin_interfaces/msg/Time')(sec=sec, nanosec=nanosec)
    return SimpleNamespace(stamp=stamp, status=SimpleNamespace(current_speed_kmh=speed_kmh),
                           torque_mode=False)


def test_clock_and_float_rows_are_written_serialized_and_received_with_their_values(nodes):
    node, reader = nodes
    outputs = endpoints.Outputs(node, ROWS, SimpleNamespace(base_frame='car1/base_link'),
                                resolve=lambda name: name if name.startswith('/') else
                                f'/fast/{name}')
    received = {}
    for row in ROWS:
        name = outputs.publishers[row].topic_name
        reader.create_subscription(row.ros_type, name,
                                   lambda msg, name=name: received.setdefault(name, []).append(
                                       msg), row.qos)
    assert wait_for(lambda: all(p.get_subscription_count() for p in
                                outputs.publishers.values()), spin=reader)
    values = [(7, 250_000_000, 36.5), (8, 0, -0.0), (9, 1, math.inf), (2**31 - 1, 5, -12.25)]
    for sec, nanosec, speed in values:
        outputs.publish(itf.EACH_STEP, _call(sec, nanosec, speed))
        outputs.publish(itf.EACH_PUBLISH, _call(sec, nanosec, speed))
    assert [p.serialized_writes for p in outputs.publishers.values()] == [4, 4]
    speeds, clocks = received.setdefault('/fast/automobile/current_speed', []), \
        received.setdefault('/clock', [])
    assert wait_for(lambda: len(speeds) == 4 and clocks and clocks[-1].clock.sec == 2**31 - 1,
                    spin=reader)
    assert [(s.header.stamp.sec, s.header.stamp.nanosec, s.data) for s in speeds] == values
    assert [s.header.frame_id for s in speeds] == ['car1/base_link'] * 4
    assert math.copysign(1.0, speeds[1].data) == -1.0
    assert (clocks[-1].clock.sec, clocks[-1].clock.nanosec) == (2**31 - 1, 5)


def test_outputs_messages_are_messages_on_the_fast_path_too(nodes):
    node, _ = nodes
    outputs = endpoints.Outputs(node, (SPEED,), SimpleNamespace(base_frame='b'),
                                resolve=lambda name: f'/fast/{name}')
    found = outputs.messages(itf.EACH_PUBLISH, _call(3, 4, 5.5))
    message = found[SPEED]
    assert type(message) is msg_types.message_type(SPEED.ros_type)
    assert (message.header.stamp.sec, message.header.frame_id, message.data) == (3, 'b', 5.5)
    assert outputs.publishers[SPEED].serialized_writes == 0


def test_a_kit_without_serializers_builds_messages_and_one_with_them_gives_bytes(nodes):
    node, _ = nodes
    wiring, call = SimpleNamespace(base_frame='car1/base_link'), _call(1, 2, 3.0)
    plain = SPEED.converter(endpoints.MessageKit(node.msg), wiring)
    fast = SPEED.converter(endpoints.MessageKit(node.msg, node.serializer), wiring)
    assert (plain.serialized, fast.serialized) == (False, True)
    message, data = plain(call), fast(call)
    assert type(message) is msg_types.message_type(SPEED.ros_type)
    assert data == message.serialize()


def test_the_embedded_node_has_serializers_for_the_fast_cdr_types_only(nodes):
    node, _ = nodes
    for ros_type in ('rosgraph_msgs/msg/Clock', 'vehicle_msgs/msg/Float64Stamped',
                     'nav_msgs/msg/Odometry', 'sensor_msgs/msg/JointState',
                     'tf2_msgs/msg/TFMessage'):
        assert node.serializer(ros_type) is not None
    assert node.serializer('sensor_msgs/msg/Imu') is None


def test_a_transport_without_serializers_refuses_serialized_publishing():
    class MessagesOnly(port.Publisher):
        topic_name = '/x'

        def publish(self, msg):
            pass

    with pytest.raises(TransportError, match='messages only'):
        MessagesOnly().publish_serialized(b'\0\1\0\0')


def test_odometry_and_joint_state_rows_are_written_serialized_and_received(nodes):
    node, reader = nodes
    rows = (itf.ODOM, itf.JOINT_STATES)
    wiring = SimpleNamespace(base_frame='car1/base_link', odom_frame='car1/odom',
                             joint_names=('car1/a', 'car1/b'))
    outputs = endpoints.Outputs(node, rows, wiring, resolve=lambda name: f'/fast/{name}')
    received = []
    for row in rows:
        reader.create_subscription(row.ros_type, outputs.publishers[row].topic_name,
                                   received.append, row.qos)
    assert wait_for(lambda: all(p.get_subscription_count() for p in
                                outputs.publishers.values()), spin=reader)
    call = _call(4, 6, 0.0)
    call.joints = ((0.5, 1.5), (2.0, -2.0))
    call.odom = ((1.0, 2.0, 0.0), (0.0, 0.0, 0.0, 1.0), (3.0, 0.0, 0.0), (0.0, 0.0, 0.25))
    outputs.publish(itf.EACH_PUBLISH, call)     # both rows' cadence
    assert [p.serialized_writes for p in outputs.publishers.values()] == [1, 1]
    assert wait_for(lambda: len(received) == 2, spin=reader)
    odom, = [r for r in received if hasattr(r, 'child_frame_id')]
    state, = [r for r in received if hasattr(r, 'name')]
    assert (odom.header.frame_id, odom.child_frame_id) == ('car1/odom', 'car1/base_link')
    assert (odom.pose.pose.position.x, odom.pose.pose.position.y, odom.twist.twist.linear.x,
            odom.twist.twist.angular.z, odom.header.stamp.nanosec) == (1.0, 2.0, 3.0, 0.25, 6)
    assert list(odom.pose.covariance) == [0.0] * 36
    assert (state.name, state.position, state.velocity, state.effort) == \
        (['car1/a', 'car1/b'], [0.5, 1.5], [2.0, -2.0], [])


def test_the_tf_row_is_written_serialized_and_static_tf_stays_a_message(nodes):
    node, reader = nodes
    rows = (endpoints.TF, endpoints.TF_STATIC)
    wiring = SimpleNamespace(tf_frames=[('odom', 'base_link'), ('car1/odom', 'car1/base_link')],
                             static_transforms=[('world', 'odom', (1.0, 2.0, 0.0),
                                                 (0.0, 0.0, 0.0, 1.0))])
    outputs = endpoints.Outputs(node, rows, wiring, resolve=lambda name: f'/fast{name}')
    received = []
    reader.create_subscription(endpoints.TF.ros_type, '/fast/tf', received.append,
                               endpoints.TF.qos)
    assert wait_for(lambda: outputs.publishers[endpoints.TF].get_subscription_count(),
                    spin=reader)
    call = _call(5, 7, 0.0)
    call.tf_poses = [((1.0, 2.0, 3.0), (0.0, 0.0, 0.5, 0.75)),
                     ((-4.0, 0.5, 0.0), (0.0, 0.0, 0.0, 1.0))]
    outputs.publish(itf.EACH_PUBLISH, call)
    outputs.publish(itf.ONCE_LATCHED, call)
    assert [p.serialized_writes for p in outputs.publishers.values()] == [1, 0]
    assert wait_for(lambda: received, spin=reader)
    transforms = received[0].transforms
    assert [(t.header.frame_id, t.child_frame_id, t.header.stamp.sec, t.header.stamp.nanosec,
             t.transform.translation.x, t.transform.rotation.w) for t in transforms] == \
        [('odom', 'base_link', 5, 7, 1.0, 0.75), ('car1/odom', 'car1/base_link', 5, 7, -4.0, 1.0)]


def test_a_raw_subscription_gets_the_bytes_and_deserialize_decodes_them(nodes):
    node, reader = nodes
    outputs = endpoints.Outputs(node, (SPEED,), SimpleNamespace(base_frame='b'),
                                resolve=lambda name: f'/fast/{name}')
    raw, decoded = [], []
    reader.create_subscription(SPEED.ros_type, '/fast/automobile/current_speed', raw.append,
                               SPEED.qos, raw=True)
    reader.create_subscription(SPEED.ros_type, '/fast/automobile/current_speed', decoded.append,
                               SPEED.qos)
    assert wait_for(lambda: outputs.publishers[SPEED].get_subscription_count() == 2, spin=reader)
    outputs.publish(itf.EACH_PUBLISH, _call(6, 9, -3.25))
    assert wait_for(lambda: raw and decoded, spin=reader)
    assert type(raw[0]) is bytes
    assert raw[0] == outputs.messages(itf.EACH_PUBLISH, _call(6, 9, -3.25))[SPEED].serialize()
    message = reader.deserialize(SPEED.ros_type, raw[0])
    assert message == decoded[0]
    assert (message.header.stamp.sec, message.header.frame_id, message.data) == (6, 'b', -3.25)
