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
Our vehicles in SUMO (the SUMO engine, physics/sumo_traffic.py): each an external SUMO vehicle.

Each of our vehicles is a SUMO vehicle of its own type (its footprint's length and width),
added on the nearest lane of SUMO's cars and moved every SUMO step with ``moveToXY`` to its
front bumper where the physics has it (SUMO taking its speed from the move): SUMO's drivers
queue behind it and its pedestrians wait for it. One off the road is taken out of SUMO and put
in again when it is back near a lane. One with a route (a world vehicle's ``route:``, or the
edges a scenario actor's waypoints pass: :meth:`SumoOurs.give_route`) has it in SUMO: the edges
from where it is to its route's first (SUMO's own router between them) and on along its route,
so that SUMO's drivers and pedestrians know where it will turn (SUMO keeps a vehicle's route
while ``moveToXY`` moves it along it, and replaces it by the edges it takes when it leaves it).
"""

import math

from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.physics.traffic_boxes import our_vehicle

OURS_PREFIX = 'vehicle_sim.'     # our vehicles' SUMO ids: this + their names
# our vehicle is in SUMO while its front is within this of the centreline of a lane SUMO's cars
# may use [m] (a lane and a half of 3.2 m)
OFF_ROAD_M = 5.0
RETRY_STEPS = 10                 # SUMO steps between two looks for a lane of one out of SUMO

__all__ = ['OURS_PREFIX', 'SumoOurs']


class SumoOurs:
    """
    Our vehicles in one started SUMO (made again at each start).

    :param session: the started SumoSession.
    :param ours: the world's vehicle bodies.
    :param outlines: their outlines (footprints), in that order.
    :param routes: {name: the SUMO edges of its route} of those with a route.
    :param source: quoted in errors ('world.yaml: traffic').
    """

    def __init__(self, session, ours, outlines, routes=None, source='traffic'):
        self.session = session
        self._ours = ours
        self._outlines = outlines
        self._routes_given = dict(routes or {})
        self.routes = {}                   # {name: its whole route's SUMO edges}
        self._source = source
        self._in_sumo = set()              # the names of our vehicles in SUMO now
        self._retry = {}                   # {name: out of SUMO, looked for since}
        self._shapes = {}                  # {SUMO lane id: its shape}
        self._routes = 0

    def add_types(self, api):
        """Give SUMO a vehicle type of each of our vehicles' footprints."""
        for index, body in enumerate(self._ours):
            outline = self._outlines[index]
            type_id = f'{OURS_PREFIX}{body.name}'
            api.vehicletype.copy('DEFAULT_VEHTYPE', type_id)
            api.vehicletype.setLength(type_id, outline.length_m)
            api.vehicletype.setWidth(type_id, outline.width_m)

    def check_routes(self, api):
        """
        Join each route's edges by SUMO's router (the edges between two given ones).

        :raises InvalidParameterError: SUMO finds no way from one edge of a route to the next,
            naming both.
        """
        for name, edges in self._routes_given.items():
            whole, stuck = self._joined(api, edges)
            if stuck is not None:
                raise InvalidParameterError(
                    f"{self._source}: vehicle {name!r}: field 'route': SUMO finds no way "
                    f'from edge {whole[-1]!r} to edge {stuck!r}')
            self.routes[name] = whole

    def give_route(self, api, name, edges):
        """
        Give our vehicle ``name`` a route from now on (a scenario actor's: the edges it passes).

        The edges are joined by SUMO's router, up to the first SUMO finds no way to; the
        vehicle, when in SUMO, gets it at once (its route from the edge it is on).

        :return: the route's SUMO edges as joined.
        """
        whole, _ = self._joined(api, edges)
        self._routes_given[name] = self.routes[name] = whole
        if name in self._in_sumo:
            vid = f'{OURS_PREFIX}{name}'
            refused = self.session.refusal
            try:
                edge = api.vehicle.getRoadID(vid)
                if edge.startswith(':'):     # inside a junction: the edge it came from
                    edge = api.vehicle.getRoute(vid)[api.vehicle.getRouteIndex(vid)]
                api.vehicle.setRoute(vid, self.route_from(api, name, edge))
            except refused:                  # SUMO lost it: it gets the route when put in again
                self._take_out(api, vid, name)
        return whole

    def _joined(self, api, edges):
        """Return (the edges joined by SUMO's router, the first edge it finds no way to)."""
        whole = [edges[0]]
        for edge in edges[1:]:
            try:
                way = tuple(api.simulation.findRoute(whole[-1], edge).edges)
            except self.session.refusal:
                way = ()
            if not way:
                return tuple(whole), edge
            whole += way[1:]
        return tuple(whole), None

    def route_from(self, api, name, edge):
        """Return the SUMO edges of our vehicle ``name`` on ``edge``: its route from there."""
        whole = self.routes.get(name)
        if not whole:
            return [edge]
        if edge in whole:
            return list(whole[whole.index(edge):])
        try:                              # not on it yet: SUMO's way to its first edge
            way = tuple(api.simulation.findRoute(edge, whole[0]).edges)
        except self.session.refusal:
            way = ()
        return list(way) + list(whole[1:]) if way else [edge]

    def arrived(self, vid):
        """SUMO removed our vehicle ``vid`` (its SUMO id): it is put in again at the next step."""
        self._in_sumo.discard(vid[len(OURS_PREFIX):])

    def push(self, steps):
        """
        Put each of our vehicles into SUMO where the physics has it (its front bumper).

        A vehicle whose front is farther than OFF_ROAD_M from the lane SUMO has it on (a car
        park, a field: ``moveToXY`` puts it anywhere) is taken out of SUMO; one out of SUMO is
        put in again when its front is that near a lane of SUMO's passenger cars (looked for
        every RETRY_STEPS SUMO steps: the search costs some 0.5 ms); one SUMO removed (it
        teleports a vehicle stuck for its --time-to-teleport) comes back at the next step.

        :param steps: SUMO steps since its start.
        :return: our vehicles where the physics has them (physics/traffic_boxes.py our_vehicle).
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
                if steps % RETRY_STEPS and self._retry.get(o.name):
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
                    api.route.add(route, self.route_from(api, o.name, edge))
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

