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
The transport layer: one small port (``port``), two adapters (``dds``, ``rclpy_adapter``).

Nodes import :func:`create_node` / :func:`run_node` from here and are written against
:class:`NodePort`; docs/transport.md describes what users of the embedded one see.

May import: vehicle_msgs_py, vehicle_sim.core.specs.errors.
"""

from vehicle_sim.transport.errors import ServiceTimeoutError, TransportError
from vehicle_sim.transport.parameter_types import Parameter, SetParametersResult
from vehicle_sim.transport.port import NodePort
from vehicle_sim.transport.qos import (
    QOS_CLOCK,
    QOS_DEFAULT,
    QOS_LATCHED,
    QOS_PARAMETER_EVENTS,
    QOS_PARAMETERS,
    QOS_ROSOUT,
    QOS_SENSOR_DATA,
    QOS_SERVICES,
    QOS_TF,
    QOS_TF_STATIC,
    QosProfile,
)
from vehicle_sim.transport.ros_time import Time
from vehicle_sim.transport.selection import create_node, run_node, transport_name

__all__ = [
    'NodePort', 'Parameter', 'QOS_CLOCK', 'QOS_DEFAULT', 'QOS_LATCHED', 'QOS_PARAMETER_EVENTS',
    'QOS_PARAMETERS', 'QOS_ROSOUT', 'QOS_SENSOR_DATA', 'QOS_SERVICES', 'QOS_TF',
    'QOS_TF_STATIC', 'QosProfile', 'ServiceTimeoutError', 'SetParametersResult', 'Time',
    'TransportError', 'create_node', 'run_node', 'transport_name',
]
