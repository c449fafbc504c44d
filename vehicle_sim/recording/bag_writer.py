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
The MCAP file of a recording, written through the ``mcap`` library in the ROS 2 profile.

As rosbag2_storage_mcap writes it: header profile ``ros2``; a schema per message type
(``ros2msg``, the type's definition followed by every type it uses); a channel per topic
(``cdr``, metadata ``offered_qos_profiles`` and ``topic_type_hash``); messages with their log
and publish times in compressed chunks; at the end, a ``rosbag2`` metadata record holding the
bag's ``serialized_metadata`` (as ``ros2 bag info`` reads it) and the summary with the chunk
index and statistics.

A write that fails (a full disk) stops the recording: the file is cut back to the end of its
last complete record, so that it holds a valid MCAP data section (header, schemas, channels
and whole chunks) without a summary; :mod:`.bag_reader` reads such a file and says it was cut
short, and ``mcap recover`` rewrites it with a summary.
"""

import os
import time
from typing import Callable, Dict, Optional

from vehicle_sim import __version__
from vehicle_sim.core.specs.errors import VehicleSimError

PROFILE = 'ros2'
SCHEMA_ENCODING = 'ros2msg'
MESSAGE_ENCODING = 'cdr'
COMPRESSIONS = ('zstd', 'lz4', 'none')
DEFAULT_COMPRESSION = 'zstd'
# rosbag2_storage_mcap's default chunk size (1 MiB, its "default" preset).
DEFAULT_CHUNK_SIZE = 1024 * 1024
# rosbag2's metadata version written into the ``rosbag2`` record (Jazzy).
ROSBAG2_VERSION = 9
ROS_DISTRO = 'jazzy'
EXTRA_HINT = "pip install 'vehicle_sim[record]'"


class RecordingError(VehicleSimError):
    """A recording that cannot be written, or a file that cannot be read or played."""


def require_mcap():
    """
    Return the ``mcap`` writer module, or explain which extra to install.

    :raises RecordingError: when the ``mcap`` package is missing.
    """
    try:
        from mcap import writer
    except ImportError:
        raise RecordingError(f'recording needs the mcap package: {EXTRA_HINT}') from None
    return writer


def check_output(path: str) -> str:
    """
    Check that a recording can be created at ``path`` before anything starts.

    :return: the path.
    :raises RecordingError: naming the path, when it is a folder or its folder is missing or
        not writable.
    """
    folder = os.path.dirname(os.path.abspath(path))
    if os.path.isdir(path):
        raise RecordingError(f'{path}: is a folder, not a file')
    if not os.path.isdir(folder):
        raise RecordingError(f'{path}: its folder {folder} does not exist')
    if not os.access(folder, os.W_OK | os.X_OK) or (
            os.path.exists(path) and not os.access(path, os.W_OK)):
        raise RecordingError(f'{path}: not writable')
    return path


class _RecordFile:
    """
    The output file as the mcap writer sees it: a write is whole or undone.

    A write that fails (an OSError such as ENOSPC) truncates the file back to the end of the
    previous write, which the mcap writer makes a record boundary, and raises.
    """

    def __init__(self, raw):
        self._raw = raw
        self.size = 0

    def write(self, data) -> int:
        view = memoryview(data)
        done = 0
        try:
            while done < len(view):
                written = self._raw.write(view[done:])
                if not written:
                    raise OSError(f'wrote nothing of {len(view) - done} bytes')
                done += written
        except OSError:
            self._undo()
            raise
        self.size += done
        return done

    def _undo(self) -> None:
        try:
            self._raw.seek(self.size)
            self._raw.truncate(self.size)
        except (OSError, ValueError):
            pass

    def tell(self) -> int:
        return self.size

    def flush(self) -> None:
        self._raw.flush()

    def close(self) -> None:
        self._raw.close()


class BagWriter:
    """
    One MCAP recording in the ROS 2 profile.

    :param path: the file to create (replaced if it exists).
    :param compression: ``zstd``, ``lz4`` or ``none``.
    :param chunk_size: uncompressed bytes of a chunk before it is written.
    :param opener: ``opener(path)`` -> an unbuffered binary file (tests: a disk that fills).
    :raises RecordingError: for an unknown compression, a missing ``mcap`` package or a file
        that cannot be created.
    """

    def __init__(self, path: str, compression: str = DEFAULT_COMPRESSION,
                 chunk_size: int = DEFAULT_CHUNK_SIZE,
                 opener: Optional[Callable[[str], object]] = None):
        mcap_writer = require_mcap()
        if compression not in COMPRESSIONS:
            raise RecordingError(f'compression {compression!r}: use one of '
                                 f'{", ".join(COMPRESSIONS)}')
        kind = {'zstd': mcap_writer.CompressionType.ZSTD, 'lz4': mcap_writer.CompressionType.LZ4,
                'none': mcap_writer.CompressionType.NONE}[compression]
        self.path = path
        self.compression = compression
        try:
            raw = opener(path) if opener is not None else open(path, 'wb', buffering=0)
        except OSError as error:
            raise RecordingError(f'{path}: cannot create it: {error.strerror or error}') from None
        self._file = _RecordFile(raw)
        try:
            self._writer = mcap_writer.Writer(self._file, chunk_size=chunk_size, compression=kind)
        except Exception as error:  # noqa: BLE001 - the library's missing compressor
            self._file.close()
            raise RecordingError(f'{path}: {error}; {EXTRA_HINT}') from None
        self._schemas: Dict[str, int] = {}
        self.channels: Dict[str, int] = {}
        self._topics: Dict[int, tuple] = {}     # channel id -> (topic, type, qos text)
        self.counts: Dict[int, int] = {}
        self.message_count = 0
        self.start_ns: Optional[int] = None
        self.end_ns: Optional[int] = None
        self.error: Optional[str] = None
        self.closed = False
        self._guard(lambda: self._writer.start(profile=PROFILE,
                                               library=f'vehicle_sim {__version__}'))
        if self.error:
            self._file.close()
            raise RecordingError(self.error)

    @property
    def failed(self) -> bool:
        """True once a write failed: the recording stopped there."""
        return self.error is not None

    def _guard(self, action) -> bool:
        if self.error is not None or self.closed:
            return False
        try:
            action()
        except OSError as error:
            self._fail(error)
            return False
        return True

    def _fail(self, error: OSError) -> None:
        reason = error.strerror or str(error)
        self.error = (f'recording {self.path} stopped: {reason}, after '
                      f'{self.message_count} messages; the file keeps the complete chunks '
                      f'written before ({self._file.size} bytes, without its summary; the '
                      'messages of the chunk being written are lost)')

    def add_channel(self, topic: str, ros_type: str, offered_qos_profiles: str) -> int:
        """
        Register a topic; return its channel id (the same one for a topic seen again).

        :raises RecordingError: for a type whose definition is unknown.
        """
        if topic in self.channels:
            return self.channels[topic]
        from vehicle_msgs_py import message_definition, type_hash
        schema_id = self._schemas.get(ros_type)
        if schema_id is None:
            try:
                definition = message_definition(ros_type)
            except (KeyError, ValueError) as error:
                raise RecordingError(f'{topic}: type {ros_type} has no known definition '
                                     f'({error})') from None
            schema_id = self._writer.register_schema(ros_type, SCHEMA_ENCODING,
                                                     definition.encode())
            self._schemas[ros_type] = schema_id
        metadata = {'offered_qos_profiles': offered_qos_profiles}
        try:
            metadata['topic_type_hash'] = type_hash(ros_type)
        except (KeyError, ValueError):
            pass
        channel_id = self._writer.register_channel(topic, MESSAGE_ENCODING, schema_id, metadata)
        self.channels[topic] = channel_id
        self._topics[channel_id] = (topic, ros_type, offered_qos_profiles)
        self.counts[channel_id] = 0
        return channel_id

    def write(self, channel_id: int, data: bytes, log_time_ns: int,
              publish_time_ns: int) -> bool:
        """
        Add one message; return False when the recording has stopped (a failed write).

        :param data: the CDR bytes with their encapsulation header.
        """
        if self.error is not None or self.closed:
            return False
        count = self.counts[channel_id]
        try:
            self._writer.add_message(channel_id, log_time_ns, data, publish_time_ns,
                                     sequence=count)
        except OSError as error:
            self._fail(error)
            return False
        self.counts[channel_id] = count + 1
        self.message_count += 1
        if self.start_ns is None or log_time_ns < self.start_ns:
            self.start_ns = log_time_ns
        if self.end_ns is None or log_time_ns > self.end_ns:
            self.end_ns = log_time_ns
        return True

    def queue(self, channel_id: int):
        """Return ``put(log_time_ns, publish_time_ns, data)`` writing messages of one channel."""
        def put(log_time_ns: int, publish_time_ns: int, data) -> bool:
            return self.write(channel_id, data, log_time_ns, publish_time_ns)
        return put

    def rosbag2_metadata(self) -> str:
        """Return the ``serialized_metadata`` YAML of the ``rosbag2`` record (BagMetadata)."""
        import yaml
        start = self.start_ns or 0
        duration = (self.end_ns - start) if self.end_ns is not None else 0
        name = os.path.basename(self.path)
        from vehicle_sim.recording import qos_text
        # Version 9 metadata holds the profiles as a YAML list (the channels: as YAML text).
        topics = [{'topic_metadata': {'name': topic, 'type': ros_type,
                                      'serialization_format': MESSAGE_ENCODING,
                                      'offered_qos_profiles': qos_text.parse(qos),
                                      'type_description_hash': _hash_or_empty(ros_type)},
                   'message_count': self.counts[channel_id]}
                  for channel_id, (topic, ros_type, qos) in self._topics.items()]
        info = {
            'version': ROSBAG2_VERSION, 'storage_identifier': 'mcap',
            'duration': {'nanoseconds': duration},
            'starting_time': {'nanoseconds_since_epoch': start},
            'message_count': self.message_count,
            'topics_with_message_count': topics,
            'compression_format': '', 'compression_mode': '',
            'relative_file_paths': [name],
            'files': [{'path': name, 'starting_time': {'nanoseconds_since_epoch': start},
                       'duration': {'nanoseconds': duration},
                       'message_count': self.message_count}],
            'custom_data': {'recorded_by': f'vehicle_sim {__version__}'},
            'ros_distro': ROS_DISTRO,
        }
        return yaml.safe_dump(info, default_flow_style=False, sort_keys=False)

    def close(self) -> Optional[str]:
        """
        Finish the file (metadata, summary, footer) and close it; return the error, if any.

        After a failed write the file is closed as it is (cut at its last complete record).
        """
        if self.closed:
            return self.error
        if self.error is None:
            self._guard(lambda: self._writer.add_metadata(
                'rosbag2', {'serialized_metadata': self.rosbag2_metadata(),
                            'ROS_DISTRO': ROS_DISTRO}))
            self._guard(self._writer.finish)
        self.closed = True
        try:
            self._file.close()
        except OSError as error:
            if self.error is None:
                self.error = f'recording {self.path}: closing it failed: {error.strerror}'
        return self.error


def _hash_or_empty(ros_type: str) -> str:
    from vehicle_msgs_py import type_hash
    try:
        return type_hash(ros_type)
    except (KeyError, ValueError):
        return ''


def wall_ns() -> int:
    """Return the wall clock in nanoseconds since the epoch (publish times)."""
    return time.time_ns()
