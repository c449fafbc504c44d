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
SUMO by one step, reads every SUMO vehicle's and person's position, heading and speed (libsumo's
getters, or over TraCI one subscription each read in one call: physics/sumo_reads.py) and puts a
body at each: a placed box of its vehicle type's length, width and height, a person an upright
cylinder (its class's shape, core/traffic/objects.py CLASS_SHAPES: about 0.5 m across, 1.7 m
high; two persons SUMO has closer than that moved apart, physics/sumo_pool.py). The bodies come
from a pool:
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

What it is made of: physics/sumo_pool.py (the pool of bodies: taken, parked, placed, moved,
stopped), physics/sumo_ours.py (our vehicles in SUMO), physics/sumo_reads.py (reading SUMO's
vehicles and persons), physics/sumo_signals.py (the signal bridge), physics/sumo_views.py (the
contract's views: agents, objects with their lane paths, boxes).
"""

import math

import pybullet

from vehicle_sim.core.map.sumo_net_params import SumoNetMapSpec
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.traffic.idm import IdmParams
from vehicle_sim.core.traffic.lane_paths import edges_along
from vehicle_sim.physics.gui import FRAME_PERIOD_S
from vehicle_sim.physics.sumo_demand import demand_routes
from vehicle_sim.physics.sumo_ours import OURS_PREFIX, SumoOurs
from vehicle_sim.physics.sumo_pool import extend_trail, JUMP_M, SumoPool
from vehicle_sim.physics.sumo_reads import reads_for
from vehicle_sim.physics.sumo_session import load_traci, SumoError, SumoSession
from vehicle_sim.physics.sumo_signals import SumoSignals
from vehicle_sim.physics.sumo_views import SumoViews
from vehicle_sim.physics.traffic_boxes import NEAR_M, touched
from vehicle_sim.physics.traffic_kinematics import MotionTable

__all__ = ['build_sumo', 'SumoBodies', 'SumoError', 'sumo_network']

# a body near ours is put where it is at each step when it is within this of touching one of
# ours (their sizes apart): ours runs 0.3 m in a 10 ms step at 110 km/h
TOUCH_MARGIN_M = 1.0


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
    return SumoBodies(world, traffic, net, every, signals, programs, graph,
                      route_edges(spec, graph))


def route_edges(spec, graph):
    """
    Return {vehicle name: its route's SUMO edges} of the world's vehicles with a ``route:``.

    Each lane (an id or a name of the lane map, whose lane names are SUMO's lane ids) gives
    its edge (the lane id without its ``_<index>``); a lane inside a junction is refused.

    :raises InvalidParameterError: a lane not in the map, or inside a junction, naming it.
    """
    found = {}
    for index, vehicle in enumerate(getattr(spec, 'vehicles', ())):
        edges = []
        for lane in vehicle.route:
            where = f"{spec.source}: vehicles[{index}]: field 'route': lane {lane!r}"
            try:
                name = graph.lanes[lane].name if isinstance(lane, int) else \
                    graph.lane_named(lane).name
            except (KeyError, InvalidParameterError):
                raise InvalidParameterError(f'{where} is not in the map') from None
            if name.startswith(':'):
                raise InvalidParameterError(f'{where} is inside a junction: give the lanes '
                                            'of the roads it takes')
            edge = name.rsplit('_', 1)[0]
            if not edges or edges[-1] != edge:
                edges.append(edge)
        if edges:
            found[vehicle.name] = tuple(edges)
    return found



class SumoBodies(SumoPool, SumoViews):
    """
    SUMO's vehicles and persons as bodies in a World (a world step hook).

    The traffic-body contract of physics/traffic_bodies.py TrafficBodies: :meth:`reset`,
    :meth:`agents`, :meth:`moving_names`, :meth:`objects`, :meth:`boxes`, :meth:`body_of`,
    :meth:`expect_path`, :attr:`follow_params`, ``colours``, ``heights`` and
    :attr:`since_update_s`; and
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
    :param routes: {our vehicle's name: the SUMO edges of its route} (:func:`route_edges`).
    """

    def __init__(self, world, spec, net, every, signals=None, programs=(), graph=None,
                 routes=None):
        self.world = world
        self.routes = dict(routes or {})  # {our vehicle's name: its route's SUMO edges}
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
        self._table = MotionTable()       # kinematics(), rebuilt after each update
        self._updates = 0                 # SUMO's positions taken (_place) since the start
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
        self._steps = 0                    # SUMO steps since the start
        self._our = SumoOurs(self.session, self._ours, self._outlines, self.routes,
                             self.spec.source)
        self._signals = SumoSignals(self.session, self.signals, self.programs, self._constants)
        self._reads = reads_for(self.session, self._constants, OURS_PREFIX)
        self._our.check_routes(api)
        with self.session.errors('at the start'):
            self._our.add_types(api)
            c = self._constants
            api.simulation.subscribe((c.VAR_DEPARTED_VEHICLES_IDS,
                                      c.VAR_DEPARTED_PERSONS_IDS, c.VAR_ARRIVED_VEHICLES_IDS))
            self._signals.begin(api)
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

    def expect_path(self, name, points):
        """
        Give our vehicle ``name`` in SUMO the route of the path it will drive (an actor's).

        The SUMO edges the path passes (core/traffic/lane_paths.py ``edges_along``: its points
        located on the network's lanes), joined by SUMO's router as a vehicle's ``route:`` is,
        up to the first edge SUMO finds no way to; kept over resets. SUMO's drivers and
        pedestrians then know where it will turn. A path on no lane of the network changes
        nothing.

        :param name: the name of one of our vehicles.
        :param points: [(x, y)] [m] of the path, from where the vehicle is.
        :return: the route's SUMO edges (() for none).
        """
        edges = () if self.graph is None else edges_along(self.graph, points)
        if not edges:
            return ()
        with self.session.errors(f'giving {name!r} its route'):
            self.routes[name] = self._our.give_route(self.session.api, name, edges)
        return self.routes[name]

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
        if self._synced_step != count and self._move(self._touching()):
            world.mark_moved()

    def _touching(self):
        """
        Return the bodies near ours that may touch one of them in this step: put where they are.

        Those within reach of one of our vehicles now (its base) where they are or where they
        stand: their size and ours (half a diagonal each, less than half their length and width
        together; ours whole, for the base off the footprint's centre) and TOUCH_MARGIN_M. The
        others near (NEAR_M) stay where they stand until something reads them (rays, a camera,
        any reading: :meth:`before_query`); their contacts with ours are read after each step.
        """
        near = self._near_all
        if not near:
            return near
        cid = self._cid
        base = pybullet.getBasePositionAndOrientation
        ours = [(base(body.body_id, physicsClientId=cid)[0], outline.length_m + outline.width_m)
                for body, outline in zip(self._ours, self._outlines)]
        count = self.world.step_count
        elapsed = self.world.time_s - self._placed_at
        found = []
        for slot in near:
            if slot.synced == count or slot.front is None:
                continue
            x, y, _, _, _, vx, vy = self._motion(slot)
            x, y = x + vx * elapsed, y + vy * elapsed
            at = slot.at
            half = 0.5 * (slot.size[0] + slot.size[1]) + TOUCH_MARGIN_M
            for (ox, oy, _), own in ours:
                reach = half + own
                reach *= reach
                if (x - ox) ** 2 + (y - oy) ** 2 < reach or (
                        at is not None and (at[0] - ox) ** 2 + (at[1] - oy) ** 2 < reach):
                    found.append(slot)
                    break
        return found

    def _advance(self, place=True):
        """
        SUMO's step: our vehicles pushed, SUMO stepped, its readings taken; return ours.

        In this process (libsumo, TraCI) SUMO steps here. With a worker (``transport:
        worker``, physics/sumo_worker.py) the step started at the previous update is collected
        and the next one started with our vehicles as they are now, so that SUMO steps while
        the physics runs (the first update steps and collects at once).
        """
        api = self.session.api
        worker = getattr(api, 'worker', None)
        if worker is None:
            ours = self._push()
            api.simulationStep()
            self._steps += 1
            reads = self._reads
            self._read_step(api, api.simulation.getSubscriptionResults(),
                            lambda: (reads.vehicles(api), reads.persons(api), None), place)
            return ours
        if not worker.stepped:
            self._push()
            worker.step(OURS_PREFIX)
            self._steps += 1
        departed, vehicles, persons, lights = worker.collect()
        self._read_step(api, departed, lambda: (vehicles, persons, lights), place)
        ours = self._push()
        worker.step(OURS_PREFIX)
        self._steps += 1
        return ours

    def _push(self):
        # the states a scenario forces on the signals, and our vehicles, to SUMO
        self._signals.push()
        return self._our.push(self._steps)

    def _read_step(self, api, departed, readings, place):
        # SUMO's readings after a step: departures and arrivals (the simulation's subscription
        # results), then ``readings()``: the vehicles and persons (sumo_reads.py; over TraCI
        # the departed ones' subscriptions are made first) and the lights' states (None: read
        # from their subscriptions here)
        c = self._constants
        reads = self._reads
        for vid in departed.get(c.VAR_ARRIVED_VEHICLES_IDS, ()):
            if vid.startswith(OURS_PREFIX):          # SUMO removed one of ours: back next step
                self._our.arrived(vid)
        for person, key in ((False, c.VAR_DEPARTED_VEHICLES_IDS),
                            (True, c.VAR_DEPARTED_PERSONS_IDS)):
            for sumo_id in departed.get(key, ()):       # bodies in the order of departure
                if person or not sumo_id.startswith(OURS_PREFIX):
                    # a person's body too: one riding a bus has none (parked below)
                    reads.departed(api, person, sumo_id)
                    slot = self._take(api, person, sumo_id)
                    if not person:
                        slot.route = tuple(api.vehicle.getRoute(sumo_id))
        vehicles, persons_read, lights = readings()
        by_id = self._by_id
        seen = set()
        step_s = self.spec.step_s
        radians, cos, sin = math.radians, math.cos, math.sin
        for sumo_id, (fx, fy), angle, speed, lane in vehicles:
            key = (False, sumo_id)
            slot = by_id.get(key)
            if slot is None:                # back from a teleport (SUMO's jam resolution)
                slot = self._take(api, False, sumo_id)
            seen.add(key)
            if slot.front != (fx, fy, angle):   # on the line nearest its front's path (SUMO
                slot.front = (fx, fy, angle)      # bends it so), worked out when read
                extend_trail(slot.trail, fx, fy, speed * step_s + JUMP_M, slot.size[0])
                slot.state = None
            elif slot.state is not None:          # standing: where it was
                slot.state = (*slot.state[:3], speed)
            slot.speed = speed
            slot.lane = lane                      # None: read when the objects are
        persons = []
        for sumo_id, (fx, fy), angle, speed in persons_read:
            key = (True, sumo_id)
            slot = by_id.get(key)
            if slot is None:
                slot = self._take(api, True, sumo_id)
            seen.add(key)
            yaw = radians(90.0 - angle)
            half = 0.5 * slot.size[0]
            slot.front, slot.speed = (fx, fy, angle), speed
            slot.state = (fx - half * cos(yaw), fy - half * sin(yaw), yaw, speed)
            persons.append(slot)
        self._apart(persons)                # none closer than their width (SumoPool._apart)
        for key in [key for key in self._by_id if key not in seen]:   # arrived
            slot = self._by_id.pop(key)
            self._park(slot)
            self._free.setdefault(slot.key, []).append(slot)
        self._signals.drive(api, subscribed=lights)
        if place:
            self._place()

    def before_query(self):
        """World hook (``World.sync_bodies``): every body where its vehicle is now."""
        count = self.world.step_count
        if self._synced_step != count:
            if self._move(list(self._by_id.values())):
                self.world.mark_moved()
            self._synced_step = count

    def before_query_in(self, region):
        """
        World hook (``World.sync_bodies`` with a region: rays): the bodies there where they are.

        Those whose vehicle is in ``region`` (x min, y min, x max, y max [m], a body's size
        around it) now, or whose body stands there since an earlier update, are put where their
        vehicle is now; the others stay where they stand until something reads them: a lidar
        in a city moves a tenth of the bodies, not every one at every SUMO step.
        """
        if self._synced_step != self.world.step_count and self._move(self._reaching(region)):
            self.world.mark_moved()

    def _nearby(self, ours):
        # the bodies near each of ours, where SUMO has them or where they stand (not moved
        # since an earlier update): put where they are at each step, their contacts checked;
        # a vehicle's box (within half its length of its front) worked out only when near
        limit = NEAR_M * NEAR_M
        serving = list(self._by_id.values())
        near = []
        for o in ours:
            x, y = o.x_m, o.y_m
            found = []
            for slot in serving:
                at = slot.at
                if at is not None and (at[0] - x) ** 2 + (at[1] - y) ** 2 < limit:
                    found.append(slot)
                    continue
                fx, fy, _ = slot.front
                if abs(fx - x) < NEAR_M + slot.size[0] and abs(fy - y) < NEAR_M + slot.size[0]:
                    state = self._state(slot)
                    if (state[0] - x) ** 2 + (state[1] - y) ** 2 < limit:
                        found.append(slot)
            near.append(found)
        found = {slot.index: slot for slots in near for slot in slots}
        return near, [found[index] for index in sorted(found)]

    def post_step(self):
        """World hook: a SUMO vehicle or person touching one of our vehicles stops for good."""
        world = self.world
        for body, near in zip(self._ours, self._near):
            if not near:
                continue
            touching = touched(world, body.body_id)
            for slot in near:
                if slot.body_id in touching and slot.sumo_id is not None and not slot.stopped:
                    self._stop(slot)
        if world.gui and world.time_s - self._drawn_at >= FRAME_PERIOD_S - 1e-9:
            self._drawn_at = world.time_s
            self.before_query()
