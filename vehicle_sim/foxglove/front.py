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
The listener in front of foxglove-sdk's server: both names of the protocol connect.

The Foxglove WebSocket protocol has two subprotocol names: ``foxglove.sdk.v1`` (foxglove-sdk's
server, which refuses any other with HTTP 400, and the current Foxglove app) and
``foxglove.websocket.v1`` (``@foxglove/ws-protocol``'s own example, Lichtblick, older Foxglove
Studio); the protocol is the same under both. :class:`SubprotocolFront` listens on the user's
address, names the SDK's subprotocol in each client's opening handshake, names the client's own
in the answer, and then relays the connection's bytes unchanged to the SDK's server, which
listens on a loopback port of its own.

A client gone without closing (a reset) ends both ways of its relay; what the SDK logs about
it is routed by :mod:`.sdk_log`.
"""

import socket
import threading
from typing import Callable, List, Optional, Tuple

from vehicle_sim.foxglove.sdk import LiveViewError

SDK_SUBPROTOCOL = 'foxglove.sdk.v1'
# The names of the one protocol a client may offer, the SDK's first.
SUBPROTOCOLS = (SDK_SUBPROTOCOL, 'foxglove.websocket.v1')
# Where the SDK's own server listens (a free port there).
UPSTREAM_HOST = '127.0.0.1'

_HEADER = 'sec-websocket-protocol'
_HEAD_END = b'\r\n\r\n'
# An opening handshake larger than this, or slower than that, is dropped.
MAX_HEAD_BYTES = 65536
HANDSHAKE_TIMEOUT_S = 10.0
RELAY_CHUNK_BYTES = 1 << 20


def offered_subprotocols(head: bytes) -> List[str]:
    """Return the subprotocol names an HTTP request head offers, in the client's order."""
    names = []
    for line in head.split(b'\r\n')[1:]:
        name, colon, value = line.partition(b':')
        if colon and name.strip().lower() == _HEADER.encode():
            names += [v.strip() for v in value.decode('latin-1').split(',') if v.strip()]
    return names


def choose_subprotocol(offered: List[str]) -> Optional[str]:
    """Return the first offered name of the protocol, or None (the SDK then answers 400)."""
    return next((name for name in offered if name in SUBPROTOCOLS), None)


def with_subprotocol(head: bytes, name: str) -> bytes:
    """Return an HTTP head (request or response) whose only subprotocol header names ``name``."""
    lines = [line for line in head.split(b'\r\n')
             if line.partition(b':')[0].strip().lower() != _HEADER.encode()]
    return b'\r\n'.join(lines[:1] + [f'Sec-WebSocket-Protocol: {name}'.encode()] + lines[1:])


def _read_head(sock) -> Tuple[bytes, bytes]:
    """Read an HTTP head from ``sock``: (the head without its blank line, the bytes after)."""
    received = b''
    while _HEAD_END not in received:
        if len(received) > MAX_HEAD_BYTES:
            raise ConnectionError(f'an HTTP head over {MAX_HEAD_BYTES} bytes')
        chunk = sock.recv(MAX_HEAD_BYTES)
        if not chunk:
            raise ConnectionError('closed before the end of its HTTP head')
        received += chunk
    head, rest = received.split(_HEAD_END, 1)
    return head, rest


