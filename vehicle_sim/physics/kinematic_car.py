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
A car moved by a simple_planning_simulator model: placed each step, like the traffic bodies.

The body is the car's own URDF (every sensor sees it, its links keep their labels), loaded with
a fixed base: the physics never moves it and it touches the ground with none of its links. Its
collisions with other bodies are still reported (:meth:`KinematicCarBody.contact_points`, which
the collision monitor reads instead of Bullet's contacts), with no response: it drives through.

Each step, before the physics, the CarLogic runs on the model's wheel and steering angles, its
commands become the model's inputs (core/car/kinematic_drive.py), the model advances one step
(core/car/kinematic_models.py), and the body is put at the model's pose at the end of the step with
its steering and wheel joints at the model's angles; after the step the base gets the model's
velocity (base_link: vx along the heading, yaw rate vx tan(steer) / L), so every reader of the
body's twist sees it.
"""

import math

import pybullet

from vehicle_sim.core.car.ackermann import ackermann_angles
from vehicle_sim.core.car.kinematic_drive import model_inputs
from vehicle_sim.core.car.kinematic_models import KinematicModel
from vehicle_sim.core.car.logic import CarLogic
from vehicle_sim.core.car.speed_braking import cruise_ramp_mps2
from vehicle_sim.core.car.vehicle_io import Measurement, WHEEL_COUNT
from vehicle_sim.core.geometry.footprint import car_outline
from vehicle_sim.physics.urdf import car_urdf, joint_names
from vehicle_sim.physics.vehicle_body import VehicleBody


class KinematicCarBody(VehicleBody):
    """The car's URDF with a fixed base, put where its model says."""

    OUTLINE = staticmethod(car_outline)
    FIXED_BASE = True
    # its KinematicCar's hook, called with the pose of each rebuild (None: none)
    on_rebuild = None

    def __init__(self, world, params, position=(0.0, 0.0, 0.0), name=None):
        """
        Load the car into the world (not registered: its KinematicCar places it).

        :param world: the World.
        :param params: CarParams.
        :param position: base_link pose (x [m], y [m], yaw [rad]) on the ground.
        :param name: robot name in the URDF; the preset's model name when None.
        """
        name = name or params.model
        joints = self._load(world, params, car_urdf(params, name=name), position, name)
        names = joint_names()
        self._wheel = [joints[n] for n in names['wheel']]
        self._steer = [joints[n] for n in names['steer']]
        self._suspension = [joints[n] for n in names['suspension']]
        self._radius = (params.front_tire_radius_m,) * 2 + (params.rear_tire_radius_m,) * 2
        self._configure()

    def _configure(self):
        cid, body = self._cid, self.body_id
        self.wheel_angles = [0.0] * WHEEL_COUNT
        self.steer_angles = (0.0, 0.0)       # right, left (Webots sign)
        self._z = None
        links = range(-1, pybullet.getNumJoints(body, physicsClientId=cid))
        for link in links:           # no ground contact: the model carries the car
            pybullet.setCollisionFilterPair(body, self.world.ground_id, link, -1, 0,
                                            physicsClientId=cid)
        # every joint held where it is put (no motor moves it between the placements)
        joints = self._wheel + self._steer + self._suspension
        pybullet.setJointMotorControlArray(body, joints, pybullet.VELOCITY_CONTROL,
                                           targetVelocities=[0.0] * len(joints),
                                           forces=[0.0] * len(joints), physicsClientId=cid)

    def _teleport_joints(self):
        return self._suspension, self._wheel + self._steer

    def rebuild(self, position):
        """
        Put the body back as built at a pose (a reset), and its car's model there with it.

        A Gym reset with ``start_noise`` rebuilds an ego's body at an offset pose
        (gym/drive_sim.py ``reset_world``): without the model following, the next step would
        put the body back where the model was.
        """
        super().rebuild(position)
        if self.on_rebuild is not None:
            self.on_rebuild(position)

    def put(self, x_m, y_m, yaw_rad, steer_rad, distance_m):
        """
        Put the body at (x, y, yaw) at rest, steering at ``steer_rad`` (REP 103 sign).

        :param distance_m: how far the wheels rolled in the step (spins them).
        """
        cid = self._cid
        if self._z is None:
            self._z = pybullet.multiplyTransforms(
                *pybullet.getBasePositionAndOrientation(self.body_id, physicsClientId=cid),
                *self._com_to_link)[0][2]
        half = 0.5 * yaw_rad
        com, orn = pybullet.multiplyTransforms((x_m, y_m, self._z),
                                               (0.0, 0.0, math.sin(half), math.cos(half)),
                                               *self._link_to_com)
        pybullet.resetBasePositionAndOrientation(self.body_id, com, orn, physicsClientId=cid)
        pybullet.resetBaseVelocity(self.body_id, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0),
                                   physicsClientId=cid)
        params = self.params
        self.steer_angles = ackermann_angles(-steer_rad, params.track_front_m,
                                             params.wheelbase_m)
        for joint, angle in zip(self._steer, self.steer_angles):
            pybullet.resetJointState(self.body_id, joint, angle, 0.0, physicsClientId=cid)
        for index, (joint, radius) in enumerate(zip(self._wheel, self._radius)):
            self.wheel_angles[index] += distance_m / radius
            pybullet.resetJointState(self.body_id, joint, self.wheel_angles[index], 0.0,
                                     physicsClientId=cid)
        self.world.mark_moved()

    def set_velocity(self, vx_mps, yaw_rate_radps):
        """Give the base base_link's velocity: vx along the heading, the yaw rate about z."""
        cid = self._cid
        com, _ = pybullet.getBasePositionAndOrientation(self.body_id, physicsClientId=cid)
        pose = self.pose()
        yaw = self.yaw_rad()
        vx, vy = vx_mps * math.cos(yaw), vx_mps * math.sin(yaw)
        # v_com = v_link + w x (p_com - p_link), w = (0, 0, yaw rate)
        dx, dy = com[0] - pose[0], com[1] - pose[1]
        linear = (vx - yaw_rate_radps * dy, vy + yaw_rate_radps * dx, 0.0)
        pybullet.resetBaseVelocity(self.body_id, linear, (0.0, 0.0, yaw_rate_radps),
                                   physicsClientId=cid)

    def contact_points(self):
        """
        Return the points where the body touches others, in getContactPoints' form.

        Bullet makes no contacts between two static bodies (this one and an obstacle or a
        traffic box): the bodies whose bounding boxes overlap its links' are asked for their
        closest points at distance <= 0 instead (the normal force is 0: nothing pushes).
        """
        cid, own, ground = self._cid, self.body_id, self.world.ground_id
        others = set()
        for link in range(-1, pybullet.getNumJoints(own, physicsClientId=cid)):
            low, high = pybullet.getAABB(own, link, physicsClientId=cid)
            for body, _ in pybullet.getOverlappingObjects(low, high, physicsClientId=cid) or ():
                if body != own and body != ground:
                    others.add(body)
        points = []
        for body in sorted(others):
            points.extend(pybullet.getClosestPoints(own, body, 0.0, physicsClientId=cid))
        return points

    def pose_and_velocity(self):
        """Return ``(pose(), velocity())``, as CarBody.pose_and_velocity."""
        return self.pose(), self.velocity()

    def read(self, measurement):
        """Fill a Measurement: the wheels' and steering's angles as last put."""
        measurement.wheel_position_rad[:] = self.wheel_angles
        measurement.steer_right_rad, measurement.steer_left_rad = self.steer_angles
        return measurement

    def joint_states(self):
        """Wheel spin (4), steering (2) and suspension (4) joints, as CarBody.joint_states."""
        names = joint_names()
        speeds = [0.0] * 10
        return (names['wheel'] + names['steer'] + names['suspension'],
                tuple(self.wheel_angles) + tuple(self.steer_angles) + (0.0,) * 4, tuple(speeds))


