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
The SUMO engine's pool of bodies (physics/sumo_traffic.py): one body per SUMO vehicle or person.

A body, named ``sumo_<k>``, serves one SUMO vehicle or person from its departure to its arrival,
is parked under the ground after, and serves the next one of the same size and shape (its
class's, core/traffic/objects.py CLASS_SHAPES: a person an upright cylinder); the order of SUMO's
departures decides, so a seed gives the same names. :class:`SumoPool` takes, parks, places
(two persons SUMO has closer than their width moved apart: :meth:`SumoPool._apart`), moves
(straight on between SUMO's steps) and stops them; SumoBodies is one. A serving body's
label (``World.labels``) is its class's, its instance id that of the SUMO vehicle or person it
serves (:func:`instance_name`: one id per SUMO id for the world's life); a parked one has none.
"""

import bisect
import math

import pybullet

from vehicle_sim.core.geometry.discs import separate_discs
from vehicle_sim.core.sensors.labels import label_of_class, LABELS
from vehicle_sim.core.traffic.objects import CLASS_SHAPES, shape_extents
from vehicle_sim.core.traffic.sumo_params import object_class
from vehicle_sim.core.world.params import ObstacleSpec
from vehicle_sim.physics.traffic_boxes import COLOURS, GROUND_CLEARANCE_M, PARK_DEPTH_M

NAME_PREFIX = 'sumo_'            # the bodies' names: this + the pool index
PERSON_COLOUR = (0.95, 0.55, 0.15, 1.0)
# a vehicle's front further than its speed times the step plus this from its last point has
# jumped (SUMO's teleport): its trail starts again there
JUMP_M = 3.0
TRAIL_STEP_M = 0.01              # the front's points along its trail are this far apart at least
TRAIL_POINTS = 200               # a trail no box was worked out on drops its old points past this

__all__ = ['extend_trail', 'follow_trail', 'instance_name', 'JUMP_M', 'NAME_PREFIX', 'SumoPool',
           'SumoSlot', 'trail_pose']


def instance_name(person, sumo_id) -> str:
    """Return the name a SUMO vehicle's or person's instance id is handed out for."""
    return f"sumo {'person' if person else 'vehicle'} {sumo_id}"


def _back_along(trail, x, y, s, yaw, distance):
    """
    Return (point, index) ``distance`` back along the trail from its front (x, y) [m].

    ``s`` is the front's arc length on the trail's scale (its points' third values); the
    point lies on the segment from ``trail[index]`` forwards (found by bisection on the arc
    lengths); past the oldest point it goes on straight back along ``yaw``.
    """
    target = s - distance
    last = len(trail) - 1
    if trail[last][2] <= target:
        qx, qy, qs = trail[last]
        f = (s - target) / (s - qs) if s > qs else 0.0
        return (x + (qx - x) * f, y + (qy - y) * f), last
    index = bisect.bisect_right(trail, target, key=_arc) - 1
    if index < 0:
        qx, qy, qs = trail[0]
        need = qs - target
        return (qx - need * math.cos(yaw), qy - need * math.sin(yaw)), 0
    (qx, qy, qs), (px, py, ps) = trail[index], trail[index + 1]
    f = (ps - target) / (ps - qs)
    return (px + (qx - px) * f, py + (qy - py) * f), index


def _arc(point):
    return point[2]


def follow_trail(trail, x, y, yaw, length, jump_m):
    """
    Return (centre x, y, yaw) of a vehicle's rigid box whose front is at (x, y) [m].

    SUMO bends a vehicle along the path its front took; the box's axis is the straight line
    nearest that path between its rear (a length behind the front) and its front: along the
    chord from the rear to the front, halfway between the chord and the path's midpoint (half
    a length behind the front), so that on an arc the path strays at most half its sagitta
    (length^2 / 8R) to either side of it. A box behind the front along its heading would swing
    its rear out of the lane on a turn (by about length^2 / 2R), over the walking area's corner
    on a right turn; one centred on the path's midpoint bulges out by the whole sagitta at its
    ends, and on a U-turn inside a junction (SUMO turns a car round on a radius of 1.6 m) its
    end reaches over the corner's walking area. Where the path is shorter than the vehicle (it
    has just departed) the rest goes straight back along ``yaw`` from the path's oldest point.

    :func:`extend_trail` then :func:`trail_pose`: the engine extends each vehicle's trail at
    every SUMO step and works its box out only when something reads it, with the same result.

    :param trail: the front's earlier points [(x, y, arc length)], oldest first: (x, y) is
        added, and the points behind the rear's are dropped; the arc lengths let the points
        a half and a whole length back be found by bisection (a vehicle creeping in a queue
        leaves many points).
    :param jump_m: a front further than this from the trail's last point jumped (a teleport):
        the trail starts again.
    """
    extend_trail(trail, x, y, jump_m, length)
    return trail_pose(trail, x, y, yaw, length)


def extend_trail(trail, x, y, jump_m, length):
    """
    Add a vehicle's front (x, y) [m] to its trail (:func:`follow_trail`): a point 1 cm on.

    A front further than ``jump_m`` from the last point starts the trail again; a long trail
    drops its points more than ``length`` behind the front (those a box never needs again).
    """
    if trail:
        lx, ly, ls = trail[-1]
        d = math.hypot(x - lx, y - ly)
        if d > jump_m:
            trail.clear()
            trail.append((x, y, 0.0))
        elif d >= TRAIL_STEP_M:
            trail.append((x, y, ls + d))
            if len(trail) > TRAIL_POINTS:
                _, index = _back_along(trail, x, y, ls + d, 0.0, length)
                del trail[:index]
    else:
        trail.append((x, y, 0.0))


def trail_pose(trail, x, y, yaw, length):
    """
    Return (centre x, y, yaw) of the box whose front (x, y) [m] is at the trail's end.

    The front is the last one :func:`extend_trail` was given (the arc length to it from the
    last point: less than TRAIL_STEP_M); the points behind the rear's are dropped.
    """
    lx, ly, ls = trail[-1]
    s = ls + math.hypot(x - lx, y - ly)
    (mx, my), _ = _back_along(trail, x, y, s, yaw, 0.5 * length)
    (bx, by), index = _back_along(trail, x, y, s, yaw, length)
    del trail[:index]
    return (0.5 * mx + 0.25 * (x + bx), 0.5 * my + 0.25 * (y + by),
            math.atan2(y - by, x - bx))


class SumoSlot:
    """One body of the pool: its name, body id, box size, colour and whom it serves now."""

    __slots__ = ('index', 'name', 'body_id', 'size', 'radius', 'clearance', 'colour', 'key',
                 'sumo_id', 'person', 'vclass', 'state', 'motion', 'stopped', 'lane', 'route',
                 'trail', 'instance', 'front', 'speed', 'at', 'synced', 'placed')

    def __init__(self, index, body_id, size, clearance, colour, key, radius=0.0):
        self.index = index
        self.name = f'{NAME_PREFIX}{index}'
        self.body_id = body_id
        self.size = size                   # (length, width, height) [m] of the SUMO type
        self.radius = radius               # a person's cylinder's radius [m] (0: a box)
        self.clearance = clearance         # the box's underside above the ground [m]
        self.colour = colour
        self.key = key                     # the pool it returns to
        self.sumo_id = None                # whom it serves (None: parked)
        self.person = False
        self.vclass = 'passenger'
        self.state = None                  # (x, y, yaw, speed) of the footprint centre at the
        #                                    update (None: not worked out yet, SumoPool._state)
        self.motion = None                 # (x, y, z, qz, qw, vx, vy) at the update (when
        #                                    ``placed`` is the pool's update: SumoPool._motion)
        self.stopped = False               # touched one of ours: stopped for good
        self.lane = None                   # (SUMO lane id, lane position [m], route index)
        self.route = ()                    # its route's SUMO edges (at its departure)
        self.trail = []                    # its front's earlier points (follow_trail)
        self.instance = 0                  # the instance id of whom it serves (0: parked)
        self.front = None                  # SUMO's (x, y, angle) of its front at the update
        #                                    (None: parked, or not read from SUMO yet)
        self.speed = 0.0                   # SUMO's speed at the update [m/s]
        self.at = None                     # (x, y) where its body stands now (None: parked)
        self.synced = -1                   # the world step it was put where it is (-1: not
        #                                    since SUMO's last step)
        self.placed = -1                   # the update its ``motion`` is of

    @property
    def z(self):
        return 0.5 * (self.size[2] + self.clearance)



class SumoPool:
    """
    The pool's part of SumoBodies: its bodies taken, parked, placed, moved and stopped.

    Uses SumoBodies' ``world``, ``session``, ``_cid``, ``_slots``, ``_by_id``, ``_free``,
    ``_table``, ``_types``, ``heights``, ``_updates`` and ``_placed_at``.

    A vehicle's box is worked out on its trail (:func:`trail_pose`) when something needs it
    (:meth:`_state`, :meth:`_motion`), not at every SUMO step: a lidar in a city reads a tenth
    of the bodies.
    """

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
            body_id = self.world.add_obstacle(spec, placed=True, label=('obstacle', 0))
            slot = SumoSlot(index, body_id, size, clearance, colour, key,
                            radius=spec.radius_m if spec.shape == 'cylinder' else 0.0)
            self._slots.append(slot)
        slot.sumo_id, slot.person, slot.vclass, slot.stopped = sumo_id, person, vclass, False
        slot.trail, slot.front, slot.placed = [], None, -1
        labels = self.world.labels
        slot.instance = labels.instance(instance_name(person, sumo_id))
        labels.set(slot.body_id, LABELS[label_of_class(found_class)].name, slot.instance)
        self._by_id[(person, sumo_id)] = slot
        return slot

    def _park(self, slot):
        slot.sumo_id, slot.state, slot.motion, slot.stopped = None, None, None, False
        slot.lane, slot.route, slot.instance, slot.at, slot.synced = None, (), 0, None, -1
        slot.placed, slot.front = -1, None
        self.world.labels.forget(slot.body_id)
        self._table.invalidate()
        pybullet.resetBasePositionAndOrientation(
            slot.body_id, (0.0, 0.0, PARK_DEPTH_M - 10.0 * slot.index), (0.0, 0.0, 0.0, 1.0),
            physicsClientId=self._cid)

    def _place(self):
        """
        Take SUMO's new positions (an update): each body is put there when something reads it.

        Nothing is moved here: :meth:`_move` puts a body where its vehicle is now (straight on
        since the update) when it is near one of ours (each step), when rays pass near it, or
        before any other reading of the world.
        """
        self._updates += 1
        for slot in self._by_id.values():
            slot.synced = -1
        self._placed_at = self.world.time_s
        self._synced_step = -1
        self._table.invalidate()

    def _apart(self, slots):
        """
        Move persons' bodies apart where SUMO has them closer than their cylinders are wide.

        ``slots``: the persons read at this SUMO step (their ``state`` centres where SUMO has
        them), in SUMO's order. SUMO's pedestrian model (striping) keeps a person a length and
        a minGap (0.215 + 0.25 m) behind the next in line, short of the cylinder's 0.478 m, and
        puts two persons closer still now and then where its paths across a walking area meet:
        each overlapping pair is pushed apart, each by half its overlap
        (core/geometry/discs.py ``separate_discs``), so that no two persons' bodies overlap in
        the physics, there or going on straight until SUMO's next step (the pair pushed apart
        at its closest approach then). A person's heading and speed stay SUMO's.
        """
        centres = [slot.state[:2] for slot in slots]
        velocities = [(speed * math.cos(yaw), speed * math.sin(yaw))
                      for _, _, yaw, speed in (slot.state for slot in slots)]
        for slot, centre, apart in zip(slots, centres, separate_discs(
                centres, [slot.radius for slot in slots], velocities, self.spec.step_s)):
            if apart != centre:
                slot.state = (*apart, *slot.state[2:])

    def _state(self, slot):
        """Return a serving body's (x, y, yaw, speed) at the update (a vehicle's on its trail)."""
        state = slot.state
        if state is None:
            fx, fy, angle = slot.front
            state = slot.state = (*trail_pose(slot.trail, fx, fy, math.radians(90.0 - angle),
                                              slot.size[0]), slot.speed)
        return state

    def _motion(self, slot):
        """Return a serving body's (x, y, z, qz, qw, vx, vy) at the update."""
        if slot.placed != self._updates:
            x, y, yaw, speed = self._state(slot)
            half = 0.5 * yaw
            slot.motion = (x, y, slot.z, math.sin(half), math.cos(half), speed * math.cos(yaw),
                           speed * math.sin(yaw))
            slot.placed = self._updates
        return slot.motion

    def _move(self, slots):
        """Put the bodies of ``slots`` where their vehicles are now (straight on); say if any."""
        cid = self._cid
        reset_pose = pybullet.resetBasePositionAndOrientation
        count = self.world.step_count
        elapsed = self.world.time_s - self._placed_at
        moved = False
        for slot in slots:
            if slot.synced == count or slot.front is None:   # put, or not read from SUMO yet
                continue
            x, y, z, qz, qw, vx, vy = self._motion(slot)
            if vx or vy or slot.synced < 0:       # moving, or not put there since the update
                x, y = x + vx * elapsed, y + vy * elapsed
                reset_pose(slot.body_id, (x, y, z), (0.0, 0.0, qz, qw), physicsClientId=cid)
                slot.at = (x, y)
                moved = True
            slot.synced = count
        return moved

    def _reaching(self, region):
        """Return the serving bodies that stand, or are now, within ``region`` (a margin on)."""
        xmin, ymin, xmax, ymax = region
        count = self.world.step_count
        elapsed = self.world.time_s - self._placed_at
        found = []
        for slot in self._by_id.values():
            if slot.synced == count or slot.front is None:
                continue
            length, width, _ = slot.size
            reach = length + width                        # more than its half diagonal
            at = slot.at                                  # where it stands: moved off there
            if at is not None and xmin - reach <= at[0] <= xmax + reach and \
                    ymin - reach <= at[1] <= ymax + reach:
                found.append(slot)
                continue
            # its box now: within half its length of its front and its run since (a stopped
            # one's a little ahead of that): the box worked out only for those near
            fx, fy, _ = slot.front
            far = reach + length + abs(slot.speed) * elapsed
            if not (xmin - far <= fx <= xmax + far and ymin - far <= fy <= ymax + far):
                continue
            state = self._motion(slot)
            x, y = state[0] + state[5] * elapsed, state[1] + state[6] * elapsed
            if xmin - reach <= x <= xmax + reach and ymin - reach <= y <= ymax + reach:
                found.append(slot)
        return found

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
        x, y, z, qz, qw, vx, vy = self._motion(slot)
        x, y = x + vx * elapsed, y + vy * elapsed
        pybullet.resetBasePositionAndOrientation(slot.body_id, (x, y, z), (0.0, 0.0, qz, qw),
                                                 physicsClientId=self._cid)
        slot.motion = (x, y, z, qz, qw, 0.0, 0.0)
        slot.at, slot.synced, slot.placed = (x, y), self.world.step_count, self._updates
        _, _, yaw, _ = self._state(slot)
        slot.state, slot.speed = (x, y, yaw, 0.0), 0.0
        self.world.mark_moved()
