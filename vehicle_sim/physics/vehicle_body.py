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
The contract of a vehicle body in a World, shared by CarBody and DiffRobotBody.

A vehicle body is one URDF loaded into the World (:meth:`World.load_urdf`) with its
``base_link`` as the base. What every caller needs of it, whatever the vehicle, is here once:

- ``name``, ``params``, ``urdf``, ``body_id``, ``spawn`` (the pose it was built at) and
  ``mount_frame``, the link sensors mount on (``base_link``; mount poses are in it);
- ground truth: :meth:`pose`, :meth:`velocity`, :meth:`body_twist`, :meth:`forward_speed_mps`,
  :meth:`yaw_rad`;
- :meth:`reset` (as built at its spawn pose, in place: :meth:`rebuild`) and
  :meth:`teleport` (at rest at a pose, refused inside another body);
- :attr:`outline`, its footprint rectangle in base_link (core Outline), from its parameters.

A subclass gives its URDF, its footprint function (``OUTLINE``), its spawn height
(``SPAWN_CLEARANCE_M``), the joints a teleport zeroes or stops, and :meth:`_configure`
(dynamics and commands of a freshly loaded body).
"""


import math

import pybullet

from vehicle_sim.core.geometry.angles import yaw_from_quaternion
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.world.placement import WORLD_EXTENT_M

# Where a body stands while its contacts are dropped at an in-place reset [m] (below the world).
_AWAY_Z_M = -1.0e4


def _inside_world(position):
    # A pose (either form) with finite values and |x|, |y| <= WORLD_EXTENT_M.
    return all(math.isfinite(v) for v in position) and abs(position[0]) <= WORLD_EXTENT_M \
        and abs(position[1]) <= WORLD_EXTENT_M


class VehicleBody:
    """A vehicle's body in a World: pose, twist, reset, teleport, footprint, sensor mount."""

    mount_frame = 'base_link'
    SPAWN_CLEARANCE_M = 0.0
    FIXED_BASE = False      # True: placed each step by its owner, never moved by the physics
    OUTLINE = None      # params -> core Outline (set by each subclass)

    def _load(self, world, params, urdf, position, name):
        # Load the URDF at ``position`` and keep what every vehicle body needs.
        self.world = world
        self.params = params
        self.name = name
        self.urdf = urdf
        self.spawn = position
        cid = self._cid = world.client_id
        self._placed_beyond = False     # placed beyond the world since loaded (rebuild)
        self.body_id, self._joint = world.load_urdf(urdf, position, self.SPAWN_CLEARANCE_M,
                                                    self.FIXED_BASE)
        self._label()
        info = pybullet.getDynamicsInfo(self.body_id, -1, physicsClientId=cid)
        # pybullet reports the base at its (principal-axes) inertial frame; keep its inverse.
        self._link_to_com = (info[3], info[4])
        self._com_to_link = pybullet.invertTransform(info[3], info[4])
        return self._joint

    def _label(self):
        # a vehicle of the world: a car with its name's instance id (World.labels)
        self.world.labels.set(self.body_id, 'car', self.world.labels.instance(self.name))

    def _configure(self):
        """Set the dynamics and clear the commands of a freshly loaded body."""
        raise NotImplementedError

    def _teleport_joints(self):
        """Return (joints set to 0, joints whose velocity is stopped) for a teleport."""
        raise NotImplementedError

    # ---------------------------------------------------------------- reset and teleport
    def rebuild(self, position):
        """
        Put the body back as it was built, at a pose (a reset).

        Whatever state the physics left it in, it is then at rest, joints at 0, no command.
        In place: the same body, its pose, velocities, joints, dynamics and motors set as a
        fresh load sets them. PyBullet keeps a body's collision shapes until the whole
        simulation is reset, removed body or not, so loading the URDF again at every reset grew
        the process by about 18 KiB a reset (a car), without bound over a training run. Only a
        body Bullet may have taken out of the simulation (placed beyond the world or at a pose
        that is not finite since it was loaded, or there now: it falls through the ground
        after any reset of its pose) is loaded afresh (:meth:`World.reload_urdf`), with the same
        joint indices.

        :param position: base_link pose, as the constructor takes it.
        """
        if self._placed_beyond or not _inside_world(self.pose()):
            self.world.labels.forget(self.body_id)
            self.body_id, _ = self.world.reload_urdf(self.body_id, self.urdf, position,
                                                     self.SPAWN_CLEARANCE_M, self.FIXED_BASE)
            self._placed_beyond = False
            self._label()
        else:
            # Bullet keeps a body's contact points (and their impulses, which warm-start the
            # next solve) while the pair's boxes overlap: a body reset close to where it was
            # would start its episode from them, unlike a fresh load. Out of the world for one
            # collision pass, its pairs and their contacts are dropped.
            cid = self._cid
            _, orientation = pybullet.getBasePositionAndOrientation(self.body_id,
                                                                    physicsClientId=cid)
            pybullet.resetBasePositionAndOrientation(self.body_id, (0.0, 0.0, _AWAY_Z_M),
                                                     orientation, physicsClientId=cid)
            pybullet.performCollisionDetection(physicsClientId=cid)
            joints = range(pybullet.getNumJoints(self.body_id, physicsClientId=cid))
            self.world.place_at_rest(self.body_id, self._link_to_com, position,
                                     self.SPAWN_CLEARANCE_M, zero_joints=joints)
        self._configure()

    def reset(self):
        """Put the body back as it was built: spawn pose, at rest, joints at 0, no command."""
        self.rebuild(self.spawn)

    def place(self, position):
        """
        Put the body at a pose, at rest (a teleport without the overlap check).

        :param position: base_link pose, as the constructor takes it; the (x, y, yaw) form puts
            base_link on the ground, level, as at spawn.
        """
        if not _inside_world(position):
            self._placed_beyond = True      # Bullet may take it out: the next reset reloads it
        zero, stop = self._teleport_joints()
        self.world.place_at_rest(self.body_id, self._link_to_com, position,
                                 self.SPAWN_CLEARANCE_M, zero_joints=zero, stop_joints=stop)

    def teleport(self, position):
        """
        Put the body at rest at a pose; its commands stay.

        :raises InvalidPoseError: when it would be inside another body (nothing moved).
        """
        self.world.try_place(self.body_id, lambda: self.place(position))

    # ---------------------------------------------------------------- ground truth
    @property
    def outline(self):
        """Its footprint rectangle in base_link (core Outline), from its parameters."""
        return type(self).OUTLINE(self.params)

    def pose(self):
        """Ground-truth pose of base_link in the world: (x, y, z [m], qx, qy, qz, qw)."""
        com_pos, com_orn = pybullet.getBasePositionAndOrientation(self.body_id,
                                                                  physicsClientId=self._cid)
        pos, orn = pybullet.multiplyTransforms(com_pos, com_orn, *self._com_to_link)
        return tuple(pos) + tuple(orn)

    def yaw_rad(self):
        """Ground-truth heading of base_link [rad] (REP 103)."""
        _, _, _, qx, qy, qz, qw = self.pose()
        return yaw_from_quaternion(qx, qy, qz, qw)

    def velocity(self):
        """
        Ground-truth velocity of base_link in the world frame.

        :return: ((vx, vy, vz) [m/s], (wx, wy, wz) [rad/s]).
        """
        return self.world.base_link_velocity(self.body_id, self.pose()[:3])

    def _axes(self, pose):
        # The body's x (heading) and z (up) axes in the world frame.
        matrix = pybullet.getMatrixFromQuaternion(pose[3:], physicsClientId=self._cid)
        return (matrix[0], matrix[3], matrix[6]), (matrix[2], matrix[5], matrix[8])

    def body_twist(self):
        """
        Ground-truth twist of base_link in base_link axes.

        :return: ((vx, vy, vz) [m/s], (wx, wy, wz) [rad/s]), forward speed = vx, yaw rate = wz.
        """
        linear, angular = self.velocity()
        matrix = pybullet.getMatrixFromQuaternion(self.pose()[3:], physicsClientId=self._cid)
        # columns of the rotation matrix are the body axes in the world frame
        axes = [(matrix[0 + c], matrix[3 + c], matrix[6 + c]) for c in range(3)]
        return (tuple(sum(a * b for a, b in zip(axis, linear)) for axis in axes),
                tuple(sum(a * b for a, b in zip(axis, angular)) for axis in axes))

    def forward_speed_mps(self, pose=None):
        """
        Speed of base_link along its heading (x axis) [m/s]; negative when reversing.

        :param pose: its :meth:`pose` now, when the caller has just read it (read here if None).
        """
        if pose is None:
            pose = self.pose()      # read once: the velocity's point and the heading
        linear, _ = self.world.base_link_velocity(self.body_id, pose[:3])
        heading, _ = self._axes(pose)
        return sum(a * b for a, b in zip(linear, heading))

    def yaw_rate_radps(self):
        """Angular velocity about the body's z axis [rad/s] (positive = left, REP 103)."""
        _, angular = self.velocity()
        _, up = self._axes(self.pose())
        return sum(a * b for a, b in zip(angular, up))

    def joint_index(self, name):
        """PyBullet index of a joint by its URDF name."""
        try:
            return self._joint[name]
        except KeyError:
            raise InvalidParameterError(
                f'unknown joint {name!r}; joints: {", ".join(sorted(self._joint))}') from None

    def destroy(self):
        """Remove the body from the physics (World.remove calls this)."""
        if self.body_id is not None and not self.world.closed:
            pybullet.removeBody(self.body_id, physicsClientId=self._cid)
            self.world.labels.forget(self.body_id)
        self.body_id = None
