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
How the traffic obeys a lane map's rules: signals, stop signs, right of way and conflicts.

The rules come from ``LaneGraph.rules`` (core/map/lane_rules.py) and the world's
SignalController (core/map/signal_plan.py); :meth:`TrafficRules.apply` runs once per manager
step, after the car-following model has set each vehicle's acceleration, and lowers it where a
rule says stop: the rule is a *virtual leader* standing still at the place to stop at, which the
car-following model brakes for as for a standing vehicle (smoothly, at about its comfortable
deceleration when seen in time):

- **a traffic light's stop line** ahead whose group is red, or yellow while the vehicle can
  still stop before the line at the comfortable deceleration ``b`` (``d >= v^2 / 2b``); on red,
  one that could not stop even at the model's hardest braking goes on. The decision holds for
  that line until the group is green again (a vehicle that chose to go on yellow goes on through
  the red that follows; one that chose to stop does not change its mind as it gets closer);
- **a stop sign's or road marking's stop line**: a virtual leader until the vehicle has stood
  still (below 0.1 m/s) with its front within ``STAND_REACH_M`` of the line for
  ``STOP_SIGN_WAIT_S``; then it goes on as a vehicle that yields (below);
- **conflict zones** (``LaneRules.conflicts``: two lanes whose areas cross or merge, each with
  its arc-length range): a zone is *held* on one side by every vehicle whose footprint (with
  ``SPAN_MARGIN_M`` each end) overlaps the range on a lane it occupies (traffic vehicles, ours
  too), and by every traffic vehicle *granted* it. A vehicle whose front comes within
  ``gap_kept(v) + v^2 / 2b + REQUEST_MARGIN_M`` of a zone ahead (the least gap of the model at
  its speed plus its comfortable braking distance: it can still stop) asks for every zone of its
  path within ``GROUP_M`` beyond that one, all at once (an intersection is entered whole or not
  at all: no vehicle waits inside one zone for the next). The askers are taken in a fixed
  order: those that do not yield first, then by the time they first asked, then by index. A
  vehicle gets its zones when none of them is held or asked for on its other side (first come,
  first served: an earlier asker that waits still keeps the later ones out), and when it will
  not stop inside them (its leader beyond the zones moves, or stands with room behind it for
  the vehicle: "don't block the box"); else it stops ``ZONE_MARGIN_M`` before the first one. It
  keeps each zone until its rear is past it. A vehicle held by a stop line before a zone does
  not ask for it: a red light's queue never blocks the crossing traffic;
