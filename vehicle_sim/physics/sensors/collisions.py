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
Collision events of a vehicle: contacts with any body but the ground, debounced (core).

After each basic step the vehicle's contact points are read (getContactPoints); the points
touching another body (distance <= 0 or a normal force) are grouped by body, their normal forces
summed and their points on the other body averaged (the event's position), and core's
CollisionDebouncer turns "started touching" into one event per pair (again only after the pair
was apart for 0.1 s). The other body is named by World.body_name: an obstacle's or a vehicle's
name.
"""

from dataclasses import replace

from vehicle_sim.core.world.collision import CollisionDebouncer, DEFAULT_MIN_APART_S

_BODY_B, _POSITION_ON_B, _DISTANCE, _NORMAL_FORCE = 2, 6, 8, 9


class CollisionMonitor:
    """
    Collision events of one vehicle body.

    :param world: the World (the monitor registers its ``post_step``).
    :param body: the vehicle body (``body_id``).
    :param min_apart_s: see CollisionDebouncer.
    """

    def __init__(self, world, body, min_apart_s=DEFAULT_MIN_APART_S):
        self.world = world
        self.body = body
        self._debouncer = CollisionDebouncer(min_apart_s)
        self.fresh = []                # events of the last step
        # a body the physics does not move (a kinematic car) finds its own contacts: Bullet
        # makes none between two static bodies (looked up once: a missing attribute costs
        # more than the step's contact read)
        self._read = getattr(body, 'contact_points', None)
        world.add_body(self)

    def contacts(self):
        """
        Return the bodies touching now.

        :return: {other body's name: (sum of normal forces [N], mean contact point on it [m])}.
        """
        world = self.world
        own, ground = self.body.body_id, world.ground_id
        found = {}
        read = self._read
        points = read() if read is not None else world.contact_points(own)
        for point in points:
            other = point[_BODY_B]
            if other in (own, ground) or (point[_DISTANCE] > 0.0 and point[_NORMAL_FORCE] <= 0.0):
                continue
            found.setdefault(other, []).append((point[_NORMAL_FORCE], point[_POSITION_ON_B]))
        return {world.body_name(other): (sum(f for f, _ in points),
                                         tuple(sum(p[k] for _, p in points) / len(points)
                                               for k in range(3)))
                for other, points in found.items()}

    def post_step(self):
        """World hook: turn this step's contacts into events (``fresh``)."""
        touching = self.contacts()
        if not touching and self._debouncer.idle:
            self.fresh = []             # nothing touching, before or now (most steps)
            return
        events = self._debouncer.update(
            self.world.time_s, {name: force for name, (force, _) in touching.items()})
        self.fresh = [replace(event, position_m=touching[event.other][1]) for event in events]

    def close(self):
        """Stop monitoring."""
        if not self.world.closed:
            self.world.remove(self)
