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
Where the traffic vehicles start.

First the placed ones (checked against the lane map: lane, s, route, overlaps), then the random
ones on places ``spacing`` apart on the spawn lanes (core/traffic/params.py), drawn
without replacement, away from the placed vehicles and ours.

Away from ours twice over: along the lane one of ours is on (no place within half the spacing
of its footprint, as between two traffic vehicles), and on the ground: no vehicle starts within
CLEARANCE_M of the footprint of one of ours, whatever lane it is on (a neighbouring lane our
vehicle reaches into, a lane crossing it, one of ours off every lane).
"""

import math
from typing import List

import numpy as np

from vehicle_sim.core.geometry.footprint import clearance, polygon_footprint
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.traffic.vehicles import TrafficVehicle

# the least distance between a traffic vehicle's footprint and one of ours at the start [m]
CLEARANCE_M = 1.0


def spawn_vehicles(graph, spec, dims, ours, rng, driven=None,
                   rules=None) -> List[TrafficVehicle]:
    """
    Return the traffic vehicles at their start: the placed ones, then the random ones.

    A vehicle whose start speed is to be the safe one behind its leader has speed -1 (the
    manager sets it once every vehicle is in).

    :param graph: the LaneGraph.
    :param spec: the TrafficSpec.
    :param dims: {model: (length, width)} [m].
    :param ours: our vehicles (OurVehicle): no vehicle is spawned on them.
    :param rng: the manager's random.Random (consumed: places, models, speed factors).
    :param driven: ids of the lanes traffic drives (the default spawn lanes; a spawn lane not
        among them is refused); None = every lane.
    :param rules: the manager's TrafficRules (no random vehicle starts in a conflict zone or
        where a fork's branches overlap: ``TrafficRules.keep_clear``), or None.
    :raises InvalidParameterError: see TrafficManager.
    """
    src = spec.source
    lanes = graph.lanes
    vehicles = []
    taken = {}                            # lane -> [(s, half)] of placed vehicles and ours
    for o in ours:
        pos = graph.locate(o.x_m, o.y_m, o.yaw_rad)
        if pos is not None:
            taken.setdefault(pos.lane_id, []).append((pos.s_m, 0.5 * o.length_m))
    for p in spec.placed:
        lane = lanes.get(p.lanelet)
        if lane is None:
            raise InvalidParameterError(f"{p.where}: field 'lanelet' = {p.lanelet}: lane "
                                        f'{p.lanelet} is not in the map ({graph.source})')
        if not p.s_m <= lane.length_m:
            raise InvalidParameterError(f"{p.where}: field 's' = {p.s_m:g}: not on lane "
                                        f'{p.lanelet} (0 .. {lane.length_m:.3f} m)')
        previous = p.lanelet
        for step in p.route:
            if step not in lanes:
                raise InvalidParameterError(f"{p.where}: field 'route': lane {step} is not "
                                            f'in the map ({graph.source})')
            if step not in lanes[previous].successors:
                raise InvalidParameterError(
                    f"{p.where}: field 'route': lane {step} does not follow lane "
                    f'{previous} (its successors: {list(lanes[previous].successors)})')
            previous = step
        length, width = dims[p.model]
        for s, half in taken.get(p.lanelet, ()):
            if abs(s - p.s_m) < half + 0.5 * length:
                raise InvalidParameterError(f"{p.where}: field 's' = {p.s_m:g}: overlaps "
                                            f'another vehicle on lane {p.lanelet}')
        near = _near_ours(graph.pose_at(p.lanelet, p.s_m), length, width, ours)
        if near is not None:
            raise InvalidParameterError(f"{p.where}: field 's' = {p.s_m:g}: within "
                                        f'{CLEARANCE_M:g} m of {near!r} on lane {p.lanelet}')
        taken.setdefault(p.lanelet, []).append((p.s_m, 0.5 * length))
        v = TrafficVehicle(len(vehicles), p.model, length, width, p.speed_factor,
                           p.lanelet, p.s_m, p.route)
        v.speed_mps = -1.0 if p.speed_mps is None else p.speed_mps
        if p.change_lane != 'none':
            v.scripted, v.keep_lane = (p.change_lane, p.change_at_s), True
        vehicles.append(v)
    driven = set(lanes) if driven is None else driven
    spawn = spec.spawn_lanes if spec.spawn_lanes is not None else sorted(driven)
    for lane_id in spawn:
        if lane_id not in lanes:
            raise InvalidParameterError(f"{src}: spawn: field 'lanes': lane {lane_id} is not "
                                        f'in the map ({graph.source})')
        if lane_id not in driven:
            raise InvalidParameterError(
                f"{src}: spawn: field 'lanes': lane {lane_id} is a "
                f"{getattr(lanes[lane_id], 'subtype', 'road')!r} lane: traffic drives road "
                'and highway lanes only')
    size = (max(dims[m][0] for m in spec.models), max(dims[m][1] for m in spec.models))
    slots, length_km = _slots(spec, spawn, graph, taken, size, ours, rules)
    count = spec.vehicles if spec.density_per_km is None else int(
        round(spec.density_per_km * length_km))
    if count > len(slots):
        what = (f"field 'vehicles' = {count}" if spec.density_per_km is None else
                f"field 'density' = {spec.density_per_km:g} ({count} vehicles)")
        raise InvalidParameterError(
            f'{src}: {what}: more than fit: {len(slots)} places on the spawn lanes at '
            f'spacing {spec.spawn_spacing_m:g} m ({length_km:.3f} lane-km)')
    for slot in sorted(rng.sample(range(len(slots)), count)):
        lane_id, s = slots[slot]
        model = spec.models[rng.randrange(len(spec.models))]
        length, width = dims[model]
        mean, std = spec.speed_factor_mean, spec.speed_factor_std
        factor = min(max(rng.gauss(mean, std), mean - 2.0 * std), mean + 2.0 * std)
        v = TrafficVehicle(len(vehicles), model, length, width, factor, lane_id, s, ())
        v.speed_mps = -1.0
        vehicles.append(v)
    return vehicles

def _corners(x, y, yaw, length, width):
    c, s = math.cos(yaw), math.sin(yaw)
    return [(x + c * u - s * v, y + s * u + c * v)
            for u, v in ((-0.5 * length, -0.5 * width), (0.5 * length, -0.5 * width),
                         (0.5 * length, 0.5 * width), (-0.5 * length, 0.5 * width))]


def _near_ours(pose, length, width, ours):
    """Return the name of one of ours within CLEARANCE_M of a vehicle at ``pose``, or None."""
    x, y, yaw = pose
    reach = 0.5 * math.hypot(length, width) + CLEARANCE_M
    box = None
    for o in ours:
        if math.hypot(o.x_m - x, o.y_m - y) > reach + 0.5 * math.hypot(o.length_m, o.width_m):
            continue
        if box is None:
            box = _corners(x, y, yaw, length, width)
        footprint = polygon_footprint(o.name, _corners(o.x_m, o.y_m, o.yaw_rad, o.length_m,
                                                       o.width_m))
        if clearance(box, footprint)[0] < CLEARANCE_M:
            return o.name
    return None


def _centres(lane, places):
    """Return the centreline points (x, y arrays) at arc lengths ``places`` of a lane."""
    along = np.append(lane.s0, lane.length_m)
    return np.interp(places, along, lane.xs), np.interp(places, along, lane.ys)


def _slots(spec, spawn, graph, taken, size, ours, rules=None):
    # (the places free of the placed vehicles and ours, the spawn lanes' length [km]); a place
    # is free of ours for the longest and widest model
    lanes = graph.lanes
    spacing = spec.spawn_spacing_m
    reach = 0.5 * math.hypot(*size) + CLEARANCE_M
    slots, length_m = [], 0.0
    for lane_id in spawn:
        lane = lanes[lane_id]
        lo, hi = (0.0, lane.length_m) if spec.spawn_s_range_m is None else (
            spec.spawn_s_range_m[0], min(spec.spawn_s_range_m[1], lane.length_m))
        if hi <= lo:
            continue
        length_m += hi - lo
        places = []
        s = lo + 0.5 * spacing
        clear = () if rules is None else rules.keep_clear(lane_id, 0.5 * size[0])
        while s <= hi - 0.5 * spacing + 1e-9:
            if all(abs(s - t) >= 0.5 * spacing + half for t, half in taken.get(lane_id, ())) \
                    and not any(a < s < b for a, b in clear):
                places.append(s)
            s += spacing
        # the exact test only for the places whose centre is near one of ours
        near = np.zeros(len(places), dtype=bool)
        if ours and places:
            xs, ys = _centres(lane, places)
            for o in ours:
                near |= np.hypot(xs - o.x_m, ys - o.y_m) <= \
                    reach + 0.5 * math.hypot(o.length_m, o.width_m)
        slots.extend((lane_id, s) for s, close in zip(places, near) if not close or _near_ours(
            graph.pose_at(lane_id, s), *size, ours) is None)
    return slots, length_m / 1000.0