- **right of way** (who goes first: core/map/priority.py, the rule the ``yield`` criterion
  checks too: a ``RightOfWay``'s priority lanes, and at an unsignalled conflict the way without
  a stop or yield line): a vehicle whose way yields to the other way of a zone asks after the
  vehicles that do not yield, so that a priority vehicle asking in the same step goes first; a
  yielding vehicle waits while any vehicle on a priority lane is close enough to ask. On a
  signalised intersection the signal keeps conflicting flows apart; the zones still make a
  green vehicle wait for the vehicles already inside (the previous phase's last ones);
- **forks**: lanes that leave one lane overlap near their start; a vehicle approaching a fork,
  or at the start of one branch, follows the vehicles on the other branches that are still
  within the overlap (``fork_lengths``, conflict_zones.py), as it follows its own leader.

Everything is computed in a fixed order from the manager's state (no randomness): the same
inputs give the same decisions.
"""

from bisect import bisect_left
import math
from typing import Dict, Tuple
import weakref

from vehicle_sim.core.map.priority import priority_test
from vehicle_sim.core.traffic.conflict_zones import conflict_zones

STAND_REACH_M = 1.5         # a vehicle stands "at" a stop line within its model's gap + this
STOP_SIGN_WAIT_S = 1.0      # how long it stands there before it goes on
STANDING_MPS = 0.1          # below this a vehicle stands
SPAN_MARGIN_M = 0.5         # a footprint holds a zone with this margin at each end
ZONE_MARGIN_M = 0.5         # a waiting vehicle's virtual leader stands this far before a zone
REQUEST_MARGIN_M = 3.0      # extra distance at which a vehicle asks for the zones ahead
GROUP_M = 40.0              # the zones asked for together: up to this beyond the first
LINE_MARGIN_M = 10.0        # stop lines further than the braking reach + this do not count
SLOW_MPS = 2.0              # a leader slower than this may not clear the exit in time
GAP_S = 1.5                 # a yielding vehicle clears its zones this long before a priority one
ROOM_MARGIN_M = 1.0         # room beyond the zones a vehicle needs besides its length and gap
FORK_NEAR_M = 60.0          # a vehicle follows the other branches' vehicles from this far

# The conflict zones of each lane graph, worked out once per rules object and vehicle size:
# {graph: {(length, width): (the graph's rules then, ConflictZones)}}. A reset builds a new
# manager on the same graph; the zones are read, never changed, so its managers share them.
_ZONES = weakref.WeakKeyDictionary()


def _zones_of(graph, length_m, width_m):
    known = _ZONES.setdefault(graph, {})
    rules, found = known.get((length_m, width_m), (None, None))
    if rules is not graph.rules:        # first time, or the graph got other rules since
        found = conflict_zones(graph, length_m, width_m, priority_test(graph))
        known[(length_m, width_m)] = (graph.rules, found)
    return found


class TrafficRules:
    """
    The rules of a lane map as the traffic obeys them (see the module's docstring).

    :param graph: the LaneGraph (its ``rules``).
    :param signals: the world's SignalController, or None (every light is then off: dark
        signals, the vehicles yield by the conflicts alone).
    :param manager: the TrafficManager (its car-following model and parameters).
    :param length_m: the longest traffic vehicle [m] (footprint overlaps).
    :param width_m: the widest traffic vehicle [m] (the fork and footprint overlaps).
    """

    def __init__(self, graph, signals, manager, length_m, width_m):
        self.graph = graph
        self.signals = signals
        self.manager = manager
        rules = graph.rules
        found = _zones_of(graph, length_m, width_m)    # who goes first: core/map/priority.py
        self.zones, self._other = found.zones, found.other
        self.forks, self.siblings = found.forks, found.siblings
        self.lines = {lane: tuple(line for line in rules.stop_lines_on(lane)
                                  if line.kind != 'yield')
                      for lane in graph.lanes if rules.stop_lines_on(lane)}
        self.lines = {lane: lines for lane, lines in self.lines.items() if lines}
        # where a zone or a stop line starts, per lane (sorted): the quick test of each step
        self._starts = {}
        for lane, items in self.zones.items():
            self._starts.setdefault(lane, []).extend(zone.s0 for zone in items)
        for lane, items in self.lines.items():
            self._starts.setdefault(lane, []).extend(line.s_m for line in items)
        for items in self._starts.values():
            items.sort()
        # the lanes where anything happens (a vehicle elsewhere costs two look-ups)
        self.busy = set(self.zones) | set(self.lines) | set(self.forks) | {
            lane.id for lane in graph.lanes.values() if len(lane.successors) > 1}
        params = manager._following_params
        self._b = manager._comfortable_deceleration
        self._b_max = getattr(params, 'max_deceleration_mps2', 2.5 * self._b)
        self._a = getattr(params, 'acceleration_mps2', self._b)
        self._decided: Dict[int, Tuple[int, bool]] = {}     # vehicle -> (line, go)
        self._released: Dict[int, int] = {}                 # vehicle -> stop-sign line passed
        self._stood: Dict[int, float] = {}                  # vehicle -> time stood at its line
        self._grants: Dict[int, set] = {}                   # vehicle -> zone keys it holds
        self._asked: Dict[int, float] = {}                  # vehicle -> time it first asked
        self.waiting = {}                                   # vehicle -> why it stops (reading)

    @property
    def empty(self):
        return not self.busy

    def keep_clear(self, lane_id, half_m):
        """Return the (lo, hi) ranges of a lane where no vehicle centre may start [m]."""
        out = [(zone.s0 - half_m - SPAN_MARGIN_M, zone.s1 + half_m + SPAN_MARGIN_M)
               for zone in self.zones.get(lane_id, ())]
        if lane_id in self.forks:
            out.append((-math.inf, self.forks[lane_id] + half_m + SPAN_MARGIN_M))
        return out

    # ------------------------------------------------------------------ reading
    def grants(self, index):
        """Return the zone keys (conflict index, side) a vehicle holds."""
        return set(self._grants.get(index, ()))

    # ------------------------------------------------------------------ the step
    def _path(self, v):
        """
        Return [(lane id, distance from ``v``'s front to the lane's start)] along its path.

        Its lane, its next lane, and the lane after that when it is the only one.
        """
        lanes = self.graph.lanes
        front = v.s_m + 0.5 * v.length_m
        nxt = v.next_lane
        if nxt is None:
            return [(v.lane, -front)]
        start = lanes[v.lane].length_m - front
        after = lanes[nxt].successors
        if len(after) == 1:
            return [(v.lane, -front), (nxt, start), (after[0], start + lanes[nxt].length_m)]
        return [(v.lane, -front), (nxt, start)]

    def _first_ahead(self, v):
        """Return the distance from ``v``'s front to the next zone or stop line on its path."""
        starts = self._starts
        front = v.s_m + 0.5 * v.length_m
        here = starts.get(v.lane)
        if here is not None:
            i = bisect_left(here, front)
            if i < len(here):
                return here[i] - front
        lanes = self.graph.lanes
        nxt = v.next_lane
        if nxt is None:
            return math.inf
        start = lanes[v.lane].length_m - front
        here = starts.get(nxt)
        if here is not None:
            return start + here[0]
        after = lanes[nxt].successors
        if len(after) == 1 and after[0] in starts:
            return start + lanes[nxt].length_m + starts[after[0]][0]
        return math.inf

    def start_speed_limit(self, v):
        """Return the highest speed at which ``v`` stops comfortably before what is ahead."""
        limit = math.inf
        b = self._b
        for lane, start in self._path(v):
            for line in self.lines.get(lane, ()):
                d = start + line.s_m
                if d >= 0.0:
                    limit = min(limit, math.sqrt(2.0 * b * max(d - ZONE_MARGIN_M, 0.0)))
            for zone in self.zones.get(lane, ()):
                d = start + zone.s0
                if d >= 0.0:
                    limit = min(limit, math.sqrt(2.0 * b * max(d - ZONE_MARGIN_M, 0.0)))
        return limit

    def change_allowed(self, v, target, reach_m):
        """Return whether a lane change of ``v`` onto ``target`` stays clear of every zone."""
        lo = v.s_m - 0.5 * v.length_m - REQUEST_MARGIN_M
        hi = reach_m + REQUEST_MARGIN_M
        for lane in (v.lane, target):
            for zone in self.zones.get(lane, ()):
                if zone.s0 < hi and zone.s1 > lo:
                    return False
            for line in self.lines.get(lane, ()):
                if lo < line.s_m < hi:
                    return False
        return not (v.lane in self.forks or target in self.forks)

    def apply(self, dt_s):
        """Lower the accelerations the rules ask for (after the car-following model's)."""
        m = self.manager
        busy = self.busy
        vehicles = [v for v in m.vehicles if v.active and (
            v.lane in busy or v.next_lane in busy or v.prev_lane in busy or
            v.from_lane in busy)]
        self.waiting = {}
        held = {}                     # zone key -> vehicles whose footprint holds it
        zones = self.zones
        lanes = self.graph.lanes
        for v in vehicles:
            on, nxt, prev, old = (zones.get(v.lane), zones.get(v.next_lane),
                                  zones.get(v.prev_lane), zones.get(v.from_lane))
            if not (on or nxt or prev or old):
                continue
            index, half = v.index, 0.5 * v.length_m + SPAN_MARGIN_M
            lo, hi = v.s_m - half, v.s_m + half
            if on:
                for zone in on:                 # by their start
                    if zone.s0 >= hi:
                        break
                    if lo < zone.s1:
                        held.setdefault(zone.key, set()).add(index)
            length = lanes[v.lane].length_m
            if nxt and hi > length:
                for zone in nxt:
                    if zone.s0 >= hi - length:
                        break
                    held.setdefault(zone.key, set()).add(index)
            if prev and lo < 0.0:
                rear = lo + lanes[v.prev_lane].length_m
                for zone in prev:
                    if zone.s1 > rear:
                        held.setdefault(zone.key, set()).add(index)
            if old:
                lo, hi = v.from_s_m - half, v.from_s_m + half
                for zone in old:
                    if zone.s0 >= hi:
                        break
                    if lo < zone.s1:
                        held.setdefault(zone.key, set()).add(index)
        for k, o in enumerate(m._ours):
            at = m._ours_at.get(o.name)
            if at is None or at[0] not in zones:
                continue
            half = 0.5 * o.length_m + SPAN_MARGIN_M
            for zone in zones[at[0]]:
                if at[1] - half < zone.s1 and at[1] + half > zone.s0:
                    held.setdefault(zone.key, set()).add(-1 - k)
        grants = self._grants
        for index in [i for i, v in grants.items() if not m.vehicles[i].active]:
            del grants[index]       # it left the map
        asks = []
        gap_kept, b2 = m._gap_kept, 2.0 * self._b
        forks = self.forks
        for v in vehicles:
            index = v.index
            if v.stopped:           # collided: what its footprint holds, it holds
                grants.pop(index, None)
                continue
            speed = v.speed_mps
            if self._first_ahead(v) > gap_kept(speed) + speed * speed / b2 + LINE_MARGIN_M:
                stop_at, ask = None, None       # nothing within its reach
                if index in grants:
                    self._release_passed(v, self._path(v), held, None)
            else:
                path = self._path(v)
                stop_at = self._line(v, path, dt_s)
                if index in grants:
                    self._release_passed(v, path, held, stop_at)
                ask = self._zones_ahead(v, path)
            if stop_at is not None:
                self._stop(v, stop_at, 'stop line')
            if ask is None or (stop_at is not None and stop_at <= ask[0] + ZONE_MARGIN_M):
                # a line at (or before) the first zone holds it before any zone
                self._asked.pop(index, None)
            else:
                first, group = ask
                since = self._asked.setdefault(index, m.time_s)
                asks.append((any(z.yields for z in group), since, index, v, first, group))
            lane = lanes[v.lane]
            if (len(lane.successors) > 1 and lane.length_m - v.s_m < FORK_NEAR_M) or (
                    v.lane in forks and v.s_m - 0.5 * v.length_m < forks[v.lane]):
                self._fork(v)
        asks.sort(key=lambda a: a[:3])
        for v_index, keys in grants.items():
            for key in keys:
                held.setdefault(key, set()).add(v_index)
        for yielding, _, index, v, first, group in asks:
            free = True
            for zone in group:
                others = held.get(zone.other)
                if others and (len(others) > 1 or index not in others):
                    free = False
                    break
            if free and not self._room(v, group):
                free = False
            if free and yielding and not self._gap(v, first, group):
                free = False
            if free:
                mine = grants.setdefault(index, set())
                for zone in group:
                    mine.add(zone.key)
                self._asked.pop(index, None)
            else:
                self._stop(v, first - ZONE_MARGIN_M, 'conflict')
            for zone in group:      # granted or waiting, it keeps the later ones out
                held.setdefault(zone.key, set()).add(index)

    def _stop(self, v, distance, why):
        """Brake ``v`` for a virtual leader standing ``distance`` ahead of its front."""
        m = self.manager
        acc = m._follow(v.speed_mps, m._v0(v), distance, 0.0)
        if acc < v.acc_mps2:
            v.acc_mps2 = acc
        self.waiting[v.index] = why

    def _line(self, v, path, dt_s):
        """Return the distance from ``v``'s front to the stop line it must stop at, or None."""
        speed = v.speed_mps
        horizon = self.manager._gap_kept(speed) + speed * speed / (2.0 * self._b) + \
            LINE_MARGIN_M
        for lane, start in path:
            if start > horizon:
                return None
            for line in self.lines.get(lane, ()):
                d = start + line.s_m
                if d < 0.0:
                    continue
                if d > horizon:
                    return None
                return d if self._stops_at(v, line, d, dt_s) else None
        return None

    def _stops_at(self, v, line, d, dt_s):
        """Return whether ``v`` stops for ``line`` ``d`` ahead of its front."""
        index, speed = v.index, v.speed_mps
        if line.kind == 'traffic_light':
            state = 'off' if self.signals is None else self.signals.state(line.group_id)
            if state in ('green', 'off'):
                self._decided.pop(index, None)
                return False
            decided = self._decided.get(index)
            if decided is not None and decided[0] == line.id:
                return not decided[1]
            brake = self._b if state == 'yellow' else self._b_max
            go = d < speed * speed / (2.0 * brake)
            self._decided[index] = (line.id, go)
            return not go
        # a stop sign or a road marking: stand at the line, then go on (yielding)
        if self._released.get(index) == line.id:
            return False
        if speed < STANDING_MPS and d <= self.manager._gap_kept(0.0) + STAND_REACH_M:
            stood = self._stood.get(index, 0.0) + dt_s
            if stood >= STOP_SIGN_WAIT_S - 1e-9:
                self._released[index] = line.id
                self._stood.pop(index, None)
                return False
            self._stood[index] = stood
        else:
            self._stood.pop(index, None)
        return True

    def _release_passed(self, v, path, held, stop_at):
        """
        Drop the zones ``v`` no longer needs: behind it, or beyond a line it now stops at.

        A zone under its footprint it keeps.
        """
        mine = self._grants.get(v.index)
        if not mine:
            return
        ahead = set()
        beyond = math.inf if stop_at is None else stop_at
        for lane, start in path:
            for zone in self.zones.get(lane, ()):
                if -v.length_m - SPAN_MARGIN_M < start + zone.s1 and start + zone.s0 < beyond:
                    ahead.add(zone.key)
        keep = {key for key in mine if key in ahead or v.index in held.get(key, ())}
        if keep:
            self._grants[v.index] = keep
        else:
            del self._grants[v.index]

    def _zones_ahead(self, v, path):
        """Return (distance to the first, the zones to ask for) when ``v`` asks, else None."""
        speed = v.speed_mps
        reach = self.manager._gap_kept(speed) + speed * speed / (2.0 * self._b) + \
            REQUEST_MARGIN_M
        mine = self._grants.get(v.index, ())
        first, group = None, []
        for lane, start in path:
            for zone in self.zones.get(lane, ()):
                d = start + zone.s0
                if d < 0.0 or zone.key in mine:
                    continue            # entered (its footprint holds it) or granted
                if first is None:
                    if d > reach:
                        return None
                    first = d
                if d > first + GROUP_M:
                    break
                group.append(zone)
        return None if first is None else (first, group)

    def _gap(self, v, first, group):
        """Return whether ``v`` clears its yielding zones before a priority vehicle comes."""
        m = self.manager
        end = first
        for lane, start in self._path(v):
            for zone in group:
                if zone.lane == lane:
                    end = max(end, start + zone.s1)
        # the time to clear them from its speed at the comfortable acceleration
        a, speed, distance = self._a, v.speed_mps, end + v.length_m
        clear = (math.sqrt(speed * speed + 2.0 * a * distance) - speed) / a
        for zone in group:
            if not zone.yields:
                continue
            other = self._other[zone.other]
            dist, occupant = m._behind(other.lane, other.s0, None)
            if occupant is None or occupant.ident == v.index:
                continue
            coming = (dist - occupant.half) / max(occupant.speed, 1.0)
            if coming < clear + GAP_S:
                return False
        return True

    def _room(self, v, group):
        """Return whether ``v`` will not have to stop inside the zones of ``group``."""
        m = self.manager
        end = 0.0
        for lane, start in self._path(v):
            for zone in group:
                if zone.lane == lane:
                    end = max(end, start + zone.s1)
        gap, leader = m._leader(v, v.lane, v.s_m)
        if leader is None or leader.speed >= SLOW_MPS:
            return True
        return gap >= end + v.length_m + m._gap_kept(0.0) + ROOM_MARGIN_M

    def _fork(self, v):
        """Follow the vehicles on the other branches of a fork while they overlap ours."""
        lanes, forks, occ = self.graph.lanes, self.forks, self.manager._occ
        half = 0.5 * v.length_m
        lane = lanes[v.lane]
        if len(lane.successors) > 1:
            base, branches, here = lane.length_m - v.s_m, lane.successors, 0.0
        elif v.lane in forks and v.s_m - half < forks[v.lane]:
            base, branches, here = 0.0, self.siblings.get(v.lane, ()), v.s_m
        else:
            return
        best_gap, best_speed = None, 0.0
        for branch in branches:
            if branch == v.next_lane or branch == v.lane:
                continue
            reach = forks.get(branch)
            items = occ.get(branch)
            if reach is None or items is None:
                continue
            for o in items[1]:
                if o.ident == v.index or o.s - o.half >= reach:
                    continue
                if o.s <= here:
                    continue            # behind us on its branch: it follows us
                gap = base + o.s - here - o.half - half
                if best_gap is None or gap < best_gap:
                    best_gap, best_speed = gap, o.speed
        if best_gap is not None:
            m = self.manager
            acc = m._follow(v.speed_mps, m._v0(v), best_gap, best_speed)
            if acc < v.acc_mps2:
                v.acc_mps2 = acc
