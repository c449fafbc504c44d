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
Traffic in the physics world: one kinematic box per traffic vehicle, moved by the core manager.

:class:`TrafficPart` is the scene part (physics/scene.py) of a world file's ``traffic:``: it
takes the world's lane map (its ``roads:``, or a LaneGraph given to it, e.g. a Lanelet2 map's),
reads each model's dimensions from its car preset (the footprint of its collision boxes and
tyres, the top of its highest box), builds the core TrafficManager and adds one static
(mass 0) box per traffic vehicle as a named obstacle (``traffic_<i>``), so that lidars, distance
sensors, cameras, collision monitors and teleport checks see it like any obstacle.

Every ``update_period`` (a whole number of world steps) the step hook gives the manager our
vehicles (footprint centre, heading, speed, size), advances it and puts each box at its
vehicle's pose with its velocity; between updates Bullet moves the boxes on at that velocity.
A vehicle waiting to re-enter the map is parked under the ground. After every step the
contacts of our vehicles with the traffic vehicles near them (within NEAR_M at the last update)
are read: a traffic vehicle touching one of ours stops for good (it stays where it is, an
obstacle).
"""

import math

import pybullet

from vehicle_sim.config import load_car
from vehicle_sim.core.geometry.angles import yaw_from_quaternion
from vehicle_sim.core.geometry.footprint import car_outline
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.traffic.manager import OurVehicle, TrafficManager
from vehicle_sim.core.world.params import ObstacleSpec

GROUND_CLEARANCE_M = 0.15        # the box's underside above the ground
PARK_DEPTH_M = -50.0             # where a vehicle off the map waits (under the ground)
# body colours, picked by vehicle index (deterministic)
COLOURS = ((0.80, 0.10, 0.10, 1.0), (0.10, 0.30, 0.80, 1.0), (0.90, 0.90, 0.90, 1.0),
           (0.15, 0.15, 0.15, 1.0), (0.20, 0.60, 0.25, 1.0), (0.95, 0.75, 0.10, 1.0),
           (0.55, 0.55, 0.60, 1.0))
# the contacts of our vehicles are read with the traffic vehicles within this distance of them
# at the last update (both move less than 10 m in 100 ms; the longest box is about 6 m)
NEAR_M = 40.0


def model_dimensions(model):
    """Return (length, width, height) [m] of a car preset's box: footprint and top."""
    params = load_car(model)
    outline = car_outline(params)
    top = max(box.position_m[2] + 0.5 * box.size_m[2] for box in params.collision_boxes)
    return outline.length_m, outline.width_m, top + params.rear_tire_radius_m


def our_vehicle(body, outline=None):
    """Return a VehicleBody as the traffic manager sees it (OurVehicle); ``outline``: cached."""
    x, y, _, qx, qy, qz, qw = body.pose()
    yaw = yaw_from_quaternion(qx, qy, qz, qw)
    outline = body.outline if outline is None else outline
    cx = 0.5 * (outline.x_min_m + outline.x_max_m)
    cy = 0.5 * (outline.y_min_m + outline.y_max_m)
    c, s = math.cos(yaw), math.sin(yaw)
    return OurVehicle(body.name, x + c * cx - s * cy, y + s * cx + c * cy, yaw,
                      body.forward_speed_mps(), outline.length_m, outline.width_m)


class TrafficPart:
    """
    The scene part of ``traffic:``.

    :param graph: the lane map (a core LaneGraph); None = the world's ``roads:``.
    """

    name = 'traffic'

    def __init__(self, graph=None):
        self.graph = graph

    def build(self, world, spec):
        """Add the traffic of ``spec`` to ``world``; return its TrafficBodies (None: none)."""
        traffic = spec.traffic
        if traffic is None:
            return None
        # The world's lane map, loaded once by the scene builder (vehicle_sim/maps/lane_maps.py).
        graph = self.graph if self.graph is not None else getattr(spec, 'lanes', None)
        if graph is None:
            raise InvalidParameterError(f'{traffic.source}: traffic needs a lane map '
                                        f'(roads: in the world file, or a Lanelet2 map)')
        sizes = {model: model_dimensions(model) for model in traffic.all_models}
        ours = [our_vehicle(body) for body in world.vehicle_bodies()]
        manager = TrafficManager(graph, traffic, {m: d[:2] for m, d in sizes.items()}, ours)
        return TrafficBodies(world, manager, sizes)


