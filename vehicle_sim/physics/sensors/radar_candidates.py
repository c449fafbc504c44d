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
What a radar can see: every object body of the world as arrays (position, velocity, size).

The radar's targets are the world's objects, what Webots gives a ``radarCrossSection`` > 0: the
traffic's bodies (both engines: vehicles and pedestrians), the obstacles and the other vehicles
of the world; not the ground, the map's walls or the lane layer (stuff, instance 0). They are
gathered cheaply, without a PyBullet call per traffic body:

- traffic: each traffic part's ``kinematics()`` (the traffic-body contract,
  physics/traffic_kinematics.py): arrays rebuilt once per traffic update, the positions now
  from the velocities (the engines' speed along the heading, exactly the motion the placed
  bodies have between updates);
- static obstacles (mass 0): their pose from their ObstacleSpec, once, velocity zero;
- free obstacles (mass > 0) and the other vehicles: Bullet's pose and velocity now (a few
  calls each; worlds have few of them).

Extents are each body's length, width and height along its own axes (a cylinder's and a
sphere's: their diameter).
"""

import numpy as np
import pybullet

from vehicle_sim.physics.traffic_kinematics import body_table


class RadarCandidates:
    """
    The object bodies of a world but one vehicle's, as body tables.

    :param world: the World.
    :param own_body_id: the radar's vehicle body (never a target of its own radar).
    """

    def __init__(self, world, own_body_id):
        self.world = world
        self.own = own_body_id
        self._key = None
        self._static = None          # body table of the fixed obstacles
        self._free = ()              # [(body id, extents)] of obstacles Bullet moves
        self._traffic = ()           # the traffic parts (their kinematics())
        self._vehicles = {}          # body id -> extents of the other vehicles

    def _refresh(self):
        # The world's obstacles and parts changed (a SUMO pool grows): sort them again.
        world = self.world
        self._traffic = tuple(body for body in world.bodies if hasattr(body, 'kinematics'))
        moved = set().union(*(part.moving_names() for part in self._traffic))
        ids, positions, extents, yaw, free = [], [], [], [], []
        for name, body_id in world.obstacles.items():
            if name in moved:
                continue
            spec = world.obstacle_spec(name)
            if spec.static:
                ids.append(body_id)
                positions.append(spec.position_m)
                extents.append(spec.size_m)
                yaw.append(spec.yaw_rad)
            else:
                free.append((body_id, tuple(spec.size_m)))
        self._static = body_table(ids, positions, np.zeros((len(ids), 3)), extents, yaw)
        self._free = tuple(free)

    def _vehicle_rows(self):
        cid = self.world.client_id
        rows = []
        for body in self.world.vehicle_bodies():
            body_id = body.body_id
            if body_id == self.own:
                continue
            extents = self._vehicles.get(body_id)
            if extents is None:
                low, high = pybullet.getAABB(body_id, physicsClientId=cid)
                outline = body.outline
                extents = self._vehicles[body_id] = (outline.length_m, outline.width_m,
                                                     high[2] - low[2])
            rows.append((body_id, extents))
        return rows

    def now(self):
        """
        Return every object body now, in the world frame, as blocks.

        :return: [(body table (physics/traffic_kinematics.py columns: centre, velocity,
            extents, heading, bounding radius, body id), since [s], kept)]: a body is at
            ``X..Z + VX..VZ * since`` now; ``kept``: the table is the same object while its
            bodies' motion is (a traffic part's until its next update, the fixed obstacles'
            for good), so what a reader derives from it holds as long; the bodies Bullet
            moves (free obstacles, other vehicles) come in a table of their own made now.
        """
        world = self.world
        key = (len(world.obstacles), len(world.bodies))
        if key != self._key:
            self._refresh()
            self._key = key
        blocks = [part.kinematics() + (True,) for part in self._traffic]
        if len(self._static):
            blocks.append((self._static, 0.0, True))
        moving = list(self._free) + self._vehicle_rows()
        if moving:
            blocks.append((self._bullet_block(moving), 0.0, False))
        return blocks

    def _bullet_block(self, rows):
        # Bullet's pose and velocity of bodies it moves: centre of mass, its linear velocity.
        cid = self.world.client_id
        pose, velocity = pybullet.getBasePositionAndOrientation, pybullet.getBaseVelocity
        positions, velocities, yaw = [], [], []
        for body_id, _ in rows:
            position, (qx, qy, qz, qw) = pose(body_id, physicsClientId=cid)
            positions.append(position)
            velocities.append(velocity(body_id, physicsClientId=cid)[0])
            yaw.append(np.arctan2(2.0 * (qw * qz + qx * qy), 1.0 - 2.0 * (qy * qy + qz * qz)))
        return body_table([row[0] for row in rows], positions, velocities,
                          [row[1] for row in rows], yaw)
