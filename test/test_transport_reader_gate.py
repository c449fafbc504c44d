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


"""Rows whose volatile publisher has no matched reader are neither built nor written."""

from types import SimpleNamespace

from automobile_helpers import wait_for
import pytest

from vehicle_msgs_py import types as msg_types
from vehicle_sim.ros import automobile_interfaces as itf
from vehicle_sim.ros import endpoints
from vehicle_sim.ros.automobile_node import AutomobileNode
from vehicle_sim.transport import port
from vehicle_sim.transport.dds import DdsNode
from vehicle_sim.transport.reader_gate import ALWAYS_OPEN

SPEED = itf.topic('automobile/current_speed')
SPEED_NAME = '/gate/automobile/current_speed'


@pytest.fixture
def node():
    publisher = DdsNode('gate_publisher', '/gate')
    try:
        yield publisher
    finally:
        publisher.shutdown()


class _Car:
    """A wiring call whose status counts how often the rows read it."""

    def __init__(self, sec, speed_kmh):
        self.stamp = msg_types.message_type('builtin_interfaces/msg/Time')(sec=sec, nanosec=0)
        self.torque_mode = False
        self._speed_kmh = speed_kmh
        self.reads = 0

    @property
    def status(self):
        self.reads += 1
        return SimpleNamespace(current_speed_kmh=self._speed_kmh)


def _speed_outputs(node):
    return endpoints.Outputs(node, (SPEED,), SimpleNamespace(base_frame='b'),
                             resolve=lambda name: f'/gate/{name}')


def test_a_volatile_row_without_a_reader_is_neither_built_nor_written(node):
    outputs = _speed_outputs(node)
    publisher = outputs.publishers[SPEED]
    car = _Car(1, 10.0)
    outputs.publish(itf.EACH_PUBLISH, car)
    assert publisher.reader_gate.open is False
    assert (car.reads, publisher.serialized_writes) == (0, 0)


def test_a_reader_that_matches_gets_the_next_message_and_one_that_leaves_closes_the_gate(node):
    outputs = _speed_outputs(node)
    publisher = outputs.publishers[SPEED]
    outputs.publish(itf.EACH_PUBLISH, _Car(1, 10.0))    # no reader: goes nowhere
    reader, received = DdsNode('gate_reader', '/gate'), []
    try:
        reader.create_subscription(SPEED.ros_type, SPEED_NAME, received.append, SPEED.qos)
        assert wait_for(lambda: publisher.get_subscription_count() == 1, spin=reader)
        assert wait_for(lambda: publisher.reader_gate.open)
        car = _Car(2, 36.5)
        outputs.publish(itf.EACH_PUBLISH, car)
        assert (car.reads, publisher.serialized_writes) == (1, 1)
        assert wait_for(lambda: received, spin=reader)
        assert [(m.header.stamp.sec, m.data) for m in received] == [(2, 36.5)]
    finally:
        reader.shutdown()
    assert wait_for(lambda: not publisher.reader_gate.open)
    car = _Car(3, 1.0)
    outputs.publish(itf.EACH_PUBLISH, car)
    assert (car.reads, publisher.serialized_writes) == (0, 1)


def test_a_latched_row_is_written_without_a_reader_and_a_late_reader_gets_it(node):
    row = endpoints.TF_STATIC
    wiring = SimpleNamespace(static_transforms=[('world', 'odom', (1.0, 2.0, 0.0),
                                                 (0.0, 0.0, 0.0, 1.0))])
    outputs = endpoints.Outputs(node, (row,), wiring, resolve=lambda name: f'/gate{name}')
    assert outputs.publishers[row].reader_gate is ALWAYS_OPEN
    outputs.publish(itf.ONCE_LATCHED, _Car(4, 0.0))     # before any reader
    reader, received = DdsNode('gate_late_reader', '/gate'), []
    try:
        reader.create_subscription(row.ros_type, '/gate/tf_static', received.append, row.qos)
        assert wait_for(lambda: received, spin=reader)
        (transform,) = received[0].transforms
        assert (transform.header.frame_id, transform.child_frame_id,
                transform.transform.translation.y) == ('world', 'odom', 2.0)
    finally:
        reader.shutdown()


def test_publishers_of_other_transports_are_always_open():
    class Other(port.Publisher):
        topic_name = '/x'

        def publish(self, msg):
            pass

    assert Other().reader_gate.open is True and Other().reader_gate is ALWAYS_OPEN


class _Counted:
    """Wrap ``owner.name`` so that its calls are counted (the original still answers)."""

    def __init__(self, owner, name):
        self.calls = 0
        original = getattr(owner, name)

        def counted(*args, **kwargs):
            self.calls += 1
            return original(*args, **kwargs)
        setattr(owner, name, counted)


def test_a_step_reads_only_the_car_state_its_subscribed_rows_need():
    app = AutomobileNode(['t', '--ros-args', '-r', '__ns:=/lazy', '-p', 'synchronous:=true'],
                         transport='dds')
    listener = DdsNode('lazy_listener')
    try:
        car = app.vehicles['']
        pose = _Counted(car.body, 'pose_and_velocity')
        joints = _Counted(car.body, 'joint_states')
        status = _Counted(car.logic, 'status')

        def steps(count=20):
            pose.calls = joints.calls = status.calls = 0
            app.step(count)
            return pose.calls, joints.calls, status.calls

        assert steps() == (0, 0, 0)     # /clock has no reader either: nothing is read
        received = []
        subscriptions = [listener.create_subscription(
            'vehicle_msgs/msg/Float64Stamped', '/lazy/automobile/current_speed',
            received.append)]
        assert wait_for(lambda: app._fleet_outputs is not None and all(
            gate.open for gate in _gates(app, 'automobile/current_speed')), spin=listener)
        assert steps() == (0, 0, 20)    # the status once a step, no pose, no joints
        subscriptions.append(listener.create_subscription(
            'nav_msgs/msg/Odometry', '/lazy/odom', received.append))
        subscriptions.append(listener.create_subscription(
            'tf2_msgs/msg/TFMessage', '/tf', received.append))
        assert wait_for(lambda: all(gate.open for gate in _gates(app, 'odom', '/tf')),
                        spin=listener)
        assert steps() == (20, 0, 20)   # odometry and /tf share one read of the pose
        subscriptions.append(listener.create_subscription(
            'sensor_msgs/msg/JointState', '/lazy/joint_states', received.append))
        assert wait_for(lambda: all(gate.open for gate in _gates(app, 'joint_states')),
                        spin=listener)
        assert steps() == (20, 20, 20)
    finally:
        listener.shutdown()
        app.close()


def _gates(app, *names):
    """Return the reader gates of the node's publishers whose row name ends with ``names``."""
    found = [publisher.reader_gate
             for outputs in [app._fleet_outputs] + [v.outputs for v in app._vehicles]
             for row, publisher in outputs.publishers.items() if row.name.endswith(names)]
    assert len(found) == len(names), names
    return found
