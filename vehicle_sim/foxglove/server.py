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
Where the Foxglove WebSocket server listens, and starting it.

Loopback only unless asked: the Foxglove WebSocket protocol has no authentication, so anyone
who can reach the port can call the simulation's services and set its parameters.
"""

import ipaddress
import socket
from typing import Optional

from vehicle_sim.foxglove.sdk import LiveViewError

DEFAULT_PORT = 8765
DEFAULT_HOST = '127.0.0.1'


def is_loopback(host: str) -> bool:
    """Say whether ``host`` is a loopback address (or ``localhost``)."""
    if host == 'localhost':
        return True
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        return False


def exposure_warning(host: str, port: int) -> Optional[str]:
    """Return the warning printed when the server listens beyond loopback, else None."""
    if is_loopback(host):
        return None
    return (f'the Foxglove server listens on {host}:{port}, beyond this machine: the Foxglove '
            'WebSocket protocol has no authentication, so anyone who can reach the port can '
            'watch the simulation, call its services and set its parameters')


def check_host(host: str, source: str) -> None:
    """
    Refuse a host that is not an IP address or ``localhost``.

    :raises LiveViewError: naming ``source`` and the value.
    """
    if host == 'localhost':
        return
    try:
        ipaddress.ip_address(host)
    except ValueError:
        raise LiveViewError(f'{source} = {host!r}: not an IP address (e.g. 127.0.0.1, 0.0.0.0, '
                            '::1) or localhost') from None


def check_port_free(host: str, port: int, source: str) -> None:
    """
    Refuse a port something already listens on (before anything is started).

    The probe binds as a server's listener does, with ``SO_REUSEADDR``: the closed connections
    of a server that just stopped (TIME_WAIT, for a minute after a client was connected) do not
    keep a new listener off the port, a listening socket does.

    :raises LiveViewError: one line naming ``source``, the address and the reason.
    """
    family = socket.AF_INET6 if ':' in host else socket.AF_INET
    with socket.socket(family, socket.SOCK_STREAM) as probe:
        probe.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        try:
            probe.bind((host, port))
        except OSError as error:
            raise LiveViewError(f'{source}: cannot listen on {host}:{port}: '
                                f'{error.strerror or error}') from None


def start_server(sdk, *, context, host: str, port: int, listener, name: str):
    """
    Start the SDK's WebSocket server with the services and parameters capabilities.

    :raises LiveViewError: when the address is refused (port in use), in one line.
    """
    capabilities = [sdk.websocket.Capability.Services, sdk.websocket.Capability.Parameters]
    try:
        return sdk.start_server(name=name, host=host, port=port, context=context,
                                capabilities=capabilities, server_listener=listener,
                                supported_encodings=['cdr'])
    except RuntimeError as error:
        reason = str(error).splitlines()[0] if str(error) else type(error).__name__
        raise LiveViewError(f'Foxglove server on {host}:{port}: {reason}') from None