class _Connection:
    """One client's connection and its relay to the SDK's server, each way on a thread."""

    def __init__(self, client, front: 'SubprotocolFront'):
        self.client = client
        self.upstream = None
        self._front = front
        self._ways = 2
        self._lock = threading.Lock()

    def run(self) -> None:
        """Do the opening handshake, then relay (on this thread and one more)."""
        front = self._front
        try:
            self.client.settimeout(HANDSHAKE_TIMEOUT_S)
            head, rest = _read_head(self.client)
            chosen = choose_subprotocol(offered_subprotocols(head))
            if chosen is not None:
                head = with_subprotocol(head, SDK_SUBPROTOCOL)
            self.upstream = socket.create_connection((UPSTREAM_HOST, front.upstream_port),
                                                     timeout=HANDSHAKE_TIMEOUT_S)
            self.upstream.sendall(head + _HEAD_END + rest)
            answer, rest = _read_head(self.upstream)
            upgraded = answer.split(b' ', 2)[1:2] == [b'101']
            if upgraded and chosen is not None:
                answer = with_subprotocol(answer, chosen)
            self.client.sendall(answer + _HEAD_END + rest)
        except OSError as error:
            front.log(f'Foxglove client {front.peer(self.client)}: handshake not completed: '
                      f'{error}')
            self.close()
            return
        self.client.settimeout(None)
        self.upstream.settimeout(None)
        if upgraded:
            front.connected(self)
        threading.Thread(target=self._relay, args=(self.upstream, self.client),
                         name='foxglove-front-down', daemon=True).start()
        self._relay(self.client, self.upstream)

    def _relay(self, source, sink) -> None:
        buffer = memoryview(bytearray(RELAY_CHUNK_BYTES))
        try:
            while True:
                count = source.recv_into(buffer)
                if not count:
                    sink.shutdown(socket.SHUT_WR)       # a close: passed on
                    break
                sink.sendall(buffer[:count])
        except OSError:                                 # a reset: both ways end
            self.shutdown()
        with self._lock:
            self._ways -= 1
            done = self._ways == 0
        if done:
            self.close()

    def close(self) -> None:
        """Close both sockets; the front forgets the client."""
        for sock in (self.client, self.upstream):
            if sock is not None:
                sock.close()
        self._front.disconnected(self)

    def shutdown(self) -> None:
        """End both ways at once (the front closes)."""
        for sock in (self.client, self.upstream):
            if sock is not None:
                try:
                    sock.shutdown(socket.SHUT_RDWR)
                except OSError:
                    pass


class SubprotocolFront:
    """
    Listen on ``host``:``port`` for Foxglove clients and relay them to the SDK's server.

    :param host: the address the user asked for.
    :param port: its port.
    :param upstream_port: the SDK's server's port on :data:`UPSTREAM_HOST`.
    :param log: ``log(text)`` for a connection that failed (a debug line).
    :raises LiveViewError: when the address cannot be listened on (one line).
    """

    def __init__(self, host: str, port: int, upstream_port: int,
                 log: Callable[[str], None]):
        self.upstream_port = upstream_port
        self.log = log
        family = socket.AF_INET6 if ':' in host else socket.AF_INET
        try:
            # SO_REUSEADDR (create_server's default here): TIME_WAIT connections of a server
            # that just stopped do not keep this one off the port.
            self._listener = socket.create_server((host, port), family=family)
        except OSError as error:
            raise LiveViewError(f'Foxglove server on {host}:{port}: '
                                f'{error.strerror or error}') from None
        self.port = self._listener.getsockname()[1]
        self._lock = threading.Lock()
        self._connections = set()
        self._upgraded = set()
        self._client_came = threading.Event()
        self._closed = False
        self._thread = threading.Thread(target=self._accept, name='foxglove-front', daemon=True)
        self._thread.start()

    @staticmethod
    def peer(sock) -> str:
        try:
            host, port = sock.getpeername()[:2]
        except OSError:
            return '(gone)'
        return f'{host}:{port}'

    @property
    def clients(self) -> int:
        """The number of clients connected now (their handshake done)."""
        with self._lock:
            return len(self._upgraded)

    def wait_for_client(self, timeout_s: float) -> bool:
        """Wait up to ``timeout_s`` for a client to have connected; return whether one has."""
        return self._client_came.wait(timeout_s)

    def connected(self, connection: _Connection) -> None:
        with self._lock:
            self._upgraded.add(connection)
        self._client_came.set()

    def disconnected(self, connection: _Connection) -> None:
        with self._lock:
            self._connections.discard(connection)
            self._upgraded.discard(connection)

    def _accept(self) -> None:
        while True:
            try:
                client, _ = self._listener.accept()
            except OSError:
                return                                  # the listener was shut down
            connection = _Connection(client, self)
            with self._lock:
                if self._closed:
                    client.close()
                    return
                self._connections.add(connection)
            threading.Thread(target=connection.run, name='foxglove-front-up',
                             daemon=True).start()

    def close(self) -> None:
        """Stop listening and end every connection (idempotent)."""
        with self._lock:
            if self._closed:
                return
            self._closed = True
            connections = list(self._connections)
        try:
            self._listener.shutdown(socket.SHUT_RDWR)   # wakes accept()
        except OSError:
            pass
        self._listener.close()
        self._thread.join()
        for connection in connections:
            connection.shutdown()
