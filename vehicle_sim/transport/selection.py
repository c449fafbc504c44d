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
Transport selection: ``VEHICLE_SIM_TRANSPORT=auto|rclpy|dds``.

``auto`` (the default) uses rclpy when it can be imported, else the embedded Cyclone DDS
transport. Node code is written once against :mod:`vehicle_sim.transport.port`.
"""

import importlib.util
import os
from typing import Any, Dict, Optional

from vehicle_sim.transport.errors import TransportError
from vehicle_sim.transport.port import NodePort

TRANSPORTS = ('auto', 'rclpy', 'dds')
ENV_VAR = 'VEHICLE_SIM_TRANSPORT'


def rclpy_available() -> bool:
    """Return True when ``rclpy`` can be imported (a sourced ROS 2 installation)."""
    return importlib.util.find_spec('rclpy') is not None


def transport_name(requested: Optional[str] = None) -> str:
    """
    Return the transport to use: 'rclpy' or 'dds'.

    :param requested: overrides the ``VEHICLE_SIM_TRANSPORT`` environment variable.
    :raises TransportError: for an unknown value, or 'rclpy' when rclpy is not importable.
    """
    value = (requested if requested is not None else os.environ.get(ENV_VAR, 'auto'))
    value = value.strip().lower() or 'auto'
    if value not in TRANSPORTS:
        raise TransportError(
            f'{ENV_VAR}={value!r} is not a transport; valid: {", ".join(TRANSPORTS)}')
    if value == 'auto':
        return 'rclpy' if rclpy_available() else 'dds'
    if value == 'rclpy' and not rclpy_available():
        raise TransportError(
            f'{ENV_VAR}=rclpy but rclpy is not importable: source a ROS 2 Jazzy setup.bash, '
            f'or use {ENV_VAR}=dds')
    return value


def create_node(name: str, namespace: str = '', args=None,
                parameter_overrides: Optional[Dict[str, Any]] = None,
                transport: Optional[str] = None, **kwargs) -> NodePort:
    """
    Create a node on the selected transport.

    :param name: node name.
    :param namespace: node namespace ('' = root).
    :param args: the command line; its ``--ros-args`` part is applied.
    :param parameter_overrides: parameter values that win over the command line.
    :param transport: 'auto', 'rclpy' or 'dds' instead of the environment variable.
    :param kwargs: adapter-specific options (e.g. ``reply_match_timeout_s`` for dds).
    """
    if transport_name(transport) == 'rclpy':
        from vehicle_sim.transport.rclpy_adapter import create_rclpy_node
        return create_rclpy_node(name, namespace, args=args,
                                 parameter_overrides=parameter_overrides, **kwargs)
    from vehicle_sim.transport.dds import create_dds_node
    return create_dds_node(name, namespace, args=args, parameter_overrides=parameter_overrides,
                           **kwargs)


def run_node(node_factory, args=None, transport: Optional[str] = None) -> int:
    """
    Run a node main the Jazzy way: init, build, spin, finally destroy and shut down.

    SIGINT and SIGTERM end the spin; the node then leaves the graph at once.

    :param node_factory: ``node_factory(args)`` returning a NodePort, or an object whose
        ``.node`` is one (it should build its node with ``create_node(..., args=args)``).
    :param args: the command line (default ``sys.argv``).
    :return: the process exit status.
    """
    if transport_name(transport) == 'rclpy':
        from vehicle_sim.transport.rclpy_adapter import run_rclpy_node
        return run_rclpy_node(node_factory, args)
    from vehicle_sim.transport.dds import run_dds_node
    return run_dds_node(node_factory, args)
