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
Cross-process tests of the automobile node over real DDS (docs/ros_interface.md).

The node runs in a subprocess in synchronous mode; the test talks to it with its own DdsNode
and, for wire-level checks, with raw cyclonedds readers. Every service and topic comes from
``vehicle_sim.ros.automobile_interfaces``. Simulated time is asserted exactly (deterministic
stepping); waits are generous bounds on outcomes.
"""

import math
import os
import struct

from automobile_helpers import (
    automobile_fixtures,
    car_fixture,
    node_fixture,
    NodeProcess,
    stamp_of,
    VehicleClient,
    wait_for,
    WAIT_S,
)
from conftest import REPO_ROOT
from cyclonedds.builtin import (
    BuiltinDataReader,
    BuiltinTopicDcpsPublication,
    BuiltinTopicDcpsSubscription,
)
from cyclonedds.domain import DomainParticipant
from cyclonedds.sub import DataReader
from cyclonedds.topic import Topic
import pytest

from vehicle_msgs_py import types as msg_types
from vehicle_sim.config import load_car, read_yaml
from vehicle_sim.core.car.logic import CarLogic
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.ros import automobile_interfaces as itf
from vehicle_sim.ros import sim_params
from vehicle_sim.ros.automobile_node import AutomobileNode
from vehicle_sim.transport import dds
from vehicle_sim.transport.dds.domain_config import domain_id
from vehicle_sim.transport.parameter_types import Parameter
from vehicle_sim.transport.qos import QOS_DEFAULT, QOS_DISCOVERY_INFO_READER, QOS_SERVICES

pytestmark = pytest.mark.transport

SETTERS = [s for s in itf.SERVICES if s.kind == itf.SETTER]
GETTERS = [s for s in itf.SERVICES if s.kind == itf.GETTER]
INVALID = [(s, v) for s in SETTERS for v in s.invalid]
FLOAT_TOPICS = [t.name for t in itf.AUTOMOBILE_TOPICS if t not in itf.TORQUE_ONLY_TOPICS]
# Topic observations step the world long enough for the steering motors to settle.
SETTLE_MS = 500


def _param(spec, value=None):
    label = spec.short_name if value is None else f'{spec.short_name}={value!r}'
    return pytest.param(spec, id=label) if value is None else pytest.param(spec, value, id=label)


def _default_car(request):
    """Run the default car: synchronous from a params file, the model from ``-p``."""
    path = request.getfixturevalue('tmp_path_factory').mktemp('automobile') / 'params.yaml'
    path.write_text('/**:\n  ros__parameters:\n    synchronous: true\n    time_step_ms: 10\n')
    return ['--ros-args', '--params-file', str(path), '-p', 'car_model:=ToyotaPrius']


sim, tester, car = automobile_fixtures('automobile_tester', _default_car,
                                       FLOAT_TOPICS + ['/clock'])
two_cars = node_fixture(['--ros-args', '-p', 'world:=two_cars', '-p', 'synchronous:=true'],
                        name='two_cars')


@pytest.fixture(scope='module')
def raw():
    dds.ensure_domain()
    return DomainParticipant(domain_id())


def _reader(raw, topic_name, data_type, qos=QOS_DEFAULT):
    return DataReader(raw, Topic(raw, topic_name, data_type),
                      qos=dds.dds_qos(qos, b'', writer=False))


# ------------------------------------------------------------------------------- services

@pytest.mark.parametrize('spec', [_param(s) for s in SETTERS])
def test_setter_with_a_valid_value_changes_what_its_getter_or_topic_reports(car, spec):
    # TORQUE mode first, so that get_gear reports the gear (0 in SPEED mode, as in Webots).
    assert car.call('automobile/set_throttle', 0.0).success
    assert car.call(spec.name, spec.example).success is True
    if spec.observed_by is None:
        return  # Webots offers no getter for it: success is all a client can see
    observed = car.observe(spec.observed_by, SETTLE_MS)
    assert observed == pytest.approx(spec.example, abs=0.02)


def test_getters_report_the_toyota_prius_chosen_by_the_car_model_argument(car):
    expected = CarLogic(load_car('ToyotaPrius'))
    for spec in GETTERS:
        assert car.call(spec.name).value is not None
    assert car.call('automobile/get_engine_type').value == int(expected.engine_type)
    assert car.call('automobile/get_type').value == int(expected.car_type)
    assert car.call('automobile/get_gear_number').value == expected.gear_number
    dims = car.call('automobile/get_dimensions')
    assert (dims.track_front, dims.track_rear, dims.wheel_base, dims.front_wheel_radius,
            dims.rear_wheel_radius) == pytest.approx(
        (expected.track_front_m, expected.track_rear_m, expected.wheelbase_m,
         expected.front_wheel_radius_m, expected.rear_wheel_radius_m), rel=1e-12)
    assert car.call('robot/get_basic_time_step').value == 10.0


@pytest.mark.parametrize('spec,value', [_param(s, v) for s, v in INVALID])
def test_setter_refuses_an_invalid_value_and_changes_nothing(car, spec, value):
    observer = spec.observed_by
    before = car.observe(observer)
    assert car.call(spec.name, value).success is False
    after = car.observe(observer)
    assert after == pytest.approx(before, abs=1e-3)
    assert car.call('robot/get_time').value > 0.0   # still serving


def test_time_step_advances_clock_and_get_time_by_exactly_the_requested_duration(car):
    clock = car.step_and_read('/clock')
    start = car.time_s()
    assert stamp_of(clock) == pytest.approx(start, abs=1e-9)
    assert car.call('robot/time_step', 10).success
    assert car.time_s() == pytest.approx(start + 0.01, abs=1e-9)
    assert car.call('robot/time_step', 30).success
    assert car.time_s() == pytest.approx(start + 0.04, abs=1e-9)
    assert wait_for(lambda: abs(stamp_of(car.latest['/clock']) - (start + 0.04)) < 1e-9,
                    spin=car.node)
    for bad in (7, -10):
        assert car.call('robot/time_step', bad).success is False
    assert car.time_s() == pytest.approx(start + 0.04, abs=1e-9)


def test_rpm_is_published_in_torque_mode_only(car):
    car.wait_matched(['automobile/rpm'])
    assert car.call('automobile/set_cruising_speed', 5.0).success
    switched_s = car.time_s()
    car.step_and_read('automobile/throttle', 20)
    rpm = car.latest.get('automobile/rpm')
    assert rpm is None or stamp_of(rpm) <= switched_s + 1e-9
    assert car.call('automobile/set_throttle', 0.1).success
    assert car.step_and_read('automobile/rpm', 20).data >= 0.0


def test_services_outside_the_table_are_not_served(car, raw):
    reader = BuiltinDataReader(raw, BuiltinTopicDcpsSubscription)
    names = set()
    wanted = {f'rq/{s.name}Request' for s in itf.SERVICES}

    def all_listed():
        names.update(s.topic_name for s in reader.take(N=1024) if s.sample_info.valid_data)
        return wanted <= names

    assert wait_for(all_listed)
    for name in itf.NOT_SERVED + ('automobile/set_brake_intensities',):
        assert f'rq/{name}Request' not in names


# ------------------------------------------------------------------------------- the wire

def _rosbags_bytes(obj, ros_type):
    store = msg_types.typestore()
    return bytes(store.serialize_cdr(msg_types.to_rosbags(obj), ros_type))


WIRE_TOPICS = ['automobile/current_speed', '/clock', 'odom', '/tf', '/tf_static', 'joint_states',
               'robot_description']


@pytest.mark.parametrize('name', WIRE_TOPICS)
def test_topic_bytes_equal_rosbags_cdr_of_the_same_message(car, raw, name):
    spec = itf.topic(name)
    data_type = msg_types.message_type(spec.ros_type)
    topic_name = 'rt' + car.name(name)
    reader = _reader(raw, topic_name, data_type, spec.qos)
    samples = []

    def received():
        if spec.cadence != itf.ONCE_LATCHED:
            car.call('robot/time_step', 0)
        samples.extend(s for s in reader.take(N=16) if s.sample_info.valid_data)
        return samples

    assert wait_for(received)
    sample = samples[-1]
    assert sample.serialize() == _rosbags_bytes(sample, spec.ros_type)


def _first_service_of_each_type():
    seen = {}
    for spec in itf.SERVICES:
        seen.setdefault(spec.srv_type, spec)
    return list(seen.values())


@pytest.mark.parametrize('spec', [_param(s) for s in _first_service_of_each_type()])
def test_service_bytes_equal_rosbags_cdr_after_the_16_byte_request_header(car, raw, spec):
    types = msg_types.service_types(spec.srv_type)
    name = car.name(spec.name)
    requests = _reader(raw, f'rq{name}Request', types.request_wire, QOS_SERVICES)
    replies = _reader(raw, f'rr{name}Reply', types.response_wire, QOS_SERVICES)
    car.client(spec.name)        # its request writer, which the raw reader must match
    assert wait_for(lambda: requests.get_matched_publications() and
                    replies.get_matched_publications())
    car.call(spec.name, spec.example if spec.kind == itf.SETTER else None)
    for reader, srv_part in ((requests, '_Request'), (replies, '_Response')):
        samples = wait_for(lambda r=reader: [s for s in r.take(N=16) if s.sample_info.valid_data])
        assert samples
        wire = samples[-1]
        _, _, plain = (types.request_from_wire(wire) if srv_part == '_Request'
                       else types.response_from_wire(wire))
        expected = _rosbags_bytes(plain, spec.srv_type + srv_part)
        header = struct.pack('<Qq', wire.client_id, wire.sequence)
        assert wire.serialize() == expected[:4] + header + expected[4:]


def test_discovery_info_lists_the_node_with_every_table_endpoint(car, raw):
    info_type = msg_types.message_type('rmw_dds_common/msg/ParticipantEntitiesInfo')
    info = _reader(raw, 'ros_discovery_info', info_type, QOS_DISCOVERY_INFO_READER)
    publications = BuiltinDataReader(raw, BuiltinTopicDcpsPublication)
    entries = []
    writers = {}

    def listed():
        for sample in info.take(N=256):
            if sample.sample_info.valid_data:
                entries.extend(n for n in sample.node_entities_info_seq
                               if (n.node_namespace, n.node_name) == ('/', 'automobile'))
        for sample in publications.take(N=1024):
            if sample.sample_info.valid_data and sample.topic_name.startswith('rt/automobile/'):
                writers[sample.topic_name] = sample.key.bytes
        return entries and len(writers) >= len(itf.AUTOMOBILE_TOPICS)

    assert wait_for(listed)
    node_info = entries[-1]
    listed_writers = {bytes(g.data)[:16] for g in node_info.writer_gid_seq}
    assert set(writers.values()) <= listed_writers
    assert len(node_info.reader_gid_seq) >= len(itf.SERVICES)
    assert len(listed_writers) >= len(itf.SERVICES) + len(itf.TOPICS)


# ------------------------------------------------------------------------------- two cars

car1 = car_fixture(['odom'], 'car1', node='two_cars', name='car1')
car2 = car_fixture(['odom'], 'car2', node='two_cars', name='car2')


def test_two_car_world_serves_each_namespace_independently(car1, car2):
    assert car1.call('automobile/set_gear', 1).success
    assert car1.call('automobile/set_throttle', 0.0).success
    assert car1.call('automobile/get_gear').value == 1
    assert car2.call('automobile/get_gear').value == 0
    prius = load_car('ToyotaPrius')
    tesla = load_car('TeslaModel3')
    assert car1.call('automobile/get_dimensions').wheel_base == prius.wheelbase_m
    assert car2.call('automobile/get_dimensions').wheel_base == tesla.wheelbase_m
    # One shared world: stepping through either namespace advances both clocks.
    assert car2.call('robot/time_step', 20).success
    assert car1.time_s() == car2.time_s()


def test_odometry_moves_forward_after_set_cruising_speed_and_stepping(car1, car2):
    assert car1.call('automobile/set_cruising_speed', 20.0).success
    odom1 = car1.step_and_read('odom', 2000)
    odom2 = car2.step_and_read('odom', 0)
    assert odom1.header.frame_id == 'car1/odom'
    assert odom1.child_frame_id == 'car1/base_link'
    assert odom1.pose.pose.position.x > 1.0
    assert abs(odom1.pose.pose.position.y) < 0.2
    assert odom1.twist.twist.linear.x > 1.0
    assert abs(odom2.pose.pose.position.x) < 0.05
    assert abs(odom2.twist.twist.linear.x) < 0.05


def test_tf_static_holds_every_spawn_pose_in_one_latched_message(car1, car2):
    car1.subscribe('/tf_static')
    # /tf_static is global: other automobile nodes of this run publish their own message.
    msg = wait_for(lambda: next((m for m in car1.history['/tf_static']
                                 if any(t.child_frame_id == 'car1/odom' for t in m.transforms)),
                                None), spin=car1.node)
    assert msg
    poses = {t.child_frame_id: (t.header.frame_id, t.transform.translation.y)
             for t in msg.transforms}
    assert poses == {'car1/odom': ('world', 0.0), 'car2/odom': ('world', 6.0)}
    car2.subscribe('robot_description')
    urdf = wait_for(lambda: car2.latest.get('robot_description'), spin=car2.node)
    assert urdf and 'car2/base_link' in urdf.data


# ------------------------------------------------------------------------------- parameters

def test_bad_car_model_fails_clearly():
    process = NodeProcess('--ros-args', '-p', 'car_model:=NoSuchCar')
    try:
        assert process.wait(WAIT_S) != 0
    finally:
        process.stop()
    text = process.text()
    assert 'NoSuchCar' in text and 'ToyotaPrius' in text
    assert 'Traceback' not in text


def test_config_file_lists_every_parameter_with_its_default():
    data = read_yaml(os.path.join(REPO_ROOT, 'config', 'automobile.yaml'))
    assert data == {'automobile': {'ros__parameters': sim_params.defaults()}}


def test_time_step_is_refused_when_not_synchronous():
    # A namespace of its own, so that its services cannot answer the other tests' calls.
    app = AutomobileNode(['x', '--ros-args', '-r', '__ns:=/in_process'], transport='dds',
                         parameter_overrides={'real_time_factor': 0.0})
    try:
        response = app._handle_time_step(itf.service('robot/time_step'), None, 'robot/time_step',
                                         _Value(10), _Value(None))
        assert response.success is False
        assert math.isclose(app.world.time_s, 0.0)
    finally:
        app.close()


def test_misspelt_publish_period_is_warned_naming_publish_period_ms(capsys):
    # The case: `vehicle-sim run -- --ros-args -p publish_period:=0.02`.
    app = AutomobileNode(['x', '--ros-args', '-r', '__ns:=/misspelt', '-p',
                          'publish_period:=0.02'], transport='dds',
                         parameter_overrides={'synchronous': True})
    try:
        app.node.spin_once(0.0)
        app.node.spin_once(0.0)
        warnings = [line for line in capsys.readouterr().err.splitlines() if '[WARN]' in line]
        assert len(warnings) == 1
        assert 'ignored parameter override publish_period (did you mean publish_period_ms?)' \
            in warnings[0]
        assert ', '.join(sorted(sim_params.defaults())) in warnings[0]
    finally:
        app.close()


def test_parameters_are_read_only_at_run_time_except_use_sim_time():
    app = AutomobileNode(['x', '--ros-args', '-r', '__ns:=/param_rules'], transport='dds',
                         parameter_overrides={'synchronous': True})
    try:
        node = app.node
        (refused,) = node.set_parameters([Parameter('car_model', 'BmwX5')])
        assert (refused.successful, refused.reason) == (
            False, 'Trying to set a read-only parameter: car_model.')
        assert node.get_parameter('car_model') == 'Car'
        (accepted,) = node.set_parameters([Parameter('use_sim_time', True)])
        assert accepted.successful and node.get_parameter('use_sim_time') is True
    finally:
        app.close()


class _Value:
    def __init__(self, value):
        self.value = value
        self.success = None


def test_setter_refusals_of_the_strict_ros_policy_in_process():
    # Odd input, ROS column (docs/deviations.md): a tiny indicator period (it used to answer true,
    # then crash the
    # next step) and a cruising speed beyond the top speed (the core stores it; a service must
    # not) answer success=false and change nothing.
    app = AutomobileNode(['x', '--ros-args', '-r', '__ns:=/in_process_setters'],
                         transport='dds', parameter_overrides={'real_time_factor': 0.0})
    try:
        vehicle = app._vehicles[0]
        logic = vehicle.logic

        def call(name, value):
            return app._handle_setter(itf.service(name), vehicle, name, _Value(value),
                                      _Value(None)).success

        assert call('automobile/set_hazard_flashers', True) is True
        for period in (5e-324, 1e-300, 9.99e-4):
            assert call('automobile/set_indicator_period', period) is False
        assert logic.indicator_period_s == 0.34
        app.step(2)
        assert math.isclose(app.world.time_s, 0.02)
        top_kmh = logic.max_cruising_speed_kmh
        for speed in (top_kmh + 1e-6, -top_kmh - 1.0, 300.0):
            assert call('automobile/set_cruising_speed', speed) is False
        assert logic.target_cruising_speed_kmh == 0.0
        assert call('automobile/set_cruising_speed', top_kmh) is True
        assert call('automobile/set_indicator_period', 1e-3) is True
        app.step(2)
        assert (logic.target_cruising_speed_kmh, logic.indicator_period_s) == (top_kmh, 1e-3)
    finally:
        app.close()


def test_ros_interface_doc_contains_the_generated_tables():
    with open(os.path.join(REPO_ROOT, 'docs', 'ros_interface.md'), encoding='utf-8') as stream:
        text = stream.read()
    assert itf.interface_table_markdown() in text
    assert itf.sensor_table_markdown() in text
    assert sim_params.parameter_table_markdown() in text


@pytest.mark.parametrize('world', ['default', 'two_cars'])
def test_shipped_worlds_parse(world):
    settings = sim_params.SimSettings('ToyotaPrius', world, 0.0, 0.0, 0.0, 10, 0, 1.0, False, 1.0)
    vehicles = sim_params.world_vehicles(settings)
    assert vehicles and all(v.model for v in vehicles)
    if world == 'default':
        assert [(v.name, v.namespace, v.model) for v in vehicles] == [('Car', '', 'ToyotaPrius')]


@pytest.mark.parametrize('data', [
    {}, {'vehicles': []}, {'vehicles': [{'name': 'a', 'model': 'NoSuchCar'}]},
    {'vehicles': [{'namespace': 'a'}, {'namespace': '/a'}]},
    {'vehicles': [{'pose': {'x': float('nan')}}]}, {'vehicles': [{'colour': 'red'}]},
    {'vehicles': [{'namespace': '1bad'}]},
])
def test_invalid_world_file_is_refused_with_a_reason(data):
    with pytest.raises(InvalidParameterError, match='w.yaml'):
        sim_params.parse_world(data, 'w.yaml', 'Car')


def test_publish_period_not_a_multiple_of_the_step_is_refused():
    with pytest.raises(InvalidParameterError, match='publish_period_ms'):
        AutomobileNode(['x', '--ros-args', '-r', '__ns:=/in_process_bad', '-p',
                        'publish_period_ms:=15'], transport='dds')


def test_free_running_node_steps_while_serving_and_refuses_time_step(tester):
    process = NodeProcess('--ros-args', '-r', '__ns:=/fast', '-p', 'real_time_factor:=0.0')
    try:
        fast = VehicleClient(tester, 'fast')   # node namespace /fast: same names
        start = fast.time_s()
        assert wait_for(lambda: fast.time_s() > start + 0.5)
        assert fast.call('robot/time_step', 10).success is False
        assert fast.call('automobile/set_gear', 1).success
        assert fast.call('automobile/get_gear').value == 1
    finally:
        process.stop()
