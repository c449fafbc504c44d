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
``ros_discovery_info`` samples (``rmw_dds_common/msg/ParticipantEntitiesInfo``) in both layouts.

Humble's Gid is ``char[24]`` (the 16-byte GUID, then 8 zero bytes), Jazzy's ``char[16]``; both
distributions use the same DDS type name, so a reader gets either. A typed reader of one layout
reads the other one wrongly without an error (a Humble sample read as Jazzy's is a participant
with no nodes; a Jazzy sample read as Humble's is garbage), so samples are written and read
here, as CDR bytes, in the layout the caller asks for (:func:`encode`) or in the one they fit
(:func:`decode`): a sample fits a layout when it parses to its last byte, strings and all.
"""

from dataclasses import dataclass
import struct
from typing import Iterable, List, Sequence, Tuple

from vehicle_msgs_py import distro

# Encapsulation headers of plain (XCDR1) CDR, as rmw_cyclonedds writes it.
CDR_LE = b'\x00\x01'
CDR_BE = b'\x00\x00'


@dataclass(frozen=True)
class NodeEntry:
    """One node of a participant: its name and the GUIDs (16 bytes) of its endpoints."""

    namespace: str
    name: str
    reader_gids: Tuple[bytes, ...] = ()
    writer_gids: Tuple[bytes, ...] = ()


@dataclass(frozen=True)
class ParticipantEntities:
    """A decoded sample: the participant GUID, its nodes, and the Gid size it was written with."""

    gid: bytes
    nodes: Tuple[NodeEntry, ...]
    gid_size: int

    @property
    def distro(self) -> str:
        """``'humble'`` for 24-byte Gids, ``'jazzy'`` (Iron and later too) for 16-byte ones."""
        return distro.HUMBLE if self.gid_size == distro.GID_SIZES[distro.HUMBLE] else \
            distro.JAZZY


class UndecodableSample(ValueError):
    """A sample that fits neither layout."""


# --------------------------------------------------------------------------------------------
# Writing

def _gid(guid: bytes, size: int) -> bytes:
    guid = bytes(guid)
    if len(guid) > size:
        raise ValueError(f'a GUID of {len(guid)} bytes does not fit a {size}-byte Gid')
    return guid + bytes(size - len(guid))


def encode(gid: bytes, nodes: Iterable[NodeEntry], gid_size: int) -> bytes:
    """
    Return the CDR bytes (little endian, with the 4-byte encapsulation header) of a sample.

    :param gid: the participant GUID (16 bytes); zero-padded to ``gid_size``.
    :param gid_size: 16 (Jazzy) or 24 (Humble).
    """
    out = bytearray()

    def align4():
        out.extend(bytes(-len(out) % 4))

    def string(text: str):
        raw = text.encode('utf-8') + b'\x00'
        align4()
        out.extend(struct.pack('<I', len(raw)))
        out.extend(raw)

    def gids(values: Sequence[bytes]):
        align4()
        out.extend(struct.pack('<I', len(values)))
        for value in values:
            out.extend(_gid(value, gid_size))

    out.extend(_gid(gid, gid_size))
    nodes = list(nodes)
    align4()
    out.extend(struct.pack('<I', len(nodes)))
    for node in nodes:
        string(node.namespace)
        string(node.name)
        gids(node.reader_gids)
        gids(node.writer_gids)
    padding = -len(out) % 4
    out.extend(bytes(padding))
    # Like Cyclone: the low two bits of the options say how many padding bytes end the sample.
    return CDR_LE + bytes((0, padding)) + bytes(out)


# --------------------------------------------------------------------------------------------
# Reading

class _Reader:
    def __init__(self, body: bytes, order: str):
        self.body = body
        self.order = order
        self.pos = 0

    def take(self, count: int) -> bytes:
        end = self.pos + count
        if count < 0 or end > len(self.body):
            raise UndecodableSample('sample ends early')
        chunk = self.body[self.pos:end]
        self.pos = end
        return chunk

    def count(self, element_size: int) -> int:
        self.take(-self.pos % 4)
        (value,) = struct.unpack(self.order + 'I', self.take(4))
        if value * element_size > len(self.body) - self.pos:
            raise UndecodableSample(f'sequence of {value} does not fit the sample')
        return value

    def string(self) -> str:
        raw = self.take(self.count(1))
        if not raw or raw[-1] != 0:
            raise UndecodableSample('string without its terminating NUL')
        try:
            return raw[:-1].decode('utf-8')
        except UnicodeDecodeError:
            raise UndecodableSample('string is not UTF-8') from None


def _parse(body: bytes, order: str, gid_size: int) -> ParticipantEntities:
    reader = _Reader(body, order)
    gid = reader.take(gid_size)[:distro.GUID_SIZE]
    nodes: List[NodeEntry] = []
    for _ in range(reader.count(8)):   # a node is at least two empty strings
        namespace = reader.string()
        name = reader.string()
        readers = tuple(reader.take(gid_size)[:distro.GUID_SIZE]
                        for _ in range(reader.count(gid_size)))
        writers = tuple(reader.take(gid_size)[:distro.GUID_SIZE]
                        for _ in range(reader.count(gid_size)))
        nodes.append(NodeEntry(namespace, name, readers, writers))
    rest = body[reader.pos:]
    if len(rest) > 3 or any(rest):
        raise UndecodableSample(f'{len(rest)} bytes left over')
    return ParticipantEntities(gid, tuple(nodes), gid_size)


def decode(data: bytes, prefer: int = 16) -> ParticipantEntities:
    """
    Decode a sample in the layout it fits, trying the Gid size ``prefer`` first.

    :raises UndecodableSample: when it fits neither (truncated, not UTF-8, not CDR...).
    """
    data = bytes(data)
    if len(data) < 4 or data[:2] not in (CDR_LE, CDR_BE):
        raise UndecodableSample('not a plain CDR sample')
    order = '<' if data[:2] == CDR_LE else '>'
    body = data[4:]
    sizes = sorted(set(distro.GID_SIZES.values()), key=lambda size: size != prefer)
    reasons = []
    for size in sizes:
        try:
            return _parse(body, order, size)
        except (UndecodableSample, struct.error) as exc:
            reasons.append(f'{size}-byte Gid: {exc}')
    raise UndecodableSample('; '.join(reasons))
