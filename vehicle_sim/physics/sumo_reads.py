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
Reading SUMO's vehicles and persons after each of its steps (the SUMO engine, sumo_traffic.py).

Each SUMO vehicle's and walking person's front position, angle and speed, and a vehicle's lane,
place on it and route index (its predicted path: only when the objects are read). Two ways, one
answer:

- libsumo (SUMO in this process): the getters (``vehicle.getIDList``, ``vehicle.getPosition``
  ...), a fraction of a microsecond each. No subscriptions: SUMO computes and stores every
  subscribed value at each of its steps, which in the shipped city (about 250 vehicles and
  persons, benchmarks/bench_sumo.py) doubled its step, and turning the results into Python
  dictionaries cost more than the getters' calls.
- TraCI (a sumo process over a socket): a subscription per vehicle and person, every result in
  one call a step (a getter is a round trip to the process).

Both leave out our own vehicles (SUMO ids starting with ``OURS_PREFIX``), persons riding a
vehicle (one on a bus has no body of its own) and vehicles off the road for a while (SUMO's
teleport: the getters' id list and the subscription results both skip them).
"""

__all__ = ['GetterReads', 'reads_for', 'SubscribedReads']


def reads_for(session, constants, ours_prefix):
    """
    Return the reader for a started SumoSession: getters on libsumo, else subscriptions.

    A worker (``transport: worker``, physics/sumo_worker.py) runs libsumo: its readings after
    each step come from its getters in one message; between steps (a vehicle's lane when it
    is not known) the getters are called in it.
    """
    kind = GetterReads if session.transport in ('libsumo', 'worker') else SubscribedReads
    return kind(constants, ours_prefix)


class GetterReads:
    """
    libsumo's getters, called for every vehicle and person after each step.

    :param constants: TraCI's constants module.
    :param ours_prefix: the SUMO ids of our vehicles start with this.
    """

    def __init__(self, constants, ours_prefix):
        self._ours = ours_prefix

    def departed(self, api, person, sumo_id):
        """Set nothing up for a departed vehicle (or person): the getters read any."""

    def vehicles(self, api):
        """Return [(SUMO id, (x, y) of its front, angle [deg], speed, None)]: the lane later."""
        domain = api.vehicle
        position, angle, speed = domain.getPosition, domain.getAngle, domain.getSpeed
        ours = self._ours
        return [(vid, position(vid), angle(vid), speed(vid), None)
                for vid in domain.getIDList() if not vid.startswith(ours)]

    def persons(self, api):
        """Return [(SUMO id, (x, y), angle [deg], speed)] of the persons not in a vehicle."""
        domain = api.person
        position, angle, speed, vehicle = (domain.getPosition, domain.getAngle,
                                           domain.getSpeed, domain.getVehicle)
        return [(pid, position(pid), angle(pid), speed(pid))
                for pid in domain.getIDList() if not vehicle(pid)]

    def lane(self, api, sumo_id):
        """Return a vehicle's (SUMO lane id, lane position [m], route index) now."""
        domain = api.vehicle
        return (domain.getLaneID(sumo_id), domain.getLanePosition(sumo_id),
                domain.getRouteIndex(sumo_id))


class SubscribedReads:
    """
    TraCI's subscriptions: one per vehicle and person, made at its departure, read in one call.

    :param constants: TraCI's constants module.
    :param ours_prefix: the SUMO ids of our vehicles start with this.
    """

    def __init__(self, constants, ours_prefix):
        c = self._c = constants
        self._ours = ours_prefix
        self._fields = (c.VAR_POSITION, c.VAR_ANGLE, c.VAR_SPEED)
        # a vehicle's lane, place on it and route index: its predicted path
        self._vehicle_fields = self._fields + (c.VAR_LANE_ID, c.VAR_LANEPOSITION,
                                               c.VAR_ROUTE_INDEX)
        self._person_fields = self._fields + (c.VAR_VEHICLE,)

    def departed(self, api, person, sumo_id):
        """Subscribe to a departed vehicle (or person) that gets a body."""
        if person:
            api.person.subscribe(sumo_id, self._person_fields)
        else:
            api.vehicle.subscribe(sumo_id, self._vehicle_fields)

    def vehicles(self, api):
        """Return [(SUMO id, (x, y) of its front, angle [deg], speed, (lane, position, index))]."""
        c, ours = self._c, self._ours
        return [(vid, values[c.VAR_POSITION], values[c.VAR_ANGLE], values[c.VAR_SPEED],
                 (values[c.VAR_LANE_ID], values[c.VAR_LANEPOSITION], values[c.VAR_ROUTE_INDEX]))
                for vid, values in api.vehicle.getAllSubscriptionResults().items()
                if not vid.startswith(ours)]

    def persons(self, api):
        """Return [(SUMO id, (x, y), angle [deg], speed)] of the persons not in a vehicle."""
        c = self._c
        return [(pid, values[c.VAR_POSITION], values[c.VAR_ANGLE], values[c.VAR_SPEED])
                for pid, values in api.person.getAllSubscriptionResults().items()
                if not values.get(c.VAR_VEHICLE)]

    def lane(self, api, sumo_id):
        """Return a vehicle's (SUMO lane id, lane position [m], route index) now (a getter)."""
        domain = api.vehicle
        return (domain.getLaneID(sumo_id), domain.getLanePosition(sumo_id),
                domain.getRouteIndex(sumo_id))
