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
What a node attaches to show itself live in Foxglove: :class:`LiveView`.

The node makes one before it creates its endpoints (it is the node's publish tap, so every
publisher and service created afterwards is seen), hands it the built scene, and calls
:meth:`LiveView.publish` at each publish period. Everything but the calls the SDK makes from
its own threads (services, parameters, subscriptions) runs on the node's thread.
"""

import time
from typing import Callable, Iterable, Optional

from vehicle_sim.foxglove import scene_messages
from vehicle_sim.foxglove.entities import Transform
from vehicle_sim.foxglove.front import SubprotocolFront, UPSTREAM_HOST
from vehicle_sim.foxglove.parameters import NodeParameters
from vehicle_sim.foxglove.scene_stream import SceneStream
from vehicle_sim.foxglove.sdk import load_sdk
from vehicle_sim.foxglove.sdk_log import log_on_node_thread, SdkLogRoute
from vehicle_sim.foxglove.server import check_host, exposure_warning, start_server
from vehicle_sim.foxglove.services import NodeServices
from vehicle_sim.foxglove.topics import TopicChannels
from vehicle_sim.transport.publish_tap import PublishTap

SCENE_TOPIC = '/foxglove/scene'
TRANSFORMS_TOPIC = '/foxglove/transforms'
# Wall time between two scene updates [s]: the boxes move smoothly at 20 Hz whatever the
# real-time factor, and a fast run does not flood the clients.
SCENE_PERIOD_S = 0.05


def _listener(sdk, view: 'LiveView'):
    """Return the SDK's ServerListener of ``view``: subscriptions and the parameters."""

    class Listener(sdk.websocket.ServerListener):
        # The base gives the callbacks not used here (they do nothing).

        def on_subscribe(self, client, channel) -> None:
            view.subscribed(channel.id)

        def on_unsubscribe(self, client, channel) -> None:
            view.unsubscribed(channel.id)

        def on_get_parameters(self, client, param_names, request_id=None):
            return view.parameters.get(param_names)

        def on_set_parameters(self, client, parameters, request_id=None):
            return view.parameters.set(parameters)

    return Listener()


