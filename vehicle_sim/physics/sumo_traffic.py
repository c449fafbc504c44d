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
SUMO as a world's traffic engine (``traffic: {engine: sumo}``): its vehicles and persons as bodies.

:func:`build_sumo` (``TRAFFIC_BUILDERS['sumo']``) starts SUMO (physics/sumo_session.py: libsumo
in process, or TraCI) on the world's SUMO network with the routes of ``routes:`` and the random
trips of ``demand:`` (physics/sumo_demand.py), and returns :class:`SumoBodies`, a world step hook
with the traffic-body contract of physics/traffic_bodies.py.

Every ``step`` of simulated time (a whole number of world steps) the hook puts our vehicles into
SUMO where the physics has them (each an external SUMO vehicle of its footprint's size, moved
with ``moveToXY`` to its front bumper, SUMO taking its speed from the move: SUMO's drivers queue
behind it and its pedestrians wait for it), pushes the signal states a scenario forces, advances
SUMO by one step, reads every SUMO vehicle's and person's position, heading and speed (one
subscription each, read in one call) and puts a body at each: a placed box of its vehicle type's
length, width and height, a person an upright cylinder (its class's shape, core/traffic/objects.py
CLASS_SHAPES: about 0.5 m across, 1.7 m high). The bodies come from a pool:
a body, named ``sumo_<k>``, serves one SUMO vehicle or person (its SUMO id: :meth:`sumo_id`) from
its departure to its arrival, is parked under the ground after, and serves the next one of the
same size; the order of SUMO's departures decides, so a seed gives the same names. Between
SUMO's steps a body goes on straight at its speed, put where it is when something can tell, as
the builtin engine's (physics/traffic_bodies.py; what they share: physics/traffic_boxes.py). A
SUMO vehicle that touches one of ours stops for good there (SUMO's speed 0, as the builtin
engine's).

SUMO's signal programs drive the world's signal controller (``drive(states)``): after each SUMO
step each program's state string, link by link, gives the state of the group of that link; a
group a scenario forces is pushed to SUMO (``trafficlight.setLinkState``) and given back to its
program when released.

A SUMO error while the world runs stops the world's step with :class:`SumoError` and SUMO's
message; closing the world closes SUMO.
"""

import math

import pybullet

from vehicle_sim.core.map.signal_programs import SUMO_STATES
from vehicle_sim.core.map.sumo_net_params import SumoNetMapSpec
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.traffic.idm import IdmParams
from vehicle_sim.core.traffic.lane_paths import route_path
from vehicle_sim.core.traffic.objects import (
    CLASS_SHAPES,
    PREDICTION_HORIZON_S,
    PREDICTION_STEP_S,
    shape_extents,
    TrafficObject,
)
from vehicle_sim.core.traffic.sumo_params import object_class
from vehicle_sim.core.world.params import ObstacleSpec
from vehicle_sim.physics.gui import FRAME_PERIOD_S
from vehicle_sim.physics.sumo_demand import demand_routes
from vehicle_sim.physics.sumo_session import load_traci, SumoError, SumoSession
from vehicle_sim.physics.traffic_boxes import (
    COLOURS,
    GROUND_CLEARANCE_M,
    NEAR_M,
    our_vehicle,
    PARK_DEPTH_M,
)

OURS_PREFIX = 'vehicle_sim.'     # our vehicles' SUMO ids: this + their names
NAME_PREFIX = 'sumo_'            # the bodies' names: this + the pool index
# our vehicle is in SUMO while its front is within this of the centreline of a lane SUMO's cars
# may use [m] (a lane and a half of 3.2 m)
OFF_ROAD_M = 5.0
RETRY_STEPS = 10                 # SUMO steps between two looks for a lane of one out of SUMO
PERSON_COLOUR = (0.95, 0.55, 0.15, 1.0)
# SUMO's state character of each of our signal states (what a forced state is pushed as)
SUMO_CHARACTER = {'green': 'G', 'yellow': 'y', 'red': 'r', 'off': 'O'}

__all__ = ['build_sumo', 'SumoBodies', 'SumoError', 'sumo_network']


def sumo_network(spec):
    """
    Return the .net.xml path of a world's map of a SUMO kind (sumo, opendrive, osm).

    The map's own network, or netconvert's of an OpenDRIVE or OSM file (maps/netconvert.py,
    cached: the lane map was read from it).

    :raises InvalidParameterError: the world has no SUMO network, naming its map's kind.
    """
    world_map = getattr(spec, 'map', None)
    if not isinstance(world_map, SumoNetMapSpec):
        kind = getattr(world_map, 'type', None) or getattr(world_map, 'kind', None)
        have = ('roads: only' if getattr(spec, 'roads', None) else 'no map') \
            if world_map is None else f'a map of kind {kind or type(world_map).__name__}'
        raise InvalidParameterError(
            f'{spec.traffic.source}: the sumo engine runs on a SUMO network: give the world a '
            f'map of kind sumo (map: {{type: sumo, net: city.net.xml}}), opendrive or osm; it '
            f'has {have}')
    from vehicle_sim.maps.netconvert import net_file
    return net_file(world_map)


def sumo_arguments(spec, net, seed, routes):
    """Return sumo's options for the engine's spec (core SumoTrafficSpec)."""
    args = ['-n', net, '--seed', str(seed), '--step-length', f'{spec.step_s:.17g}',
            '--begin', f'{spec.begin_s:.17g}']
    if routes:
        args += ['-r', ','.join(routes)]
    return args + list(spec.options)


def build_sumo(part, world, spec, parts):
    """Return the SumoBodies of a world's ``traffic: {engine: sumo}`` (TRAFFIC_BUILDERS)."""
    traffic = spec.traffic
    net = sumo_network(spec)
    every = max(1, int(round(traffic.step_s / world.time_step_s)))
    if abs(every * world.time_step_s - traffic.step_s) > 1e-9:
        raise InvalidParameterError(
            f"{traffic.source}: field 'step' = {traffic.step_s:g}: must be a multiple of the "
            f'world step {world.time_step_s:g} s')
    signals = getattr(parts.get('signals'), 'controller', None)
    graph = getattr(spec, 'lanes', None)
    programs = tuple(getattr(getattr(graph, 'rules', None), 'programs', None) or ())
    return SumoBodies(world, traffic, net, every, signals, programs, graph)


class _Slot:
    """One body of the pool: its name, body id, box size, colour and whom it serves now."""

    __slots__ = ('index', 'name', 'body_id', 'size', 'clearance', 'colour', 'key', 'sumo_id',
                 'person', 'vclass', 'state', 'motion', 'stopped', 'lane', 'route')

    def __init__(self, index, body_id, size, clearance, colour, key):
        self.index = index
        self.name = f'{NAME_PREFIX}{index}'
        self.body_id = body_id
        self.size = size                   # (length, width, height) [m] of the SUMO type
        self.clearance = clearance         # the box's underside above the ground [m]
        self.colour = colour
        self.key = key                     # the pool it returns to
        self.sumo_id = None                # whom it serves (None: parked)
        self.person = False
        self.vclass = 'passenger'
        self.state = None                  # (x, y, yaw, speed) of the footprint centre
        self.motion = None                 # (x, y, z, qz, qw, vx, vy) at the last update
        self.stopped = False               # touched one of ours: stopped for good
        self.lane = None                   # (SUMO lane id, lane position [m], route index)
        self.route = ()                    # its route's SUMO edges (at its departure)

    @property
    def z(self):
        return 0.5 * (self.size[2] + self.clearance)


class SumoBodies:
    """
    SUMO's vehicles and persons as bodies in a World (a world step hook).

    The traffic-body contract of physics/traffic_bodies.py TrafficBodies: :meth:`reset`,
    :meth:`agents`, :meth:`moving_names`, :meth:`objects`, :meth:`boxes`, :meth:`body_of`,
    :attr:`follow_params`, ``colours``, ``heights`` and :attr:`since_update_s`; and
    :meth:`sumo_id` / :meth:`name_of` between body names and SUMO ids, ``session`` (the running
    SumoSession: ``session.api`` is TraCI's API).

    :param world: the World.
    :param spec: the core SumoTrafficSpec.
    :param net: the .net.xml path.
    :param every: world steps per SUMO step.
    :param signals: the world's SignalController, or None.
    :param programs: the lane map's SignalPrograms (core/map/signal_programs.py).
    :param graph: the world's lane graph (the network's: the objects' predicted paths follow
        its lanes), or None.
    """

    def __init__(self, world, spec, net, every, signals=None, programs=(), graph=None):
        self.world = world
        self.spec = spec
        self.net = net
        self.every = every
        self.signals = signals
        self.programs = programs
        self.graph = graph
        self._lengths = {}                # {SUMO lane id: its length in SUMO [m]}
        self.heights = {}                 # {SUMO type id: box height [m]}
        self.follow_params = IdmParams.from_dict({}, f'{spec.source}: idm')
        self._constants = load_traci().constants
        self._cid = world.client_id
        self._slots = []
        self._ours = world.vehicle_bodies()
        self._outlines = [body.outline for body in self._ours]
        self.session = None
        self._start(spec.seed)
        world.add_body(self)

    # ------------------------------------------------------------------ starting, closing
    def _start(self, seed):
        """Start SUMO with ``seed``, run its warmup; SUMO's time: the spec's begin + warmup."""
        spec = self.spec
        routes = list(spec.routes)
        if spec.demand is not None:
            demand_seed = seed if spec.demand.seed is None else spec.demand.seed
            routes += demand_routes(self.net, spec.demand, demand_seed, spec.begin_s,
                                    spec.source)
        self.session = SumoSession(sumo_arguments(spec, self.net, seed, routes),
                                   spec.transport, spec.source)
        self.seed = seed
        try:
            self._begin()
        except BaseException:
            self.session.close()          # no SUMO left behind (libsumo free again)
            raise

    def _begin(self):
        """Set up the started SUMO: our vehicles' types, the subscriptions, the warmup."""
        spec = self.spec
        api = self.session.api
        self._types = {}                   # {SUMO type id: (length, width, height, vClass)}
        self._by_id = {}                   # {(person?, SUMO id): slot}
        self._free = {}                    # {pool key: [slots], lowest index last}
        for slot in self._slots:
            self._park(slot)
        for slot in reversed(self._slots):
            self._free.setdefault(slot.key, []).append(slot)
        self._in_sumo = set()              # the names of our vehicles in SUMO now
        self._retry = {}                   # {name: out of SUMO, looked for since}
        self._shapes = {}                  # {SUMO lane id: its shape}
        self._steps = 0                    # SUMO steps since the start
        self._strings = {}                 # {tls id: its state string at the last drive}
        self._routes = 0
        self._pushed = {}                  # {group id: state} forced states pushed to SUMO
        self._tls_links = {}               # {group id: (tls id, link index)}
        self._groups_of = {}               # {tls id: ((link index, group id), ...)}
        for program in self.programs:
            self._groups_of[program.tls_id] = tuple(
                (link, group) for link, group in enumerate(program.links) if group is not None)
            for link, group in self._groups_of[program.tls_id]:
                self._tls_links[group] = (program.tls_id, link)
        with self.session.errors('at the start'):
            for index, body in enumerate(self._ours):
                outline = self._outlines[index]
                type_id = f'{OURS_PREFIX}{body.name}'
                api.vehicletype.copy('DEFAULT_VEHTYPE', type_id)
                api.vehicletype.setLength(type_id, outline.length_m)
                api.vehicletype.setWidth(type_id, outline.width_m)
            c = self._constants
            api.simulation.subscribe((c.VAR_DEPARTED_VEHICLES_IDS,
                                      c.VAR_DEPARTED_PERSONS_IDS, c.VAR_ARRIVED_VEHICLES_IDS))
            if self._tls_links:
                for tls in {tls for tls, _ in self._tls_links.values()}:
                    api.trafficlight.subscribe(tls, (c.TL_RED_YELLOW_GREEN_STATE,))
            self._programs_of = {program.tls_id: program.program_id for program in self.programs}
            if self._tls_links:
                self._drive_signals(api, {tls: api.trafficlight.getRedYellowGreenState(tls)
                                          for tls in self._programs_of})
        self._start_step = self.world.step_count
        self._placed_at = self.world.time_s
        self._synced_step = self.world.step_count
        self._drawn_at = -math.inf
        self._near = [[] for _ in self._ours]
        self._near_all = []
        warmup = int(round(spec.warmup_s / spec.step_s))
        if warmup:
            with self.session.errors('warming up'):
                for left in range(warmup - 1, -1, -1):
                    ours = self._advance(place=not left)     # the bodies placed at its end
            self._near, self._near_all = self._nearby(ours)

    def on_close(self):
        """World hook (``World.close``): close SUMO."""
        if self.session is not None:
            self.session.close()

    def reset(self, seed=None):
        """
        Start SUMO again (its time back at begin, then its warmup run); say so in words.

        :param seed: SUMO's seed (and the demand's when it has none of its own); None = the
            spec's seed.
        """
        seed = self.spec.seed if seed is None else seed
        self.session.close()
        self._start(seed)
        self.world.mark_moved()
        return f'traffic: SUMO started again (seed {seed})'

    # ------------------------------------------------------------------ our vehicles in SUMO
    def _push_ours(self):
        """
        Put each of our vehicles into SUMO where the physics has it (its front bumper).

        A vehicle whose front is farther than OFF_ROAD_M from the lane SUMO has it on (a car
        park, a field: ``moveToXY`` puts it anywhere) is taken out of SUMO; one out of SUMO is
        put in again when its front is that near a lane of SUMO's passenger cars (looked for
        every RETRY_STEPS SUMO steps: the search costs some 0.5 ms); one SUMO removed (it
        teleports a vehicle stuck for its --time-to-teleport) comes back at the next step.
        """
        api = self.session.api
        refused = self.session.refusal          # a call refused; SUMO's end goes on up
        ours = []
        for body, outline in zip(self._ours, self._outlines):
            o = our_vehicle(body, outline)
            ours.append(o)
            vid = f'{OURS_PREFIX}{o.name}'
            half = 0.5 * o.length_m
            x, y = o.x_m + half * math.cos(o.yaw_rad), o.y_m + half * math.sin(o.yaw_rad)
            angle = 90.0 - math.degrees(o.yaw_rad)
            if o.name in self._in_sumo:
                lane = api.vehicle.getLaneID(vid)
                if not lane or self._off_lane(api, lane, x, y):
                    self._take_out(api, vid, o.name)
                    continue
            else:
                if self._steps % RETRY_STEPS and self._retry.get(o.name):
                    continue
                self._retry[o.name] = True
                try:                              # the nearest lane of SUMO's cars
                    edge, s, lane = api.simulation.convertRoad(x, y, False, 'passenger')
                    lx, ly = api.simulation.convert2D(edge, s, lane)
                except refused:
                    continue
                if edge.startswith(':') or math.hypot(lx - x, ly - y) > OFF_ROAD_M:
                    continue                      # added on a normal edge, near its lane
                route = f'{vid}.route{self._routes}'
                self._routes += 1
                try:
                    api.route.add(route, [edge])
                    api.vehicle.add(vid, route, typeID=vid, departSpeed='0')
                except refused:
                    continue
                self._in_sumo.add(o.name)
                self._retry[o.name] = False
            try:
                api.vehicle.moveToXY(vid, '', -1, x, y, angle, keepRoute=2)
            except refused:                       # SUMO lost it (a teleport): added again
                self._take_out(api, vid, o.name)
        return ours

    def _take_out(self, api, vid, name):
        """Take one of our vehicles out of SUMO (off the road, or lost by SUMO)."""
        self._in_sumo.discard(name)
        self._retry[name] = False             # looked for again at once
        try:
            api.vehicle.remove(vid)
        except self.session.refusal:
            pass

    def _off_lane(self, api, lane, x, y):
        """Return whether (x, y) is farther than OFF_ROAD_M from SUMO's lane ``lane``."""
        shape = self._shapes.get(lane)
        if shape is None:
            shape = self._shapes[lane] = tuple(api.lane.getShape(lane))
        limit = OFF_ROAD_M * OFF_ROAD_M
        points = shape if len(shape) > 1 else shape * 2
        for (ax, ay), (bx, by) in zip(points, points[1:]):
            dx, dy = bx - ax, by - ay
            span = dx * dx + dy * dy
            t = 0.0 if span == 0.0 else min(1.0, max(0.0, ((x - ax) * dx + (y - ay) * dy) / span))
            if (ax + t * dx - x) ** 2 + (ay + t * dy - y) ** 2 <= limit:
                return False
        return True

    # ------------------------------------------------------------------ the step
    def pre_step(self):
        """World hook: every ``step``, advance SUMO and place the bodies."""
        if self.session.closed:
            raise SumoError(f'{self.spec.source}: SUMO is not running (closed, or its restart '
                            'failed)')
        world = self.world
        count = world.step_count
        since = count - self._start_step
        if since and since % self.every == 0:
            with self.session.errors(f'at t = {world.time_s:.3f} s'):
                ours = self._advance()
            self._near, self._near_all = self._nearby(ours)
        elif self._synced_step != count:
            self._move(self._near_all)

    def _advance(self, place=True):
        api = self.session.api
        self._push_signals()
        ours = self._push_ours()
        api.simulationStep()
        self._steps += 1
        c = self._constants
        departed = api.simulation.getSubscriptionResults()
        for vid in departed.get(c.VAR_ARRIVED_VEHICLES_IDS, ()):
            if vid.startswith(OURS_PREFIX):          # SUMO removed one of ours: back next step
                self._in_sumo.discard(vid[len(OURS_PREFIX):])
        fields = (c.VAR_POSITION, c.VAR_ANGLE, c.VAR_SPEED)
        for person, key in ((False, c.VAR_DEPARTED_VEHICLES_IDS),
                            (True, c.VAR_DEPARTED_PERSONS_IDS)):
            domain = api.person if person else api.vehicle
            for sumo_id in departed.get(key, ()):       # bodies in the order of departure
                if person or not sumo_id.startswith(OURS_PREFIX):
                    # a person's vehicle too: one riding a bus has no body of its own; a
                    # vehicle's lane, place on it and route index: its predicted path
                    domain.subscribe(sumo_id, fields + ((c.VAR_VEHICLE,) if person else (
                        c.VAR_LANE_ID, c.VAR_LANEPOSITION, c.VAR_ROUTE_INDEX)))
                    slot = self._take(api, person, sumo_id)
                    if not person:
                        slot.route = tuple(api.vehicle.getRoute(sumo_id))
        seen = set()
        for person, results in ((False, api.vehicle.getAllSubscriptionResults()),
                                (True, api.person.getAllSubscriptionResults())):
            for sumo_id, values in results.items():
                if (sumo_id.startswith(OURS_PREFIX) if not person
                        else values.get(c.VAR_VEHICLE)):
                    continue                        # ours, or a person riding a vehicle
                key = (person, sumo_id)
                slot = self._by_id.get(key)
                if slot is None:            # back from a teleport (SUMO's jam resolution)
                    slot = self._take(api, person, sumo_id)
                seen.add(key)
                (fx, fy), angle, speed = (values[c.VAR_POSITION], values[c.VAR_ANGLE],
                                          values[c.VAR_SPEED])
                yaw = math.radians(90.0 - angle)
                half = 0.5 * slot.size[0]
                cos, sin = math.cos(yaw), math.sin(yaw)
                slot.state = (fx - half * cos, fy - half * sin, yaw, speed)
                if not person:
                    slot.lane = (values[c.VAR_LANE_ID], values[c.VAR_LANEPOSITION],
                                 values[c.VAR_ROUTE_INDEX])
        for key in [key for key in self._by_id if key not in seen]:   # arrived
            slot = self._by_id.pop(key)
            self._park(slot)
            self._free.setdefault(slot.key, []).append(slot)
        self._drive_signals(api)
        if place:
            self._place()
        return ours

    def _take(self, api, person, sumo_id):
        """Return the slot for a new SUMO vehicle or person (a free one of its size, or new)."""
        domain = api.person if person else api.vehicle
        type_id = domain.getTypeID(sumo_id)
        kind = self._types.get(type_id)
        if kind is None:
            t = api.vehicletype
            kind = self._types[type_id] = (t.getLength(type_id), t.getWidth(type_id),
                                           t.getHeight(type_id), t.getVehicleClass(type_id))
            self.heights[type_id] = kind[2]
        length, width, height, vclass = kind
        if person:
            vclass = 'pedestrian'
        found_class = object_class(vclass)
        key = (round(length, 3), round(width, 3), round(height, 3), person,
               CLASS_SHAPES[found_class])
        free = self._free.get(key)
        if free:
            slot = free.pop()
        else:
            index = len(self._slots)
            clearance = 0.0 if person else min(GROUND_CLEARANCE_M, 0.25 * height)
            colour = PERSON_COLOUR if person else COLOURS[index % len(COLOURS)]
            size = (length, width, height)
            # the body of its class's shape (a pedestrian an upright cylinder)
            extents = shape_extents(found_class, length, width, height - clearance)
            spec = ObstacleSpec(f'{NAME_PREFIX}{index}', CLASS_SHAPES[found_class],
                                (0.0, 0.0, PARK_DEPTH_M - 10.0 * index), 0.0, 0.0, 0.0, 0.0,
                                colour, extents, radius_m=0.5 * extents[0],
                                height_m=extents[2])
            body_id = self.world.add_obstacle(spec, placed=True)
            slot = _Slot(index, body_id, size, clearance, colour, key)
            self._slots.append(slot)
        slot.sumo_id, slot.person, slot.vclass, slot.stopped = sumo_id, person, vclass, False
        self._by_id[(person, sumo_id)] = slot
        return slot

    def _park(self, slot):
        slot.sumo_id, slot.state, slot.motion, slot.stopped = None, None, None, False
        slot.lane, slot.route = None, ()
        pybullet.resetBasePositionAndOrientation(
            slot.body_id, (0.0, 0.0, PARK_DEPTH_M - 10.0 * slot.index), (0.0, 0.0, 0.0, 1.0),
            physicsClientId=self._cid)

    def _place(self):
        """Put every serving body where SUMO has its vehicle or person now (an update)."""
        cid = self._cid
        reset_pose = pybullet.resetBasePositionAndOrientation
        cos, sin = math.cos, math.sin
        for slot in self._by_id.values():
            x, y, yaw, speed = slot.state
            half = 0.5 * yaw
            z, qz, qw = slot.z, sin(half), cos(half)
            reset_pose(slot.body_id, (x, y, z), (0.0, 0.0, qz, qw), physicsClientId=cid)
            slot.motion = (x, y, z, qz, qw, speed * cos(yaw), speed * sin(yaw))
        self._placed_at = self.world.time_s
        self._synced_step = self.world.step_count
        self.world.mark_moved()

    def _move(self, slots):
        """Put the bodies of ``slots`` where their vehicles are now (straight on)."""
        cid = self._cid
        reset_pose = pybullet.resetBasePositionAndOrientation
        elapsed = self.world.time_s - self._placed_at
        for slot in slots:
            state = slot.motion
            if state is None:
                continue
            x, y, z, qz, qw, vx, vy = state
            if vx or vy:
                reset_pose(slot.body_id, (x + vx * elapsed, y + vy * elapsed, z),
                           (0.0, 0.0, qz, qw), physicsClientId=cid)

    def before_query(self):
        """World hook (``World.sync_bodies``): every body where its vehicle is now."""
        count = self.world.step_count
        if self._synced_step != count:
            self._move(list(self._by_id.values()))
            self._synced_step = count
            self.world.mark_moved()

    def _nearby(self, ours):
        limit = NEAR_M * NEAR_M
        serving = list(self._by_id.values())
        near = [[slot for slot in serving
                 if (slot.state[0] - o.x_m) ** 2 + (slot.state[1] - o.y_m) ** 2 < limit]
                for o in ours]
        found = {slot.index: slot for slots in near for slot in slots}
        return near, [found[index] for index in sorted(found)]

    def post_step(self):
        """World hook: a SUMO vehicle or person touching one of our vehicles stops for good."""
        cid = self._cid
        contacts = pybullet.getContactPoints
        for body, near in zip(self._ours, self._near):
            for slot in near:
                if slot.sumo_id is not None and not slot.stopped and contacts(
                        bodyA=body.body_id, bodyB=slot.body_id, physicsClientId=cid):
                    self._stop(slot)
        world = self.world
        if world.gui and world.time_s - self._drawn_at >= FRAME_PERIOD_S - 1e-9:
            self._drawn_at = world.time_s
            self.before_query()

    def _stop(self, slot):
        # Stopped where its body was during the step, in SUMO at once (no deceleration bound).
        api = self.session.api
        with self.session.errors(f'stopping {slot.sumo_id!r}'):
            try:
                if slot.person:
                    api.person.setSpeed(slot.sumo_id, 0.0)
                else:
                    api.vehicle.setSpeedMode(slot.sumo_id, 0)
                    api.vehicle.setSpeed(slot.sumo_id, 0.0)
                    api.vehicle.setLaneChangeMode(slot.sumo_id, 0)
            except self.session.refusal:    # SUMO took it off the road this step: its body
                pass                        # stays where it was until SUMO's next step
        slot.stopped = True
        elapsed = max(0.0, self.world.time_s - self.world.time_step_s - self._placed_at)
        x, y, z, qz, qw, vx, vy = slot.motion
        x, y = x + vx * elapsed, y + vy * elapsed
        pybullet.resetBasePositionAndOrientation(slot.body_id, (x, y, z), (0.0, 0.0, qz, qw),
                                                 physicsClientId=self._cid)
        slot.motion = (x, y, z, qz, qw, 0.0, 0.0)
        _, _, yaw, _ = slot.state
        slot.state = (x, y, yaw, 0.0)
        self.world.mark_moved()

    # ------------------------------------------------------------------ signals
    def _drive_signals(self, api, strings=None):
        """Give the world's signal controller SUMO's states ({tls: state string}: now)."""
        controller = self.signals
        if controller is None or not self._tls_links:
            return
        if strings is None:
            c = self._constants
            strings = {tls: values[c.TL_RED_YELLOW_GREEN_STATE]
                       for tls, values in api.trafficlight.getAllSubscriptionResults().items()}
        states, last = {}, self._strings
        for tls, text in strings.items():
            if last.get(tls) == text:
                continue                          # no change at this light
            last[tls] = text
            for link, group in self._groups_of[tls]:
                if link < len(text):
                    states[group] = SUMO_STATES[text[link]]
        if states or not controller.driven:     # the changes (checking a group costs)
            controller.drive(states)

    def _push_signals(self):
        """Push the states a scenario forces on the world's controller to SUMO (and releases)."""
        controller = self.signals
        if controller is None or not self._tls_links:
            return
        api = self.session.api
        forced = controller.forced()
        for group, state in forced.items():
            where = self._tls_links.get(group)
            if where is not None and self._pushed.get(group) != state:
                api.trafficlight.setLinkState(where[0], where[1], SUMO_CHARACTER[state])
                self._pushed[group] = state
        released = {self._tls_links[g][0] for g in self._pushed if g not in forced}
        if released:
            self._pushed = {g: s for g, s in self._pushed.items() if g in forced}
            for tls in released:
                api.trafficlight.setProgram(tls, self._programs_of[tls])
                for group, state in self._pushed.items():    # still forced at that light
                    if self._tls_links[group][0] == tls:
                        api.trafficlight.setLinkState(tls, self._tls_links[group][1],
                                                      SUMO_CHARACTER[state])

    # ------------------------------------------------------------------ the contract
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
        return [(slot.name, *slot.state[:3], slot.size[0], slot.size[1], slot.state[3])
                for slot in self._serving()]

    def moving_names(self):
        """Return the names of every body SUMO moves (serving or parked)."""
        return {slot.name for slot in self._slots}

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

    def objects(self, horizon_s=PREDICTION_HORIZON_S, step_s=PREDICTION_STEP_S):
        """
        Return SUMO's vehicles and persons as core TrafficObjects now.

        Each is where its body is (gone on straight since SUMO's step), its class from its
        SUMO vehicle class (core/traffic/sumo_params.py object_class); a vehicle's predicted
        path follows its lane and the lanes of its route after it at its speed
        (core/traffic/lane_paths.py), a person's (or one on a lane the lane graph lacks) goes
        on straight.
        """
        since = self.since_update_s
        count = int(round(horizon_s / step_s))
        found = []
        for slot in self._serving():
            x, y, yaw, speed = slot.state
            c, s = math.cos(yaw), math.sin(yaw)
            gone = speed * since
            x, y = x + gone * c, y + gone * s
            path = self._lane_path(slot, since, count, step_s)
            if path is None:
                path = tuple((x + speed * step_s * k * c, y + speed * step_s * k * s, yaw)
                             for k in range(1, count + 1))
            found.append(TrafficObject(slot.index, slot.name, x, y, yaw, speed, slot.size[0],
                                       slot.size[1], slot.size[2], path, step_s,
                                       object_class(slot.vclass)))
        return tuple(found)

    def _lane_path(self, slot, since, count, step_s):
        """Return a vehicle's path along the lane graph, or None (no graph, lane not in it)."""
        if self.graph is None or slot.lane is None:
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
        speed = slot.state[3]
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
