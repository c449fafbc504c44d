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
Publish taps: what sees the bytes a node's publishers write (a recorder, the Foxglove live view).

A :class:`PublishTap` hands each new publisher of a node a sink (or leaves it alone);
:func:`tap_publisher` rewires a publisher so that the bytes it writes go to its sinks too,
serialized once, and widens its reader gate (:class:`TappedGate`) while a sink wants messages.
:meth:`NodePort.add_publish_tap <vehicle_sim.transport.port.NodePort.add_publish_tap>` attaches
taps; the adapters call it for each publisher they create.
"""

from typing import Any, Callable

from vehicle_sim.transport.qos import QosProfile
from vehicle_sim.transport.reader_gate import ReaderGate


class PublishTap:
    """
    Sees what a node sends: the bytes of every message its publishers write, and its services.

    A live view (``vehicle_sim.foxglove``) or an in-process recorder attaches one with
    :meth:`NodePort.add_publish_tap` before the node creates its endpoints; the publishers
    created after that hand it the serialized message (CDR with its 4-byte encapsulation
    header) that the transport writes, so nothing is encoded twice. Both methods run on the
    node's thread.
    """

    def topic(self, topic_name: str, ros_type: str, qos: 'QosProfile'):
        """
        Return the sink of a new publisher's messages, or None to leave the topic alone.

        A sink has ``open`` (read before each message: False skips building it unless a DDS
        reader wants it) and ``write(data)``.
        """
        return None

    def service(self, service_name: str, srv_type: str, callback) -> None:
        """Hear of a service the node created (its fully-qualified name and its callback)."""


class _AlwaysOpenSink:
    """A sink taking every message: the ``write`` of :meth:`NodePort.tap_publishers`."""

    __slots__ = ('write',)
    open = True

    def __init__(self, write):
        self.write = write


class FunctionTap(PublishTap):
    """A PublishTap made of one function ``tap(topic, ros_type, qos)`` -> ``write`` or None."""

    def __init__(self, tap):
        self._tap = tap

    def topic(self, topic_name, ros_type, qos):
        write = self._tap(topic_name, ros_type, qos)
        return None if write is None else _AlwaysOpenSink(write)


class TappedGate:
    """A publisher's reader gate widened by its tap sinks: open while any of them wants it."""

    __slots__ = ('_gate', '_sinks')

    def __init__(self, gate: ReaderGate, sinks):
        self._gate = gate
        self._sinks = tuple(sinks)

    @property
    def open(self) -> bool:
        if self._gate.open:
            return True
        for sink in self._sinks:
            if sink.open:
                return True
        return False


def tap_publisher(publisher, sinks, serialize: Callable[[Any], bytes]) -> None:
    """
    Make ``publisher`` hand every message's bytes to ``sinks`` too.

    The transport's write is skipped while the publisher's own reader gate is closed (a
    volatile publisher with no matched subscription: the message would go nowhere), so a
    topic only a sink wants costs no DDS write.

    :param serialize: ``serialize(msg)`` -> the bytes the transport would write for ``msg``;
        ``publish(msg)`` then serializes once and writes those bytes itself.
    """
    sinks = tuple(sinks)
    write = publisher.publish_serialized
    check = getattr(publisher, 'check_message', None)
    gate = publisher.reader_gate

    def publish_serialized(data) -> None:
        if gate.open:       # closed: no subscriber would receive it (port.ReaderGate)
            write(data)
        for sink in sinks:
            if sink.open:
                sink.write(data)

    def publish(msg) -> None:
        if check is not None:
            check(msg)
        publish_serialized(serialize(msg))

    if hasattr(write, 'count'):     # the embedded transport's count of serialized writes
        publish_serialized.count = write.count
    publisher.publish_serialized = publish_serialized
    publisher.publish = publish
    publisher.reader_gate = TappedGate(publisher.reader_gate, sinks)