class TrafficBodies:
    """
    The traffic vehicles' bodies in a World, moved by a TrafficManager (a world step hook).

    :param world: the World.
    :param manager: the core TrafficManager.
    :param sizes: {model: (length, width, height)} [m].
    """

    def __init__(self, world, manager, sizes):
        self.world = world
        self.manager = manager
        dt = world.time_step_s
        self.every = max(1, int(round(manager.spec.update_period_s / dt)))
        if abs(self.every * dt - manager.spec.update_period_s) > 1e-9:
            raise InvalidParameterError(
                f"{manager.spec.source}: field 'update_period' = "
                f'{manager.spec.update_period_s:g}: must be a multiple of the world step '
                f'{dt:g} s')
        self._heights = [sizes[v.model][2] for v in manager.vehicles]
        self.heights = {model: size[2] for model, size in sizes.items()}   # {model: height}
        self.colours = COLOURS
        self.body_ids = []
        self._index = {}
        cid = world.client_id
        for v in manager.vehicles:
            x, y, yaw = manager.pose(v)
            length, width, height = sizes[v.model]
            spec = ObstacleSpec(v.name, 'box', (x, y, self._z(v.index)), 0.0, 0.0, yaw, 0.0,
                                COLOURS[v.index % len(COLOURS)],
                                (length, width, height - GROUND_CLEARANCE_M))
            body_id = world.add_obstacle(spec)
            self.body_ids.append(body_id)
            self._index[body_id] = v.index
        self._cid = cid
        self._ours = world.vehicle_bodies()
        self._outlines = [body.outline for body in self._ours]
        self._parked = set()
        self._place()
        self._near = self._nearby([our_vehicle(body, outline)
                                   for body, outline in zip(self._ours, self._outlines)])
        world.add_body(self)

    def reset(self):
        """Start the traffic again as built (same seed: the same places); say so in words."""
        old = self.manager
        ours = [our_vehicle(body, outline) for body, outline in zip(self._ours, self._outlines)]
        self.manager = TrafficManager(old.graph, old.spec, old.dimensions, ours)
        self._parked = set()
        self._place()
        self._near = self._nearby(ours)
        return f'traffic: its {len(self.manager.vehicles)} vehicles back at their start'

    def _z(self, index):
        return 0.5 * (self._heights[index] + GROUND_CLEARANCE_M)

    def _place(self):
        cid = self._cid
        manager = self.manager
        reset_pose, reset_velocity = pybullet.resetBasePositionAndOrientation, \
            pybullet.resetBaseVelocity
        parked, heights = self._parked, self._heights
        self._positions = positions = []       # (index, x, y) of the vehicles on the map
        for v, body_id in zip(manager.vehicles, self.body_ids):
            index = v.index
            if not v.active:
                if index not in parked:        # under the ground until it re-enters
                    reset_pose(body_id, (0.0, 0.0, PARK_DEPTH_M - 10.0 * index),
                               (0.0, 0.0, 0.0, 1.0), physicsClientId=cid)
                    reset_velocity(body_id, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0),
                                   physicsClientId=cid)
                    parked.add(index)
                continue
            parked.discard(index)
            x, y, yaw = manager.pose(v)
            positions.append((index, x, y))
            half = 0.5 * yaw
            reset_pose(body_id, (x, y, 0.5 * (heights[index] + GROUND_CLEARANCE_M)),
                       (0.0, 0.0, math.sin(half), math.cos(half)), physicsClientId=cid)
            speed = v.speed_mps
            reset_velocity(body_id, (speed * math.cos(yaw), speed * math.sin(yaw), 0.0),
                           (0.0, 0.0, 0.0), physicsClientId=cid)

    def pre_step(self):
        """World hook: every ``update_period``, advance the traffic and place the bodies."""
        count = self.world.step_count
        if count == 0 or count % self.every:
            return
        ours = [our_vehicle(body, outline) for body, outline in zip(self._ours, self._outlines)]
        self.manager.set_ours(ours)
        self.manager.step(self.every * self.world.time_step_s)
        self._place()
        self._near = self._nearby(ours)

    def _nearby(self, ours):
        """Return, per one of our vehicles, the traffic vehicles within NEAR_M of it."""
        limit = NEAR_M * NEAR_M
        return [[index for index, x, y in self._positions
                 if (x - o.x_m) ** 2 + (y - o.y_m) ** 2 < limit] for o in ours]

    def post_step(self):
        """World hook: a traffic vehicle touching one of our vehicles stops for good."""
        cid, manager, body_ids = self._cid, self.manager, self.body_ids
        contacts = pybullet.getContactPoints
        for body, near in zip(self._ours, self._near):
            for i in near:
                if not manager.vehicles[i].stopped and contacts(
                        bodyA=body.body_id, bodyB=body_ids[i], physicsClientId=cid):
                    manager.stop(i)
                    pybullet.resetBaseVelocity(body_ids[i], (0.0, 0.0, 0.0), (0.0, 0.0, 0.0),
                                               physicsClientId=cid)

    def boxes(self):
        """
        Return the traffic vehicles on the map as drawn (the Foxglove scene's ``traffic/``).

        :return: [(name, body id, (length, width, height) of its box [m], colour)]; a vehicle
            parked under the ground (waiting to re-enter) is left out.
        """
        dimensions, colours = self.manager.dimensions, self.colours
        return [(v.name, body_id, dimensions[v.model][:2] + (
                     self.heights[v.model] - GROUND_CLEARANCE_M,),
                 colours[v.index % len(colours)])
                for v, body_id in zip(self.manager.vehicles, self.body_ids) if v.active]

    def body_of(self, name):
        """Return the body id of the traffic vehicle called ``name`` (``traffic_<i>``)."""
        for v, body_id in zip(self.manager.vehicles, self.body_ids):
            if v.name == name:
                return body_id
        raise KeyError(name)
