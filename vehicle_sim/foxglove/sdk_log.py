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
foxglove-sdk's log lines through the node's logger.

The SDK (Rust) logs through Python's ``logging`` (pyo3-log), under loggers named after its
modules (``foxglove.websocket.server``, ``foxglove.websocket.connected_client.poller``, ...).
With no handler configured, Python's last-resort handler wrote its warnings and errors raw to
stderr, such as ``Error receiving from client 127.0.0.1:40822: ... Connection reset by peer
(os error 104)`` whenever an app went away without closing. While a live view runs, the
``foxglove`` logger's records go to its node's logger instead (run on the node's thread,
prefixed ``Foxglove:``): those about one client's connection (a client gone, slow, or whose
handshake failed) at debug level, the others at their own.
"""

import logging
import threading

SDK_LOGGER = 'foxglove'
# The SDK's loggers and message starts that are about one client's connection.
CLIENT_CONNECTION_LOGGERS = ('foxglove.websocket.connected_client',)
CLIENT_CONNECTION_MESSAGES = ('Dropping client ', 'Error receiving from client ',
                              'Error sending message to client ')
_NODE_LEVELS = (10, 20, 30, 40, 50)     # the node logger's: debug .. fatal


def node_level(record: logging.LogRecord) -> int:
    """Return the node logger's level for an SDK record (debug for a client's connection)."""
    message = record.getMessage()
    if (record.name.startswith(CLIENT_CONNECTION_LOGGERS)
            or message.startswith(CLIENT_CONNECTION_MESSAGES)):
        return 10
    return max(level for level in _NODE_LEVELS if level <= max(record.levelno, 10))


def log_on_node_thread(node, logger, level: int, message: str) -> None:
    """Log ``message`` at ``level`` on ``node``'s thread, from any thread (dropped at its end)."""
    try:
        node.call_soon(lambda: logger.log(level, message))
    except Exception:  # noqa: BLE001 - a node shutting down: the line is dropped
        pass


class _Route(logging.Handler):
    """The handler on the SDK's logger: hands each record to the latest live view's node."""

    def __init__(self):
        super().__init__()
        self.targets = []               # (node, logger), the latest last

    def emit(self, record: logging.LogRecord) -> None:
        targets = self.targets
        if not targets:
            return
        node, logger = targets[-1]
        log_on_node_thread(node, logger, node_level(record), f'Foxglove: {record.getMessage()}')


_route = _Route()
_lock = threading.Lock()


class SdkLogRoute:
    """
    Route the SDK's log records to ``node``'s ``logger`` until :meth:`close`.

    :param node: the NodePort (its ``call_soon`` runs the logging on its thread).
    :param logger: its logger.
    """

    def __init__(self, node, logger):
        self._target = (node, logger)
        sdk_logger = logging.getLogger(SDK_LOGGER)
        with _lock:
            if not _route.targets:
                sdk_logger.addHandler(_route)
                sdk_logger.propagate = False    # not also to the last-resort handler
            _route.targets = [*_route.targets, self._target]

    def close(self) -> None:
        """Stop routing to this node (idempotent); with no route left, the SDK logs as before."""
        sdk_logger = logging.getLogger(SDK_LOGGER)
        with _lock:
            if self._target not in _route.targets:
                return
            targets = list(_route.targets)
            targets.remove(self._target)
            _route.targets = targets
            if not targets:
                sdk_logger.removeHandler(_route)
                sdk_logger.propagate = True
