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


"""The fast serializers' bytes equal rosbags' CDR and cyclonedds-python's of the same message."""

import math

import pytest

from vehicle_msgs_py import message_type, to_rosbags, typestore
from vehicle_sim.ros import messages as m
from vehicle_sim.transport import fast_cdr

STAMPS = [(0, 0), (1, 999_999_999), (-5, 3), (2**31 - 1, 4_000_000_000), (1_700_000_000, 1)]
VALUES = [0.0, -0.0, 27.5, -1e-3, 1e300, -math.inf, math.inf, math.nan, 5, True]
FRAME_IDS = ['', 'a', 'ab', 'abc', 'abcd', 'abcde', 'abcdef', 'abcdefg', 'abcdefgh',
             'vehicle/base_link', 'é']


def rosbags_bytes(obj):
    return bytes(typestore().serialize_cdr(to_rosbags(obj), type(obj).__ros_type__))


def stamp(sec, nanosec):
    return message_type(m.TIME)(sec=sec, nanosec=nanosec)


def same_bytes(fast, message):
    # NaN compares unequal as a value; the bytes compare what goes on the wire.
    return fast == rosbags_bytes(message) == message.serialize()


@pytest.mark.parametrize('sec, nanosec', STAMPS)
def test_clock_bytes_equal_rosbags_and_cyclonedds(sec, nanosec):
    t = stamp(sec, nanosec)
    data = fast_cdr.clock()(t)
    assert same_bytes(data, m.clock_builder(message_type)(t))
    assert len(data) == 12


@pytest.mark.parametrize('frame_id', FRAME_IDS)
def test_float64_stamped_bytes_equal_rosbags_for_every_frame_id_alignment(frame_id):
    serialize = fast_cdr.float64_stamped(frame_id)
    build = m.float64_stamped_builder(message_type, frame_id)
    for (sec, nanosec), value in zip(STAMPS * 2, VALUES):
        t = stamp(sec, nanosec)
        data = serialize(t, value)
        assert same_bytes(data, build(t, value)), (sec, nanosec, value)
        decoded = message_type(m.FLOAT64_STAMPED).deserialize(data)
        assert decoded.header.frame_id == frame_id
        assert (decoded.header.stamp.sec, decoded.header.stamp.nanosec) == (sec, nanosec)
        assert decoded.data == float(value) or (math.isnan(value) and math.isnan(decoded.data))


def test_serializers_take_the_builders_constants_and_values():
    assert set(fast_cdr.SERIALIZERS) == {m.CLOCK, m.FLOAT64_STAMPED, m.ODOMETRY, m.JOINT_STATE,
                                        m.TF_MESSAGE}
    assert fast_cdr.SERIALIZERS[m.FLOAT64_STAMPED] is fast_cdr.float64_stamped
    assert fast_cdr.SERIALIZERS[m.CLOCK] is fast_cdr.clock


def test_frame_id_with_nul_is_refused_at_build_time():
    with pytest.raises(ValueError, match='NUL'):
        fast_cdr.float64_stamped('base\0link')


POSES = [((1.0, -2.5, 0.0), (0.0, 0.0, 0.38268343236508984, 0.9238795325112867),
          (3.0, -0.0, 1e-9), (math.nan, 0.25, -math.inf)),
         ((1e12, 0.0, -7.0), (1.0, 0.0, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 0.5))]


@pytest.mark.parametrize('frame_id', FRAME_IDS)
@pytest.mark.parametrize('child', ['', 'c', 'car1/base_link', 'abcdefg'])
def test_odometry_bytes_equal_rosbags_for_every_pair_of_frame_id_lengths(frame_id, child):
    serialize = fast_cdr.odometry(frame_id, child)
    build = m.odometry_builder(message_type, frame_id, child)
    for (sec, nanosec), pose in zip(STAMPS, POSES):
        t = stamp(sec, nanosec)
        assert same_bytes(serialize(t, *pose), build(t, *pose)), (sec, nanosec, pose)


NAME_LISTS = [(), ('a',), ('front_left', 'front_right'), ('ab', 'abc', 'abcd', 'abcde', 'x')]


@pytest.mark.parametrize('names', NAME_LISTS)
@pytest.mark.parametrize('frame_id', ['', 'ab', 'abcd', 'base'])
def test_joint_state_bytes_equal_rosbags_for_names_frames_and_lengths(names, frame_id):
    serialize = fast_cdr.joint_state(names, frame_id)
    build = m.joint_state_builder(message_type, names, frame_id)
    n = len(names)
    cases = [([0.5 * i for i in range(n)], [-1e300 * i for i in range(n)]),
             ([math.nan] * n, [math.inf] * n), ([], []), ([1.0], []), ([], [2.0, 3.0])]
    for (sec, nanosec), (positions, velocities) in zip(STAMPS, cases):
        t = stamp(sec, nanosec)
        for _ in range(2):     # the second call takes the cached layout
            assert same_bytes(serialize(t, positions, velocities),
                              build(t, positions, velocities)), (positions, velocities)


