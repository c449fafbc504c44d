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
Reading a recording: its summary (``bag info``) and its messages in log-time order (``play``).

A recording is an MCAP file or a rosbag2 folder, as ``ros2 bag record`` writes it (a
``metadata.yaml`` and the storage files it names, split by size or duration).

An MCAP file is read through the ``mcap`` library. A file that is not MCAP, is cut in the
middle of a record, or whose records do not decode (a corrupted chunk, a wrong CRC) gives a
:class:`RecordingError` of one line naming the file and what is wrong. A file without a summary
that ends on a record boundary (a recording stopped by a failed write) is read from its
records, and says so (``BagInfo.complete`` is False).

A folder is read as rosbag2 reads it, through rosbags' rosbag2 reader: its metadata (topics,
types, counts, QoS, time span) and its files one after the other in the metadata's order, in
any storage rosbags reads (``mcap``, ``sqlite3``), compressed per file or per message or not.
Its MCAP files' chunks are summarised as a single file's are.
"""

from dataclasses import dataclass, field
import os
from pathlib import PurePath
import struct
from typing import Dict, Iterable, Iterator, List, Optional, Tuple

import yaml

from vehicle_sim.recording import qos_text
from vehicle_sim.recording.bag_writer import EXTRA_HINT, RecordingError

MAGIC = b'\x89MCAP0\r\n'
# The file of a rosbag2 folder that names its storage files and describes its topics.
METADATA = 'metadata.yaml'
_RECORD_HEAD = struct.Struct('<BQ')
_OP_FOOTER = 0x02


@dataclass
class TopicInfo:
    """A channel of the file: its topic, type, message count and recorded QoS text."""

    name: str
    ros_type: str
    count: int
    offered_qos_profiles: str = ''
    message_encoding: str = 'cdr'


@dataclass
class BagInfo:
    """What ``vehicle-sim bag info`` prints."""

    path: str
    size: int
    profile: str
    library: str
    topics: List[TopicInfo] = field(default_factory=list)
    message_count: int = 0
    start_ns: Optional[int] = None
    end_ns: Optional[int] = None
    compression: str = ''
    chunk_count: Optional[int] = 0       # None: not known (a folder's non-MCAP files)
    complete: bool = True
    files: List[str] = field(default_factory=list)
    storage_id: str = 'mcap'

    @property
    def duration_ns(self) -> int:
        return 0 if self.start_ns is None else self.end_ns - self.start_ns

    def topic(self, name: str) -> TopicInfo:
        for topic in self.topics:
            if topic.name == name:
                return topic
        raise KeyError(name)


def _require_reader():
    try:
        from mcap import reader
    except ImportError:
        raise RecordingError(f'reading recordings needs the mcap package: {EXTRA_HINT}') \
            from None
    return reader


def _broken(path: str, error: BaseException) -> RecordingError:
    text = str(error).strip().splitlines()[0] if str(error).strip() else type(error).__name__
    return RecordingError(f'{path}: not a readable MCAP recording: {text}')


def _open(path: str):
    try:
        stream = open(path, 'rb')
    except OSError as error:
        raise RecordingError(f'{path}: cannot open it: {error.strerror}') from None
    head = stream.read(len(MAGIC))
    if head != MAGIC:
        stream.close()
        raise RecordingError(f'{path}: not an MCAP file (it does not start with the MCAP '
                             'magic bytes)')
    stream.seek(0)
    return stream


def _framing(stream, size: int) -> Tuple[bool, Optional[str]]:
    """
    Walk the record frames after the magic; return (has a footer, why it is cut or None).

    Each record is an opcode, a 64-bit length and that many bytes.
    """
    offset = len(MAGIC)
    stream.seek(offset)
    while offset < size:
        head = stream.read(_RECORD_HEAD.size)
        if len(head) < _RECORD_HEAD.size:
            return False, f'cut short at byte {size}: a record header at byte {offset} is ' \
                          'incomplete'
        opcode, length = _RECORD_HEAD.unpack(head)
        end = offset + _RECORD_HEAD.size + length
        if end > size:
            return False, (f'cut short at byte {size}: the record at byte {offset} (opcode '
                           f'0x{opcode:02x}) needs {end - size} more bytes')
        if opcode == _OP_FOOTER:
            return True, None
        offset = end
        stream.seek(offset)
    return False, None


def read_info(path: str) -> BagInfo:
    """
    Return the summary of the recording at ``path``: an MCAP file or a rosbag2 folder.

    :raises RecordingError: (one line) for a missing, truncated or corrupted file, a folder
        without rosbag2's metadata or with metadata that rosbags cannot read.
    """
    if os.path.isdir(path):
        return _folder_info(path)
    reader_module = _require_reader()
    stream = _open(path)
    size = os.path.getsize(path)
    try:
        has_footer, cut = _framing(stream, size)
        if cut is not None:
            raise RecordingError(f'{path}: not a readable MCAP recording: {cut}')
        stream.seek(0)
        try:
            if has_footer:
                reader = reader_module.SeekingReader(stream, validate_crcs=True)
                header = reader.get_header()
                summary = reader.get_summary()
                if summary is not None and summary.statistics is not None:
                    return _from_summary(path, size, header, summary)
            stream.seek(0)
            return _from_records(path, size, reader_module, stream, has_footer)
        except RecordingError:
            raise
        except Exception as error:  # noqa: BLE001 - any decoding failure is a broken file
            raise _broken(path, error) from None
    finally:
        stream.close()


def _topics(channels, schemas, counts: Dict[int, int]) -> List[TopicInfo]:
    topics = []
    for channel_id, channel in sorted(channels.items()):
        schema = schemas.get(channel.schema_id)
        topics.append(TopicInfo(channel.topic, schema.name if schema else '',
                                counts.get(channel_id, 0),
                                channel.metadata.get('offered_qos_profiles', ''),
                                channel.message_encoding))
    return topics


def _from_summary(path, size, header, summary) -> BagInfo:
    stats = summary.statistics
    compressions = sorted({c.compression for c in summary.chunk_indexes})
    count = stats.message_count
    return BagInfo(
        path, size, header.profile, header.library,
        _topics(summary.channels, summary.schemas, stats.channel_message_counts), count,
        stats.message_start_time if count else None, stats.message_end_time if count else None,
        ', '.join(c or 'none' for c in compressions), stats.chunk_count, True,
        [os.path.basename(path)])


def _from_records(path, size, reader_module, stream, has_footer) -> BagInfo:
    from mcap.records import Channel, Chunk, Header, Message, Schema
    from mcap.stream_reader import breakup_chunk, StreamReader
    schemas, channels, counts = {}, {}, {}
    header = None
    start = end = None
    total = 0
    compressions = set()
    chunks = 0
    for record in _until_end(StreamReader(stream, validate_crcs=True, emit_chunks=True).records):
        if isinstance(record, Chunk):
            chunks += 1
            compressions.add(record.compression)
            records = breakup_chunk(record, validate_crc=True)
        else:
            records = (record,)
        for item in records:
            if isinstance(item, Header):
                header = item
            elif isinstance(item, Schema):
                schemas[item.id] = item
            elif isinstance(item, Channel):
                channels[item.id] = item
            elif isinstance(item, Message):
                counts[item.channel_id] = counts.get(item.channel_id, 0) + 1
                total += 1
                start = item.log_time if start is None else min(start, item.log_time)
                end = item.log_time if end is None else max(end, item.log_time)
    if header is None:
        raise RecordingError(f'{path}: not a readable MCAP recording: no header record after '
                             'the magic bytes')
    return BagInfo(path, size, header.profile, header.library,
                   _topics(channels, schemas, counts), total, start, end,
                   ', '.join(c or 'none' for c in sorted(compressions)), chunks,
                   complete=has_footer, files=[os.path.basename(path)])


def _until_end(records):
    # A file without a footer ends after its last record (checked by _framing): the mcap
    # reader's EndOfFile there is the end, not a fault.
    from mcap.exceptions import EndOfFile
    try:
        yield from records
    except EndOfFile:
        return


def _open_folder(path: str):
    """Return rosbags' reader of the rosbag2 folder at ``path``, open."""
    from rosbags.rosbag2 import Reader
    if not os.path.isfile(os.path.join(path, METADATA)):
        raise RecordingError(f'{path}: a folder without {METADATA}: not a rosbag2 recording')
    reader = Reader(path)
    try:
        reader.open()
    except Exception as error:  # noqa: BLE001 - rosbags' errors of a folder it cannot read
        raise _broken_folder(path, error) from None
    return reader


