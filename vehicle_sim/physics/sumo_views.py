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
The traffic-body contract's views of the SUMO engine's bodies (physics/sumo_traffic.py).

``agents()``, ``objects()`` (with each vehicle's predicted path along its lane and route),
``boxes()``, ``moving_names()``, ``body_of``, ``colours``, ``since_update_s``, and between body
names and SUMO ids; SumoBodies is one :class:`SumoViews`.
"""

import math

from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.traffic.lane_paths import route_path
from vehicle_sim.core.traffic.objects import (
    CLASS_SHAPES,
    PREDICTION_HORIZON_S,
    PREDICTION_STEP_S,
    shape_extents,
    TrafficObject,
)
from vehicle_sim.core.traffic.sumo_params import object_class
from vehicle_sim.physics.traffic_boxes import COLOURS

__all__ = ['SumoViews']


class SumoViews:
    """
    The traffic-body contract's views of SumoBodies' serving bodies (agents, objects, boxes).

    Uses SumoBodies' ``world``, ``session``, ``graph``, ``_slots``, ``_by_id``, ``_lengths``,
    ``_reads``, ``_placed_at``, ``_state`` and ``_motion``.
    """

    @property
    def colours(self):
        """Each body's colour by its index (a person's orange; the markers colour by index)."""
        return tuple(slot.colour for slot in self._slots) or COLOURS

    @property
    def since_update_s(self):
        """Time since SUMO's last step [s] (its vehicles went on straight since)."""
        return self.world.time_s - self._placed_at

    def _serving(self):
        return sorted(self._by_id.values(), key=lambda slot: slot.index)

    def agents(self):
        """
        Return every SUMO vehicle and person in the world now, as the scenarios see them.

        :return: [(name, x, y, yaw, length, width, speed)] at SUMO's last step: footprint
            centre and heading [m, rad], footprint size [m], speed along the heading [m/s].
        """
        return [(slot.name, *state[:3], slot.size[0], slot.size[1], state[3])
                for slot, state in ((slot, self._state(slot)) for slot in self._serving())]

    def moving_names(self):
        """Return the names of every body SUMO moves (serving or parked)."""
        return {slot.name for slot in self._slots}

    def kinematics(self):
        """
        Return the serving bodies: a body table and the time since (traffic_kinematics.py).

        Each body as placed at SUMO's last step, its velocity SUMO's speed along its heading:
        where it is now is that plus the velocity times the time since.
        """
        def rows():
            return [(slot.body_id, self._motion(slot), (slot.size[0], slot.size[1],
                                                        slot.size[2] - slot.clearance))
                    for slot in self._serving() if slot.front is not None]
        return self._table.now(self.since_update_s, rows)

    def boxes(self):
        """
        Return [(name, body id, size [m], colour, shape)] of the serving bodies.

        Each body's shape is its class's (a pedestrian an upright cylinder), its size that
        shape's extents (core/traffic/objects.py shape_extents).
        """
        found = []
        for slot in self._serving():
            name = object_class(slot.vclass)
            found.append((slot.name, slot.body_id,
                          shape_extents(name, slot.size[0], slot.size[1],
                                        slot.size[2] - slot.clearance),
                          slot.colour, CLASS_SHAPES[name]))
        return found

    def objects(self, horizon_s=PREDICTION_HORIZON_S, step_s=PREDICTION_STEP_S, paths=True):
        """
        Return SUMO's vehicles and persons as core TrafficObjects now.

        Each is where its body is (gone on straight since SUMO's step), its class from its
        SUMO vehicle class (core/traffic/sumo_params.py object_class); a vehicle's predicted
        path follows its lane and the lanes of its route after it at its speed
        (core/traffic/lane_paths.py), a person's (or one on a lane the lane graph lacks) goes
        on straight. ``paths`` False: no paths (each empty), for readers of poses and speeds.
        """
        since = self.since_update_s
        count = int(round(horizon_s / step_s))
        found = []
        for slot in self._serving():
            x, y, yaw, speed = self._state(slot)
            c, s = math.cos(yaw), math.sin(yaw)
            gone = speed * since
            x, y = x + gone * c, y + gone * s
            path = self._lane_path(slot, since, count, step_s) if paths else ()
            if path is None:
                path = tuple((x + speed * step_s * k * c, y + speed * step_s * k * s, yaw)
                             for k in range(1, count + 1))
            found.append(TrafficObject(slot.index, slot.name, x, y, yaw, speed, slot.size[0],
                                       slot.size[1], slot.size[2], path, step_s,
                                       object_class(slot.vclass), slot.instance))
        return tuple(found)

    def _lane_path(self, slot, since, count, step_s):
        """Return a vehicle's path along the lane graph, or None (no graph, lane not in it)."""
        if self.graph is None or slot.person:
            return None
        if slot.lane is None:             # read now, once per SUMO step (sumo_reads.py)
            with self.session.errors(f'reading vehicle {slot.sumo_id!r}'):
                try:
                    slot.lane = self._reads.lane(self.session.api, slot.sumo_id)
                except self.session.refusal:
                    return None
        lane_id, position, route_index = slot.lane
        try:
            lane = self.graph.lane_named(lane_id)
        except InvalidParameterError:
            return None
        length = self._lengths.get(lane_id)
        if length is None:
            with self.session.errors(f'reading lane {lane_id!r}'):
                length = self._lengths[lane_id] = self.session.api.lane.getLength(lane_id)
        scale = lane.length_m / length if length > 0.0 else 1.0
        speed = slot.speed
        centre = position * scale - 0.5 * slot.size[0] + speed * since
        return route_path(self.graph, lane.id, centre, speed, count, step_s,
                          slot.route[route_index + 1:])

    def body_of(self, name):
        """Return the body id of the body called ``name`` (``sumo_<k>``)."""
        for slot in self._slots:
            if slot.name == name:
                return slot.body_id
        raise KeyError(name)

    def sumo_id(self, name):
        """Return the SUMO id of whom body ``name`` serves now (None: parked)."""
        for slot in self._slots:
            if slot.name == name:
                return slot.sumo_id
        raise KeyError(name)

    def name_of(self, sumo_id, person=False):
        """Return the name of the body of SUMO vehicle (or person) ``sumo_id`` now."""
        return self._by_id[(person, sumo_id)].name
