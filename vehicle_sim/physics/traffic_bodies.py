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
Traffic in the physics world: one placed box per traffic vehicle, moved by the core manager.

:class:`TrafficPart` is the scene part (physics/scene.py) of a world file's ``traffic:``: it
takes the world's lane map (its ``roads:``, or a LaneGraph given to it, e.g. a Lanelet2 map's),
reads each model's dimensions from its car preset (the footprint of its collision boxes and
tyres, the top of its highest box), builds the core TrafficManager and adds one static box per
traffic vehicle as a named obstacle (``traffic_<i>``), so that lidars, distance sensors,
cameras, collision monitors and teleport checks see it like any obstacle; its label
(``World.labels``) is its object class's and its instance id its name's.

Every ``update_period`` (a whole number of world steps) the step hook gives the manager our
vehicles (footprint centre, heading, speed, size), advances it and puts the boxes near ours (within
NEAR_M) at their vehicles' poses; the others wait under the ground until they come near or
something reads the world. Between updates a vehicle goes on straight at its speed, and its box is
put there whenever something can tell: before each step for the vehicles near ours (the step's
contacts), before anything reads the world (``World.sync_bodies``: rays, cameras, overlap checks,
body states) for all of them, and once a frame (gui.FRAME_PERIOD_S) with a GUI window, not each
step. Bullet never moves the boxes itself: a static rigid body costs its step almost nothing, where
50 moving bodies cost it some 20 us a step (docs/traffic.md, Cost). A vehicle waiting to re-enter
the map is parked under the ground. After every step the contacts of our vehicles with the traffic
vehicles near them (within NEAR_M at the last update) are read: a traffic vehicle touching one of
ours stops for good where its box was (it stays there, an obstacle).
"""

from dataclasses import replace
import math

import pybullet

from vehicle_sim.config import load_car
from vehicle_sim.core.geometry.footprint import car_outline
from vehicle_sim.core.sensors.labels import label_of_class, LABELS
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.traffic.manager import TrafficManager
from vehicle_sim.core.traffic.objects import CLASS_SHAPES, shape_extents, traffic_objects
from vehicle_sim.core.world.params import ObstacleSpec
from vehicle_sim.physics.gui import FRAME_PERIOD_S
from vehicle_sim.physics.traffic_boxes import (
    COLOURS,
    GROUND_CLEARANCE_M,
    NEAR_M,
    our_vehicle,
    PARK_DEPTH_M,
    touched,
)
from vehicle_sim.physics.traffic_kinematics import MotionTable

# the object class of the builtin engine's vehicles (core/traffic/objects.py OBJECT_CLASSES)
OBJECT_CLASS = 'car'


def model_dimensions(model):
    """Return (length, width, height) [m] of a car preset's box: footprint and top."""
    params = load_car(model)
    outline = car_outline(params)
    top = max(box.position_m[2] + 0.5 * box.size_m[2] for box in params.collision_boxes)
    return outline.length_m, outline.width_m, top + params.rear_tire_radius_m


class TrafficPart:
    """
    The scene part of ``traffic:``.

    The traffic obeys the world's signals: the SignalController of the scene part ``signals``
    (``parts['signals'].controller``), built before it, when the world has one.

    :param graph: the lane map (a core LaneGraph); None = the world's ``roads:``.
    """

    name = 'traffic'
    reads_parts = True          # built as build(world, spec, parts): the parts built before it

    def __init__(self, graph=None):
        self.graph = graph

    def build(self, world, spec, parts=None):
        """
        Add the traffic of ``spec`` to ``world``; return its TrafficBodies (None: none).

        :param parts: the scene parts built before it, by name (the signals part's controller).
        """
        traffic = spec.traffic
        if traffic is None:
            return None
        return TRAFFIC_BUILDERS[traffic.engine](self, world, spec, parts or {})

    def build_builtin(self, world, spec, parts):
        """Return the TrafficBodies of the builtin engine (``TRAFFIC_BUILDERS['builtin']``)."""
        traffic = spec.traffic
        # The world's lane map, loaded once by the scene builder (vehicle_sim/maps/lane_maps.py).
        graph = self.graph if self.graph is not None else getattr(spec, 'lanes', None)
        if graph is None:
            raise InvalidParameterError(f'{traffic.source}: traffic needs a lane map '
                                        f'(roads: in the world file, or a Lanelet2 map)')
        sizes = {model: model_dimensions(model) for model in traffic.all_models}
        ours = [our_vehicle(body) for body in world.vehicle_bodies()]
        signals = getattr(parts.get('signals'), 'controller', None)
        manager = TrafficManager(graph, traffic, {m: d[:2] for m, d in sizes.items()}, ours,
                                 signals)
        return TrafficBodies(world, manager, sizes)


