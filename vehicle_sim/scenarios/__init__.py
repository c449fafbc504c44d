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
Scenario files run headless to a pass/fail verdict (docs/scenarios.md).

A scenario holds a world, vehicles, scripted actors, what drives the vehicle under test, and
pass criteria.

Modules: :mod:`.yaml_lines` (YAML with line numbers), :mod:`.schema` (the file format),
:mod:`.criteria` (pass criteria), :mod:`.actors` (waypoint followers), :mod:`.sim` (the
simulation a scenario runs in, ROS-free) and :mod:`.served_sim` (the same served over ROS),
:mod:`.runner` (running one), :mod:`.external` (controllers in subprocesses), :mod:`.junit` and
:mod:`.plot` (reports), :mod:`.pytest_items` (scenario files as pytest tests).

May import: core, config, maps, physics, webots, transport, ros, recording.
"""