def _broken_folder(path: str, error: BaseException) -> RecordingError:
    text = str(error).strip().splitlines()[0] if str(error).strip() else type(error).__name__
    return RecordingError(f'{path}: not a readable rosbag2 recording: {text}')


def _folder_files(path: str) -> Tuple[str, List[str]]:
    """Return the folder's storage identifier and its files in order (names, as rosbags)."""
    with open(os.path.join(path, METADATA), encoding='utf-8') as stream:
        metadata = yaml.safe_load(stream)['rosbag2_bagfile_information']
    return (metadata['storage_identifier'],
            [PurePath(name).name for name in metadata['relative_file_paths']])


def _folder_info(path: str) -> BagInfo:
    reader = _open_folder(path)
    try:
        storage_id, names = _folder_files(path)
        count = reader.message_count
        topics = [TopicInfo(c.topic, c.msgtype, c.msgcount,
                            qos_text.from_rosbags(c.ext.offered_qos_profiles),
                            c.ext.serialization_format) for c in reader.connections]
        # rosbags' end time is one past the last message.
        start, end = (reader.start_time, reader.end_time - 1) if count else (None, None)
        mode, kind = reader.compression_mode, reader.compression_format
    finally:
        reader.close()
    paths = [os.path.join(path, name) for name in names]
    info = BagInfo(path, sum(os.path.getsize(p) for p in paths), 'ros2', 'rosbag2', topics,
                   count, start, end, f'{kind} ({mode})' if mode else 'none', None, True, names,
                   storage_id)
    if storage_id == 'mcap' and mode != 'file':
        # Each MCAP file of the folder is a whole one: its chunks, and whether it was cut.
        parts = [read_info(p) for p in paths]
        chunked = sorted({name for part in parts if part.chunk_count
                          for name in part.compression.split(', ')})
        info.compression = ', '.join(chunked or ['none'])
        if mode:    # 'message': each message compressed too
            info.compression += f' ({kind} per message)'
        info.chunk_count = sum(part.chunk_count for part in parts)
        info.complete = all(part.complete for part in parts)
    return info


