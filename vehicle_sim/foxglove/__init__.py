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
The live Foxglove view of a running simulation (Foxglove WebSocket protocol).

``vehicle-sim run --foxglove`` (the node's ``foxglove`` parameter) starts a server of the PyPI
``foxglove-sdk`` package in the node's process: every topic the node publishes is a channel
carrying the very CDR bytes the transport writes (``cdr`` encoding, ``ros2msg`` schema), a 3D
scene of the world is a ``foxglove.SceneUpdate`` channel and the transforms a
``foxglove.FrameTransforms`` one; the node's services and parameters are served through the
protocol's service and parameter capabilities, by the same handlers and validation as over ROS.
docs/foxglove.md.

Modules: :mod:`.sdk` (the optional package, imported lazily), :mod:`.server` (host, port,
start), :mod:`.front` (the listener in front of the SDK's server: both subprotocol names),
:mod:`.sdk_log` (the SDK's log lines through the node's logger), :mod:`.topics` (topic
channels), :mod:`.services` and :mod:`.parameters` (the capabilities, run on the node's
thread), :mod:`.scene` (entities of the world, the registry of entity sources),
:mod:`.scene_messages` (those as Foxglove messages), :mod:`.live_view` (what the node
attaches).

May import: core, transport, vehicle_msgs_py.
"""
