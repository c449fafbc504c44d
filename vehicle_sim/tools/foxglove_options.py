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


"""The ``--foxglove [PORT]`` and ``--foxglove-host`` options of ``run`` and ``scenario``."""

from typing import Optional, Tuple

from vehicle_sim.tools.command import CliError, EXIT_USAGE

# The Foxglove WebSocket port (Foxglove's default) and the loopback address, kept here so that
# the parser needs no import of the optional package.
DEFAULT_PORT = 8765
DEFAULT_HOST = '127.0.0.1'


def add_arguments(parser) -> None:
    """Add the live view's options to a sub-parser."""
    parser.add_argument('--foxglove', nargs='?', const=DEFAULT_PORT, type=int, metavar='PORT',
                        help='serve a live Foxglove view on ws://127.0.0.1:PORT (default '
                             f'{DEFAULT_PORT}; needs the foxglove extra; docs/foxglove.md)')
    parser.add_argument('--foxglove-host', metavar='HOST',
                        help='address of the Foxglove server (default 127.0.0.1; beyond '
                             'loopback anyone who reaches it can drive the simulation: the '
                             'protocol has no authentication)')


def live_view_address(args) -> Optional[Tuple[str, int]]:
    """
    Return (host, port) of the asked live view, or None; checked before anything starts.

    :raises CliError: a port out of range or in use, a host that is not an address, the SDK
        missing (naming the extra), ``--foxglove-host`` without ``--foxglove``.
    """
    port, host = args.foxglove, args.foxglove_host
    if port is None:
        if host is not None:
            raise CliError('--foxglove-host needs --foxglove [PORT]', EXIT_USAGE)
        return None
    if not 1 <= port <= 65535:
        raise CliError(f'--foxglove {port}: the port must be 1 .. 65535', EXIT_USAGE)
    host = DEFAULT_HOST if host is None else host
    from vehicle_sim.foxglove.sdk import LiveViewError, load_sdk
    from vehicle_sim.foxglove.server import check_host, check_port_free
    try:
        load_sdk()
        check_host(host, '--foxglove-host')
        check_port_free(host, port, '--foxglove')
    except LiveViewError as error:
        raise CliError(str(error), EXIT_USAGE) from None
    return host, port
