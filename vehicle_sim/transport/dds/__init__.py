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
The embedded Cyclone DDS adapter: a ROS 2 Jazzy (or Humble) graph citizen without ROS.

On the wire it does what rmw_cyclonedds (Jazzy, ``rmw_node.cpp``) does, so that ROS 2 nodes and
the ``ros2`` tools see its nodes, topics, services and parameters; a process can speak Humble's
conventions instead (:mod:`vehicle_msgs_py.distro`).

One concern per module:

* ``context``: the domain, the process's one participant (USER_DATA ``enclave=/;``), topics,
  ``serviceid``/``clientid`` tokens and ``ros_discovery_info``;
* ``discovery_info``: ``ros_discovery_info`` samples as bytes, in Humble's and Jazzy's layouts;
* ``peers``: a participant's DDS vendor and the warnings about peers we cannot fully serve;
* ``qos``: ROS QoS profiles and USER_DATA (``typehash=``) as rmw_cyclonedds maps them;
* ``endpoints``: publishers, subscriptions, and the per-sample decoding of every reader;
* ``services``: services and clients with the rmw_cyclonedds request header, deferred replies;
* ``executor``: the per-node WaitSet, timers and ``run_dds_node``;
* ``parameters``: a node's parameters, ``/parameter_events`` and the rcl_interfaces services;
* ``param_messages``: parameter values <-> rcl_interfaces messages (shared with the CLI);
* ``node``: DdsNode, which wires them together;
* ``domain_config``: ROS_DOMAIN_ID, the discovery range and the Cyclone domain they configure;
* ``cyclone_private``: the cyclonedds internals the others need (below);
* ``graph``: GraphView, the graph seen from a participant of its own (the CLI, the test client).

The cyclonedds internals it needs are all in :mod:`vehicle_sim.transport.dds.cyclone_private`,
which says why each one is needed; everything else uses the public cyclonedds API.
"""

from vehicle_sim.transport.dds.context import ensure_domain, get_participant, participant_guid
from vehicle_sim.transport.dds.endpoints import DdsPublisher, DdsSubscription
from vehicle_sim.transport.dds.executor import DdsTimer, run_dds_node
from vehicle_sim.transport.dds.node import create_dds_node, DdsLogger, DdsNode
from vehicle_sim.transport.dds.qos import dds_qos, endpoint_qos, endpoint_user_data
from vehicle_sim.transport.dds.services import DdsClient, DdsService
from vehicle_sim.transport.errors import TransportError

__all__ = ['DdsClient', 'DdsLogger', 'DdsNode', 'DdsPublisher', 'DdsService', 'DdsSubscription',
           'DdsTimer', 'TransportError', 'create_dds_node', 'dds_qos', 'endpoint_qos',
           'endpoint_user_data', 'ensure_domain', 'get_participant', 'participant_guid',
           'run_dds_node']
