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
One interface-table kind: every node's publishers, subscriptions and services come from rows.

The nodes are built in-process on the embedded transport (never spun) while the transport's
``create_*`` calls are recorded, leaving out the transport's own endpoints (parameter services,
/rosout, /parameter_events). The recorded endpoints must be exactly the rows of the node's
tables (name as resolved, type, QoS), once each. /clock, /tf and /tf_static are one row each for
every node (docs/ros_interface.md: /clock reliable, depth 1).
"""

import ast
from pathlib import Path
import sys
from types import SimpleNamespace

from conftest import REPO_ROOT
import pytest

from vehicle_msgs_py import types as msg_types
from vehicle_sim.ros import automobile_interfaces as itf
from vehicle_sim.ros import autoware_interfaces as awi
from vehicle_sim.ros import bridge_interfaces as bi
from vehicle_sim.ros import endpoints
from vehicle_sim.ros import robot_interfaces as ri
from vehicle_sim.transport import dds
from vehicle_sim.transport.qos import as_qos, QOS_CLOCK, RELIABLE, VOLATILE

pytestmark = pytest.mark.transport

ROS_DIR = Path(REPO_ROOT) / 'vehicle_sim' / 'ros'
NAMESPACE = '/tables'
SYNCHRONOUS = {'synchronous': True}


@pytest.fixture
def created(monkeypatch):
    """Record (kind, name, type, QoS) of every endpoint a node module asks the transport for."""
    calls = []

    def recording(kind, original):
        def create(self, ros_type, name, *args, **kwargs):
            endpoint = original(self, ros_type, name, *args, **kwargs)
            caller = sys._getframe(1).f_globals.get('__name__', '')
            if not caller.startswith('vehicle_sim.transport'):
                qos = None if kind == 'service' else as_qos(
                    args[-1] if kind == 'subscription' and len(args) > 1 else
                    args[0] if kind == 'publisher' and args else kwargs.get('qos'))
                calls.append((kind, getattr(endpoint, 'topic_name', None) or
                              endpoint.service_name, ros_type, qos))
            return endpoint
        return create

    for kind, attr in (('publisher', 'create_publisher'),
                       ('subscription', 'create_subscription'), ('service', 'create_service')):
        monkeypatch.setattr(dds.DdsNode, attr, recording(kind, getattr(dds.DdsNode, attr)))
    return calls


def _expected(rows, resolve):
    found = []
    for row in rows:
        if isinstance(row, endpoints.Service):
            found.append(('service', resolve(row.name), row.ros_type, None))
        else:
            kind = 'publisher' if row.direction == endpoints.OUT else 'subscription'
            found.append((kind, resolve(row.name), row.ros_type, row.qos))
    return sorted(found, key=repr)


def _global_or(prefix):
    return lambda name: name if name.startswith('/') else f'{prefix}/{name}'


def _automobile_rows(namespaces, inputs=(itf.CMD_VEL, itf.DRIVE)):
    rows = [(row, NAMESPACE) for row in itf.WORLD_TOPICS + itf.WORLD_SERVICES + itf.WORLD_INPUTS]
    for ns in namespaces:
        prefix = f'{NAMESPACE}/{ns}' if ns else NAMESPACE
        rows += [(row, prefix) for row in itf.VEHICLE_TOPICS + itf.SERVICES + inputs]
    return rows


def _build_automobile(world):
    from vehicle_sim.ros.automobile_node import AutomobileNode
    app = AutomobileNode(['x', '--ros-args', '-r', f'__ns:={NAMESPACE}'], transport='dds',
                         parameter_overrides={**SYNCHRONOUS, 'world': world})
    return app, app.close


def _expected_of(pairs):
    found = []
    for row, prefix in pairs:
        found += _expected([row], _global_or(prefix))
    return sorted(found, key=repr)


def test_automobile_endpoints_are_its_rows_once_per_vehicle_and_the_global_rows_once(created):
    app, close = _build_automobile('two_cars')
    try:
        assert sorted(created, key=repr) == _expected_of(_automobile_rows(['car1', 'car2']))
    finally:
        close()


def test_autoware_automobile_endpoints_are_the_car_rows_and_the_autoware_side_rows(created):
    from vehicle_sim.ros.autoware_automobile_node import AutowareAutomobileNode
    app = AutowareAutomobileNode(['x', '--ros-args', '-r', f'__ns:={NAMESPACE}'],
                                 transport='dds', parameter_overrides=SYNCHRONOUS)
    try:
        autoware = (awi.STATUS_TOPICS + (awi.BRIDGE_INPUTS[awi.DEFAULT_INPUT_TYPE],) +
                    awi.COMMAND_INPUTS + (awi.CONTROL_MODE_REQUEST,))
        # Autoware's command drives the car: no cmd_vel or drive of the car.
        expected = _expected_of(_automobile_rows([''], inputs=())) + _expected(autoware,
                                                                                lambda n: n)
        assert sorted(created, key=repr) == sorted(expected, key=repr)
    finally:
        app.close()


def test_diff_robot_endpoints_are_its_rows_under_its_name(created):
    from vehicle_sim.ros.diff_robot_node import DiffRobotNode
    robot = DiffRobotNode(transport='dds', namespace=NAMESPACE, parameter_overrides=SYNCHRONOUS)
    try:
        # It owns its world: /sim/reset, /sim/pause and /initialpose too.
        rows = (ri.ROBOT_INPUTS + ri.ROBOT_OUTPUTS + ri.ROBOT_SERVICES + itf.WORLD_SERVICES
                + itf.WORLD_INPUTS)
        assert sorted(created, key=repr) == _expected(
            rows, _global_or(f'{NAMESPACE}/{ri.ROBOT_NODE_NAME}'))
    finally:
        robot.destroy()


@pytest.mark.parametrize('overrides', [
    {},
    {'publish_differential_command': False, 'publish_wheel_velocities': False,
     'publish_twist': True, 'publish_twist_stamped': True, 'vehicle_status': False,
     'use_sim_time': True, 'input_type': awi.ACKERMANN_DRIVE},
], ids=['defaults', 'switched'])
def test_bridge_endpoints_are_its_rows_that_its_switches_enable(created, overrides):
    from vehicle_sim.ros.bridge_node import AckermannToDifferentialNode
    bridge = AckermannToDifferentialNode(transport='dds', parameter_overrides=overrides,
                                         namespace=NAMESPACE)
    try:
        switches = {'publish_differential_command': True, 'publish_wheel_velocities': True,
                    'publish_twist': False, 'publish_twist_stamped': False,
                    'vehicle_status': True, 'use_sim_time': False}
        switches.update({k: v for k, v in overrides.items() if k in switches})
        rows = (bi.BRIDGE_OUTPUTS + awi.STATUS_TOPICS + awi.COMMAND_INPUTS +
                (bi.JOINT_STATES_IN, bi.CLOCK_IN, awi.CONTROL_MODE_REQUEST))
        rows = (awi.BRIDGE_INPUTS[overrides.get('input_type', awi.DEFAULT_INPUT_TYPE)],) + tuple(
            row for row in rows if row.switch is None or switches[row.switch])
        assert sorted(created, key=repr) == _expected(rows, lambda n: n)
    finally:
        bridge.destroy()


@pytest.mark.parametrize('build', ['automobile', 'diff_robot'])
def test_clock_is_published_reliable_with_depth_1_by_every_node(created, build):
    # docs/ros_interface.md: one /clock definition; rclpy's best-effort TimeSource reader matches
    # it.
    if build == 'automobile':
        app, close = _build_automobile('')
    else:
        from vehicle_sim.ros.diff_robot_node import DiffRobotNode
        app = DiffRobotNode(transport='dds', namespace=NAMESPACE,
                            parameter_overrides=SYNCHRONOUS)
        close = app.destroy
    try:
        clocks = [qos for kind, name, _, qos in created
                  if kind == 'publisher' and name == '/clock']
        assert [(q.reliability, q.durability, q.depth) for q in clocks] == [
            (RELIABLE, VOLATILE, 1)]
    finally:
        close()


def _table_rows():
    rows = []
    for module in (itf, bi, endpoints):
        for value in vars(module).values():
            values = value.values() if isinstance(value, dict) else \
                value if isinstance(value, tuple) else (value,)
            rows += [v for v in values if isinstance(v, (endpoints.Topic, endpoints.Service))]
    return rows


@pytest.mark.parametrize('shared', [endpoints.CLOCK, endpoints.TF, endpoints.TF_STATIC],
                         ids=lambda row: row.name)
def test_clock_tf_and_tf_static_are_defined_once_for_every_table(shared):
    outputs = {id(row): row for row in _table_rows()
               if row.name == shared.name and getattr(row, 'direction', None) == endpoints.OUT}
    assert list(outputs.values()) == [shared]


def test_the_bridge_reads_clock_by_the_one_clock_row_best_effort():
    assert (bi.CLOCK_IN.name, bi.CLOCK_IN.ros_type) == (bi.CLOCK.name, bi.CLOCK.ros_type)
    assert bi.CLOCK_IN.qos == QOS_CLOCK   # rclpy's TimeSource reader profile


def test_every_row_has_a_converter_and_every_service_a_type():
    for row in _table_rows():
        if isinstance(row, endpoints.Topic):
            assert callable(row.converter), row.name
            assert row.direction in (endpoints.OUT, endpoints.IN), row.name
        else:
            assert msg_types.is_service(row.ros_type), row.name


def _calls_of(path, names):
    found = []
    for node in ast.walk(ast.parse(path.read_text(encoding='utf-8'))):
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and \
                node.func.attr in names:
            found.append(f'{path.name}:{node.lineno} {node.func.attr}')
    return found


def test_no_ros_module_but_endpoints_creates_a_publisher_subscription_or_service():
    names = {'create_publisher', 'create_subscription', 'create_service'}
    found = [call for path in sorted(ROS_DIR.glob('*.py')) if path.name != 'endpoints.py'
             for call in _calls_of(path, names)]
    assert not found, 'wire rows through ros/endpoints.py instead: ' + ', '.join(found)


# --------------------------------------------------------------------------------------------
# Converters


def _msg(ros_type):
    return msg_types.message_type(ros_type)


def _kit():
    return endpoints.MessageKit(_msg)


def _vehicle_context():
    wiring = SimpleNamespace(base_frame='car1/base_link', odom_frame='car1/odom',
                             joint_names=('car1/a', 'car1/b'))
    stamp = _msg('builtin_interfaces/msg/Time')(sec=3, nanosec=5)
    call = SimpleNamespace(stamp=stamp, joints=((0.5, 1.5), (2.0, -2.0)),
                           odom=((1.0, 2.0, 0.0), (0.0, 0.0, 0.0, 1.0), (3.0, 0.0, 0.0),
                                 (0.0, 0.0, 0.25)))
    return wiring, call


def test_joint_state_converter_fixes_the_name_list_once_and_fills_the_values_per_call():
    wiring, call = _vehicle_context()
    convert = itf.JOINT_STATES.converter(_kit(), wiring)
    first, second = convert(call), convert(call)
    assert first.name == ['car1/a', 'car1/b'] and first.name is second.name
    assert (first.position, first.velocity, first.effort) == ([0.5, 1.5], [2.0, -2.0], [])
    assert (first.header.stamp.sec, first.header.stamp.nanosec) == (3, 5)


def test_odometry_converter_gives_the_vehicle_frames_and_the_values_of_the_call():
    wiring, call = _vehicle_context()
    odom = itf.ODOM.converter(_kit(), wiring)(call)
    assert (odom.header.frame_id, odom.child_frame_id) == ('car1/odom', 'car1/base_link')
    position = odom.pose.pose.position
    assert (position.x, position.y, odom.twist.twist.linear.x,
            odom.twist.twist.angular.z) == (1.0, 2.0, 3.0, 0.25)


def test_float_rows_of_one_vehicle_share_one_header_per_stamp():
    kit, wiring = _kit(), SimpleNamespace(base_frame='car1/base_link')
    speed, throttle = (itf.topic(f'automobile/{name}').converter(kit, wiring)
                       for name in ('current_speed', 'throttle'))
    time_type = _msg('builtin_interfaces/msg/Time')
    status = SimpleNamespace(current_speed_kmh=36.0, throttle=0.5)
    call = SimpleNamespace(stamp=time_type(sec=1, nanosec=0), status=status)
    first, second = speed(call), throttle(call)
    assert (first.data, second.data) == (36.0, 0.5)
    assert first.header is second.header and first.header.frame_id == 'car1/base_link'
    later = speed(SimpleNamespace(stamp=time_type(sec=2, nanosec=0), status=status))
    assert later.header is not first.header and later.header.stamp.sec == 2
    assert first.header.stamp.sec == 1


def test_rpm_converter_gives_nothing_outside_torque_mode():
    status = SimpleNamespace(rpm=1500.0)
    convert = itf.RPM.converter(_kit(), SimpleNamespace(base_frame='base_link'))
    stamp = _msg('builtin_interfaces/msg/Time')(sec=1, nanosec=0)
    assert convert(SimpleNamespace(stamp=stamp, status=status, torque_mode=False)) is None
    message = convert(SimpleNamespace(stamp=stamp, status=status, torque_mode=True))
    assert (message.data, message.header.frame_id) == (1500.0, 'base_link')


def test_status_rows_skip_velocity_and_steering_until_measured():
    stamp = _msg('builtin_interfaces/msg/Time')(sec=2, nanosec=0)
    outputs = {row: row.converter(_kit(), SimpleNamespace(frame_id='base_link'))
               for row in awi.STATUS_TOPICS}
    unmeasured = awi.VehicleReport(stamp, None, None, None, 2, 1, 1, 1)
    assert [row for row, convert in outputs.items() if convert(unmeasured) is not None] == \
        [awi.GEAR_STATUS, awi.TURN_INDICATORS_STATUS, awi.HAZARD_LIGHTS_STATUS,
         awi.CONTROL_MODE_STATUS]
    measured = awi.VehicleReport(stamp, 1.5, 0.25, 0.1, 20, 2, 2, 4)
    velocity = outputs[awi.VELOCITY_STATUS](measured)
    assert (velocity.header.frame_id, velocity.longitudinal_velocity,
            velocity.heading_rate) == ('base_link', 1.5, 0.25)
    assert outputs[awi.STEERING_STATUS](measured).steering_tire_angle == pytest.approx(0.1)
    assert (outputs[awi.GEAR_STATUS](measured).report,
            outputs[awi.CONTROL_MODE_STATUS](measured).mode) == (20, 4)


def test_wheel_velocities_follow_the_wheel_joints_sides():
    command = SimpleNamespace(left_radps=-1.0, right_radps=2.0)
    convert = bi.WHEEL_VELOCITIES_OUT.converter(
        _kit(), SimpleNamespace(frame_id='base_link', wheel_sides=('right', 'left', 'left')))
    assert convert(SimpleNamespace(stamp=None, command=command)).data == [2.0, -1.0, -1.0]


# --------------------------------------------------------------------------------------------
# Docs


def test_autoware_doc_embeds_the_tables_generated_from_the_rows():
    with open(Path(REPO_ROOT) / 'docs' / 'autoware.md', encoding='utf-8') as stream:
        text = stream.read()
    for table in (awi.autoware_side_markdown(), bi.vehicle_side_markdown(), ri.robot_markdown()):
        assert table in text


def test_autoware_automobile_with_a_twist_stamped_input_owns_cmd_vel_alone(created):
    # Its /cmd_vel is Autoware's TwistStamped command; the car's Twist cmd_vel is not wired,
    # which would be a second type on one topic (refused by DDS in one process).
    from vehicle_sim.ros.autoware_automobile_node import AutowareAutomobileNode
    app = AutowareAutomobileNode(transport='dds', parameter_overrides={
        **SYNCHRONOUS, 'input_type': awi.TWIST_STAMPED})
    try:
        cmd_vel = [(kind, ros_type) for kind, name, ros_type, _ in created if name == '/cmd_vel']
        assert cmd_vel == [('subscription', awi.TWIST_STAMPED)]
    finally:
        app.close()
