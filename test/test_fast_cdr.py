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
from vehicle_sim.transport.dds import fast_cdr

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
    assert set(fast_cdr.SERIALIZERS) == {m.CLOCK, m.FLOAT64_STAMPED}
    assert fast_cdr.SERIALIZERS[m.FLOAT64_STAMPED] is fast_cdr.float64_stamped
    assert fast_cdr.SERIALIZERS[m.CLOCK] is fast_cdr.clock


def test_frame_id_with_nul_is_refused_at_build_time():
    with pytest.raises(ValueError, match='NUL'):
        fast_cdr.float64_stamped('base\0link')
