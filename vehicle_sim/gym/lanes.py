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
The ego's lane state in the Gym environment: the ``lane`` and ``lane_id`` observation keys.

Present when the world has a lane map (``roads:`` or ``map: {type: lanelet2}``; the scene's
``lanes``): :func:`lane_part` is in observations.PART_FACTORIES and returns None for a world
without lanes, so such worlds keep their observation keys. The DriveSim owns the ego's
VehicleLanes (core/map/vehicle_lanes.py: a LaneTracker and a LaneInvasionDetector), resets it
after each in-place reset (and start offset) and updates it once per env step; this part only
reads its state.

- ``lane``: (6,) float32: [s along the lane's centreline [m], lateral offset from it, + = left
  [m], heading error (yaw minus the lane's direction) [rad], the lane's width there [m], its
  speed limit [m/s], on_lane (1.0 on a lane, 0.0 off every lane: then every entry is 0)].
- ``lane_id``: (1,) int64: the lane's id (a lanelet id, or a road lane's id of docs/lanes.md);
  0 off every lane. An identifier, not a magnitude: ``DriveSim.lane_ids`` lists them sorted,
  for an index or a one-hot code.
"""

import math

import numpy as np

LANE = 'lane'
LANE_ID = 'lane_id'
# Margin on the offset bound [m]: the tracker counts a point within 1e-6 m of the edge as on it.
_EDGE_M = 1e-3


class LanePart:
    """
    The ``lane`` and ``lane_id`` keys, read from a VehicleLanes the simulation updates.

    :param vehicle_lanes: the ego's VehicleLanes (its ``state`` is read).
    """

    def __init__(self, vehicle_lanes):
        self.vehicle_lanes = vehicle_lanes
        lanes = vehicle_lanes.graph.lanes.values()
        self._length = max(lane.length_m for lane in lanes)
        self._width = max(max(lane.widths) for lane in lanes)
        self._limit = max(lane.speed_limit_mps for lane in lanes)
        ids = [lane.id for lane in lanes]
        self._ids = (min(0, min(ids)), max(0, max(ids)))

    def spaces(self):
        half = 0.5 * self._width + _EDGE_M
        return {
            LANE: ((0.0, -half, -math.pi, 0.0, 0.0, 0.0),
                   (self._length, half, math.pi, self._width, self._limit, 1.0),
                   (6,), np.float32),
            LANE_ID: (self._ids[0], self._ids[1], (1,), np.int64),
        }

    def reset(self):
        pass        # the DriveSim resets and updates the VehicleLanes after the teleport

    def read(self, out):
        state = self.vehicle_lanes.state
        out[LANE] = np.array((state.s_m, state.offset_m, state.heading_error_rad,
                              state.width_m, state.speed_limit_mps, float(state.on_lane)),
                             dtype=np.float32)
        out[LANE_ID] = np.array((state.lane_id,), dtype=np.int64)


def lane_part(sim):
    """Return the ego's LanePart when the world has lanes, else None (a PART_FACTORIES entry)."""
    return None if sim.lanes is None else LanePart(sim.lanes)
