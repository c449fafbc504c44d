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

A :class:`CriteriaScene` holds each vehicle's footprint rectangle (core Outline) and gives the
footprints around them now: fixed ones (static obstacles, and an occupancy map's walls,
:func:`map_walls`) computed once, movable obstacles' read from the world at each call; and the
traffic vehicles now (``traffic``: (name, x, y, yaw, length, width) of each, their box centre),
the vehicles of the scenario now (``samples``) and the world's signals (``signals``, its
SignalController). Criteria get it through ``Criterion.bind``; unit tests build one by hand.
:meth:`CriteriaScene.footprints_near` leaves out, by their boxes along the axes, the footprints too
far to matter (a map has a thousand wall rectangles).
"""

import math
from typing import Callable, Dict, Iterable, Sequence, Tuple

import numpy as np

from vehicle_sim.core.geometry.footprint import Footprint, obstacle_footprint, Outline
from vehicle_sim.physics.map_layer import MAP_BODY_NAME


def bounding_box(footprint: Footprint):
    """Return (x_min, y_min, x_max, y_max) of a footprint [m] (its box along the axes)."""
    if footprint.is_circle:
        (x, y), r = footprint.center_m, footprint.radius_m
        return x - r, y - r, x + r, y + r
    xs, ys = zip(*footprint.vertices)
    return min(xs), min(ys), max(xs), max(ys)


def _box_distance(boxes, box):
    """Return the distances [m] of boxes (n, 4) to a box, all along the axes (0 overlapping)."""
    x0, y0, x1, y1 = box
    dx = np.maximum(np.maximum(boxes[:, 0] - x1, x0 - boxes[:, 2]), 0.0)
    dy = np.maximum(np.maximum(boxes[:, 1] - y1, y0 - boxes[:, 3]), 0.0)
    return np.hypot(dx, dy)


class CriteriaScene:
    """
    The outlines of the vehicles and the footprints of what surrounds them.

    :param outlines: {vehicle name: Outline}.
    :param fixed: footprints that never move (static obstacles, map walls).
    :param moving: returns the footprints of the movable obstacles now; None = none.
    :param traffic: returns the traffic vehicles now, each (name, x, y, yaw, length, width)
        of its box centre [m, rad]; None = the world has no traffic.
    :param lanes: the world's lane map (a core LaneGraph; the lane criteria read it), or None.
    :param walls: an occupancy map's walls (:func:`map_walls`): fixed footprints too.
    :param samples: returns {name: Sample} of every vehicle of the scenario now; None = none.
    :param signals: the world's SignalController (core/map/signal_plan.py; the traffic rule
        criteria read it), or None.
    :param traffic_speeds: returns {name: speed [m/s]} of the traffic vehicles now (their
        poses change only at the traffic's updates); None = not known.
    """

    def __init__(self, outlines: Dict[str, Outline], fixed: Sequence[Footprint] = (),
                 moving: Callable[[], Iterable[Footprint]] = None,
                 traffic: Callable[[], Iterable[tuple]] = None, lanes=None,
                 walls: Sequence[Footprint] = (), samples: Callable[[], dict] = None,
                 signals=None, traffic_speeds: Callable[[], Dict[str, float]] = None):
        self.lanes = lanes
        self.samples = samples
        self.signals = signals
        self.traffic_speeds = traffic_speeds
        self.walls = tuple(walls)
        self._outlines = dict(outlines)
        self._fixed = tuple(fixed) + self.walls
        self._moving = moving
        self.traffic = traffic
        self._boxes = np.array([bounding_box(f) for f in self._fixed], dtype=float).reshape(-1, 4)
        self._names = sorted({f.name for f in self._fixed})
        codes = {name: index for index, name in enumerate(self._names)}
        self._codes = np.array([codes[f.name] for f in self._fixed], dtype=np.int64)

    def outline(self, vehicle) -> Outline:
        """Return a vehicle's footprint rectangle in its base_link frame."""
        return self._outlines[vehicle]

    def footprints(self):
        """Return every footprint now: the fixed ones, then the movable obstacles'."""
        if self._moving is None:
            return self._fixed
        return self._fixed + tuple(self._moving())

    def footprint_names(self):
        """Return the names of the footprints (obstacles, 'map' for a map's walls), a set."""
        return {f.name for f in self.footprints()}

    def footprints_near(self, box, within) -> Sequence[Tuple[float, Footprint]]:
        """
        Return the footprints now that may come nearer than a distance to a box.

        :param box: (x_min, y_min, x_max, y_max) [m] along the axes, e.g. around a vehicle's
            outline.
        :param within: {footprint name: distance [m]}: of a name in it, only the footprints
            whose box along the axes is nearer than that to ``box`` (none at 0: nothing comes
            nearer); all of the others.
        :return: [(a lower bound of the distance to what ``box`` holds [m], footprint)],
            smallest first.
        """
        found = []
        if self._fixed:
            lower = _box_distance(self._boxes, box)
            limits = np.array([within.get(name, math.inf) for name in self._names])
            limits = limits[self._codes]
            for index in np.flatnonzero((lower < limits) & (limits > 0.0)):
                found.append((float(lower[index]), self._fixed[index]))
        if self._moving is not None:
            for footprint in self._moving():
                lower = float(_box_distance(np.array([bounding_box(footprint)]), box)[0])
                limit = within.get(footprint.name, math.inf)
                if lower < limit and limit > 0.0:
                    found.append((lower, footprint))
        found.sort(key=lambda item: item[0])
        return found


def map_walls(built) -> Tuple[Footprint, ...]:
    """
    Return the walls of a built scene's occupancy map as footprints, none without one.

    :param built: the physics Scene (its ``parts['map']``, whose ``wall_boxes()`` they are).
    :return: one rectangle per merged wall rectangle, each named 'map' as the map's
        collisions are.
    """
    part = built.parts.get('map')
    boxes = None if part is None else part.wall_boxes()
    if boxes is None:
        return ()
    c, s = math.cos(boxes.yaw_rad), math.sin(boxes.yaw_rad)
    walls = []
    for (x, y, _), (length, width, _) in zip(boxes.centres_m.tolist(), boxes.sizes_m.tolist()):
        hx, hy = 0.5 * length, 0.5 * width
        walls.append(Footprint(MAP_BODY_NAME, vertices=tuple(
            (x + c * u - s * v, y + s * u + c * v)
            for u, v in ((-hx, -hy), (hx, -hy), (hx, hy), (-hx, hy)))))
    return tuple(walls)


def world_scene(world, vehicles, obstacles, walls: Sequence[Footprint] = (),
                lanes=None, traffic=None, signals=None) -> CriteriaScene:
    """
    Return the scene of a built simulation.

    :param world: the physics World holding the obstacles.
    :param vehicles: {name: VehicleHandle}.
    :param obstacles: the world's ObstacleSpecs.
    :param walls: further fixed footprints (a map's walls).
    :param lanes: the world's lane map (the built scene's ``lanes``), or None.
    :param traffic: the world's traffic (physics TrafficBodies), or None.
    :param signals: the world's SignalController, or None.
    """
    fixed = [obstacle_footprint(spec) for spec in obstacles if spec.static]
    movable = [spec for spec in obstacles if not spec.static]

    def moving():
        for spec in movable:
            (position, orientation), _, _ = world.body_state(world.obstacles[spec.name])
            yield obstacle_footprint(spec, position, orientation)

    def traffic_now():
        return [agent[:6] for agent in traffic.agents()]

    def traffic_speeds():
        return {agent[0]: agent[6] for agent in traffic.agents()}

    def samples():
        return {name: handle.sample(world.time_s) for name, handle in vehicles.items()}

    return CriteriaScene({name: handle.outline for name, handle in vehicles.items()}, fixed,
                         moving if movable else None, None if traffic is None else traffic_now,
                         lanes, walls, samples, signals,
                         None if traffic is None else traffic_speeds)
