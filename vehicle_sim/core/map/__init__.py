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
Maps, ROS-, PyBullet- and file-free (numbers in, numbers out).

The map layer: ``kinds`` (the ``map:`` key of world files, one registry of map kinds),
``occupancy`` (nav2 map_server's YAML and thresholding, cells, a ray march for tests),
``rectangles`` (wall cells merged into few boxes), ``grid_rays`` (rays against the walls over
the grid: what lidar and distance sensors meet). Files are read by ``vehicle_sim/maps``; the
physics part is ``physics/map_layer.py``.

Lanes: every lane map kind (a Lanelet2 ``.osm`` file, the ``roads:`` segments of a world file)
becomes one :class:`~vehicle_sim.core.map.lane_graph.LaneGraph`; what builds on lanes (lane
state, lane invasion, the lane criteria of scenarios) reads only that.

May import (core): specs, geometry, sensors.
"""
