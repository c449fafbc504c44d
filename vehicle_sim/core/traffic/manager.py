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
The traffic manager: vehicles that drive the lanes of a LaneGraph with the traffic models.

The models are a car-following and a lane-change model (IDM and MOBIL by default;
core/traffic/models.py), looked up once when the manager is built.

Each traffic vehicle is on one lane at an arc length ``s`` (its centre) with a speed; while it
changes lanes it is already on the target lane, with a lateral ``offset`` from that lane's
centreline that goes smoothly to 0 over ``lane_change_duration``, and it still occupies the lane
it left (at the proportional ``s``), so that the vehicles there keep seeing it.

Every :meth:`TrafficManager.step`:

1. the occupants of each lane are sorted by ``s``: the traffic vehicles and *our* vehicles
   (:class:`OurVehicle`, given by :meth:`TrafficManager.set_ours`, located on the graph each
   step; one that reaches into a neighbouring lane occupies that lane too);
2. each vehicle's leader is the next occupant ahead along its lane and its planned successors
   (up to ``LOOKAHEAD_M``); the car-following model gives its acceleration (the lower of the
   two lanes' while it changes lanes);
3. the vehicles whose turn it is (every ``lane_change_period``, staggered) weigh a change to each
   neighbour a change is allowed onto with the lane-change model; a change is never made in
   front of one of our vehicles closer than the car-following model's gap at its speed (IDM's
   ``s0 + v T``), nor when it would not end on the two lanes;