def _folder_messages(path: str, info: BagInfo, topics: Optional[Iterable[str]],
                     start_ns: Optional[int]) -> Iterator[Tuple[TopicInfo, int, int, bytes]]:
    by_name = {topic.name: topic for topic in info.topics}
    reader = _open_folder(path)
    try:
        wanted = None if topics is None else set(topics)
        connections = [c for c in reader.connections if wanted is None or c.topic in wanted]
        if not connections:     # rosbags reads an empty selection as every topic
            return
        messages = reader.messages(connections, start=start_ns)
        while True:
            try:
                connection, log_ns, data = next(messages)
            except StopIteration:
                return
            except Exception as error:  # noqa: BLE001 - a broken file midway
                raise _broken_folder(path, error) from None
            # A rosbag2 folder keeps one time per message (rosbags reads no publish time).
            yield by_name[connection.topic], log_ns, log_ns, bytes(data)
    finally:
        reader.close()


def iter_messages(path: str, topics: Optional[Iterable[str]] = None,
                  start_ns: Optional[int] = None
                  ) -> Iterator[Tuple[TopicInfo, int, int, bytes]]:
    """
    Yield ``(topic, log_time_ns, publish_time_ns, data)`` in log-time order.

    A rosbag2 folder's files are read one after the other, in the order its metadata names
    them (as rosbag2 plays them).

    :param topics: only these topic names (None: all).
    :param start_ns: only messages logged at or after this time.
    :raises RecordingError: (one line) when the file is broken, also midway.
    """
    info = read_info(path)
    if os.path.isdir(path):
        yield from _folder_messages(path, info, topics, start_ns)
        return
    by_name = {topic.name: topic for topic in info.topics}
    reader_module = _require_reader()
    from mcap.exceptions import EndOfFile as EOFError_
    stream = _open(path)
    try:
        if info.complete:
            reader = reader_module.SeekingReader(stream, validate_crcs=True)
        else:
            reader = reader_module.NonSeekingReader(stream, validate_crcs=True)
        # Without a summary: in file order (a recorder writes in log-time order), not sorted
        # in memory.
        messages = reader.iter_messages(topics=list(topics) if topics is not None else None,
                                        starting_at=start_ns, log_time_order=info.complete)
        while True:
            try:
                _, channel, message = next(messages)
            except StopIteration:
                return
            except EOFError_ as error:
                if info.complete:
                    raise _broken(path, error) from None
                return
            except Exception as error:  # noqa: BLE001 - a broken chunk midway
                raise _broken(path, error) from None
            yield by_name[channel.topic], message.log_time, message.publish_time, message.data
    finally:
        stream.close()