FRAME_PAIRS = [(), (('odom', 'base_link'),), (('', ''), ('a', 'abcd')),
               (('car1/odom', 'car1/base_link'), ('ab', 'abc'), ('abcde', 'abcdefg'),
                ('world', 'x'))]


@pytest.mark.parametrize('frames', FRAME_PAIRS)
def test_tf_message_bytes_equal_rosbags_for_every_frame_id_alignment(frames):
    serialize = fast_cdr.tf_message(frames)
    build = m.tf_message_builder(message_type, frames)
    for (sec, nanosec), pose in zip(STAMPS, POSES * 3):
        t = stamp(sec, nanosec)
        poses = [(tuple(x + i for x in pose[0]), pose[1]) for i in range(len(frames))]
        data = serialize(t, poses)
        assert same_bytes(data, build(t, poses)), (sec, nanosec, poses)
        decoded = message_type(m.TF_MESSAGE).deserialize(data)
        assert [(s.header.frame_id, s.child_frame_id) for s in decoded.transforms] == \
            [tuple(pair) for pair in frames]


@pytest.mark.parametrize('little_endian', [True, False])
@pytest.mark.parametrize('sec, nanosec', STAMPS)
def test_leading_stamp_reads_the_stamp_of_clock_and_header_led_messages(sec, nanosec,
                                                                          little_endian):
    t = stamp(sec, nanosec)
    messages = (m.clock_builder(message_type)(t),
                m.float64_stamped_builder(message_type, 'abc')(t, 2.5),
                message_type(m.ODOMETRY)(header=message_type('std_msgs/msg/Header')(
                    stamp=t, frame_id='odom')))
    for message in messages:
        data = bytes(typestore().serialize_cdr(to_rosbags(message), type(message).__ros_type__,
                                               little_endian=little_endian))
        assert fast_cdr.leading_stamp_ns(data) == sec * 1_000_000_000 + nanosec


def test_leading_stamp_is_none_for_other_encapsulations_and_short_data():
    data = fast_cdr.clock()(stamp(3, 4))
    assert fast_cdr.leading_stamp_ns(data) == 3_000_000_004
    assert fast_cdr.leading_stamp_ns(b'\x00\x09' + data[2:]) is None    # XCDR2 delimited
    assert fast_cdr.leading_stamp_ns(data[:10]) is None


def _fixed_services():
    from vehicle_msgs_py import types
    types.typestore()
    found = []
    for srv in sorted(types._services):
        st = types.service_types(srv)
        for part in ('request', 'response'):
            fields = st.wire_primitives(part)
            if fields is not None and fast_cdr.fixed_layout([k for _, k in fields]):
                found.append((st, part, fields))
    return found


# Extremes of each primitive, as the generic serializer takes them.
EXTREMES = {'bool': [False, True], 'int8': [-128, 127], 'uint8': [0, 255],
            'int16': [-32768, 32767], 'uint16': [0, 65535], 'int32': [-2**31, 2**31 - 1],
            'uint32': [0, 2**32 - 1], 'int64': [-2**63, 2**63 - 1], 'uint64': [0, 2**64 - 1],
            'float32': [-1.5, 3.25], 'float64': [-math.inf, 1e-300]}


def test_fixed_layout_bytes_equal_cyclonedds_for_every_fixed_service_wire_type():
    from vehicle_sim.transport.dds.services import _WireCodec
    cases = _fixed_services()
    names = {st.srv_type for st, _, _ in cases}
    assert {'vehicle_msgs/srv/SetInt', 'vehicle_msgs/srv/GetFloat',
            'vehicle_msgs/srv/GetDimensions', 'std_srvs/srv/Empty'} <= names
    for st, part, fields in cases:
        wire_cls = st.request_wire if part == 'request' else st.response_wire
        codec = _WireCodec.of(st, part)
        for pick in (0, 1):
            wire = wire_cls(**{name: EXTREMES[kind][pick] for name, kind in fields})
            data = codec.encode(wire)
            assert data == wire.serialize(), (st.srv_type, part, pick)
            assert codec.decode(data) == wire_cls.deserialize(data) == wire


def test_wire_codec_decodes_big_endian_the_generic_way_and_leaves_refused_values_to_it():
    import struct

    from vehicle_msgs_py import types
    from vehicle_sim.transport.dds.services import _WireCodec
    st = types.service_types('vehicle_msgs/srv/SetInt')
    codec = _WireCodec.of(st, 'request')
    big = b'\x00\x00\x00\x00' + struct.pack('>QqI', 7, 8, 9)   # CDR_BE: client, seq, value
    assert codec.decode(big) == st.request_wire(client_id=7, sequence=8, value=9)
    with pytest.raises(Exception):
        codec.decode(codec.encode(st.request_wire(client_id=1, sequence=2, value=3))[:-1])
    assert codec.encode(st.request_wire(client_id=1, sequence=2, value=2**31)) is None
    assert codec.encode(st.request_wire(client_id=1, sequence=2, value='x')) is None
    assert _WireCodec.of(types.service_types('std_srvs/srv/Trigger'), 'response') is None
