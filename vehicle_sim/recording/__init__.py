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
Recording and replaying the simulation's topics as MCAP files in the ROS 2 profile.

The files are what ``ros2 bag record -s mcap`` (rosbag2_storage_mcap) writes: one channel per
topic with the publishers' QoS (``offered_qos_profiles``), ``ros2msg`` schemas with their
dependent definitions, ``cdr`` messages exactly as they were on the wire, chunked and compressed.

- :mod:`.qos_text`: QoS profiles as rosbag2 stores them, and back.
- :mod:`.bag_writer`: the file, written through the ``mcap`` library.
- :mod:`.recorder`: topics to channels, log times from the simulated or the wall clock; a tap
  on a node's publishers (in-process) and a recorder of topics on the graph.
- :mod:`.bag_reader`: a file's summary and messages, with clear errors for a broken file.
- :mod:`.player`: republishing a file's messages at their recorded pace.

The ``mcap`` package is an optional dependency: ``pip install 'vehicle_sim[record]'``.

May import: core, transport, vehicle_msgs_py, vehicle_sim.
"""