class TrafficBodies:
    """
    The traffic vehicles' bodies in a World, moved by a TrafficManager (a world step hook).

    What every engine's traffic part offers (the traffic-body contract, read by the node, the
    scenarios, the Gym environment and the live view; docs/traffic.md): :meth:`reset`,
    :meth:`agents`, :meth:`moving_names`, :meth:`objects`, :meth:`boxes`, :meth:`body_of`,
    :meth:`kinematics`, :meth:`expect_path`,
    :attr:`follow_params`, ``colours`` and :attr:`since_update_s`. Each body is a named
    obstacle of the World, placed (never moved by Bullet).

    Each box is a Bullet rigid body that is only ever placed (it costs a physics step almost
    nothing, where a moving body costs Bullet some 0.4 us a step each). Between two updates a
    vehicle goes on straight at its speed: a box is put at that pose (the last update's plus
    the velocity times the time since) when something can tell: before each step for the
    vehicles near ours (their contacts), and before anything reads the world between steps
    (:meth:`before_query`, called by ``World.sync_bodies``: rays, cameras, overlap checks), and
    once a frame (``FRAME_PERIOD_S`` of simulated time) with a GUI window.

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
        for v in manager.vehicles:
            x, y, yaw = manager.pose(v)
            length, width, height = sizes[v.model]
            spec = ObstacleSpec(v.name, 'box', (x, y, self._z(v.index)), 0.0, 0.0, yaw, 0.0,
                                COLOURS[v.index % len(COLOURS)],
                                (length, width, height - GROUND_CLEARANCE_M))
            body_id = world.add_obstacle(spec, placed=True, label=(
                LABELS[label_of_class(OBJECT_CLASS)].name, world.labels.instance(v.name)))
            self.body_ids.append(body_id)
        self._cid = world.client_id
        self._ours = world.vehicle_bodies()
        self._outlines = [body.outline for body in self._ours]
        self._parked = set()
        self._away = set()             # vehicles on the map whose boxes wait under the ground
        # per vehicle on the map: (x, y, z, qz, qw, vx, vy) of its box at the last update
        self._motion = [None] * len(self.body_ids)
        self._placed_at = 0.0          # the time of the last update [s]
        self._synced_step = -1         # the step count at which every box was last put
        self._start_step = world.step_count    # updates every ``every`` steps from here
        self._drawn_at = -math.inf     # when every box was last put for the GUI window [s]
        self._table = MotionTable()    # kinematics(), rebuilt after each update
        self._place()
        world.add_body(self)

    def reset(self, seed=None):
        """
        Start the traffic again, clear of our vehicles where they are now; say so in words.

        :param seed: the seed of the new start (places, models, speed factors, route choices);
            None = the world's ``seed`` (as built, when our vehicles are at their spawn poses).
        :raises InvalidParameterError: when the traffic does not fit around our vehicles (a
            placed vehicle on one of them, fewer free places than vehicles); nothing changed.
        """
        old = self.manager
        spec = old.spec if seed is None else replace(old.spec, seed=seed)
        ours = [our_vehicle(body, outline) for body, outline in zip(self._ours, self._outlines)]
        self.manager = TrafficManager(old.graph, spec, old.dimensions, ours, old.signals)
        self._start_step = self.world.step_count
        self._parked = set()
        self._away = set()
        self._place(ours)
        return f'traffic: its {len(self.manager.vehicles)} vehicles back at their start'

    def _z(self, index):
        return 0.5 * (self._heights[index] + GROUND_CLEARANCE_M)

    def _place(self, ours=None):
        """
        Put the boxes near ``ours`` (OurVehicles; None: read now) at their vehicles' poses.

        The others wait under the ground, where no vehicle of ours can touch them, until
        something reads the world (:meth:`before_query`) or they come near: a box left where it
        was put long ago could stand in our vehicles' way with its vehicle far off. Putting a
        box costs more than the rest of its update.
        """
        if ours is None:
            ours = [our_vehicle(body, outline)
                    for body, outline in zip(self._ours, self._outlines)]
        cid = self._cid
        manager = self.manager
        reset_pose = pybullet.resetBasePositionAndOrientation
        parked, away, heights = self._parked, self._away, self._heights
        motion, body_ids = self._motion, self.body_ids
        self._positions = positions = []       # (index, x, y) of the vehicles on the map
        cos, sin = math.cos, math.sin
        for v in manager.vehicles:
            index = v.index
            if not v.active:
                motion[index] = None
                away.discard(index)
                if index not in parked:        # under the ground until it re-enters
                    self._park(index)
                    parked.add(index)
                continue
            parked.discard(index)
            x, y, yaw = manager.pose(v)
            positions.append((index, x, y))
            half = 0.5 * yaw
            speed = v.speed_mps
            motion[index] = (x, y, 0.5 * (heights[index] + GROUND_CLEARANCE_M), sin(half),
                             cos(half), speed * cos(yaw), speed * sin(yaw))
        self._near, self._near_all = self._nearby(ours)
        near = set(self._near_all)
        for index, _, _ in positions:
            if index in near:
                x, y, z, qz, qw, _, _ = motion[index]
                reset_pose(body_ids[index], (x, y, z), (0.0, 0.0, qz, qw), physicsClientId=cid)
                away.discard(index)
            elif index not in away:
                self._park(index)
                away.add(index)
        self._placed_at = self.world.time_s
        self._synced_step = self.world.step_count
        self._table.invalidate()
        self.world.mark_moved()

    def _park(self, index):
        # a box under the ground (each at its own depth): off the map, or far from ours
        pybullet.resetBasePositionAndOrientation(
            self.body_ids[index], (0.0, 0.0, PARK_DEPTH_M - 10.0 * index), (0.0, 0.0, 0.0, 1.0),
            physicsClientId=self._cid)

    def _move(self, indices, standing=()):
        """
        Put the boxes of ``indices`` where their vehicles are now (straight on).

        A vehicle at rest is put only when it is in ``standing`` (its box is elsewhere).
        """
        cid, body_ids, motion = self._cid, self.body_ids, self._motion
        reset_pose = pybullet.resetBasePositionAndOrientation
        elapsed = self.world.time_s - self._placed_at
        for index in indices:
            state = motion[index]
            if state is None:
                continue
            x, y, z, qz, qw, vx, vy = state
            if vx or vy or index in standing:
                # (the client id by position: its keyword costs PyBullet 0.2 us a call)
                reset_pose(body_ids[index], (x + vx * elapsed, y + vy * elapsed, z),
                           (0.0, 0.0, qz, qw), cid)

    def pre_step(self):
        """
        World hook: every ``update_period``, advance the traffic and place the bodies.

        Between updates, the boxes near our vehicles are put where they are now (this step's
        contacts).
        """
        world = self.world
        count = world.step_count
        since = count - self._start_step
        if since and since % self.every == 0:
            ours = [our_vehicle(body, outline)
                    for body, outline in zip(self._ours, self._outlines)]
            self.manager.set_ours(ours)
            self.manager.step(self.every * world.time_step_s)
            self._place(ours)
        elif self._synced_step != count:
            self._move(self._near_all)

    def before_query(self):
        """World hook (``World.sync_bodies``): every box where its vehicle is now."""
        count = self.world.step_count
        if self._synced_step != count or self._away:
            self._move(range(len(self.body_ids)), self._away)
            self._away = set()
            self._synced_step = count
            self.world.mark_moved()

    def _nearby(self, ours):
        """Return the traffic vehicles within NEAR_M of each of our vehicles, and all of them."""
        limit = NEAR_M * NEAR_M
        near = [[index for index, x, y in self._positions
                 if (x - o.x_m) ** 2 + (y - o.y_m) ** 2 < limit] for o in ours]
        return near, sorted(set().union(*near))

    def post_step(self):
        """World hook: a traffic vehicle touching one of our vehicles stops for good."""
        manager, body_ids, world = self.manager, self.body_ids, self.world
        for body, near in zip(self._ours, self._near):
            touching = None         # the bodies ours touches (one read, when needed)
            for i in near:
                if manager.vehicles[i].stopped:
                    continue
                if touching is None:
                    touching = touched(world, body.body_id)
                if body_ids[i] in touching:
                    self._stop(i)
                    touching = None     # a box moved: read again
        if world.gui and world.time_s - self._drawn_at >= FRAME_PERIOD_S - 1e-9:
            self._drawn_at = world.time_s  # the window shows every box where it is, each frame
            self.before_query()

    def _stop(self, index):
        # A vehicle that touched one of ours stops where its box was during the step.
        v = self.manager.vehicles[index]
        elapsed = self.world.time_s - self.world.time_step_s - self._placed_at
        self.manager.stop(index, max(0.0, v.speed_mps * elapsed))
        x, y, yaw = self.manager.pose(v)
        z = self._z(index)
        half = 0.5 * yaw
        qz, qw = math.sin(half), math.cos(half)
        pybullet.resetBasePositionAndOrientation(self.body_ids[index], (x, y, z),
                                                 (0.0, 0.0, qz, qw), physicsClientId=self._cid)
        self._motion[index] = (x, y, z, qz, qw, 0.0, 0.0)
        self._table.invalidate()
        self.world.mark_moved()

    @property
    def since_update_s(self):
        """Time since the manager's last step [s] (its vehicles went on straight since)."""
        return self.world.time_s - self._placed_at

    def boxes(self):
        """
        Return the traffic bodies on the map as drawn (the Foxglove scene's ``traffic/``).

        :return: [(name, body id, size [m], colour, shape)]: the shape of the body's object
            class (core CLASS_SHAPES: 'box' or an upright 'cylinder'), its size the extents of
            that shape as an obstacle's (x, y, z; a cylinder's x and y its diameter), centred
            on the body's pose. The builtin engine's: boxes of its cars. A vehicle parked under
            the ground (waiting to re-enter) is left out.
        """
        dimensions, colours = self.manager.dimensions, self.colours
        shape = CLASS_SHAPES[OBJECT_CLASS]
        return [(v.name, body_id, shape_extents(OBJECT_CLASS, *dimensions[v.model][:2],
                                                self.heights[v.model] - GROUND_CLEARANCE_M),
                 colours[v.index % len(colours)], shape)
                for v, body_id in zip(self.manager.vehicles, self.body_ids) if v.active]

    def agents(self):
        """
        Return every traffic body on the map now, as the scenarios see it.

        :return: [(name, x, y, yaw, length, width, speed)]: footprint centre and heading [m,
            rad], footprint size [m], speed along the heading [m/s], at the last update.
        """
        manager = self.manager
        return [(v.name, *manager.pose(v), v.length_m, v.width_m, v.speed_mps)
                for v in manager.vehicles if v.active]

    def moving_names(self):
        """Return the names of every body the traffic moves (on the map or waiting)."""
        return {v.name for v in self.manager.vehicles}

    def kinematics(self):
        """
        Return the bodies on the map: a body table and the time since (traffic_kinematics.py).

        Each box as placed at the last update, its velocity the vehicle's speed along its
        heading: where it is now is that plus the velocity times the time since.
        """
        def rows():
            dimensions, motion = self.manager.dimensions, self._motion
            return [(body_id, motion[v.index], (*dimensions[v.model][:2],
                                                self.heights[v.model] - GROUND_CLEARANCE_M))
                    for v, body_id in zip(self.manager.vehicles, self.body_ids)
                    if v.active and motion[v.index] is not None]
        return self._table.now(self.since_update_s, rows)

    def objects(self, paths=True):
        """
        Return the traffic on the map as core TrafficObjects now (core/traffic/objects.py).

        :param paths: False: without predicted paths (each empty), for readers of poses and
            speeds only.
        """
        return traffic_objects(self.manager, self.heights, since_s=self.since_update_s,
                               instance_of=self.world.labels.instance, paths=paths)

    @property
    def follow_params(self):
        """The IdmParams scenario actors follow their leaders with (the traffic's own)."""
        return self.manager.idm

    def expect_path(self, name, points):
        """
        Hear of the path one of our vehicles will drive (a scenario actor's waypoints).

        The builtin traffic reacts to where our vehicles are and how fast they go: it keeps
        nothing (the SUMO engine gives SUMO the path's route, physics/sumo_traffic.py).

        :return: () (no route).
        """
        return ()

    def body_of(self, name):
        """Return the body id of the traffic vehicle called ``name`` (``traffic_<i>``)."""
        for v, body_id in zip(self.manager.vehicles, self.body_ids):
            if v.name == name:
                return body_id
        raise KeyError(name)


def build_sumo(part, world, spec, parts):
    """Return SUMO's bodies (physics/sumo_traffic.py, imported when a world asks for it)."""
    from vehicle_sim.physics.sumo_traffic import build_sumo as build
    return build(part, world, spec, parts)


# traffic engine (core/traffic/engines.py TRAFFIC_ENGINES) -> build(part, world, spec, parts)
# -> its bodies (the traffic-body contract of TrafficBodies).
TRAFFIC_BUILDERS = {
    'builtin': TrafficPart.build_builtin,
    'sumo': build_sumo,
}
