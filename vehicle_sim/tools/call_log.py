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
The log lines a node wrote while it served one call, read from ``/rosout``.

A refused setter answers ``success: false``; its reason is in the node's log. Every ROS 2 node
publishes its log on ``/rosout`` (``rcl_interfaces/msg/Log``; rcl's QoS: reliable, transient
local, depth 1000, lifespan 10 s), so ``vehicle-sim call`` subscribes before it sends the
request and prints, under the response, the records of the serving node stamped within the call.
"""

import time
from typing import List, Optional

# After the reply: how long records sent before it may still be on their way [s]. The node
# logs before it replies, on the same connection, so they normally came first.
GRACE_S = 0.2
# How long to wait for our /rosout reader to match the writers the graph shows [s].
MATCH_TIMEOUT_S = 2.0


def logger_name(fqn: str) -> str:
    """Return the logger name rcl gives a node: ``/ns/name`` → ``ns.name``."""
    return '.'.join(token for token in fqn.split('/') if token)


def format_record(record) -> str:
    """Return a Log record as the node's console prints it (rcutils' default format)."""
    from vehicle_sim.transport.logger import LOG_LEVEL_NAMES
    level = LOG_LEVEL_NAMES.get(record.level, record.level)
    return (f'[{level}] [{record.stamp.sec}.{record.stamp.nanosec:09d}] '
            f'[{record.name}]: {record.msg}')


class CallLog:
    """
    The ``/rosout`` records of one node between :meth:`start` and :meth:`stop`.

    :param node: the CLI's helper node (it subscribes now, before the call).
    :param graph: the GraphView, to find the serving node and the /rosout writers.
    :param service: the service called.
    """

    def __init__(self, node, graph, service: str):
        from vehicle_sim.transport.qos import QOS_ROSOUT
        self._node = node
        self._graph = graph
        self._records = []
        self._subscription = node.create_subscription(
            'rcl_interfaces/msg/Log', '/rosout', self._records.append, QOS_ROSOUT)
        self._logger = self._server_logger(service)
        self._start_ns = self._end_ns = 0

    def _server_logger(self, service: str) -> Optional[str]:
        servers = {e.gid for e in self._graph.service_servers(service)}
        for info in self._graph.nodes():
            if info.reader_gids & servers:
                return logger_name(info.fqn)
        return None

    def _matched(self) -> bool:
        self._graph.refresh()
        return self._subscription.get_publisher_count() >= len(self._graph.publishers('/rosout'))

    def start(self) -> None:
        """Mark the call's start (just before the request is sent)."""
        self._start_ns = time.time_ns()

    def stop(self) -> None:
        """Mark the call's end (the reply came) and collect the records sent before it."""
        self._end_ns = time.time_ns()
        if self._logger is None:
            return
        # Transient local: a reader matching late still gets the node's recent records.
        self._node.spin_until(self._matched, MATCH_TIMEOUT_S)
        deadline = time.monotonic() + GRACE_S
        while time.monotonic() < deadline:
            self._node.spin_once(0.02)

    def lines(self) -> List[str]:
        """Return the serving node's records stamped within the call, as console lines."""
        found = []
        if self._logger is None:   # the server's node is not on the graph (not announced)
            return found
        for record in self._records:
            stamp_ns = record.stamp.sec * 1_000_000_000 + record.stamp.nanosec
            name = record.name
            if (name == self._logger or name.startswith(f'{self._logger}.')) and \
                    self._start_ns <= stamp_ns <= self._end_ns:
                found.append(format_record(record))
        return found
