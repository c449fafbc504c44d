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
Fast CDR serializers: the bytes of a message packed with ``struct``, no message object built.

Each ``<type>`` factory here takes the same constants as its message builder in
``vehicle_sim.ros.messages`` and returns ``serialize(*values)`` taking the same per-call values,
so a row's converter can use either one (:data:`SERIALIZERS`, by ROS type). The bytes are plain
XCDR1 little endian with the 4-byte encapsulation header, as ``DdsPublisher.publish_serialized``
writes them; test/test_fast_cdr.py checks them equal to rosbags' and cyclonedds-python's CDR.

Layout: after the encapsulation header, offsets count from 0; a primitive is aligned to its
size; a string is its uint32 length (NUL included), its bytes and the NUL. A Header-led type has
a constant part from the frame id's length field up to the first field after it (the frame id
and the padding that aligns that field), packed once at build time.
"""

import struct

CDR_LE = b'\x00\x01\x00\x00'     # encapsulation header: CDR, little endian, no options


def _string_tail(offset: int, text: str, align: int) -> bytes:
    """
    Return the bytes of string ``text`` at ``offset`` and the padding after it.

    :param offset: where the string's length field starts (a multiple of 4).
    :param align: the alignment of the field after the string.
    """
    data = text.encode('utf-8')
    if b'\0' in data:
        raise ValueError(f'a CDR string cannot hold a NUL character: {text!r}')
    body = struct.pack('<I', len(data) + 1) + data + b'\0'
    end = offset + len(body)
    return body + bytes(-end % align)


def clock():
    """Return ``serialize(stamp)``: rosgraph_msgs/Clock (``stamp`` a builtin_interfaces/Time)."""
    pack = struct.Struct('<4siI').pack

    def serialize(stamp):
        return pack(CDR_LE, stamp.sec, stamp.nanosec)
    return serialize


def float64_stamped(frame_id: str):
    """Return ``serialize(stamp, value)``: vehicle_msgs/Float64Stamped in ``frame_id``."""
    middle = _string_tail(8, frame_id, 8)
    pack = struct.Struct(f'<4siI{len(middle)}sd').pack

    def serialize(stamp, value):
        return pack(CDR_LE, stamp.sec, stamp.nanosec, middle, value)
    return serialize


# ROS type -> serializer factory (the constants of the type's message builder).
SERIALIZERS = {
    'rosgraph_msgs/msg/Clock': clock,
    'vehicle_msgs/msg/Float64Stamped': float64_stamped,
}
