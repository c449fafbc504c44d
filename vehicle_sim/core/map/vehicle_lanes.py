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
One vehicle on a lane map: its lane state and the markings it crosses, from its poses.

:class:`VehicleLanes` pairs a LaneTracker (core/map/lane_state.py) with a LaneInvasionDetector
(core/map/lane_invasion.py) on one LaneGraph, fed with the vehicle's reference point
(``base_link``) and heading; what publishes lane state (the automobile node's
``<ns>/lane_state`` and ``<ns>/lane_invasion``, the Webots facade's ``getLaneState``) holds one
per vehicle and calls :meth:`VehicleLanes.reset` after each reset or teleport, so that the jump
is neither a crossing nor a move along the lanes.
"""

from typing import Tuple

from vehicle_sim.core.map.lane_graph import LaneGraph
from vehicle_sim.core.map.lane_invasion import LaneInvasion, LaneInvasionDetector
from vehicle_sim.core.map.lane_state import LaneState, LaneTracker, OFF_LANE


class VehicleLanes:
    """
    A vehicle's lane state and lane invasions.

    :param graph: the world's LaneGraph.
    :param signals: the world's SignalController, or None (LaneTracker: the signal state of the
        next stop line).
    :attr state: the LaneState of the last update (OFF_LANE before the first).
    """

    def __init__(self, graph: LaneGraph, signals=None):
        self.graph = graph
        self.tracker = LaneTracker(graph, signals)
        self.detector = LaneInvasionDetector(graph)
        self.state: LaneState = OFF_LANE

    def reset(self):
        """Forget the previous pose (after a reset or a teleport)."""
        self.tracker.reset()
        self.detector.reset()
        self.state = OFF_LANE

    def update(self, x_m, y_m, yaw_rad, time_s) -> Tuple[LaneState, Tuple[LaneInvasion, ...]]:
        """Return the lane state at the pose and the markings crossed since the last update."""
        self.state = state = self.tracker.update(x_m, y_m, yaw_rad)
        return state, self.detector.update(x_m, y_m, time_s)
