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
A :class:`~.bag_writer.BagWriter` in a child process, fed in batches: recording off the hot path.

The ``mcap`` library's writer is Python and costs a few microseconds per message; a simulation
step publishes a score of messages. :class:`WriterProcess` has the BagWriter's interface
(``add_channel``, ``queue``, ``close``), but what ``queue`` returns only appends the message to
a batch, sent through a pipe to a child process (a fresh interpreter running this module,
nothing of the parent's threads or its main script) that writes the file.
A failed write in the child (a full disk) comes back as the recording's error at the next batch;
messages after it are dropped, as the BagWriter does. The child ignores SIGINT (Ctrl-C reaches
the whole process group: the parent decides when the file is closed) and dies with the parent.
"""

from multiprocessing.connection import Connection
import os
import signal
import subprocess
import sys
from typing import Dict, Optional

from vehicle_sim.recording.bag_writer import (
    BagWriter,
    DEFAULT_CHUNK_SIZE,
    DEFAULT_COMPRESSION,
    RecordingError,
    require_mcap,
)

# Messages per batch sent to the child (a few hundred kilobytes at most for a car's topics).
BATCH = 512
# How long close() waits for the child to finish the file, and the start for its reply [s].
CLOSE_TIMEOUT_S = 60.0
START_TIMEOUT_S = 60.0


def _serve(receive, send, path: str, compression: str, chunk_size: int) -> None:
    """Run the child: open the BagWriter, then apply the parent's commands in order."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        writer = BagWriter(path, compression, chunk_size)
    except RecordingError as error:
        send.send(('error', str(error)))
        return
    send.send(('ok', None))
    ids: Dict[int, int] = {}
    reported = False
    while True:
        try:
            command, payload = receive.recv()
        except EOFError:             # the parent died: leave the file as it is
            return
        if command == 'channel':
            parent_id, topic, ros_type, qos = payload
            ids[parent_id] = writer.add_channel(topic, ros_type, qos)
        elif command == 'messages':
            write = writer.write
            for parent_id, log_ns, publish_ns, data in payload:
                write(ids[parent_id], data, log_ns, publish_ns)
        elif command == 'close':
            send.send(('closed', writer.close()))
            return
        if writer.failed and not reported:
            reported = True
            send.send(('error', writer.error))


def main(argv=None) -> int:
    """Child entry point: ``python -m vehicle_sim.recording.writer_process IN OUT PATH C N``."""
    args = sys.argv[1:] if argv is None else argv
    receive = Connection(int(args[0]), writable=False)
    send = Connection(int(args[1]), readable=False)
    _serve(receive, send, args[2], args[3], int(args[4]))
    return 0


class WriterProcess:
    """
    A BagWriter's interface, the writing done by a child process.

    :raises RecordingError: when the file cannot be created or ``mcap`` is missing (from the
        child, at once).
    """

    def __init__(self, path: str, compression: str = DEFAULT_COMPRESSION,
                 chunk_size: int = DEFAULT_CHUNK_SIZE):
        require_mcap()
        to_child, child_in = os.pipe()[::-1]
        child_out, from_child = os.pipe()[::-1]
        package_root = os.path.dirname(os.path.dirname(os.path.dirname(
            os.path.abspath(__file__))))
        env = dict(os.environ)
        env['PYTHONPATH'] = package_root + os.pathsep + env.get('PYTHONPATH', '')
        try:
            self._process = subprocess.Popen(
                [sys.executable, '-m', 'vehicle_sim.recording.writer_process', str(child_in),
                 str(child_out), path, compression, str(chunk_size)],
                pass_fds=(child_in, child_out), env=env, stdin=subprocess.DEVNULL)
        finally:
            os.close(child_in)
            os.close(child_out)
        self._out = Connection(to_child, readable=False)
        self._in = Connection(from_child, writable=False)
        self.path = path
        self.channels: Dict[str, int] = {}
        self.error: Optional[str] = None
        self.closed = False
        self._batch = []             # one list for the writer's life: cleared once sent
        self._sent = 0               # messages sent to the child
        if self._in.poll(START_TIMEOUT_S):
            kind, text = self._receive()
        else:
            kind, text = 'error', (f'recording {path}: the writer process did not start within '
                                   f'{START_TIMEOUT_S:g} s')
        if kind != 'ok':
            self._end()
            raise RecordingError(text)

    @property
    def failed(self) -> bool:
        return self.error is not None

    def _receive(self):
        try:
            return self._in.recv()
        except (EOFError, OSError):
            return 'error', f'recording {self.path}: the writer process ended unexpectedly'

    def _send(self, message) -> None:
        try:
            self._out.send(message)
        except (BrokenPipeError, OSError):
            if self.error is None:
                self.error = f'recording {self.path}: the writer process ended unexpectedly'

    def _check(self) -> None:
        try:
            while self.error is None and self._in.poll():
                kind, text = self._receive()
                if kind == 'error':
                    self.error = text
        except OSError:
            if self.error is None:
                self.error = f'recording {self.path}: the writer process ended unexpectedly'

    def add_channel(self, topic: str, ros_type: str, offered_qos_profiles: str) -> int:
        """Register a topic; return its channel id. :raises RecordingError: unknown type."""
        if topic in self.channels:
            return self.channels[topic]
        from vehicle_msgs_py import message_definition
        try:
            message_definition(ros_type)
        except (KeyError, ValueError) as error:
            raise RecordingError(f'{topic}: type {ros_type} has no known definition '
                                 f'({error})') from None
        channel_id = len(self.channels) + 1
        self._flush()
        self._send(('channel', (channel_id, topic, ros_type, offered_qos_profiles)))
        self.channels[topic] = channel_id
        return channel_id

    @property
    def message_count(self) -> int:
        """Messages written or queued so far."""
        return self._sent + len(self._batch)

    def queue(self, channel_id: int):
        """
        Return ``put(log_time_ns, publish_time_ns, data)`` queuing messages of one channel.

        The recorder's hot path (one call per message): it returns False once a batch sent
        finds the recording stopped; the caller stops calling it then (and after close).
        """
        batch = self._batch
        append = batch.append

        def put(log_time_ns: int, publish_time_ns: int, data) -> bool:
            append((channel_id, log_time_ns, publish_time_ns, data))
            if len(batch) >= BATCH:
                self._flush()
                return self.error is None
            return True
        return put

    def _flush(self) -> None:
        batch = self._batch
        if batch and self.error is None:
            self._send(('messages', batch))      # pickled here: the list can be reused
            self._sent += len(batch)
        batch.clear()
        self._check()

    def close(self) -> Optional[str]:
        """Send what is queued, let the child finish the file; return the error, if any."""
        if self.closed:
            return self.error
        self.closed = True
        if self.error is None:
            self._flush()
        self._send(('close', None))
        if self._poll(CLOSE_TIMEOUT_S):
            while True:
                kind, text = self._receive()
                if kind == 'closed':
                    self.error = self.error or text
                    break
                if kind == 'error':
                    self.error = self.error or text
                    if not self._poll(CLOSE_TIMEOUT_S):
                        break
        elif self.error is None:
            self.error = f'recording {self.path}: the writer process did not finish the file'
        self._end()
        return self.error

    def _poll(self, timeout_s: float) -> bool:
        try:
            return self._in.poll(timeout_s)
        except OSError:
            return False

    def _end(self) -> None:
        self._out.close()
        self._in.close()
        try:
            self._process.wait(CLOSE_TIMEOUT_S)
        except subprocess.TimeoutExpired:
            self._process.kill()
            self._process.wait()


if __name__ == '__main__':
    sys.exit(main())