4. the speeds and positions advance ballistically; a vehicle passing a lane's end goes on to its
   planned successor (its route's next lane, else a seeded random choice at forks); at a dead
   end it leaves the map and re-enters, when there is room, at the start of an entry lane (a
   lane without predecessors).

A vehicle that collided (:meth:`TrafficManager.stop`) stands still where it is from then on.
Everything random comes from one ``random.Random(seed)`` consumed in a fixed order, so two runs
with the same inputs give the same trajectories bit for bit.
"""

from bisect import bisect_left, bisect_right
import math
import random
from typing import Dict, List, Optional, Sequence, Tuple

from vehicle_sim.core.geometry.angles import wrap_angle_rad
from vehicle_sim.core.traffic.idm import advance
from vehicle_sim.core.traffic.mobil import LaneChangeAccelerations
from vehicle_sim.core.traffic.models import CAR_FOLLOWING_MODELS, LANE_CHANGE_MODELS
from vehicle_sim.core.traffic.params import TrafficSpec
from vehicle_sim.core.traffic.rules import TrafficRules
from vehicle_sim.core.traffic.spawn import spawn_vehicles
from vehicle_sim.core.traffic.vehicles import OurVehicle, TrafficVehicle

__all__ = ['OurVehicle', 'TrafficManager', 'TrafficVehicle']

# the lane subtypes traffic drives (Lane.subtype; a lane without one is a road)
DRIVEN_SUBTYPES = ('road', 'highway')

LOOKAHEAD_M = 250.0       # leaders further ahead do not count (IDM's interaction is ~0 there)
LOOKBACK_M = 150.0        # followers further behind do not count in MOBIL
ENTRY_MARGIN_M = 1.0      # extra room a re-entering vehicle needs ahead


class _Occupant:
    __slots__ = ('s', 'speed', 'half', 'ident', 'v0')

    def __init__(self, s, speed, half, ident, v0):
        self.s, self.speed, self.half, self.ident, self.v0 = s, speed, half, ident, v0


def _by_s(occupant):
    return occupant.s


def _smoothstep(x):
    return x * x * (3.0 - 2.0 * x)


class TrafficManager:
    """
    Traffic vehicles on a LaneGraph.

    :param graph: the LaneGraph.
    :param spec: the TrafficSpec (``traffic:`` of the world).
    :param dimensions: {model: (length, width)} [m] of every model the spec names.
    :param ours: our vehicles at the start (no vehicle is spawned on them).
    :param signals: the world's SignalController (core/map/signal_plan.py), whose lights the
        traffic obeys; None = every light is off (the vehicles still yield at conflicts and
        stop at stop signs: core/traffic/rules.py).
    :raises InvalidParameterError: a spawn or placed lane not in the map, ``s`` off its lane,
        a route through a lane not in the map or not a successor, placed vehicles on top of each
        other, or more vehicles than fit; naming the file and field.
    """

    def __init__(self, graph, spec: TrafficSpec, dimensions: Dict[str, Tuple[float, float]],
                 ours: Sequence[OurVehicle] = (), signals=None):
        self.graph = graph
        self.spec = spec
        self.idm = spec.idm                   # scenario actors follow with these
        # The two models, looked up once: the step calls only what they bind.
        following = CAR_FOLLOWING_MODELS[spec.car_following]
        following_params = spec.params_of(spec.car_following)
        self._follow = following.bind(following_params)
        self._min_gap = following.min_gap
        self._following_params = following_params
        self._comfortable_deceleration = following.comfortable_deceleration(following_params)
        self._should_change = LANE_CHANGE_MODELS[spec.lane_change].bind(
            spec.params_of(spec.lane_change))
        self.rng = random.Random(spec.seed)
        self.time_s = 0.0
        self.steps = 0
        self.lane_changes = 0
        self.vehicles: List[TrafficVehicle] = []
        self._ours: List[OurVehicle] = []
        self._ours_at = {}                    # our vehicle's name -> (lane, s) last located
        self._occ: Dict[int, Tuple[list, list]] = {}
        self.dimensions = dimensions
        self.signals = signals
        self._driven = {i for i, lane in graph.lanes.items()
                        if getattr(lane, 'subtype', 'road') in DRIVEN_SUBTYPES}
        self._entries = sorted(i for i, pred in graph.predecessors.items()
                               if not pred and i in self._driven)
        rules = TrafficRules(graph, signals, self,
                             max((d[0] for d in dimensions.values()), default=0.0),
                             max((d[1] for d in dimensions.values()), default=0.0))
        self.rules = None if rules.empty else rules
        self.vehicles = spawn_vehicles(graph, spec, dimensions, ours, self.rng, self._driven,
                                       self.rules)
        for v in self.vehicles:
            v.next_lane = self._choose_next(v)
        self.set_ours(ours)
        self._occupancy()
        for v in self.vehicles:               # start speeds: safe behind the leaders
            if v.speed_mps < 0.0:
                gap, leader = self._leader(v, v.lane, v.s_m)
                v.speed_mps = self._start_speed(v, gap, leader)

    def _choose_next(self, v):
        successors = self.graph.lanes[v.lane].successors
        if v.route:
            return v.route.pop(0)
        if len(successors) > 1 or (successors and successors[0] not in self._driven):
            successors = [s for s in successors if s in self._driven]
        if not successors:
            return None
        if len(successors) == 1:
            return successors[0]
        return successors[self.rng.randrange(len(successors))]

    def _start_speed(self, v, gap, leader):
        """Return the safe speed behind the leader and before the stops ahead (the rules)."""
        speed = self._safe_speed(v, gap, leader)
        return speed if self.rules is None else min(speed, self.rules.start_speed_limit(v))

    def _safe_speed(self, v, gap, leader):
        """Return the highest start speed <= desired at which the model brakes at most b."""
        v0 = self._v0(v)
        if gap is None:
            return v0
        lo, hi = 0.0, v0
        follow, comfortable = self._follow, -self._comfortable_deceleration
        if follow(hi, v0, gap, leader.speed) >= comfortable:
            return hi
        for _ in range(30):
            mid = 0.5 * (lo + hi)
            if follow(mid, v0, gap, leader.speed) >= comfortable:
                lo = mid
            else:
                hi = mid
        return lo

    # ------------------------------------------------------------------ queries
    def _v0(self, v):
        return self.graph.lanes[v.lane].speed_limit_mps * v.factor

    def desired_speed(self, v: TrafficVehicle):
        """Return a vehicle's desired speed [m/s]: its lane's limit times its speed factor."""
        return self._v0(v)

    def pose(self, v: TrafficVehicle):
        """Return (x, y, yaw) of a vehicle's centre (lane-change offset and heading included)."""
        lane = self.graph.lanes[v.lane]
        k = bisect_right(lane.s0, v.s_m) - 1
        k = 0 if k < 0 else (k if k < len(lane.seg_len) else len(lane.seg_len) - 1)
        t = v.s_m - lane.s0[k]
        length = lane.seg_len[k]
        t = 0.0 if t < 0.0 else (length if t > length else t)
        ux, uy = lane.ux[k], lane.uy[k]
        yaw = lane.vertex_headings[k] + lane.turns[k] * (t / length)
        if v.from_lane is not None and v.speed_mps > 0.1:
            duration = self.spec.lane_change_duration_s
            tau = min(v.change_s / duration, 1.0)
            lateral = -v.change_from_m * 6.0 * tau * (1.0 - tau) / duration
            yaw += math.atan2(lateral, v.speed_mps)
        off = v.offset_m
        if yaw > math.pi or yaw <= -math.pi:
            yaw = wrap_angle_rad(yaw)
        return (lane.xs[k] + ux * t - uy * off, lane.ys[k] + uy * t + ux * off, yaw)

    # ------------------------------------------------------------------ our vehicles
    def set_ours(self, ours: Sequence[OurVehicle]):
        """Give our vehicles' current states (before each :meth:`step`)."""
        self._ours = list(ours)

    def stop(self, index, travelled_m=0.0):
        """
        Stop a traffic vehicle for good (it collided): it stays where it is, at rest.

        :param travelled_m: how far it went on along its lane since the last step [m], >= 0
            (where it was when it collided, between two steps); the end of its lane at most.
        """
        if not (math.isfinite(travelled_m) and travelled_m >= 0.0):
            raise ValueError(f'travelled_m = {travelled_m!r}: must be finite and >= 0')
        v = self.vehicles[index]
        lane_length = self.graph.lanes[v.lane].length_m
        travelled_m = min(travelled_m, lane_length - v.s_m)     # no lane change here
        if travelled_m > 0.0:
            v.s_m += travelled_m
            if v.from_lane is not None:
                v.from_s_m += travelled_m
        v.stopped, v.speed_mps, v.acc_mps2 = True, 0.0, 0.0

    # ------------------------------------------------------------------ the step
    def _add(self, lane_id, occupant):
        keys, items = self._occ.setdefault(lane_id, ([], []))
        i = bisect_left(keys, occupant.s)
        keys.insert(i, occupant.s)
        items.insert(i, occupant)

    def _occupancy(self):
        lists = {}
        graph = self.graph
        lanes = graph.lanes
        for v in self.vehicles:
            if not v.active:
                continue
            v0 = lanes[v.lane].speed_limit_mps * v.factor
            half = 0.5 * v.length_m
            lists.setdefault(v.lane, []).append(_Occupant(v.s_m, v.speed_mps, half, v.index, v0))
            if v.from_lane is not None:
                lists.setdefault(v.from_lane, []).append(
                    _Occupant(v.from_s_m, v.speed_mps, half, v.index, v0))
        for k, o in enumerate(self._ours):
            pos = self._locate_ours(o)
            if pos is None:
                continue
            speed = o.speed_mps * math.cos(pos.heading_error_rad)
            half = 0.5 * o.length_m
            ident = -1 - k
            lists.setdefault(pos.lane_id, []).append(
                _Occupant(pos.s_m, speed, half, ident, pos.speed_limit_mps))
            lane = lanes[pos.lane_id]
            # the lateral reach of its footprint: a heading error widens it
            reach = 0.5 * (o.width_m * abs(math.cos(pos.heading_error_rad))
                           + o.length_m * abs(math.sin(pos.heading_error_rad)))
            for side, other in ((1.0, lane.left_lane), (-1.0, lane.right_lane)):
                if other is not None and side * pos.offset_m + reach > 0.5 * pos.width_m:
                    s = pos.s_m * lanes[other].length_m / lane.length_m
                    lists.setdefault(other, []).append(
                        _Occupant(s, speed, half, ident, pos.speed_limit_mps))
        occ = {}
        for lane_id, items in lists.items():
            items.sort(key=_by_s)       # stable: equal s keep the vehicles' order
            occ[lane_id] = ([o.s for o in items], items)
        self._occ = occ

    def _locate_ours(self, o):
        """Locate one of our vehicles: on the lane it was on (cheap), else on the whole map."""
        last = self._ours_at.get(o.name)
        if last is not None:
            pos, on_lane = self.graph.locate_on(last[0], o.x_m, o.y_m, o.yaw_rad, last[1])
            if on_lane:
                self._ours_at[o.name] = (pos.lane_id, pos.s_m)
                return pos
        pos = self.graph.locate(o.x_m, o.y_m, o.yaw_rad)
        self._ours_at[o.name] = None if pos is None else (pos.lane_id, pos.s_m)
        return pos

    def _ahead(self, lane_id, s, ident, path):
        """Return (centre distance, occupant) of the next occupant ahead, or (None, None)."""
        lanes = self.graph.lanes
        dist = 0.0
        hop = 0
        while True:
            occ = self._occ.get(lane_id)
            if occ is not None:
                keys, items = occ
                i = bisect_left(keys, s)
                while i < len(items) and items[i].ident == ident:
                    i += 1
                if i < len(items):
                    return dist + items[i].s - s, items[i]
            lane = lanes[lane_id]
            dist += lane.length_m - s
            if dist > LOOKAHEAD_M:
                return None, None
            if hop < len(path) and path[hop] is not None:
                lane_id = path[hop]
            elif lane.successors:
                lane_id = lane.successors[0]
            else:
                return None, None
            hop += 1
            s = 0.0

    def _behind(self, lane_id, s, ident):
        """Return (centre distance, occupant) of the nearest occupant behind, or (None, None)."""
        lanes, preds = self.graph.lanes, self.graph.predecessors
        dist = 0.0
        while True:
            occ = self._occ.get(lane_id)
            if occ is not None:
                keys, items = occ
                i = bisect_left(keys, s) - 1
                while i >= 0 and items[i].ident == ident:
                    i -= 1
                if i >= 0:
                    return dist + s - items[i].s, items[i]
            dist += s
            if dist > LOOKBACK_M or not preds[lane_id]:
                return None, None
            lane_id = preds[lane_id][0]
            s = lanes[lane_id].length_m + 1e-9

    def _leader(self, v, lane_id, s):
        """Return (bumper gap, occupant) of ``v``'s leader on ``lane_id`` from ``s``."""
        dist, leader = self._ahead(lane_id, s, v.index, (v.next_lane,) if lane_id == v.lane
                                   else ())
        if leader is None:
            return None, None
        return dist - leader.half - 0.5 * v.length_m, leader

    def _acc(self, v0, speed, gap, leader):
        if leader is None:
            return self._follow(speed, v0, None, 0.0)
        return self._follow(speed, v0, gap, leader.speed)

    def _gap_kept(self, speed):
        """Return the car-following model's least gap [m] at ``speed`` (IDM: s0 + v T)."""
        return self._min_gap(self._following_params, speed)

    def step(self, dt_s):
        """Advance every traffic vehicle by ``dt_s`` [s]."""
        if not (math.isfinite(dt_s) and dt_s > 0.0):
            raise ValueError(f'dt_s = {dt_s!r}: must be finite and > 0')
        self._occupancy()
        self._accelerations()
        if self.rules is not None:
            self.rules.apply(dt_s)
        vehicles = self.vehicles
        period = max(1, int(round(self.spec.lane_change_period_s / dt_s)))
        for v in vehicles:
            if v.scripted is not None and self.time_s >= v.scripted[1] - 1e-9 and v.active \
                    and not v.stopped and v.from_lane is None:
                self._scripted_change(v)
        for v in vehicles:
            if v.active and not v.stopped and v.from_lane is None and not v.keep_lane and \
                    (self.steps + v.index) % period == 0:
                self._consider_change(v)
        duration = self.spec.lane_change_duration_s
        lanes = self.graph.lanes
        waiting = False
        for v in vehicles:
            if not v.active or v.stopped:
                waiting = waiting or not v.active
                continue
            s_old, speed, acc = v.s_m, v.speed_mps, v.acc_mps2
            new_speed = speed + acc * dt_s
            if new_speed >= 0.0:          # core/traffic/idm.advance, inline (the hot loop)
                v.s_m, v.speed_mps = s_old + (speed + 0.5 * acc * dt_s) * dt_s, new_speed
            else:
                v.s_m, v.speed_mps = advance(s_old, speed, acc, dt_s)
            if v.from_lane is not None:
                v.from_s_m += v.s_m - s_old
                v.change_s += dt_s
                if v.change_s >= duration:
                    v.from_lane, v.offset_m = None, 0.0
                else:
                    v.offset_m = v.change_from_m * (1.0 - _smoothstep(v.change_s / duration))
            if v.s_m > lanes[v.lane].length_m:
                self._pass_lane_end(v)
                waiting = waiting or not v.active
        if waiting:
            self._reenter()
        self.steps += 1
        self.time_s += dt_s

    def _accelerations(self):
        """Set every moving vehicle's acceleration (one pass over each lane's occupants)."""
        vehicles, lanes = self.vehicles, self.graph.lanes
        follow = self._follow
        for v in vehicles:
            v.acc_mps2 = math.inf
        for lane_id, (_, items) in self._occ.items():
            count = len(items)
            lane = lanes[lane_id]
            for i, o in enumerate(items):
                ident = o.ident
                if ident < 0:
                    continue
                v = vehicles[ident]
                if v.stopped:
                    continue
                j = i + 1
                while j < count and items[j].ident == ident:
                    j += 1
                if j < count:
                    leader = items[j]
                    dist = leader.s - o.s
                else:
                    path = (v.next_lane,) if lane_id == v.lane else ()
                    nxt = path[0] if path and path[0] is not None else (
                        lane.successors[0] if lane.successors else None)
                    if nxt is None or lane.length_m - o.s > LOOKAHEAD_M:
                        leader = None
                    else:
                        dist, leader = self._ahead(nxt, 0.0, ident, ())
                        if leader is not None:
                            dist += lane.length_m - o.s
                if leader is None:
                    acc = follow(o.speed, o.v0, None, 0.0)
                else:
                    acc = follow(o.speed, o.v0, dist - leader.half - o.half, leader.speed)
                if acc < v.acc_mps2:
                    v.acc_mps2 = acc

    def _pass_lane_end(self, v):
        lanes = self.graph.lanes
        while v.s_m > lanes[v.lane].length_m:
            if v.next_lane is None:
                v.active, v.from_lane, v.offset_m = False, None, 0.0
                return
            v.s_m -= lanes[v.lane].length_m
            v.prev_lane, v.lane = v.lane, v.next_lane
            v.next_lane = self._choose_next(v)

    def _reenter(self):
        for v in self.vehicles:
            if v.active:
                continue
            order = list(self._entries)
            self.rng.shuffle(order)
            for lane_id in order:
                s = 0.5 * v.length_m
                dist, leader = self._ahead(lane_id, 0.0, v.index, ())
                _, behind = self._behind(lane_id, s, v.index)
                if behind is not None and behind.s + behind.half > 0.0:
                    continue
                gap = None if leader is None else dist - leader.half - v.length_m
                if gap is not None and gap < self._gap_kept(0.0) + ENTRY_MARGIN_M:
                    continue
                v.lane, v.s_m, v.active, v.prev_lane = lane_id, s, True, None
                v.next_lane = self._choose_next(v)
                v.speed_mps = self._start_speed(v, gap, leader)
                self._add(lane_id, _Occupant(s, v.speed_mps, 0.5 * v.length_m, v.index,
                                             self._v0(v)))
                break

    # ------------------------------------------------------------------ lane changes
    def _consider_change(self, v):
        lane = self.graph.lanes[v.lane]
        reach = v.s_m + v.speed_mps * self.spec.lane_change_duration_s + v.length_m
        if reach > lane.length_m:
            return
        best, best_gain = None, None
        for target, allowed, side in ((lane.left_lane, lane.left_change, 1.0),
                                      (lane.right_lane, lane.right_change, -1.0)):
            if not allowed or (self.rules is not None and
                               not self.rules.change_allowed(v, target, reach)):
                continue
            gain = self._change_gain(v, lane, target, reach)
            if gain is not None and (best_gain is None or gain > best_gain):
                best, best_gain = (target, side), gain
        if best is None:
            return
        self._start_change(v, lane, *best)

    def _scripted_change(self, v):
        """Start a placed vehicle's scripted change once its lane allows it (no MOBIL)."""
        lane = self.graph.lanes[v.lane]
        side = v.scripted[0]
        target, allowed = ((lane.left_lane, lane.left_change) if side == 'left' else
                           (lane.right_lane, lane.right_change))
        reach = v.s_m + v.speed_mps * self.spec.lane_change_duration_s + v.length_m
        if not allowed or reach > lane.length_m or \
                reach * self.graph.lanes[target].length_m / lane.length_m > \
                self.graph.lanes[target].length_m:
            return                      # not here: on a later lane
        v.scripted = None
        self._start_change(v, lane, target, 1.0 if side == 'left' else -1.0)

    def _start_change(self, v, lane, target, side):
        """Move ``v`` onto lane ``target`` (``side``: +1 left, -1 right), offset where it was."""
        other = self.graph.lanes[target]
        s_new = v.s_m * other.length_m / lane.length_m
        v.from_lane, v.from_s_m = v.lane, v.s_m
        v.lane, v.s_m = target, s_new
        # the lateral distance between the centrelines: half of each width
        k = lane.segment_at(v.from_s_m)
        k2 = other.segment_at(s_new)
        dist = 0.5 * (lane.width_at(k, v.from_s_m - lane.s0[k])
                      + other.width_at(k2, s_new - other.s0[k2]))
        v.change_from_m = -side * dist
        v.offset_m, v.change_s = v.change_from_m, 0.0
        v.next_lane = self._choose_next(v)
        self._add(target, _Occupant(s_new, v.speed_mps, 0.5 * v.length_m, v.index, self._v0(v)))
        self.lane_changes += 1

    def _change_gain(self, v, lane, target_id, reach):
        """Return the own gain of a change to ``target_id`` when the model makes it, else None."""
        target = self.graph.lanes[target_id]
        if reach * target.length_m / lane.length_m > target.length_m:
            return None
        half = 0.5 * v.length_m
        s_new = v.s_m * target.length_m / lane.length_m
        v0 = self._v0(v)
        gap, leader = self._leader(v, v.lane, v.s_m)
        own_now = self._acc(v0, v.speed_mps, gap, leader)
        dist_lead, new_leader = self._ahead(target_id, s_new, v.index, ())
        new_gap = None if new_leader is None else dist_lead - new_leader.half - half
        own_after = self._acc(target.speed_limit_mps * v.factor, v.speed_mps, new_gap,
                              new_leader)
        dist_back, follower = self._behind(target_id, s_new, v.index)
        nf_now = nf_after = None
        if follower is not None:
            back_gap = dist_back - follower.half - half
            if follower.ident < 0 and back_gap < self._gap_kept(follower.speed):
                return None                   # never cut in front of one of ours
            nf_gap = None if new_leader is None else dist_back + dist_lead - new_leader.half \
                - follower.half
            nf_now = self._acc(follower.v0, follower.speed, nf_gap, new_leader)
            nf_after = self._follow(follower.speed, follower.v0, back_gap, v.speed_mps)
        if new_leader is not None and new_leader.ident < 0 and new_gap < self._gap_kept(0.0):
            return None
        dist_old, old_follower = self._behind(v.lane, v.s_m, v.index)
        of_now = of_after = None
        if old_follower is not None:
            of_now = self._follow(old_follower.speed, old_follower.v0,
                                  dist_old - old_follower.half - half, v.speed_mps)
            of_gap = None if leader is None else dist_old + gap + half - old_follower.half
            of_after = self._acc(old_follower.v0, old_follower.speed, of_gap, leader)
        acc = LaneChangeAccelerations(own_now, own_after, nf_now, nf_after, of_now, of_after)
        if not self._should_change(acc):
            return None
        return acc.own_after - acc.own_now

    # ------------------------------------------------------------------ reading
    def active_vehicles(self) -> List[TrafficVehicle]:
        """Return the vehicles on the map (not waiting to re-enter)."""
        return [v for v in self.vehicles if v.active]

    def desired_speeds(self) -> List[Optional[float]]:
        """Each vehicle's desired speed [m/s] (None while off the map)."""
        return [self._v0(v) if v.active else None for v in self.vehicles]
