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
The node's services through the Foxglove protocol's service capability.

A call from the app runs the very callback the ROS service runs, on the node's thread (handed
over with ``NodePort.call_soon``; the SDK calls handlers from its own threads), with the
request decoded from and the response encoded to CDR as over ROS. So a value the ROS service
refuses is refused here too (``success: false``, nothing changed, the reason logged).
"""

import threading
from typing import Callable, Dict

import vehicle_msgs_py
from vehicle_sim.foxglove.sdk import LiveViewError
from vehicle_sim.foxglove.topics import MESSAGE_ENCODING, SCHEMA_ENCODING
from vehicle_sim.transport.future import Future

# How long a call from the app waits for the node's thread [s]. A running node serves it
# between two steps; this is reached only when the node no longer spins.
NODE_THREAD_TIMEOUT_S = 10.0

# Service types the live view leaves out: the node's parameters go through the parameter
# capability instead.
HIDDEN_SERVICE_PACKAGES = ('rcl_interfaces/',)


def on_node_thread(node, work: Callable[[], object],
                   timeout_s: float = NODE_THREAD_TIMEOUT_S):
    """
    Run ``work()`` on the node's thread and return its result (a Future's, once done).

    :raises LiveViewError: when the node did not run it within ``timeout_s``.
    :raises Exception: what ``work`` raised.
    """
    done = threading.Event()
    outcome = []

    def finish(ok, value):
        outcome.append((ok, value))
        done.set()

    def run():
        try:
            result = work()
        except Exception as error:  # noqa: BLE001 - handed to the calling thread
            finish(False, error)
            return
        if isinstance(result, Future):
            result.add_done_callback(
                lambda future: finish(future.exception() is None,
                                      future.exception() or future.result()))
        else:
            finish(True, result)

    node.call_soon(run)
    if not done.wait(timeout_s):
        raise LiveViewError(f'the simulation did not answer within {timeout_s:g} s '
                            '(its node is not spinning)')
    ok, value = outcome[0]
    if not ok:
        raise value
    return value


def _message_schema(sdk, ros_type: str):
    return sdk.MessageSchema(encoding=MESSAGE_ENCODING, schema=sdk.Schema(
        name=ros_type, encoding=SCHEMA_ENCODING,
        data=vehicle_msgs_py.message_definition(ros_type).encode('utf-8')))


class NodeServices:
    """
    The node's services offered to Foxglove clients (the service side of the publish tap).

    :param sdk: the ``foxglove`` module.
    :param node: the NodePort whose thread runs the callbacks.
    :param logger: the node's logger.
    """

    def __init__(self, sdk, node, logger):
        self._sdk = sdk
        self._node = node
        self._logger = logger
        self._server = None
        self.services: Dict[str, object] = {}
        self._waiting = []

    def attach(self, server) -> None:
        """Offer the services heard of so far, and those to come, on ``server``."""
        self._server = server
        if self._waiting:
            server.add_services(self._waiting)
            self._waiting = []

    def service(self, service_name: str, srv_type: str, callback) -> None:
        if srv_type.startswith(HIDDEN_SERVICE_PACKAGES) or service_name in self.services:
            return
        sdk = self._sdk
        try:
            schema = sdk.ServiceSchema(
                srv_type, request=_message_schema(sdk, f'{srv_type}_Request'),
                response=_message_schema(sdk, f'{srv_type}_Response'))
        except ValueError as error:
            self._logger.warn(f'Foxglove: service {service_name} is not offered: {error}')
            return
        classes = self._node.srv(srv_type)
        service = sdk.Service(service_name, schema=schema,
                              handler=self._handler(service_name, classes, callback))
        self.services[service_name] = service
        if self._server is None:
            self._waiting.append(service)
        else:
            self._server.add_services([service])

    def _handler(self, service_name, classes, callback):
        node = self._node

        def handle(request) -> bytes:
            # SDK thread: decode here, run the ROS callback on the node's thread.
            if request.encoding != MESSAGE_ENCODING:
                raise LiveViewError(f'{service_name}: request encoding {request.encoding!r}; '
                                    f'this server takes {MESSAGE_ENCODING!r}')
            try:
                message = node.deserialize_as(classes.Request, request.payload)
            except Exception as error:  # noqa: BLE001 - any malformed payload
                raise LiveViewError(f'{service_name}: the request is not a CDR '
                                    f'{classes.Request.__name__} ({error})') from None
            response = on_node_thread(node, lambda: callback(message, classes.Response()))
            return node.serialize(response)
        return handle
