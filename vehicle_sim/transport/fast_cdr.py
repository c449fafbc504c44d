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
XCDR1 little endian with the 4-byte encapsulation header, what ``DdsPublisher.publish_serialized``
writes and what rclpy's ``Publisher.publish`` takes as bytes (``rcl_publish_serialized_message``);
test/test_transport_fast_cdr.py checks them equal to rosbags' and cyclonedds-python's CDR. Both
transports use them; this module needs nothing but ``struct``.

Layout: after the encapsulation header, offsets count from 0; a primitive is aligned to its
size; a string is its uint32 length (NUL included), its bytes and the NUL. A Header-led type has
a constant part from the frame id's length field up to the first field after it (the frame id
and the padding that aligns that field), packed once at build time.
"""

import struct

CDR_LE = b'\x00\x01\x00\x00'     # encapsulation header: CDR, little endian, no options


def _pad(offset: int, align: int) -> int:
    """Return how many padding bytes align ``offset`` to ``align``."""
    return -offset % align


def _strings(offset: int, texts, align: int) -> bytes:
    """
    Return the bytes of the strings ``texts`` in a row from ``offset``, and the padding after.

    :param offset: where the first string's length field starts (a multiple of 4).
    :param align: the alignment of the field after the last string.
    """
    out = b''
    for text in texts:
        data = text.encode('utf-8')
        if b'\0' in data:
            raise ValueError(f'a CDR string cannot hold a NUL character: {text!r}')
        out += bytes(_pad(offset + len(out), 4)) + struct.pack('<I', len(data) + 1) + data + b'\0'
    return out + bytes(_pad(offset + len(out), align))


# The stamp a Header-led message or a Clock starts with, by encapsulation kind (the first two
# bytes: plain CDR and XCDR2 plain, big and little endian; both put it right after the header).
_LEADING_STAMP = {b'\x00\x00': struct.Struct('>iI'), b'\x00\x01': struct.Struct('<iI'),
                  b'\x00\x06': struct.Struct('>iI'), b'\x00\x07': struct.Struct('<iI')}


def leading_stamp_ns(data: bytes):
    """
    Return the stamp [ns] a serialized Header-led message or Clock starts with, without decoding.

    None for an encapsulation kind other than plain CDR or XCDR2 plain (decode the message then).
    """
    layout = _LEADING_STAMP.get(bytes(data[:2]))
    if layout is None or len(data) < 12:
        return None
    sec, nanosec = layout.unpack_from(data, 4)
    return sec * 1_000_000_000 + nanosec


# ROS primitive type -> struct code (the size is the CDR alignment: XCDR1 aligns up to 8);
# byte and char are left to the generic serializer (their Python values vary by binding).
_PRIMITIVES = {'bool': '?', 'int8': 'b', 'uint8': 'B', 'int16': 'h',
               'uint16': 'H', 'int32': 'i', 'uint32': 'I', 'int64': 'q', 'uint64': 'Q',
               'float32': 'f', 'float64': 'd'}


def fixed_layout(kinds):
    """
    Return ``(pack, unpack)`` for a struct of fixed-size primitives, or None for other structs.

    :param kinds: the fields' ROS primitive types in order (e.g. ``['uint64', 'int64', 'bool']``).
    ``pack(*values)`` returns the CDR bytes (encapsulation header included, no trailing padding,
    as cyclonedds-python writes them); ``unpack(data)`` returns the values of little-endian
    plain-CDR bytes, or None for another encapsulation (decode those the generic way).
    """
    layout, offset = '<4s', 0
    for kind in kinds:
        code = _PRIMITIVES.get(kind)
        if code is None:
            return None
        size = struct.calcsize('<' + code)
        pad = _pad(offset, size)
        layout += 'x' * pad + code
        offset += pad + size
    packer = struct.Struct(layout)
    pack_into_bytes, unpack_from = packer.pack, packer.unpack_from

    def pack(*values):
        return pack_into_bytes(CDR_LE, *values)

    def unpack(data):
        if data[:2] != CDR_LE[:2] or len(data) < packer.size:
            return None
        return unpack_from(data)[1:]
    return pack, unpack


def clock():
    """Return ``serialize(stamp)``: rosgraph_msgs/Clock (``stamp`` a builtin_interfaces/Time)."""
    pack = struct.Struct('<4siI').pack

    def serialize(stamp):
        return pack(CDR_LE, stamp.sec, stamp.nanosec)
    return serialize


def float64_stamped(frame_id: str):
    """Return ``serialize(stamp, value)``: vehicle_msgs/Float64Stamped in ``frame_id``."""
    middle = _strings(8, (frame_id,), 8)
    pack = struct.Struct(f'<4siI{len(middle)}sd').pack

    def serialize(stamp, value):
        return pack(CDR_LE, stamp.sec, stamp.nanosec, middle, value)
    return serialize


def odometry(frame_id: str, child_frame_id: str):
    """
    Return ``serialize(stamp, xyz, q, linear, angular)``: nav_msgs/Odometry, zero covariances.

    The same constants and values as ``odometry_builder``.
    """
    middle = _strings(8, (frame_id, child_frame_id), 8)
    zeros = bytes(36 * 8)
    pack = struct.Struct(f'<4siI{len(middle)}s7d{len(zeros)}s6d{len(zeros)}s').pack

    def serialize(stamp, xyz, q, linear, angular):
        return pack(CDR_LE, stamp.sec, stamp.nanosec, middle, xyz[0], xyz[1], xyz[2],
                    q[0], q[1], q[2], q[3], zeros, linear[0], linear[1], linear[2],
                    angular[0], angular[1], angular[2], zeros)
    return serialize


def joint_state(names, frame_id: str = ''):
    """
    Return ``serialize(stamp, positions, velocities)``: sensor_msgs/JointState, no efforts.

    The same constants and values as ``joint_state_builder``; the layout of each pair of
    lengths is computed once.
    """
    names = tuple(names)
    head = _strings(8, (frame_id,), 4) + struct.pack('<I', len(names))
    head += _strings(8 + len(head), names, 4)
    packs = {}

    def layout(n_positions, n_velocities):
        offset = 8 + len(head)                 # the position count (4-aligned)
        fmt = f'<4siI{len(head)}sI'
        offset += 4
        for count, follows in ((n_positions, 'I'), (n_velocities, 'I')):
            pad = _pad(offset, 8) if count else 0
            fmt += f'{pad}x{count}d' + follows
            offset += pad + 8 * count + 4
        return struct.Struct(fmt).pack

    def serialize(stamp, positions, velocities):
        key = (len(positions), len(velocities))
        pack = packs.get(key)
        if pack is None:
            pack = packs[key] = layout(*key)
        return pack(CDR_LE, stamp.sec, stamp.nanosec, head, key[0], *positions, key[1],
                    *velocities, 0)
    return serialize


def tf_message(frames):
    """
    Return ``serialize(stamp, poses)``: tf2_msgs/TFMessage, one transform per (parent, child).

    The same constants and values as ``tf_message_builder``. The frame ids are constant, so
    the whole layout (each transform's frame ids and paddings) is packed once here; a call packs
    the stamp and the seven numbers of each pose.
    """
    frames = tuple(frames)
    fmt, offset, middles = '<4sI', 4, []        # offset: after the sequence length
    for pair in frames:
        pad = _pad(offset, 4)                     # each TransformStamped starts 4-aligned
        middle = _strings(offset + pad + 8, pair, 8)
        middles.append(middle)
        fmt += f'{pad}xiI{len(middle)}s7d'
        offset += pad + 8 + len(middle) + 7 * 8
    pack = struct.Struct(fmt).pack
    count = len(frames)

    def serialize(stamp, poses):
        sec, nanosec = stamp.sec, stamp.nanosec
        values = [CDR_LE, count]
        for middle, (xyz, q) in zip(middles, poses):
            values += (sec, nanosec, middle, xyz[0], xyz[1], xyz[2], q[0], q[1], q[2], q[3])
        return pack(*values)
    return serialize


def cdr_string(text: str) -> bytes:
    """Return a CDR string's bytes: its uint32 length (NUL included), its UTF-8 and the NUL."""
    data = text.encode('utf-8')
    if b'\0' in data:
        raise ValueError(f'a CDR string cannot hold a NUL character: {text!r}')
    return struct.pack('<I', len(data) + 1) + data + b'\0'


_ZEROS = tuple(bytes(n) for n in range(8))


class CdrWriter:
    """
    Little-endian XCDR1 bytes of a message of variable shape, written part by part.

    For messages whose layout changes with their content (sequences of structs): each
    :meth:`pack` aligns to its first field and appends a ``struct.Struct``'s bytes, whose own
    fields the caller lays out (explicit ``x`` padding, as in the factories above).
    :meth:`data` returns the message's bytes, encapsulation header first.
    """

    __slots__ = ('_parts', '_offset')

    U32 = struct.Struct('<I')

    def __init__(self):
        self._parts = [CDR_LE]
        self._offset = 0

    def pack(self, align: int, layout: struct.Struct, *values) -> None:
        """Append ``layout.pack(*values)`` at the next offset aligned to ``align``."""
        pad = -self._offset % align
        if pad:
            self._parts.append(_ZEROS[pad])
        self._parts.append(layout.pack(*values))
        self._offset += pad + layout.size

    def raw(self, align: int, data: bytes) -> None:
        """Append bytes packed before (a constant part) at the next offset aligned to ``align``."""
        pad = -self._offset % align
        if pad:
            self._parts.append(_ZEROS[pad])
        self._parts.append(data)
        self._offset += pad + len(data)

    def data(self) -> bytes:
        return b''.join(self._parts)


# ROS type -> serializer factory (the constants of the type's message builder).
SERIALIZERS = {
    'rosgraph_msgs/msg/Clock': clock,
    'vehicle_msgs/msg/Float64Stamped': float64_stamped,
    'nav_msgs/msg/Odometry': odometry,
    'sensor_msgs/msg/JointState': joint_state,
    'tf2_msgs/msg/TFMessage': tf_message,
}