class KinematicCar:
    """
    CarLogic + a simple_planning_simulator model + KinematicCarBody, stepped by the World.

    The same interface as SimulatedCar (``logic``, ``body``, ``reset``, ``teleport``).
    """

    drives_body = True

    def __init__(self, world, params, vehicle_model, position=(0.0, 0.0, 0.0), name=None):
        """
        Place a car moved by a model.

        :param vehicle_model: VehicleModelParams (core/car/kinematic_models.py).
        """
        self.world = world
        self.params = params
        self.vehicle_model = vehicle_model
        self.spawn = position
        self.logic = CarLogic(params)
        self.body = KinematicCarBody(world, params, position, name=name)
        self.model = KinematicModel(vehicle_model, params.wheelbase_m, world.time_step_s,
                                    self._pose_of(position))
        self.body.on_rebuild = self._rebuilt
        self.measurement = Measurement()
        self._a_ramp = cruise_ramp_mps2(params)
        world.add_body(self)

    def _pose_of(self, position):
        if len(position) == 3:
            return position
        pose = self.body.pose()
        return pose[0], pose[1], self.body.yaw_rad()

    def pre_step(self):
        """World hook: the logic on the model's angles, the model's step, the body put."""
        model, world = self.model, self.world
        self.logic.step(self.body.read(self.measurement), world.time_s, world.time_step_s)
        x0, y0 = model.x_m, model.y_m
        model.step(*model_inputs(self.logic, model, self._a_ramp))
        distance = math.copysign(math.hypot(model.x_m - x0, model.y_m - y0), model.vx_mps)
        self.body.put(model.x_m, model.y_m, model.yaw_rad, model.steer_rad, distance)

    def post_step(self):
        """World hook: the base gets the model's velocity, for every reader of the twist."""
        self.body.set_velocity(self.model.vx_mps, self.model.yaw_rate_radps)

    def _rebuilt(self, position):
        # the body was rebuilt at a pose (its reset, a Gym reset's start_noise): the model
        # starts there, at rest, its delayed inputs 0
        self.model.reset(self._pose_of(position))

    def reset(self):
        """Back as built: spawn pose, at rest, the model's delayed inputs 0, logic reset."""
        self.body.reset()
        self.logic.reset()

    def teleport(self, position):
        """
        Put the car at rest at (x, y, yaw); its commands stay.

        :raises InvalidPoseError: when the car would be inside another body (nothing moved).
        """
        self.body.teleport(position)
        self.logic.come_to_rest()
        pose = self.body.pose()
        self.model.reset((pose[0], pose[1], self.body.yaw_rad()))

    def destroy(self):
        """Remove the car's bodies from the physics."""
        self.body.destroy()
