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
A car body in a World: the URDF generated from CarParams, realising Actuation, filling Measurement.

Mappings (derivations in docs/physics.md):

- steering: POSITION_CONTROL like Webots' default RotationalMotor, commanded velocity
  10 * error capped at 10 rad/s, force limit maxSteeringTorque (positionGain = 10 * dt_sub,
  velocityGain = 1, maxVelocity = 10 rad/s).
- suspension: Bullet's implicit joint motor as a spring-damper normalised by a reference mass
  m_ref (the sprung mass per corner): positionGain = k * dt_sub^2 / m_ref, velocityGain =
  c * dt_sub / m_ref, target = 0 = static equilibrium.
- wheels: VELOCITY = velocity motor with WHEEL_MOTOR_TORQUE_NM; TORQUE = applied joint torque
  plus the brake motor; FREE = brake motor only. The brake motor is a velocity motor with target
  0 and force limit brake_torque_nm (Coulomb-like, holds at standstill). wheelsDampingConstant is
  PyBullet's joint damping (-c * omega each sub-step).
"""


import pybullet

from vehicle_sim.core.car.vehicle_io import as_floats, WHEEL_COUNT, WheelMode
from vehicle_sim.core.geometry.footprint import car_outline
from vehicle_sim.physics.urdf import car_urdf, joint_names, STEER_MAX_VELOCITY_RADPS
from vehicle_sim.physics.vehicle_body import VehicleBody
from vehicle_sim.physics.world import point_velocity

# Webots' driven-wheel motors have maxTorque 1e8 N*m (Car.proto); Bullet's implicit motor is
# stable with it, the impulse actually used is what the tyre can transmit.
WHEEL_MOTOR_TORQUE_NM = 1.0e8
# Webots' default RotationalMotor controlP (Webots' RotationalMotor default, controlPID 10 0 0).
STEER_P_PER_S = 10.0
# Suspension motor force limit, in multiples of the static corner load.
SUSPENSION_FORCE_LIMIT_G = 20.0
WHEEL_FRICTION = 1.0     # multiplied with the ground's friction by Bullet
CHASSIS_FRICTION = 0.5
# Enum members as plain names for apply() (each ``WheelMode.X`` lookup costs about 0.1 us on
# CPython 3.11).
_VELOCITY, _TORQUE = WheelMode.VELOCITY, WheelMode.TORQUE


def sprung_mass_per_corner_kg(params):
    """
    Return the reference mass of each suspension corner, front and rear [kg].

    The body mass split over the axles by the centre of mass (static moment balance), then
    halved; the front share is kept inside [0.1, 0.9] for odd presets.
    """
    share = min(0.9, max(0.1, params.center_of_mass_m[0] / params.wheelbase_m))
    return params.mass_kg * share / 2.0, params.mass_kg * (1.0 - share) / 2.0


class CarBody(VehicleBody):
    """A car's rigid bodies and joints in a World (PyBullet), driven through Actuation."""

    OUTLINE = staticmethod(car_outline)

    def __init__(self, world, params, position=(0.0, 0.0, 0.0), name=None,
                 wheel_shape='sphere', register=True):
        """
        Load the car into the world, at rest on its wheels.

        :param world: the World to live in (the body registers itself).
        :param params: CarParams.
        :param position: base_link pose: (x [m], y [m], yaw [rad]) on the ground, or the full
            (x, y, z, qx, qy, qz, qw) in the world frame.
        :param name: robot name in the URDF; the preset's model name when None.
        :param wheel_shape: wheel collision shape, 'sphere' (default) or 'cylinder' (see
            car_urdf).
        :param register: register with the world's step hooks; False when an owner (e.g.
            SimulatedCar) calls ``pre_step``/``pre_substep`` itself.
        """
        name = name or params.model
        joints = self._load(world, params, car_urdf(params, name=name, wheel_shape=wheel_shape),
                            position, name)
        names = joint_names()
        self._wheel = [joints[n] for n in names['wheel']]
        self._steer = [joints[n] for n in names['steer']]
        self._suspension = [joints[n] for n in names['suspension']]
        self._state_names = names['wheel'] + names['steer'] + names['suspension']
        self._state_joints = self._wheel + self._steer + self._suspension
        self._read_joints = self._wheel + self._steer
        self._configure()
        if register:
            world.add_body(self)

    # ---------------------------------------------------------------- set-up
    def _configure(self):
        # A freshly loaded body: no command in force, the dynamics set.
        self._last_velocity_cmd = None
        self._last_steer_cmd = None
        self._torque_joints = []
        self._torques = []
        self._configure_dynamics()

    def _configure_dynamics(self):
        cid, body, params = self._cid, self.body_id, self.params
        for link in range(-1, pybullet.getNumJoints(body, physicsClientId=cid)):
            # No artificial velocity damping: only the Webots dampers act.
            pybullet.changeDynamics(body, link, linearDamping=0.0, angularDamping=0.0,
                                    lateralFriction=CHASSIS_FRICTION, jointDamping=0.0,
                                    physicsClientId=cid)
        for joint in self._wheel:
            pybullet.changeDynamics(body, joint, lateralFriction=WHEEL_FRICTION,
                                    jointDamping=params.wheels_damping_nms_per_rad,
                                    physicsClientId=cid)
        dt = self.world.substep_s
        m_front, m_rear = sprung_mass_per_corner_kg(params)
        self.suspension_gains = []
        for index, joint in enumerate(self._suspension):
            front = index < 2
            m_ref = m_front if front else m_rear
            k = (params.suspension_front_spring_n_per_m if front
                 else params.suspension_rear_spring_n_per_m)
            c = (params.suspension_front_damping_ns_per_m if front
                 else params.suspension_rear_damping_ns_per_m)
            kp = min(1.0, k * dt * dt / m_ref)
            kd = min(1.0, c * dt / m_ref)
            self.suspension_gains.append((kp, kd))
            pybullet.setJointMotorControl2(
                body, joint, pybullet.POSITION_CONTROL, targetPosition=0.0, targetVelocity=0.0,
                positionGain=kp, velocityGain=kd,
                force=SUSPENSION_FORCE_LIMIT_G * m_ref * self.world.gravity, physicsClientId=cid)
        self._steer_gain = min(1.0, STEER_P_PER_S * dt)
        self._steer_force = params.max_steering_torque_nm
        self._set_steering(0.0, 0.0)
        self._set_wheels([0.0] * WHEEL_COUNT, [0.0] * WHEEL_COUNT)

    def _set_steering(self, right_rad, left_rad):
        command = (right_rad, left_rad)
        if command == self._last_steer_cmd:
            return
        self._last_steer_cmd = command
        for joint, target in zip(self._steer, command):
            # maxVelocity is the motor's velocity cap (Bullet's rhs clamp): Webots' 10 rad/s.
            pybullet.setJointMotorControl2(
                self.body_id, joint, pybullet.POSITION_CONTROL, targetPosition=target,
                targetVelocity=0.0, positionGain=self._steer_gain, velocityGain=1.0,
                maxVelocity=STEER_MAX_VELOCITY_RADPS, force=self._steer_force,
                physicsClientId=self._cid)

    def _set_wheels(self, velocities, forces):
        command = (tuple(velocities), tuple(forces))
        if command == self._last_velocity_cmd:
            return
        self._last_velocity_cmd = command
        pybullet.setJointMotorControlArray(
            self.body_id, self._wheel, pybullet.VELOCITY_CONTROL, targetVelocities=command[0],
            forces=command[1], physicsClientId=self._cid)

    # ---------------------------------------------------------------- per step
    def apply(self, actuation):
        """
        Realise an Actuation; it stays in force until the next ``apply``.

        VELOCITY wheels follow their target with WHEEL_MOTOR_TORQUE_NM (brakes have no effect
        on them, as in Webots' SPEED mode); TORQUE wheels get their torque plus the brake
        motor; FREE wheels only the brake motor.
        """
        right, left = actuation.steer_right_rad, actuation.steer_left_rad
        if (right, left) != self._last_steer_cmd:      # (it changes at decisions only)
            self._set_steering(float(right), float(left))
        # Plain floats first: indexing numpy arrays element by element costs more.
        velocities = as_floats(actuation.wheel_velocity_radps)
        brakes = as_floats(actuation.brake_torque_nm)
        forces = [0.0] * WHEEL_COUNT
        torque_joints = []
        torques = []
        for index, mode in enumerate(actuation.wheel_mode):
            if mode == _VELOCITY:
                forces[index] = WHEEL_MOTOR_TORQUE_NM
            else:
                velocities[index] = 0.0
                forces[index] = abs(brakes[index])
                if mode == _TORQUE:
                    torque = float(actuation.wheel_torque_nm[index])
                    if torque != 0.0:
                        torque_joints.append(self._wheel[index])
                        torques.append(torque)
        self._set_wheels(velocities, forces)
        self._torque_joints = torque_joints
        self._torques = torques

    def pre_step(self):
        """World hook: re-apply the joint torques (PyBullet clears them every sub-step)."""
        if self._torque_joints:
            pybullet.setJointMotorControlArray(
                self.body_id, self._torque_joints, pybullet.TORQUE_CONTROL, forces=self._torques,
                physicsClientId=self._cid)

    pre_substep = pre_step

    def read(self, measurement):
        """
        Fill a Measurement from the joints.

        Wheel spin positions (FR, FL, RR, RL; unwrapped, continuous) and the right/left
        steering angles (Webots sign, positive = right) [rad].
        """
        # (the client id passed by position: keyword arguments cost PyBullet 0.3 us a call)
        states = pybullet.getJointStates(self.body_id, self._read_joints, self._cid)
        positions = measurement.wheel_position_rad
        for index in range(WHEEL_COUNT):
            positions[index] = states[index][0]
        measurement.steer_right_rad = states[4][0]
        measurement.steer_left_rad = states[5][0]
        return measurement

    def _teleport_joints(self):
        # The wheels and steering keep their angles and the suspension goes to 0; a reset
        # zeroes every joint (rebuild).
        return self._suspension, self._wheel + self._steer

    # ---------------------------------------------------------------- ground truth
    def pose_and_velocity(self):
        """
        Return ``(pose(), velocity())`` of one instant, reading the base state once.

        The same values as the two calls, for a caller that needs both every step.
        """
        cid = self._cid
        com_pos, com_orn = pybullet.getBasePositionAndOrientation(self.body_id,
                                                                  physicsClientId=cid)
        pos, orn = pybullet.multiplyTransforms(com_pos, com_orn, *self._com_to_link)
        linear, angular = pybullet.getBaseVelocity(self.body_id, physicsClientId=cid)
        return tuple(pos) + tuple(orn), point_velocity(com_pos, linear, angular, pos)

    def joint_states(self):
        """
        Wheel spin (4), steering (2) and suspension (4) joints.

        :return: (names, positions [rad or m], velocities [rad/s or m/s]) as tuples.
        """
        states = pybullet.getJointStates(self.body_id, self._state_joints,
                                         physicsClientId=self._cid)
        return (self._state_names, tuple(s[0] for s in states), tuple(s[1] for s in states))
