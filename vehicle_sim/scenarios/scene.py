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
What a run's criteria measure distances against: vehicle outlines and obstacle footprints.

A :class:`Scene` holds each vehicle's footprint rectangle (core Outline) and gives the
footprints around them now: fixed ones (static obstacles, and the walls a map adds) computed
once, movable obstacles' read from the world at each call; and the traffic vehicles now
(``traffic``: (name, x, y, yaw, length, width) of each, their box centre). Criteria get it
through ``Criterion.bind``; unit tests build one by hand.
"""

from typing import Callable, Dict, Iterable, Sequence

from vehicle_sim.core.geometry.footprint import Footprint, obstacle_footprint, Outline


class Scene:
    """
    The outlines of the vehicles and the footprints of what surrounds them.

    :param outlines: {vehicle name: Outline}.
    :param fixed: footprints that never move (static obstacles, map walls).
    :param moving: returns the footprints of the movable obstacles now; None = none.
    :param traffic: returns the traffic vehicles now, each (name, x, y, yaw, length, width)
        of its box centre [m, rad]; None = the world has no traffic.
    :param lanes: the world's lane map (a core LaneGraph; the lane criteria read it), or None.
    """

    def __init__(self, outlines: Dict[str, Outline], fixed: Sequence[Footprint] = (),
                 moving: Callable[[], Iterable[Footprint]] = None,
                 traffic: Callable[[], Iterable[tuple]] = None, lanes=None):
        self.lanes = lanes
        self._outlines = dict(outlines)
        self._fixed = tuple(fixed)
        self._moving = moving
        self.traffic = traffic

    def outline(self, vehicle) -> Outline:
        """Return a vehicle's footprint rectangle in its base_link frame."""
        return self._outlines[vehicle]

    def footprints(self):
        """Return every footprint now: the fixed ones, then the movable obstacles'."""
        if self._moving is None:
            return self._fixed
        return self._fixed + tuple(self._moving())


def world_scene(world, vehicles, obstacles, walls: Sequence[Footprint] = (),
                lanes=None, traffic=None) -> Scene:
    """
    Return the scene of a built simulation.

    :param world: the physics World holding the obstacles.
    :param vehicles: {name: VehicleHandle}.
    :param obstacles: the world's ObstacleSpecs.
    :param walls: further fixed footprints (a map's walls).
    :param lanes: the world's lane map (the built scene's ``lanes``), or None.
    :param traffic: the world's traffic (physics TrafficBodies), or None.
    """
    fixed = [obstacle_footprint(spec) for spec in obstacles if spec.static] + list(walls)
    movable = [spec for spec in obstacles if not spec.static]

    def moving():
        for spec in movable:
            (position, orientation), _, _ = world.body_state(world.obstacles[spec.name])
            yield obstacle_footprint(spec, position, orientation)

    def traffic_now():
        manager = traffic.manager
        return [(v.name, *manager.pose(v), v.length_m, v.width_m)
                for v in manager.vehicles if v.active]

    return Scene({name: handle.outline for name, handle in vehicles.items()}, fixed,
                 moving if movable else None, None if traffic is None else traffic_now,
                 lanes)
