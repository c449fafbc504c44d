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
CDR layout, names and hashes of the generated message types (vehicle_msgs_py).

The independent reference is rosbags' CDR serializer: for every type the bytes that
cyclonedds-python's ``serialize()`` produces must equal rosbags' ``serialize_cdr`` of the same
message. Both write the 4-byte encapsulation header ``00 01 00 00`` (little-endian host) and
neither adds trailing padding (rmw pads the sample to a multiple of 4 when it writes, a
transport concern), so the comparison is of the complete byte strings, header included.
"""

import struct
import sys

import pytest

from vehicle_msgs_py import (
    dds_type_name,
    from_rosbags,
    known_services,
    known_types,
    message_type,
    service_types,
    to_rosbags,
    type_hash,
    typestore,
)
from vehicle_msgs_py.catalog import definitions
from vehicle_msgs_py.types import Nodetype

pytestmark = pytest.mark.skipif(sys.byteorder != 'little', reason='examples are little-endian')

LE_HEADER = bytes.fromhex('00010000')

# Non-trivial values per primitive, near the range limits so that sign and width errors show.
_PRIMITIVE_SAMPLES = {
    'bool': [True, False],
    'byte': [0xAB, 0x01],
    'char': [0x7F, 0x41],
    'int8': [-100, 7],
    'uint8': [200, 3],
    'int16': [-30000, 12],
    'uint16': [60000, 5],
    'int32': [-2_000_000_000, 42],
    'uint32': [4_000_000_000, 9],
    'int64': [-9_000_000_000_000_000_000, 11],
    'uint64': [2**64 - 2, 13],
    'float32': [1.5, -2.25],  # exactly representable, so round trips compare equal
    'float64': [27.5, -1e-3],
}


def _sample_value(desc, salt):
    """Deterministic non-trivial value for one field description of the type store."""
    kind, rest = desc
    if kind == Nodetype.BASE:
        base, bound = rest
        if base == 'string':
            text = f'frame_{salt}' + 'x' * (salt % 4)  # lengths vary, so padding varies
            return text[:bound] if bound else text
        return _PRIMITIVE_SAMPLES[base][salt % 2]
    if kind == Nodetype.NAME:
        return sample_message(rest, salt)
    element, size = rest
    count = size if kind == Nodetype.ARRAY else (min(size, 2) if size else 3)
    items = [_sample_value(element, salt + i) for i in range(count)]
    if kind == Nodetype.ARRAY and element[0] == Nodetype.BASE and \
            element[1][0] in ('byte', 'char', 'uint8'):
        return bytes(items)  # cyclonedds-python's representation of octet arrays
    return items


def sample_message(ros_type, salt=1):
    """Build our message ``ros_type`` with every field set to a non-default value."""
    fields = typestore().fielddefs[ros_type][1]
    values = {name: _sample_value(desc, salt + i) for i, (name, desc) in enumerate(fields)}
    return message_type(ros_type)(**values)


def rosbags_bytes(obj):
    return bytes(typestore().serialize_cdr(to_rosbags(obj), type(obj).__ros_type__))


STANDARD_TYPES = [
    'std_msgs/msg/Header',
    'std_msgs/msg/String',
    'std_msgs/msg/Float64',
    'std_msgs/msg/Float64MultiArray',
    'builtin_interfaces/msg/Time',
    'rosgraph_msgs/msg/Clock',
    'nav_msgs/msg/Odometry',
    'sensor_msgs/msg/JointState',
    'tf2_msgs/msg/TFMessage',
    'geometry_msgs/msg/Twist',
    'geometry_msgs/msg/TwistStamped',
    'rcl_interfaces/msg/Log',
    'rcl_interfaces/msg/ParameterEvent',
    'rcl_interfaces/msg/ParameterDescriptor',
    'rmw_dds_common/msg/Gid',
    'rmw_dds_common/msg/NodeEntitiesInfo',
    'rmw_dds_common/msg/ParticipantEntitiesInfo',
    # the sensors' types (docs/sensors.md)
    'sensor_msgs/msg/LaserScan',
    'sensor_msgs/msg/PointCloud2',
    'sensor_msgs/msg/Imu',
    'sensor_msgs/msg/NavSatFix',
    'sensor_msgs/msg/Range',
    'sensor_msgs/msg/Image',
    'sensor_msgs/msg/CameraInfo',
]
OWN_MESSAGES = [d.ros_type for d in definitions() if d.kind == 'msg']
OWN_SERVICES = [d.ros_type for d in definitions() if d.kind == 'srv']
SERVICE_PARTS = [srv + part for srv in OWN_SERVICES for part in ('_Request', '_Response')]


@pytest.mark.parametrize('ros_type', STANDARD_TYPES + OWN_MESSAGES + SERVICE_PARTS)
def test_serialize_of_sample_message_equals_rosbags_bytes(ros_type):
    message = sample_message(ros_type)
    data = message.serialize()
    assert data[:4] == LE_HEADER
    assert data == rosbags_bytes(message)


@pytest.mark.parametrize('ros_type', STANDARD_TYPES + OWN_MESSAGES + SERVICE_PARTS)
def test_sample_message_round_trips_through_both_serializers(ros_type):
    message = sample_message(ros_type)
    data = message.serialize()
    assert type(message).deserialize(data) == message
    assert from_rosbags(typestore().deserialize_cdr(data, ros_type)) == message


@pytest.mark.parametrize('ros_type', known_types())
def test_every_known_type_builds_with_defaults_and_matches_rosbags(ros_type):
    message = message_type(ros_type)()
    assert message.serialize() == rosbags_bytes(message)


@pytest.mark.parametrize('srv_type', OWN_SERVICES)
def test_service_wire_types_are_header_then_plain_fields(srv_type):
    types = service_types(srv_type)
    client_id = -5  # a signed instance handle (signed in cyclonedds-python) is masked to uint64
    for plain, to_wire, from_wire in (
            (sample_message(srv_type + '_Request'), types.request_to_wire,
             types.request_from_wire),
            (sample_message(srv_type + '_Response', salt=2), types.response_to_wire,
             types.response_from_wire)):
        wire = to_wire(plain, client_id, 123456789)
        expected = LE_HEADER + struct.pack('<Qq', 2**64 - 5, 123456789) + rosbags_bytes(plain)[4:]
        assert wire.serialize() == expected
        assert from_wire(type(wire).deserialize(expected)) == (2**64 - 5, 123456789, plain)


def test_service_types_names_are_ros_wire_names():
    types = service_types('vehicle_msgs/srv/SetFloat')
    assert types.request_wire.__idl__.idl_transformed_typename == \
        'vehicle_msgs::srv::dds_::SetFloat_Request_'
    assert types.response_wire.__idl__.idl_transformed_typename == \
        'vehicle_msgs::srv::dds_::SetFloat_Response_'
    assert [f for f in types.request.__dataclass_fields__] == ['value']
    assert [f for f in types.response_wire.__dataclass_fields__] == \
        ['client_id', 'sequence', 'success']


def test_known_services_include_own_parameter_and_std_services():
    assert set(OWN_SERVICES) <= set(known_services())
    for name in ('GetParameters', 'SetParameters', 'SetParametersAtomically', 'ListParameters',
                 'DescribeParameters', 'GetParameterTypes'):
        assert f'rcl_interfaces/srv/{name}' in known_services()


# Worked XCDR1 examples (alignment and padding), checked against rosbags.
def test_float64_example_matches_reference_bytes():
    data = message_type('std_msgs/msg/Float64')(data=27.5).serialize()
    assert data == bytes.fromhex('00 01 00 00 00 00 00 00 00 80 3b 40')


def test_header_example_matches_reference_bytes():
    time = message_type('builtin_interfaces/msg/Time')(sec=1700000000, nanosec=123456789)
    data = message_type('std_msgs/msg/Header')(stamp=time, frame_id='base_link').serialize()
    assert data == bytes.fromhex(
        '00 01 00 00 00 f1 53 65 15 cd 5b 07 0a 00 00 00 62 61 73 65 5f 6c 69 6e 6b 00')


def test_clock_example_matches_reference_bytes():
    time = message_type('builtin_interfaces/msg/Time')(sec=42, nanosec=5)
    data = message_type('rosgraph_msgs/msg/Clock')(clock=time).serialize()
    assert data == bytes.fromhex('00 01 00 00 2a 00 00 00 05 00 00 00')


def test_setbool_request_example_matches_reference_bytes():
    types = service_types('std_srvs/srv/SetBool')
    wire = types.request_to_wire(types.request(data=True), 0x1122334455667788, 7)
    # The reference adds zero padding to 24 bytes when rmw writes; serialize() stops at 21.
    assert wire.serialize() == bytes.fromhex(
        '00 01 00 00 88 77 66 55 44 33 22 11 07 00 00 00 00 00 00 00 01')


def test_setbool_response_layout_matches_reference_offsets():
    types = service_types('std_srvs/srv/SetBool')
    wire = types.response_to_wire(types.response(success=True, message='ok'), 1, 2)
    payload = wire.serialize()[4:]
    # 0 guid, 8 seq, 16 success, 17-19 pad, 20 length incl. NUL, 24 chars, NUL.
    assert payload[16:17] == b'\x01'
    assert payload[17:20] == bytes(3)
    assert payload[20:24] == struct.pack('<I', 3)
    assert payload[24:] == b'ok\x00'


def test_participant_entities_info_matches_real_sample_layout():
    # Byte layout of one real sample (rmw_dds_common): node /speed_node, one writer.
    gid_type = message_type('rmw_dds_common/msg/Gid')
    participant = bytes(range(16))
    writer = bytes(range(100, 116))
    node = message_type('rmw_dds_common/msg/NodeEntitiesInfo')(
        node_namespace='/', node_name='speed_node', writer_gid_seq=[gid_type(data=writer)])
    info = message_type('rmw_dds_common/msg/ParticipantEntitiesInfo')(
        gid=gid_type(data=participant), node_entities_info_seq=[node])
    expected = (LE_HEADER + participant + bytes.fromhex('01000000') +
                bytes.fromhex('02000000 2f00 0000') +
                bytes.fromhex('0b000000') + b'speed_node\x00' + b'\x00' +
                bytes.fromhex('00000000') + bytes.fromhex('01000000') + writer)
    assert info.serialize() == expected


@pytest.mark.parametrize('ros_type, dds_name', [
    ('std_msgs/msg/Float64', 'std_msgs::msg::dds_::Float64_'),
    ('std_msgs/Float64', 'std_msgs::msg::dds_::Float64_'),
    ('vehicle_msgs/msg/Float64Stamped', 'vehicle_msgs::msg::dds_::Float64Stamped_'),
    ('std_srvs/srv/SetBool_Request', 'std_srvs::srv::dds_::SetBool_Request_'),
    ('std_srvs/srv/SetBool_Response', 'std_srvs::srv::dds_::SetBool_Response_'),
    ('rmw_dds_common/msg/ParticipantEntitiesInfo',
     'rmw_dds_common::msg::dds_::ParticipantEntitiesInfo_'),
])
def test_dds_type_name_follows_rmw_mangling(ros_type, dds_name):
    assert dds_type_name(ros_type) == dds_name


@pytest.mark.parametrize('ros_type', STANDARD_TYPES + OWN_MESSAGES)
def test_message_class_carries_the_mangled_dds_type_name(ros_type):
    assert message_type(ros_type).__idl__.idl_transformed_typename == dds_type_name(ros_type)


# rmw_dds_common's graph messages; ParticipantEntitiesInfo is the value seen on a real Jazzy graph.
@pytest.mark.parametrize('ros_type, digest', [
    ('std_msgs/msg/Float64', '705ba9c3d1a09df43737eb67095534de36fd426c0587779bda2bc51fe790182a'),
    ('std_msgs/msg/String', 'df668c740482bbd48fb39d76a70dfd4bd59db1288021743503259e948f6b1a18'),
    ('std_srvs/srv/SetBool_Request',
     'c62fbb99d94e1b25e8ef9e109f9581956bb1b3361a45a4e5810c36a90d29932e'),
    ('std_srvs/srv/SetBool_Response',
     'd0814e7f7b4880ab77e9c57426c7aa1562ab69f11eef8e2e968812f9cbd0b059'),
    ('rmw_dds_common/msg/ParticipantEntitiesInfo',
     '91a0593bacdcc50ea9bdcf849a938b128412cc1ea821245c663bcd26f83c295e'),
    ('std_msgs/msg/Header', 'f49fb3ae2cf070f793645ff749683ac6b06203e41c891e17701b1cb597ce6a01'),
    ('builtin_interfaces/msg/Time',
     'b106235e25a4c5ed35098aa0a61a3ee9c9b18d197f398b0e4206cea9acf9c197'),
    ('rosgraph_msgs/msg/Clock',
     '692f7a66e93a3c83e71765d033b60349ba68023a8c689a79e48078bcb5c58564'),
    ('tf2_msgs/msg/TFMessage', 'e369d0f05a23ae52508854b66f6aa0437f3449d652e8cbf22d5abe85d020f087'),
    # the sensors' types, as Jazzy's rosidl generates them (Range with Iron's variance field)
    ('sensor_msgs/msg/LaserScan',
     '64c191398013af96509d518dac71d5164f9382553fce5c1f8cca5be7924bd828'),
    ('sensor_msgs/msg/PointCloud2',
     '9198cabf7da3796ae6fe19c4cb3bdd3525492988c70522628af5daa124bae2b5'),
    ('sensor_msgs/msg/Imu', '7d9a00ff131080897a5ec7e26e315954b8eae3353c3f995c55faf71574000b5b'),
    ('sensor_msgs/msg/NavSatFix',
     '62223ab3fe210a15976021da7afddc9e200dc9ec75231c1b6a557fc598a65404'),
    ('sensor_msgs/msg/Range', 'b42b62562e93cbfe9d42b82fe5994dfa3d63d7d5c90a317981703f7388adff3a'),
    ('sensor_msgs/msg/Image', 'd31d41a9a4c4bc8eae9be757b0beed306564f7526c88ea6a4588fb9582527d47'),
    ('sensor_msgs/msg/CameraInfo',
     'b3dfd68ff46c9d56c80fd3bd4ed22c7a4ddce8c8348f2f59c299e73118e7e275'),
    # our own: a regression value (REP 2011 over the definition in vehicle_msgs_py)
    ('vehicle_msgs/msg/Collision',
     '5c9d44765ea447598239f00bcf08b6efe0bf454d3a34926b2c7d1260ecdae1b5'),
])
def test_type_hash_equals_known_jazzy_value(ros_type, digest):
    assert type_hash(ros_type) == 'RIHS01_' + digest


@pytest.mark.parametrize('ros_type', OWN_MESSAGES + SERVICE_PARTS + OWN_SERVICES)
def test_type_hash_of_own_types_is_well_formed(ros_type):
    value = type_hash(ros_type)
    assert value.startswith('RIHS01_') and len(value) == 7 + 64
    assert int(value[7:], 16) >= 0


@pytest.mark.parametrize('ros_type, constants', [
    ('autoware_vehicle_msgs/msg/GearCommand',
     {'NONE': 0, 'NEUTRAL': 1, 'DRIVE': 2, 'DRIVE_2': 3, 'DRIVE_18': 19, 'REVERSE': 20,
      'REVERSE_2': 21, 'PARK': 22, 'LOW': 23, 'LOW_2': 24}),
    ('autoware_vehicle_msgs/msg/GearReport',
     {'NONE': 0, 'NEUTRAL': 1, 'DRIVE': 2, 'REVERSE': 20, 'PARK': 22, 'LOW': 23}),
    ('autoware_vehicle_msgs/msg/TurnIndicatorsCommand',
     {'NO_COMMAND': 0, 'DISABLE': 1, 'ENABLE_LEFT': 2, 'ENABLE_RIGHT': 3}),
    ('autoware_vehicle_msgs/msg/TurnIndicatorsReport',
     {'DISABLE': 1, 'ENABLE_LEFT': 2, 'ENABLE_RIGHT': 3}),
    ('autoware_vehicle_msgs/msg/HazardLightsCommand',
     {'NO_COMMAND': 0, 'DISABLE': 1, 'ENABLE': 2}),
    ('autoware_vehicle_msgs/msg/HazardLightsReport', {'DISABLE': 1, 'ENABLE': 2}),
    ('autoware_vehicle_msgs/msg/ControlModeReport',
     {'NO_COMMAND': 0, 'AUTONOMOUS': 1, 'AUTONOMOUS_STEER_ONLY': 2,
      'AUTONOMOUS_VELOCITY_ONLY': 3, 'MANUAL': 4, 'DISENGAGED': 5, 'NOT_READY': 6}),
    ('autoware_vehicle_msgs/srv/ControlModeCommand_Request',
     {'NO_COMMAND': 0, 'AUTONOMOUS': 1, 'AUTONOMOUS_STEER_ONLY': 2,
      'AUTONOMOUS_VELOCITY_ONLY': 3, 'MANUAL': 4}),
    ('rcl_interfaces/srv/ListParameters_Request', {'DEPTH_RECURSIVE': 0}),
    ('rcl_interfaces/msg/Log', {'DEBUG': 10, 'INFO': 20, 'WARN': 30, 'ERROR': 40, 'FATAL': 50}),
])
def test_message_constants_are_class_attributes(ros_type, constants):
    cls = message_type(ros_type)
    assert {name: getattr(cls, name) for name in constants} == constants
    assert not set(constants) & set(cls.__dataclass_fields__)


@pytest.mark.parametrize('ros_type, fields', [
    ('vehicle_msgs/msg/Float64Stamped', ['header', 'data']),
    ('vehicle_msgs/msg/WheelCommand', ['velocity']),
    ('vehicle_msgs/msg/DifferentialCommand', ['header', 'left_wheel', 'right_wheel']),
    ('vehicle_msgs/msg/Collision', ['header', 'other', 'normal_force']),
    ('vehicle_msgs/srv/GetDimensions_Response',
     ['track_front', 'track_rear', 'wheel_base', 'front_wheel_radius', 'rear_wheel_radius']),
    ('vehicle_msgs/srv/SetPose_Request', ['pose']),
    ('vehicle_msgs/srv/SetPose_Response', ['success', 'message']),
    ('autoware_control_msgs/msg/Control', ['stamp', 'control_time', 'lateral', 'longitudinal']),
    ('autoware_control_msgs/msg/Longitudinal',
     ['stamp', 'control_time', 'velocity', 'acceleration', 'jerk', 'is_defined_acceleration',
      'is_defined_jerk']),
    ('autoware_auto_control_msgs/msg/AckermannControlCommand',
     ['stamp', 'lateral', 'longitudinal']),
    ('autoware_vehicle_msgs/msg/VelocityReport',
     ['header', 'longitudinal_velocity', 'lateral_velocity', 'heading_rate']),
    ('ackermann_msgs/msg/AckermannDrive',
     ['steering_angle', 'steering_angle_velocity', 'speed', 'acceleration', 'jerk']),
    ('ackermann_msgs/msg/AckermannDriveStamped', ['header', 'drive']),
])
def test_fields_are_the_ros_field_names_in_order(ros_type, fields):
    assert list(message_type(ros_type).__dataclass_fields__) == fields


def test_default_message_is_zero_except_rosidl_defaults():
    odom = message_type('nav_msgs/msg/Odometry')()
    assert odom.header.frame_id == '' and odom.pose.covariance == [0.0] * 36
    assert odom.pose.pose.orientation.w == 1.0  # geometry_msgs/Quaternion: float64 w 1
    assert message_type('rmw_dds_common/msg/Gid')().data == bytes(16)


def test_defaults_are_not_shared_between_instances():
    joint_state_type = message_type('sensor_msgs/msg/JointState')
    first = joint_state_type()
    first.name.append('wheel')
    assert joint_state_type().name == []


def test_message_type_is_cached():
    assert message_type('std_msgs/msg/Header') is message_type('std_msgs/Header')
    assert service_types('vehicle_msgs/srv/SetInt') is service_types('vehicle_msgs/srv/SetInt')


@pytest.mark.parametrize('bad', ['no_such_pkg/msg/Nope', 'std_msgs', 'vehicle_msgs/srv/SetFloat'])
def test_message_type_of_unknown_or_service_name_raises(bad):
    with pytest.raises(ValueError):
        message_type(bad)


def test_service_types_of_unknown_service_raises():
    with pytest.raises(ValueError, match='unknown ROS service'):
        service_types('vehicle_msgs/srv/Nope')


def test_collision_example_matches_hand_computed_bytes():
    # header (stamp 12 s 5e8 ns, frame 'base_link'), other 'wall', normal_force 1234.5 N
    collision = message_type('vehicle_msgs/msg/Collision')(
        header=message_type('std_msgs/msg/Header')(
            stamp=message_type('builtin_interfaces/msg/Time')(sec=12, nanosec=500_000_000),
            frame_id='base_link'),
        other='wall', normal_force=1234.5)
    expected = (LE_HEADER + struct.pack('<iI', 12, 500_000_000)
                + struct.pack('<I', 10) + b'base_link\x00' + bytes(2)   # 22 -> pad to 24
                + struct.pack('<I', 5) + b'wall\x00' + bytes(7)         # 33 -> pad to 40
                + struct.pack('<d', 1234.5))
    assert collision.serialize() == expected == rosbags_bytes(collision)


def test_message_definition_is_the_ros2msg_text_with_its_dependencies():
    from vehicle_msgs_py import message_definition
    text = message_definition('geometry_msgs/msg/PoseStamped')
    blocks = text.split('=' * 80 + '\n')
    assert blocks[0] == 'std_msgs/Header header\ngeometry_msgs/Pose pose\n'
    headers = [block.splitlines()[0] for block in blocks[1:]]
    assert headers == ['MSG: std_msgs/Header', 'MSG: builtin_interfaces/Time',
                       'MSG: geometry_msgs/Pose', 'MSG: geometry_msgs/Point',
                       'MSG: geometry_msgs/Quaternion']
    own = message_definition('vehicle_msgs/msg/Float64Stamped')
    assert own.startswith('std_msgs/Header header\n')
    assert 'MSG: builtin_interfaces/Time\nint32 sec\nuint32 nanosec' in own


def test_message_definition_refuses_an_unknown_type():
    from vehicle_msgs_py import message_definition
    with pytest.raises(ValueError, match='nav_msgs/msg/NoSuchType'):
        message_definition('nav_msgs/msg/NoSuchType')
