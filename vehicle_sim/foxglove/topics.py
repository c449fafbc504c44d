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
The node's topics as Foxglove channels: the CDR bytes the transport writes, forwarded as they are.

Each channel has message encoding ``cdr`` and the topic type's ``ros2msg`` schema (its
definition with every dependency appended, as rosbag2 stores it), which is how Foxglove's own
ROS bridge advertises ROS 2 topics; the app decodes them with its ROS 2 CDR reader.
"""

import collections
from typing import Dict

import vehicle_msgs_py
from vehicle_sim.transport.qos import TRANSIENT_LOCAL

SCHEMA_ENCODING = 'ros2msg'
MESSAGE_ENCODING = 'cdr'


class ChannelSink:
    """
    A publish tap's sink for one topic: open while a Foxglove client subscribes to it.

    ``open`` is a plain attribute kept by the server's subscribe and unsubscribe callbacks
    (:meth:`TopicChannels.subscribed`), read by the node before building each message: asking
    the SDK instead cost about 0.6 us per topic and publish.

    :param channel: the SDK channel of the topic.
    """

    __slots__ = ('channel', 'write', 'open', 'subscribers')

    def __init__(self, channel):
        self.channel = channel
        # The bytes go to the SDK's log() as they are (it copies them into its own buffer).
        self.write = channel.log
        self.open = False
        self.subscribers = 0

    def count(self, change: int) -> None:
        """Add ``change`` (+1 subscribe, -1 unsubscribe) to the subscriptions."""
        self.subscribers = max(0, self.subscribers + change)
        self.open = self.subscribers > 0


class LatchedChannelSink:
    """
    The sink of a transient-local topic (/tf_static, robot_description).

    It keeps the last ``depth`` messages and gives them again to each client that subscribes
    later, as a DDS transient-local writer does for a late reader.
    """

    open = True     # kept whether or not anyone watches now

    def __init__(self, channel, depth: int):
        self.channel = channel
        self.kept = collections.deque(maxlen=max(1, depth))

    def write(self, data) -> None:
        self.kept.append(bytes(data))
        self.channel.log(data)

    def replay(self) -> None:
        """Log the kept messages again (a client just subscribed)."""
        for data in tuple(self.kept):
            self.channel.log(data)


class TopicChannels:
    """
    One Foxglove channel per published topic (the topic side of the node's publish tap).

    :param sdk: the ``foxglove`` module.
    :param context: the SDK context of this live view's server.
    :param logger: the node's logger (a topic whose type has no schema is left out, with a
        warning).
    """

    def __init__(self, sdk, context, logger):
        self._sdk = sdk
        self._context = context
        self._logger = logger
        self.sinks: Dict[str, object] = {}
        self._by_id: Dict[int, object] = {}

    def topic(self, topic_name: str, ros_type: str, qos):
        if topic_name in self.sinks:     # one node, one publisher per topic name
            return self.sinks[topic_name]
        try:
            definition = vehicle_msgs_py.message_definition(ros_type)
        except ValueError as error:
            self._logger.warn(f'Foxglove: {topic_name} is not shown: {error}')
            return None
        sdk = self._sdk
        schema = sdk.Schema(name=ros_type, encoding=SCHEMA_ENCODING,
                            data=definition.encode('utf-8'))
        channel = sdk.Channel(topic_name, schema=schema, message_encoding=MESSAGE_ENCODING,
                              context=self._context,
                              metadata={'reliability': qos.reliability,
                                        'durability': qos.durability})
        sink = (LatchedChannelSink(channel, qos.depth) if qos.durability == TRANSIENT_LOCAL
                else ChannelSink(channel))
        self.sinks[topic_name] = sink
        self._by_id[channel.id()] = sink
        return sink

    def subscribed(self, channel_id: int) -> None:
        """Open a topic to a new subscriber; replay a transient-local topic's kept messages."""
        sink = self._by_id.get(channel_id)
        if isinstance(sink, LatchedChannelSink):
            sink.replay()
        elif sink is not None:
            sink.count(+1)

    def unsubscribed(self, channel_id: int) -> None:
        """Close a topic whose last subscriber went (unsubscribed or disconnected)."""
        sink = self._by_id.get(channel_id)
        if isinstance(sink, ChannelSink):
            sink.count(-1)