class LiveView(PublishTap):
    """
    A Foxglove WebSocket server showing one node: its topics, services, parameters and scene.

    :param node: the NodePort (nothing created on it yet but its parameters).
    :param host: the address to listen on (loopback unless asked: docs/foxglove.md).
    :param port: the TCP port.
    :param parameter_names: the node's parameters offered through the parameter capability.
    :raises LiveViewError: the SDK is missing, the host is not an address, the port is taken;
        nothing is left running.
    """

    def __init__(self, node, *, host: str, port: int, parameter_names: Iterable[str] = ()):
        sdk = self._sdk = load_sdk()
        check_host(host, 'foxglove_host')
        self._node = node
        logger = self._logger = node.get_logger()
        self.context = sdk.Context()
        self.topics = TopicChannels(sdk, self.context, logger)
        self.services = NodeServices(sdk, node, logger)
        self.parameters = NodeParameters(sdk, node, parameter_names, logger)
        self._log_route = SdkLogRoute(node, logger)
        # The SDK's server on a loopback port of its own, behind the listener on the asked
        # address that lets both names of the protocol in (front.py).
        self.server = self.front = None
        try:
            self.server = start_server(sdk, context=self.context, host=UPSTREAM_HOST, port=0,
                                       listener=_listener(sdk, self),
                                       name=f'vehicle_sim {node.get_fully_qualified_name()}')
            self.front = SubprotocolFront(
                host, port, self.server.port,
                log=lambda text: log_on_node_thread(node, logger, 10, f'Foxglove: {text}'))
        except BaseException:
            self.close()
            raise
        self.services.attach(self.server)
        self.parameters.server = self.server
        self._scene_channel = sdk.channels.SceneUpdateChannel(SCENE_TOPIC, context=self.context)
        self._transforms_channel = sdk.channels.FrameTransformsChannel(TRANSFORMS_TOPIC,
                                                                        context=self.context)
        # Subscribers of the scene and transforms channels, by channel id (the SDK's callbacks
        # keep them; reading them costs nothing at each publish).
        self._own = {self._scene_channel.id(): 0, self._transforms_channel.id(): 0}
        self.scene = None
        self._stream = SceneStream()
        self._next_scene_s = 0.0
        # Scene subscriptions seen (SDK thread) and answered with a full update (node thread).
        self._scene_subscriptions = self._scene_subscriptions_sent = 0
        warning = exposure_warning(host, self.port)
        if warning:
            logger.warn(warning)
        self.url = f'ws://{host}:{self.port}'
        logger.info(f'Foxglove live view on {self.url} '
                    '(Foxglove app: Open connection, Foxglove WebSocket)')
        node.add_publish_tap(self)

    @property
    def port(self) -> int:
        """The port clients connect to."""
        return self.front.port

    @property
    def clients(self) -> int:
        """The number of Foxglove clients connected now."""
        return self.front.clients

    def wait_for_client(self, timeout_s: float) -> bool:
        """Wait up to ``timeout_s`` for a client to have connected; return whether one has."""
        return self.front.wait_for_client(timeout_s)

    # ------------------------------------------------------------------ the publish tap
    def topic(self, topic_name, ros_type, qos):
        return self.topics.topic(topic_name, ros_type, qos)

    def service(self, service_name, srv_type, callback) -> None:
        self.services.service(service_name, srv_type, callback)

    def subscribed(self, channel_id: int) -> None:
        """Replay latched topics and send the scene at once to a new subscriber (SDK thread)."""
        if channel_id in self._own:
            self._own[channel_id] += 1
            if channel_id == self._scene_channel.id():
                self._scene_subscriptions += 1
            self._next_scene_s = 0.0
        self.topics.subscribed(channel_id)

    def unsubscribed(self, channel_id: int) -> None:
        """Count a subscriber gone (SDK thread)."""
        if channel_id in self._own:
            self._own[channel_id] = max(0, self._own[channel_id] - 1)
        self.topics.unsubscribed(channel_id)

    # ------------------------------------------------------------------ the scene
    def show(self, scene) -> None:
        """Draw ``scene`` (the scene builder's Scene) from now on."""
        self.scene = scene

    def publish(self, time_s: float,
                transforms: Optional[Callable[[], Iterable[Transform]]] = None) -> None:
        """
        Send the scene (at most every SCENE_PERIOD_S of wall time) and the transforms.

        The scene's static entities (map, lanes) go with the first update after a client
        subscribed; the moving ones with every update (:class:`~.scene_stream.SceneStream`).

        Each only while a client subscribes to it.

        :param time_s: the simulated time of the step [s], the messages' stamp.
        :param transforms: ``transforms()`` -> the tree now (called only when wanted).
        """
        messages = self._sdk.messages
        own = self._own
        if self.scene is not None and own[self._scene_channel.id()]:
            now = time.monotonic()
            if now >= self._next_scene_s:
                self._next_scene_s = now + SCENE_PERIOD_S
                subscriptions = self._scene_subscriptions
                frame = self._stream.frame(self.scene,
                                           full=subscriptions != self._scene_subscriptions_sent)
                self._scene_subscriptions_sent = subscriptions
                self._scene_channel.log(scene_messages.scene_update(
                    messages, frame.entities, time_s, frame.deleted_ids))
        if transforms is not None and own[self._transforms_channel.id()]:
            self._transforms_channel.log(
                scene_messages.frame_transforms(messages, transforms(), time_s))

    def close(self) -> None:
        """Stop the server (idempotent); the clients see it close."""
        server, self.server = self.server, None
        if server is not None:
            server.stop()
        front, self.front = self.front, None
        if front is not None:
            front.close()
        self._log_route.close()
