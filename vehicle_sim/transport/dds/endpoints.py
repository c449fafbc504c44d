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

"""Publishers and subscriptions of the embedded transport, and how every reader takes samples."""

from typing import Optional

from cyclonedds.core import Listener
from cyclonedds.pub import DataWriter
from cyclonedds.sub import DataReader

from vehicle_sim.transport import port
from vehicle_sim.transport.dds import cyclone_private
from vehicle_sim.transport.errors import TransportError
from vehicle_sim.transport.logger import ThrottledWarning
from vehicle_sim.transport.reader_gate import ReaderGate

# The most samples one take hands over; the rest stay in the reader for the next wake.
TAKE_BATCH = 256


class Intake:
    """
    Takes a reader's samples and decodes each one on its own (cyclone_private.take).

    A sample that cannot be decoded (a string that is not UTF-8, a truncated buffer) is dropped
    and counted, with a throttled warning naming the endpoint; the rest of the batch is kept.

    :param node: the node whose logger warns.
    :param reader: the DataReader.
    :param what: the endpoint, as the warning names it.
    """

    def __init__(self, node, reader: DataReader, what: str, decode=None):
        self._node = node
        self.reader = reader
        self.what = what
        self._decode = decode
        self.dropped = 0
        self._warning = None

    def take(self) -> list:
        samples, errors = cyclone_private.take(self.reader, TAKE_BATCH, self._decode)
        for exc in errors:
            self.dropped += 1
            if self._warning is None:
                self._warning = ThrottledWarning(self._node.get_logger())
            self._warning.warn(
                f'{self.what}: dropped a sample that cannot be decoded '
                f'({type(exc).__name__}: {exc}); {self.dropped} dropped so far')
        return samples


def reader_gate_listener(gate: ReaderGate) -> Listener:
    """
    Return a Listener keeping ``gate.open`` = "the writer has a matched reader".

    Give it to the DataWriter at creation: Cyclone then calls it for every change of the
    writer's matched readers, those matched during the creation included, from the thread
    that matched them (its discovery thread, or the creating thread for readers of this
    process). The gate starts closed. Cyclone calls a writer's listener one call at a time,
    each with the current count, so the last call leaves the current state.
    """
    gate.open = False

    def on_publication_matched(writer, status) -> None:
        gate.open = status.current_count > 0

    return Listener(on_publication_matched=on_publication_matched)


class DdsPublisher(port.Publisher):
    """
    A topic's writer; ``reader_gate`` tracks its matched readers when one is given.

    :param reader_gate: the gate kept by :func:`reader_gate_listener` of the writer (volatile
        writers only: a transient-local writer keeps samples for readers matching later).
    """

    def __init__(self, node, writer: DataWriter, msg_type, topic_name: str,
                 reader_gate: Optional[ReaderGate] = None):
        if reader_gate is not None:
            self.reader_gate = reader_gate
        self._node = node
        self._writer = writer
        self._type = msg_type
        self.topic_name = topic_name
        # publish_serialized is the bound writer itself: no method frame on the hot path.
        self.publish_serialized = cyclone_private.serialized_writer(writer)

    def publish(self, msg) -> None:
        self.check_message(msg)
        self._writer.write(msg)

    def check_message(self, msg) -> None:
        """Refuse a message of another type than the topic's."""
        if type(msg) is not self._type:
            raise TransportError(
                f'{self.topic_name} takes {self._type.__ros_type__}, got {type(msg).__name__}')

    def publish_serialized(self, data: bytes) -> None:  # noqa: F811 - replaced per instance
        """Write CDR bytes (with the encapsulation header) of this topic's type, unchecked."""
        self.publish_serialized(data)

    @property
    def serialized_writes(self) -> int:
        """How many samples publish_serialized wrote."""
        return self.publish_serialized.count[0]

    def get_subscription_count(self) -> int:
        return len(self._writer.get_matched_subscriptions())

    @property
    def gid(self) -> bytes:
        return self._writer.guid.bytes


class DdsSubscription(port.Subscription):
    def __init__(self, reader: DataReader, topic_name: str, intake: Intake):
        self._reader = reader
        self.topic_name = topic_name
        self._intake = intake

    @property
    def dropped_samples(self) -> int:
        """How many samples could not be decoded and were dropped."""
        return self._intake.dropped

    def get_publisher_count(self) -> int:
        return len(self._reader.get_matched_publications())

    @property
    def gid(self) -> bytes:
        return self._reader.guid.bytes
