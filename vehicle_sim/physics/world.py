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
A PyBullet world: its own physics client, a ground plane, a fixed time step, explicit stepping.

``World.step()`` is the only thing that advances simulated time. Each basic step it calls every
registered body's ``pre_step()`` hook (bodies apply their commands there), then runs the physics
sub-steps. PyBullet clears applied joint torques (TORQUE_CONTROL and URDF joint damping) after
the first internal sub-step of ``stepSimulation``, so sub-steps are looped here, one
``stepSimulation`` per sub-step, and bodies re-apply their torques in ``pre_substep()``; see
docs/physics.md.

After the physics, with the time advanced, ``step()`` calls every ``post_step()`` hook: sensors
sample the new state there. The world also holds the obstacles (``add_obstacle``), names bodies
for collision reports (``body_name``) and gives ray sensors a mask that skips their own vehicle
(``ray_mask_excluding``).
"""

from contextlib import contextmanager
import math
import os
import tempfile

import pybullet

from vehicle_sim.core.specs.errors import InvalidPoseError
from vehicle_sim.core.specs.simulation import FRICTION, TIME_STEP_MS
from vehicle_sim.physics.body_labels import BodyLabels
from vehicle_sim.physics.pybullet_stdout import quiet_stdout
from vehicle_sim.physics.vehicle_body import VehicleBody

# How long the GUI's start waits for PyBullet's window notices ('ven = ...', twice) to silence
# them [s]; it returns as soon as they came (test_ros_gui_nodes checks stdout stays ours).
GUI_NOTICE_WAIT_S = 10.0
# The ground's friction and the basic step: the rows every entry point shares (core/specs).
DEFAULT_FRICTION = FRICTION.default
DEFAULT_TIME_STEP_S = TIME_STEP_MS.default / 1000.0
DEFAULT_SUBSTEPS = 1
GROUND_SIZE_M = 1000.0
# Constraint force mixing of every constraint row; a small value keeps the direct solver's
# matrix regular (redundant contact rows) without visible softness.
GLOBAL_CFM = 1.0e-6
# Bullet clamps every velocity coordinate of a multibody (each joint [rad/s or m/s] and the six
# base coordinates) to one per-body limit, 100 by default (btMultiBody m_maxCoordinateVelocity,
# PyBullet's maxJointVelocity): wheels then stopped at 100 rad/s, below the top speed of most
# presets (TeslaModel3: 139 rad/s at 180 km/h). Webots (ODE) has no such clamp. 1e4 is over ten
# times any speed a preset can reach: the top-speed wheel speeds (at most 176 rad/s) and the
# wheel speed at the rpm cut in the highest gear (at most 863 rad/s, RangeRoverSportSVR). It
# remains a guard against a numerical blow-up.
MAX_COORDINATE_VELOCITY = 1.0e4
GROUND_COLOR = (0.45, 0.45, 0.45, 1.0)
# Collision filter groups (Bullet): dynamic bodies are in group 1, static ones in group 2, and
# every body's mask accepts all groups. A body whose own rays must not see it gets a group bit of
# its own instead (same collisions: every mask accepts it); its rays use a mask without it.
_FIRST_RAY_GROUP_BIT = 4
# Where the bodies of a ray grid stand while Bullet casts rays (World.rays_past_grids) [m].
_AWAY_Z_M = -1.0e4
# A ray grid's body stays where it is when its bounding box is farther than this from the box
# of the rays [m] (Bullet's boxes hold a margin of their own).
_REACH_SLACK_M = 0.1
_LAST_RAY_GROUP_BIT = 30
ALL_GROUPS = -1
# A teleported body overlaps another when they interpenetrate by more than this [m] (touching,
# or the solver's contact slop, is not an overlap).
OVERLAP_TOLERANCE_M = 1.0e-3



def pose_from(position, clearance_m=0.0):
    """
    Turn a spawn position into a base pose.

    :param position: (x [m], y [m], yaw [rad]) with base_link on the ground, or the full
        (x, y, z [m], qx, qy, qz, qw) in the world frame.
    :param clearance_m: height of base_link above the ground for the (x, y, yaw) form [m].
    :return: (position, orientation quaternion) for PyBullet.
    """
    values = tuple(float(v) for v in position)
    if len(values) == 3:
        x, y, yaw = values
        return (x, y, clearance_m), (0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2))
    if len(values) == 7:
        return values[:3], values[3:]
    raise ValueError(f'position {position!r}: give (x, y, yaw) or (x, y, z, qx, qy, qz, qw)')


def _vehicle_body(registered):
    # A named vehicle body among the registered objects: a VehicleBody (CarBody, DiffRobotBody)
    # or what drives one (the SimulatedCar: ``drives_body``); None for hooks and sensors, which
    # keep the body they watch as ``body`` too (a collision monitor is no second vehicle).
    body = registered.body if getattr(registered, 'drives_body', False) else registered
    return body if isinstance(body, VehicleBody) and body.name else None


def point_velocity(com_pos, linear, angular, point):
    """
    Return the velocity of a point of a rigid body: v = v_com + w x (point - p_com).

    :return: ((vx, vy, vz) [m/s], (wx, wy, wz) [rad/s]) in the world frame.
    """
    rx, ry, rz = point[0] - com_pos[0], point[1] - com_pos[1], point[2] - com_pos[2]
    wx, wy, wz = angular
    return ((linear[0] + wy * rz - wz * ry, linear[1] + wz * rx - wx * rz,
             linear[2] + wx * ry - wy * rx), tuple(angular))

class World:
    """
    One simulation: a PyBullet client with a ground plane, stepped explicitly at a fixed dt.

    Several worlds may exist in one process (each has its own DIRECT client; at most one GUI).
    A GUI world raises ``GuiUnavailableError`` when no window can open (physics/gui.py) and
    ``GuiClosedError`` from ``step()`` once its window was closed.
    """

    def __init__(self, time_step_s=DEFAULT_TIME_STEP_S, substeps=None, gui=False,
                 friction=DEFAULT_FRICTION, gravity=9.81):
        """
        Create the world.

        :param time_step_s: basic time step [s] (Webots' basicTimeStep; 10 ms by default).
        :param substeps: physics sub-steps per basic step; None = DEFAULT_SUBSTEPS.
        :param gui: open PyBullet's GUI instead of a DIRECT client.
        :param friction: tyre-road friction coefficient of the ground [-].
        :param gravity: gravity [m/s^2], acting along -z.
        :raises ValueError: for a non-positive time step or sub-step count, or a friction the
            ``friction`` row refuses (core/specs/simulation.py).
        """
        substeps = DEFAULT_SUBSTEPS if substeps is None else substeps
        if not time_step_s > 0.0:
            raise ValueError(f'time_step_s = {time_step_s!r}: must be > 0')
        if int(substeps) != substeps or substeps < 1:
            raise ValueError(f'substeps = {substeps!r}: must be an integer >= 1')
        refusal = FRICTION.refusal(friction)
        if refusal:
            raise ValueError(refusal)
        self.time_step_s = float(time_step_s)
        self.substeps = int(substeps)
        self.substep_s = self.time_step_s / self.substeps
        self.friction = float(friction)
        self.gravity = float(gravity)
        self.gui = bool(gui)
        self.client_id = self._connect(self.gui)
        self._closed = False
        self._bodies = []
        self._pre_step = []
        self._pre_substep = []
        self._post_step = []
        self._before_query = []
        self._before_render = []
        self._names = {}              # body id -> name (obstacles)
        self.obstacles = {}           # obstacle name -> body id
        self._obstacle_specs = {}     # obstacle name -> its ObstacleSpec (reset_obstacles)
        self._static_names = set()    # names of static geometry (a map's walls): add_static
        self._blocked = []            # (name, blocked(x, y)) of static geometry: add_static
        # Static geometry that ray sensors find by other means than Bullet (a map's walls:
        # core/map/grid_rays.py's GridRays), each with a cast(origin, ends) -> fractions, and
        # the bodies it stands for (add_ray_grid).
        self.ray_grids = []
        self.ray_grid_bodies = []     # per ray grid: the body its hits read as (labels)
        self._ray_grid_bodies = []
        self._ray_masks = {}          # body id -> ray mask excluding that body
        self._renderer = None
        self.labels = BodyLabels()    # what each body is, for perception (body_labels.py)
        self._ground_visual = False
        self._broadphase_stale = True   # bodies added since the last step: rays miss them
        self.revision = 0             # bumped by every step and every body moved between steps
        self._contacts = None         # {body id: its contact points} while post-step hooks run
        self._step_count = 0
        self._rendering_pauses = 0    # rendering_paused blocks open (GUI)
        cid = self.client_id
        pybullet.setPhysicsEngineParameter(fixedTimeStep=self.substep_s, numSubSteps=0,
                                           deterministicOverlappingPairs=1,
                                           globalCFM=GLOBAL_CFM, physicsClientId=cid)
        # The direct (Dantzig) MLCP solver converges exactly where PGS leaves light wheels
        # sandwiched between a heavy chassis and the ground under-resolved (suspensions sagged
        # by up to 6 cm with 50 PGS iterations); it is also cheaper for a car-sized island.
        with quiet_stdout():   # the switch is announced with printf
            pybullet.setPhysicsEngineParameter(
                constraintSolverType=pybullet.CONSTRAINT_SOLVER_LCP_DANTZIG, physicsClientId=cid)
        pybullet.setGravity(0.0, 0.0, -self.gravity, physicsClientId=cid)
        plane = pybullet.createCollisionShape(pybullet.GEOM_PLANE, physicsClientId=cid)
        visual = self._ground_visual_shape() if gui else -1
        self.ground_id = pybullet.createMultiBody(0.0, plane, visual, physicsClientId=cid)
        self.labels.set(self.ground_id, 'ground')
        pybullet.changeDynamics(self.ground_id, -1, lateralFriction=self.friction,
                                restitution=0.0, physicsClientId=cid)
        self._step_simulation = pybullet.stepSimulation

    @staticmethod
    def _connect(gui):
        if not gui:
            client_id = pybullet.connect(pybullet.DIRECT)
            if client_id < 0:
                raise RuntimeError('PyBullet could not start a physics client')
            return client_id
        from vehicle_sim.physics.gui import (
            check_gui_available,
            display_held,
            GuiUnavailableError,
            screen_size,
            window_size,
        )
        with display_held():    # no X server reset between the check and PyBullet's connection
            check_gui_available()   # PyBullet would end the process without an X server
            width, height = window_size(screen_size())
            # The window's start-up notices come from its own thread: it makes two render
            # targets (Bullet's GLRenderToTexture), each printing 'ven = <GL vendor>', the first
            # before connect returns, the second 0.1-0.5 s later (some seconds on a cold GL
            # driver).
            with quiet_stdout(settle_on=b'ven = ', settle_count=2, max_wait_s=GUI_NOTICE_WAIT_S):
                client_id = pybullet.connect(pybullet.GUI,
                                             options=f'--width={width} --height={height}')
        if client_id < 0:
            raise GuiUnavailableError('PyBullet could not open its window: one is open in this '
                                      'process already (PyBullet allows one per process)')
        # The side panels render three synthetic camera images each frame: off until 'g'.
        pybullet.configureDebugVisualizer(pybullet.COV_ENABLE_GUI, 0, physicsClientId=client_id)
        return client_id

    @contextmanager
    def rendering_paused(self):
        """
        Build many bodies without the window drawing each one (PyBullet's COV_ENABLE_RENDERING).

        A GUI window redraws the scene as bodies are added, one by one: a world of 50 traffic
        boxes on 2 km of road took minutes to build under a software renderer. Its rendering is
        off inside the block and on again after it, also when the block raises; nested blocks
        turn it on at the outermost one's end. A DIRECT world does nothing.
        """
        if not self.gui:
            yield
            return
        cid = self.client_id
        self._rendering_pauses += 1
        if self._rendering_pauses == 1:
            pybullet.configureDebugVisualizer(pybullet.COV_ENABLE_RENDERING, 0,
                                              physicsClientId=cid)
        try:
            yield
        finally:
            self._rendering_pauses -= 1
            if not self._rendering_pauses and pybullet.isConnected(physicsClientId=cid):
                pybullet.configureDebugVisualizer(pybullet.COV_ENABLE_RENDERING, 1,
                                                  physicsClientId=cid)

    @property
    def time_s(self):
        """Simulated time [s]: basic steps taken times the time step."""
        return self._step_count * self.time_step_s

    @property
    def step_count(self):
        """Number of basic steps taken."""
        return self._step_count

    @property
    def bodies(self):
        """The registered bodies, in registration order."""
        return tuple(self._bodies)

    def vehicle_bodies(self):
        """Return the named vehicle bodies (CarBody, DiffRobotBody), in registration order."""
        return [v for v in map(_vehicle_body, self._bodies) if v is not None]

    def add_body(self, body):
        """
        Register a body so that ``step()`` calls its hooks.

        The body may define ``pre_step()`` (called once per basic step, before the physics),
        ``pre_substep()`` (called before every physics sub-step after the first),
        ``post_step()`` (called once per basic step after the physics, time already advanced)
        and ``before_query()`` (called by :meth:`sync_bodies` before anything reads the world
        between steps: rays, cameras, overlap checks, body states; bodies that are only placed
        now and then, as traffic, are put where they are now), ``before_query_in(region)``
        (with it, called instead when the reading is confined to a region, rays: only the
        bodies there need to be where they are), ``before_render()`` (called by
        :meth:`prepare_render` before an image is drawn: bodies that only images show, made
        on first need) and ``on_close()`` (called by :meth:`close`: what the body runs beside
        the world, e.g. SUMO, ends).
        """
        if body in self._bodies:
            return body
        vehicle = _vehicle_body(body)
        if vehicle is not None:
            inside = [name for name in self.overlaps(vehicle.body_id)
                      if name in self.obstacles or name in self._static_names]
            if inside:
                destroy = getattr(body, 'destroy', None)
                if destroy is not None:
                    destroy()
                raise InvalidPoseError(
                    f'vehicle {vehicle.name!r} starts inside obstacle '
                    f'{", ".join(repr(name) for name in inside)}: its '
                    'start pose must be clear of every obstacle (as set_pose requires)')
        self._bodies.append(body)
        self._rebuild_hooks()
        return body

    def remove(self, body):
        """Unregister a body and remove it from the physics (its ``destroy()`` if it has one)."""
        if body in self._bodies:
            self._bodies.remove(body)
            self._rebuild_hooks()
        destroy = getattr(body, 'destroy', None)
        if destroy is not None:
            destroy()

    def load_urdf(self, urdf, position, clearance_m=0.0, fixed_base=False):
        """
        Load a URDF string into this world (the only place bodies are loaded).

        Every body gets Bullet's velocity clamp raised to MAX_COORDINATE_VELOCITY.

        :param urdf: the URDF text (loadURDF needs a file: a temporary one is used).
        :param position: base pose, see :func:`pose_from`.
        :param clearance_m: spawn height of base_link for an (x, y, yaw) position [m].
        :param fixed_base: a base the physics does not move (a body placed each step).
        :return: (body id, {joint name: joint index}); joints are looked up by name only.
        """
        base_position, base_orientation = pose_from(position, clearance_m)
        with tempfile.TemporaryDirectory(prefix='vehicle_sim_') as folder:
            path = os.path.join(folder, 'body.urdf')
            with open(path, 'w', encoding='utf-8') as stream:
                stream.write(urdf)
            body_id = pybullet.loadURDF(
                path, base_position, base_orientation, useFixedBase=fixed_base,
                flags=pybullet.URDF_USE_INERTIA_FROM_FILE, physicsClientId=self.client_id)
        # One limit for the whole body, whatever the link index given (see the constant).
        pybullet.changeDynamics(body_id, -1, maxJointVelocity=MAX_COORDINATE_VELOCITY,
                                physicsClientId=self.client_id)
        joints = {}
        for index in range(pybullet.getNumJoints(body_id, physicsClientId=self.client_id)):
            info = pybullet.getJointInfo(body_id, index, physicsClientId=self.client_id)
            joints[info[1].decode()] = index
        self.mark_moved()
        return body_id, joints

    def reload_urdf(self, body_id, urdf, position, clearance_m=0.0, fixed_base=False):
        """
        Replace a body by a fresh load of its URDF: the body as built, whatever state it was in.

        A body that Bullet took out of the simulation (a bounding box that overflowed, e.g. after
        a pose far beyond the world) keeps falling through the ground after any reset of its
        pose and velocities; a new body does not. Its ray group (:meth:`ray_mask_excluding`)
        moves to the new body, so the masks its sensors hold stay right.

        :return: (new body id, {joint name: joint index}), as :meth:`load_urdf`.
        """
        cid = self.client_id
        mask = self._ray_masks.pop(body_id, None)
        pybullet.removeBody(body_id, physicsClientId=cid)
        new_id, joints = self.load_urdf(urdf, position, clearance_m, fixed_base)
        if mask is not None:
            for link in range(-1, pybullet.getNumJoints(new_id, physicsClientId=cid)):
                pybullet.setCollisionFilterGroupMask(new_id, link, ALL_GROUPS & ~mask,
                                                     ALL_GROUPS, physicsClientId=cid)
            self._ray_masks[new_id] = mask
        return new_id, joints

    def base_link_velocity(self, body_id, link_position):
        """
        Velocity of a body's base link origin in the world frame.

        PyBullet reports the base velocity at the centre of mass; v_link = v_com + w x (p_link -
        p_com).

        :param body_id: the body.
        :param link_position: (x, y, z) of the base link origin in the world [m].
        :return: ((vx, vy, vz) [m/s], (wx, wy, wz) [rad/s]).
        """
        cid = self.client_id
        com_pos, _ = pybullet.getBasePositionAndOrientation(body_id, physicsClientId=cid)
        linear, angular = pybullet.getBaseVelocity(body_id, physicsClientId=cid)
        return point_velocity(com_pos, linear, angular, link_position)

    # ---------------------------------------------------------------- obstacles and names
    def add_obstacle(self, spec, placed=False, label=None):
        """
        Place an obstacle (core ObstacleSpec): static when its mass is 0.

        :param placed: a static obstacle that its owner moves by placing it (traffic): a cheap
            Bullet rigid body (physics/obstacles.py).
        :param label: (label name, instance id) of its body (:attr:`labels`); None: an
            ``obstacle`` with the instance id of its name.
        :return: its body id.
        :raises ValueError: when an obstacle of that name exists already.
        :raises InvalidPoseError: when it would be inside a vehicle (nothing added).
        """
        from vehicle_sim.physics.obstacles import create_obstacle
        if spec.name in self.obstacles:
            raise ValueError(f'obstacle {spec.name!r} exists already')
        body_id = create_obstacle(self.client_id, spec, placed)
        vehicles = {v.body_id: v.name for v in self.vehicle_bodies()}
        inside = [vehicles[other] for other in self._overlapping(body_id) if other in vehicles]
        if inside:
            pybullet.removeBody(body_id, physicsClientId=self.client_id)
            raise InvalidPoseError(
                f'vehicle {", ".join(repr(n) for n in inside)} starts inside obstacle '
                f'{spec.name!r}: its start pose must be clear of every obstacle (as set_pose '
                'requires)')
        self.obstacles[spec.name] = body_id
        self._obstacle_specs[spec.name] = spec
        self.labels.set(body_id, *(label or ('obstacle', self.labels.instance(spec.name))))
        self._names[body_id] = spec.name
        self.mark_moved()
        return body_id

    def add_static(self, name, body_ids, blocked=None):
        """
        Name static bodies built elsewhere (a map's walls): collisions and rays see them.

        :param name: the name collision events and refusals give them ('map').
        :param body_ids: the bodies, already created in this world's client.
        :param blocked: ``blocked(x, y)`` -> True where a point of the ground is inside them
            (None: never). Hollow shapes (a triangle mesh's walls) need it: a body entirely
            inside one touches none of its faces, so its centre of mass is checked too.
        :raises InvalidPoseError: when a vehicle is inside one (the bodies are removed).
        """
        body_ids = list(body_ids)
        vehicles = {v.body_id: v.name for v in self.vehicle_bodies()}
        cid = self.client_id

        def inside_of(vehicle_id):
            if blocked is not None and blocked(*self._centre(vehicle_id)):
                return True
            return any(point[8] < -OVERLAP_TOLERANCE_M for body_id in body_ids
                       for point in pybullet.getClosestPoints(vehicle_id, body_id, 0.0,
                                                              physicsClientId=cid))
        inside = sorted(name_ for vehicle_id, name_ in vehicles.items() if inside_of(vehicle_id))
        if inside:
            for body_id in body_ids:
                pybullet.removeBody(body_id, physicsClientId=self.client_id)
            raise InvalidPoseError(
                f'vehicle {", ".join(repr(n) for n in inside)} starts inside {name!r}: '
                'its start pose must be clear of every wall (as set_pose requires)')
        for body_id in body_ids:
            self._names[body_id] = name
        self._static_names.add(name)
        if blocked is not None:
            self._blocked.append((name, blocked))
        self.mark_moved()

    def add_ray_grid(self, grid_rays, body_ids):
        """
        Let ray sensors find static bodies through ``grid_rays`` instead of Bullet.

        A map's walls (physics/map_layer.py): Bullet walks a static mesh's tree along the whole
        of each ray, past its first hit, so a large map's meshes cost rays dearly; the grid
        gives the same hits (physics/sensors/rays.py casts Bullet's rays only up to them, with
        the bodies out of the way: :meth:`rays_past_grids`).

        :param grid_rays: an object with ``cast(origin, ends)`` -> (n,) fractions (1.0: none)
            and ``cast_cut(origin, ends)`` -> (fractions, rays cut there, their box):
            core/map/grid_rays.py's GridRays.
        :param body_ids: the static bodies it stands for, at the origin unturned (their
            vertices in the world frame), already named with add_static.
        """
        self.ray_grids.append(grid_rays)
        self.ray_grid_bodies.append(body_ids[0] if len(body_ids) else -1)
        cid = self.client_id
        for body_id in body_ids:        # static: their boxes stay
            low, high = pybullet.getAABB(body_id, physicsClientId=cid)
            self._ray_grid_bodies.append(
                (body_id, tuple(v - _REACH_SLACK_M for v in low),
                 tuple(v + _REACH_SLACK_M for v in high)))

    @contextmanager
    def rays_past_grids(self, reach=None):
        """
        Within the block, the ray grids' bodies that rays reach stand 10 km below the world.

        PyBullet's ray mask drops a body's hits only after Bullet has walked its mesh's tree
        (measured: a 1080-ray batch costs the same with the map masked out), while a ray far
        from a body's box skips it at once. Moving a static body and back costs 3 to 10 us;
        contacts are untouched (the next step finds them where they were). A body whose box
        the rays do not reach stays: no ray can meet it, and Bullet skips it all the same.

        :param reach: ((x, y, z) lowest, (x, y, z) highest) [m]: a box that holds every ray,
            its start and end; None: every body moves.
        """
        cid = self.client_id
        if reach is None:
            moved = [body_id for body_id, _, _ in self._ray_grid_bodies]
        else:
            (x0, y0, z0), (x1, y1, z1) = reach
            moved = [body_id for body_id, low, high in self._ray_grid_bodies
                     if low[0] <= x1 and x0 <= high[0] and low[1] <= y1 and y0 <= high[1]
                     and low[2] <= z1 and z0 <= high[2]]
        try:
            for body_id in moved:
                pybullet.resetBasePositionAndOrientation(body_id, (0.0, 0.0, _AWAY_Z_M),
                                                         (0.0, 0.0, 0.0, 1.0),
                                                         physicsClientId=cid)
            yield
        finally:
            for body_id in moved:
                pybullet.resetBasePositionAndOrientation(body_id, (0.0, 0.0, 0.0),
                                                         (0.0, 0.0, 0.0, 1.0),
                                                         physicsClientId=cid)

    @contextmanager
    def rays_past_own(self, mask):
        """
        Within the block, the body that ``mask`` leaves out stands 10 km below the world.

        A sensor's rays start on or in its own vehicle (:meth:`ray_mask_excluding`), and Bullet
        tests each ray against every shape of a body whose box it crosses before the mask drops
        the hit: a car's compound of boxes and its wheels cost a 1080-ray batch some 2.5 ms of
        its 3 (benchmarks/bench_sumo.py, the empty world). The body goes back to the pose and
        velocities it had (its joints and contacts untouched): the physics goes on bit for bit
        as it would.

        With the GUI nothing moves (its window draws while the rays are cast: the car would
        flicker).

        :param mask: a mask from :meth:`ray_mask_excluding`, or another (nothing moves).
        """
        cid = self.client_id
        own = [] if self.gui else [body_id for body_id, own_mask in self._ray_masks.items()
                                   if own_mask == mask]
        # a reset of the base's pose zeroes its velocities: they go back with it
        states = [(pybullet.getBasePositionAndOrientation(body_id, physicsClientId=cid),
                   pybullet.getBaseVelocity(body_id, physicsClientId=cid)) for body_id in own]
        try:
            for body_id, ((_, orientation), _) in zip(own, states):
                pybullet.resetBasePositionAndOrientation(body_id, (0.0, 0.0, _AWAY_Z_M),
                                                         orientation, physicsClientId=cid)
            yield
        finally:
            for body_id, ((position, orientation), (linear, angular)) in zip(own, states):
                pybullet.resetBasePositionAndOrientation(body_id, position, orientation,
                                                         physicsClientId=cid)
                pybullet.resetBaseVelocity(body_id, linear, angular, physicsClientId=cid)

    def _centre(self, body_id):
        # (x, y) of a body's centre of mass.
        return pybullet.getBasePositionAndOrientation(body_id,
                                                      physicsClientId=self.client_id)[0][:2]

    def obstacle_spec(self, name):
        """Return the ObstacleSpec the obstacle ``name`` was added with (KeyError: none)."""
        return self._obstacle_specs[name]

    def reset_obstacles(self):
        """
        Put every movable obstacle (mass > 0) back at its initial pose, at rest.

        :return: the names of the obstacles put back, in the order they were added.
        """
        names = []
        for name, spec in self._obstacle_specs.items():
            if not spec.static:
                pose = spec.pose
                self._reset_base(self.obstacles[name], list(pose.xyz), list(pose.quaternion))
                names.append(name)
        return tuple(names)

    # ---------------------------------------------------------------- placing bodies
    def _reset_base(self, body_id, position, orientation):
        cid = self.client_id
        pybullet.resetBasePositionAndOrientation(body_id, position, orientation,
                                                 physicsClientId=cid)
        pybullet.resetBaseVelocity(body_id, [0.0, 0.0, 0.0], [0.0, 0.0, 0.0],
                                   physicsClientId=cid)
        self.mark_moved()

    def place_at_rest(self, body_id, link_to_com, position, clearance_m=0.0, zero_joints=(),
                      stop_joints=()):
        """
        Put a body's base link at a pose with every velocity 0 (reset and teleport).

        :param body_id: the body.
        :param link_to_com: (position, orientation) of the base's centre of mass in the base
            link frame (PyBullet's local inertial frame).
        :param position: base link pose, see :func:`pose_from`; the (x, y, yaw) form puts the
            base link ``clearance_m`` above the ground plane (z = 0), level.
        :param clearance_m: spawn height of the base link for the (x, y, yaw) form [m].
        :param zero_joints: joint indices set to position 0 (the URDF's rest position).
        :param stop_joints: joint indices that keep their position; their velocity becomes 0.
        """
        cid = self.client_id
        xyz, q = pose_from(position, clearance_m)
        com_xyz, com_q = pybullet.multiplyTransforms(xyz, q, *link_to_com)
        self._reset_base(body_id, com_xyz, com_q)
        for joint in zero_joints:
            pybullet.resetJointState(body_id, joint, 0.0, 0.0, physicsClientId=cid)
        for joint in stop_joints:
            angle = pybullet.getJointState(body_id, joint, physicsClientId=cid)[0]
            pybullet.resetJointState(body_id, joint, angle, 0.0, physicsClientId=cid)

    def body_state(self, body_id):
        """Return a body's pose, velocities and joint states, for :meth:`restore_body_state`."""
        self.sync_bodies()
        cid = self.client_id
        joints = range(pybullet.getNumJoints(body_id, physicsClientId=cid))
        return (pybullet.getBasePositionAndOrientation(body_id, physicsClientId=cid),
                pybullet.getBaseVelocity(body_id, physicsClientId=cid),
                [(joint, pybullet.getJointState(body_id, joint, physicsClientId=cid)[:2])
                 for joint in joints])

    def restore_body_state(self, body_id, state):
        """Put a body back in a state :meth:`body_state` returned."""
        cid = self.client_id
        (position, orientation), (linear, angular), joints = state
        pybullet.resetBasePositionAndOrientation(body_id, position, orientation,
                                                 physicsClientId=cid)
        pybullet.resetBaseVelocity(body_id, linear, angular, physicsClientId=cid)
        for joint, (angle, velocity) in joints:
            pybullet.resetJointState(body_id, joint, angle, velocity, physicsClientId=cid)
        self.mark_moved()

    def overlaps(self, body_id, tolerance_m=OVERLAP_TOLERANCE_M):
        """
        Return the names of the bodies (not the ground) that ``body_id`` interpenetrates now.

        :param tolerance_m: penetration depth below which touching bodies do not overlap [m].
        """
        return [self.body_name(other) for other in self._overlapping(body_id, tolerance_m)]

    def _overlapping(self, body_id, tolerance_m=OVERLAP_TOLERANCE_M):
        cid = self.client_id
        # only the placed bodies that may touch it need be where they are: those within its
        # bounding box (a body's every link)
        boxes = [pybullet.getAABB(body_id, link, physicsClientId=cid)
                 for link in range(-1, pybullet.getNumJoints(body_id, physicsClientId=cid))]
        self.sync_bodies((min(low[0] for low, _ in boxes), min(low[1] for low, _ in boxes),
                          max(high[0] for _, high in boxes), max(high[1] for _, high in boxes)))
        found = []
        for index in range(pybullet.getNumBodies(physicsClientId=cid)):
            other = pybullet.getBodyUniqueId(index, physicsClientId=cid)
            if other in (body_id, self.ground_id):
                continue
            points = pybullet.getClosestPoints(body_id, other, 0.0, physicsClientId=cid)
            if any(point[8] < -tolerance_m for point in points):
                found.append(other)
        return found

    def try_place(self, body_id, place):
        """
        Run ``place()`` (which moves ``body_id``), undoing it if the body then overlaps another.

        :raises InvalidPoseError: naming what the body would be inside; the body is back in its
            state before the call.
        """
        saved = self.body_state(body_id)
        place()
        blocking = self.overlaps(body_id)
        if self._blocked:
            centre = self._centre(body_id)
            blocking += [name for name, blocked in self._blocked
                         if blocked(*centre) and name not in blocking]
        if blocking:
            self.restore_body_state(body_id, saved)
            raise InvalidPoseError(f'that place is inside {", ".join(blocking)}')

    def update_collision_state(self, region=None):
        """
        Bring Bullet's collision structures up to date before a query between steps.

        Rays only see bodies whose bounding boxes the last step (or this call) computed; bodies
        added or moved since are refreshed here, once. Placed bodies are synced first
        (:meth:`sync_bodies`, within ``region`` when one is given).
        """
        self.sync_bodies(region)
        if self._broadphase_stale:
            pybullet.performCollisionDetection(physicsClientId=self.client_id)
            self._broadphase_stale = False

    def sync_bodies(self, region=None):
        """
        Put the bodies that are only placed now and then (traffic) where they are now.

        Called before anything reads the world between steps (rays through
        :meth:`update_collision_state`, camera images, overlap checks, :meth:`body_state`): the
        registered bodies' ``before_query()`` hooks, each a no-op when nothing moved since.

        :param region: (x min, y min, x max, y max) [m] the reading is confined to (rays), or
            None (anywhere): a body with a ``before_query_in(region)`` hook then puts only its
            bodies there (and those standing there) where they are.
        """
        for hook, hook_in in self._before_query:
            if region is None or hook_in is None:
                hook()
            else:
                hook_in(region)

    def prepare_render(self):
        """
        Make the world ready to be drawn: what only images show, then :meth:`sync_bodies`.

        Cameras, the chase image and any ``getCameraImage`` of the world's client call it first:
        the registered bodies' ``before_render()`` hooks make the bodies that nothing but an
        image shows (the signal lamps: thousands in a city, which Bullet would walk over at
        every step) the first time an image is drawn.
        """
        for hook in self._before_render:
            hook()
        self.sync_bodies()

    def contact_points(self, body_id):
        """
        Return Bullet's contact points of a body now (``getContactPoints(bodyA=body_id)``).

        While the post-step hooks run (a collision monitor, the traffic's contact check), each
        body's points are read once and shared, until a hook moves a body (:meth:`mark_moved`).
        """
        contacts = self._contacts
        if contacts is None:
            return pybullet.getContactPoints(bodyA=body_id, physicsClientId=self.client_id)
        points = contacts.get(body_id)
        if points is None:
            # by position (bodyA, bodyB, linkIndexA, linkIndexB, physicsClientId): keyword
            # arguments cost PyBullet 0.4 us a call, and this one comes at every step
            points = contacts[body_id] = pybullet.getContactPoints(
                body_id, -1, -2, -2, self.client_id)
        return points

    def mark_moved(self):
        """
        Say that bodies were put somewhere between steps (a teleport, a reset, a new body).

        Rays then refresh Bullet's bounding boxes first, and this step's renders are made
        again (``revision``; physics/sensors/render.py).
        """
        self._broadphase_stale = True
        if self._contacts:              # a body moved by a post-step hook: read them again
            self._contacts = {}
        self.mark_redrawn()

    def mark_redrawn(self):
        """Say that what bodies look like changed between steps: renders are made again."""
        self.revision += 1

    def body_name(self, body_id):
        """
        Name of a body: an obstacle's name, a registered vehicle's name, or ``body<id>``.

        Vehicles are the registered named VehicleBodies (or the SimulatedCars holding one).
        """
        name = self._names.get(body_id)
        if name is not None:
            return name
        for body in map(_vehicle_body, self._bodies):
            if body is not None and body.body_id == body_id:
                return body.name
        return 'ground' if body_id == self.ground_id else f'body{body_id}'

    @property
    def renderer(self):
        """The world's one Renderer (physics/sensors/render.py): cameras' renders per step."""
        if self._renderer is None:
            from vehicle_sim.physics.sensors.render import Renderer
            self._renderer = Renderer(self)
        return self._renderer

    def show_ground(self):
        """
        Make the ground look like a road to cameras: plain grey (idempotent).

        PyBullet's renderer draws the ground plane's collision shape, with a checker texture;
        the texture goes and the colour becomes GROUND_COLOR. Physics and rays are unchanged.
        """
        if not self._ground_visual:
            self.mark_redrawn()
            pybullet.changeVisualShape(self.ground_id, -1, rgbaColor=list(GROUND_COLOR),
                                       textureUniqueId=-1, physicsClientId=self.client_id)
            self._ground_visual = True

    def _ground_visual_shape(self):
        return pybullet.createVisualShape(
            pybullet.GEOM_BOX, halfExtents=[GROUND_SIZE_M / 2, GROUND_SIZE_M / 2, 0.001],
            rgbaColor=list(GROUND_COLOR), physicsClientId=self.client_id)

    def ray_mask_excluding(self, body_id):
        """
        Return a ray collision mask that does not see ``body_id`` (a sensor's own vehicle).

        The body (every link) moves from its default collision group to a group bit of its own;
        every body's mask accepts all groups, so its collisions are unchanged.

        :raises RuntimeError: when more bodies need their own bit than Bullet's mask has.
        """
        mask = self._ray_masks.get(body_id)
        if mask is None:
            bit = _FIRST_RAY_GROUP_BIT + len(self._ray_masks)
            if bit > _LAST_RAY_GROUP_BIT:
                raise RuntimeError(f'at most {_LAST_RAY_GROUP_BIT - _FIRST_RAY_GROUP_BIT + 1} '
                                   'vehicles can carry ray sensors in one world')
            cid = self.client_id
            for link in range(-1, pybullet.getNumJoints(body_id, physicsClientId=cid)):
                pybullet.setCollisionFilterGroupMask(body_id, link, 1 << bit, ALL_GROUPS,
                                                     physicsClientId=cid)
            mask = self._ray_masks[body_id] = ALL_GROUPS & ~(1 << bit)
        return mask

    def _rebuild_hooks(self):
        self._pre_step = [b.pre_step for b in self._bodies if hasattr(b, 'pre_step')]
        self._pre_substep = [b.pre_substep for b in self._bodies if hasattr(b, 'pre_substep')]
        self._post_step = [b.post_step for b in self._bodies if hasattr(b, 'post_step')]
        self._before_query = [(b.before_query, getattr(b, 'before_query_in', None))
                              for b in self._bodies if hasattr(b, 'before_query')]
        self._before_render = [b.before_render for b in self._bodies
                               if hasattr(b, 'before_render')]

    def step(self):
        """Advance the world by one basic time step; return the new time [s]."""
        if self._closed:
            raise RuntimeError('World.step() after close()')
        cid = self.client_id
        try:
            for hook in self._pre_step:
                hook()
            self._step_simulation(cid)      # (by position: a keyword costs PyBullet 0.3 us)
            for _ in range(self.substeps - 1):
                for hook in self._pre_substep:
                    hook()
                self._step_simulation(cid)
            self._step_count += 1
            self.revision += 1
            self._broadphase_stale = False
            self._contacts = {}
            try:
                for hook in self._post_step:
                    hook()
            finally:
                self._contacts = None
        except pybullet.error:
            if self.gui and not pybullet.isConnected(physicsClientId=cid):
                from vehicle_sim.physics.gui import GuiClosedError
                self._closed = True
                raise GuiClosedError('the PyBullet window was closed') from None
            raise
        return self.time_s

    def close(self):
        """Disconnect the physics client (idempotent)."""
        if not self._closed:
            self._closed = True
            closing = [b.on_close for b in self._bodies if hasattr(b, 'on_close')]
            self._bodies.clear()
            self._rebuild_hooks()
            try:
                with quiet_stdout():   # a GUI client's shutdown notices ('destroy semaphore')
                    pybullet.disconnect(physicsClientId=self.client_id)
            except pybullet.error:
                pass
            for hook in closing:
                hook()

    @property
    def closed(self):
        return self._closed

    @property
    def gui_closed(self):
        """True for a GUI world whose window was closed (PyBullet disconnected it)."""
        return self.gui and not pybullet.isConnected(physicsClientId=self.client_id)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False

    def __del__(self):
        try:
            self.close()
        except Exception:   # interpreter shutdown: pybullet may already be gone
            pass
