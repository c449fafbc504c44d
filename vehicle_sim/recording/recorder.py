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
Topics into a recording: one channel per topic, each message with its log and publish times.

The log time is the recorder's clock when the message arrived: the wall clock, or with
``use_sim_time`` the simulated time of the last ``/clock`` message (as ``ros2 bag record
--use-sim-time``), which is what an in-process recording uses, so that a file's times are the
simulation's. The publish time is the wall clock at the write.

:func:`record_node` taps a node's publishers (``NodePort.tap_publishers``): every message the
node publishes is written as the bytes it sent, from its first publication on.
"""

import struct
import time
from typing import Callable, Optional

from vehicle_sim.recording import qos_text
from vehicle_sim.recording.bag_writer import BagWriter, wall_ns

CLOCK_TOPIC = '/clock'
CLOCK_TYPE = 'rosgraph_msgs/msg/Clock'
# builtin_interfaces/Time after the 4-byte encapsulation header: int32 sec, uint32 nanosec.
_TIME_LE = struct.Struct('<iI')
_TIME_BE = struct.Struct('>iI')


def clock_ns(data: bytes) -> Optional[int]:
    """Return the time of a serialized rosgraph_msgs/Clock [ns], None when too short."""
    if len(data) < 12:
        return None
    sec, nanosec = (_TIME_LE if data[1] & 1 else _TIME_BE).unpack_from(data, 4)
    return sec * 1_000_000_000 + nanosec


class Recorder:
    """
    Writes topics into a :class:`BagWriter`.

    :param writer: the open BagWriter or WriterProcess (closed by :meth:`close`).
    :param use_sim_time: log times from ``/clock`` instead of the wall clock.
    :param on_error: ``on_error(text)``, called once when a write fails and the recording stops.
    """

    def __init__(self, writer: BagWriter, use_sim_time: bool = False,
                 on_error: Optional[Callable[[str], None]] = None):
        self.writer = writer
        self.use_sim_time = use_sim_time
        self._on_error = on_error
        self._sim_ns = 0
        self.stopped = False

    @property
    def path(self) -> str:
        return self.writer.path

    @property
    def error(self) -> Optional[str]:
        return self.writer.error

    def now_ns(self) -> int:
        """Return the recorder's clock [ns]: the last /clock time, or the wall clock."""
        return self._sim_ns if self.use_sim_time else wall_ns()

    def channel(self, topic: str, ros_type: str, offered_qos_profiles: str):
        """
        Register a topic and return ``write(data)``, which records one message of it.

        :param offered_qos_profiles: the publishers' QoS as rosbag2 stores it
            (:mod:`.qos_text`).
        :raises RecordingError: for a type whose definition is unknown.
        """
        channel_id = self.writer.add_channel(topic, ros_type, offered_qos_profiles)
        put = self.writer.queue(channel_id)
        follows_clock = self.use_sim_time and topic == CLOCK_TOPIC and ros_type == CLOCK_TYPE
        use_sim_time = self.use_sim_time
        time_ns = time.time_ns      # wall_ns, without its call

        def write(data: bytes) -> None:
            if self.stopped:
                return
            if follows_clock:
                found = clock_ns(data)
                if found is not None:
                    self._sim_ns = found
            wall = time_ns()
            try:
                written = put(self._sim_ns if use_sim_time else wall, wall, data)
            except Exception as error:  # noqa: BLE001 - a recorder never breaks the publisher
                self._fail(f'recording {self.path} stopped: {type(error).__name__}: {error}')
                return
            if not written:
                self._stop()
        return write

    def follow_clock(self, data: bytes) -> None:
        """Set the clock of ``use_sim_time`` from a /clock message not recorded itself."""
        found = clock_ns(data)
        if found is not None:
            self._sim_ns = found

    def tap(self, topic: str, ros_type: str, qos):
        """Record a publisher's topic with its QoS (the tap of ``NodePort.tap_publishers``)."""
        return self.channel(topic, ros_type, qos_text.dump([qos_text.profile_entry(qos)]))

    def _fail(self, text: str) -> None:
        if self.writer.error is None:
            self.writer.error = text
        self._stop()

    def _stop(self) -> None:
        if self.stopped:
            return
        self.stopped = True
        if self._on_error is not None and self.writer.error:
            self._on_error(self.writer.error)

    def close(self) -> Optional[str]:
        """Finish the file; return the error that stopped the recording, if any."""
        was_stopped = self.stopped
        self.stopped = True
        error = self.writer.close()
        if error and not was_stopped and self._on_error is not None:
            self._on_error(error)
        return error

    def summary(self) -> str:
        """Return one line: the file, its messages and topics (or why it stopped)."""
        writer = self.writer
        if writer.error:
            return writer.error
        return (f'recorded {writer.message_count} messages on {len(writer.channels)} topics '
                f'into {writer.path}')


def record_node(node, path: str, compression: Optional[str] = None,
                opener=None, background: bool = True,
                chunk_size: Optional[int] = None) -> Recorder:
    """
    Record every topic ``node`` publishes into ``path``, on the simulated clock.

    Call it before the node's publishers are wired (before the node object that publishes is
    built on ``node``), so that the first step is recorded too. A write that fails stops the
    recording with an error on the node's log; the node goes on.

    :param opener: ``opener(path)`` -> the binary file (tests; the file is then written in
        this process).
    :param background: write the file in a child process (:mod:`.writer_process`), so that
        the step only queues the bytes.
    :param chunk_size: uncompressed bytes of a chunk (default: rosbag2's 1 MiB).
    :raises RecordingError: when the file cannot be created or ``mcap`` is missing.
    :raises TransportError: when the node's transport cannot tap its publishers.
    """
    from vehicle_sim.recording.bag_writer import DEFAULT_CHUNK_SIZE, DEFAULT_COMPRESSION
    compression = compression or DEFAULT_COMPRESSION
    chunk_size = chunk_size or DEFAULT_CHUNK_SIZE
    if background and opener is None:
        from vehicle_sim.recording.writer_process import WriterProcess
        writer = WriterProcess(path, compression, chunk_size)
    else:
        writer = BagWriter(path, compression, chunk_size, opener=opener)
    recorder = Recorder(writer, use_sim_time=True,
                        on_error=lambda text: node.get_logger().error(text))
    try:
        node.tap_publishers(recorder.tap)
    except BaseException:
        writer.close()
        raise
    return recorder
