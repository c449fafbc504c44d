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
A differential-drive robot in a World: URDF generated from RobotParams, wheel velocity motors.

Frames (REP 103, FLU): ``base_link`` on the ground below the centre of the driven axle (caster
drive) or of the wheel rectangle (skid steer). Wheel joints are ``continuous`` about +y, so a
positive angle / speed rolls the wheel forward on both sides, as in the car URDF.

Layouts:

- ``caster``: ``left_wheel_joint`` at (0, +t/2, r), ``right_wheel_joint`` at (0, −t/2, r), a ball
  caster (sphere of radius r_c, fixed to the body through ``caster_joint``) touching the ground
  at x = ``caster_offset``. The caster is frictionless (lateral, rolling and spinning friction
  0), the usual simulation stand-in for a free-swivelling caster wheel.
- ``skid_steer``: four wheels at (±L/2, ±t/2, r); the left pair and the right pair get the same
  command. Turning makes the wheels slip sideways, so the yaw rate is lower than (v_r − v_l)/t
  (as on a real skid-steer base): the robot node's wheel odometry assumes the ideal law.

Wheel collision shapes are spheres of the wheel radius (see car_urdf: Bullet's cylinder-plane
contact wanders across the tread); the visuals are cylinders.
"""

from dataclasses import dataclass
import math
from typing import Tuple
from xml.sax.saxutils import escape

import pybullet

from vehicle_sim.config import load_robot  # noqa: F401  (loaded there; kept importable here)
from vehicle_sim.core.geometry.footprint import robot_outline
from vehicle_sim.core.specs.errors import InvalidCommandError
from vehicle_sim.physics.urdf import geometry_block, inertial, num, vec, wheel_inertia_kgm2
from vehicle_sim.physics.vehicle_body import VehicleBody

CASTER_MASS_KG = 0.2
# Spawn height of base_link above the ground [m]: the wheels touch down within a few steps.
SPAWN_CLEARANCE_M = 0.001
BODY_FRICTION = 0.5


def wheel_anchor_m(params, index):
    """
    Return the joint anchor of a driven wheel in base_link (FLU).

    :param params: RobotParams.
    :param index: index into ``params.wheel_joints`` (left side first).
    :return: (x, y, z) [m].
    """
    name = params.wheel_names[index]
    y = params.wheel_tread_m / 2.0 * (1.0 if 'left' in name else -1.0)
    x = 0.0
    if name.startswith('front'):
        x = params.wheel_base_m / 2.0
    elif name.startswith('rear'):
        x = -params.wheel_base_m / 2.0
    return (x, y, params.wheel_radius_m)


def robot_urdf(params, name=None, prefix=''):
    """
    Generate the URDF of a differential-drive robot.

    :param params: RobotParams.
    :param name: robot name; the preset's model name when None.
    :param prefix: put in front of every link and joint name (e.g. ``'robot1/'``).
    :return: URDF text.
    """
    length, width, height = params.body_size_m
    radius = params.wheel_radius_m
    base = f'{prefix}base_link'
    body_xyz = (params.body_offset_m, 0.0, radius)
    parts = [f'<?xml version="1.0"?>\n<robot name="{escape(name or params.model)}">\n',
             f'  <link name="{base}">\n',
             inertial(params.mass_kg, params.mass_kg * (width ** 2 + height ** 2) / 12.0,
                       params.mass_kg * (length ** 2 + height ** 2) / 12.0,
                       params.mass_kg * (length ** 2 + width ** 2) / 12.0, xyz=body_xyz)]
    box = f'<box size="{vec(params.body_size_m)}"/>'
    parts.append(geometry_block('visual', body_xyz, (0.0, 0.0, 0.0), box))
    parts.append(geometry_block('collision', body_xyz, (0.0, 0.0, 0.0), box))
    parts.append('  </link>\n')
    ixx, iyy, izz = wheel_inertia_kgm2(params.wheel_mass_kg, radius, params.wheel_width_m)
    cylinder = f'<cylinder radius="{num(radius)}" length="{num(params.wheel_width_m)}"/>'
    for index, (stem, joint) in enumerate(zip(params.wheel_names, params.wheel_joints)):
        link = f'{prefix}{stem}_wheel_link'
        parts.append(f'  <link name="{link}">\n'
                     + inertial(params.wheel_mass_kg, ixx, iyy, izz)
                     + geometry_block('visual', (0.0, 0.0, 0.0), (math.pi / 2, 0.0, 0.0), cylinder)
                     + geometry_block('collision', (0.0, 0.0, 0.0), (0.0, 0.0, 0.0),
                              f'<sphere radius="{num(radius)}"/>')
                     + '  </link>\n')
        parts.append(
            f'  <joint name="{prefix}{joint}" type="continuous">\n'
            f'    <parent link="{base}"/>\n    <child link="{link}"/>\n'
            f'    <origin xyz="{vec(wheel_anchor_m(params, index))}" rpy="0 0 0"/>\n'
            f'    <axis xyz="0 1 0"/>\n'
            f'    <limit effort="{num(params.wheel_motor_torque_nm)}" '
            f'velocity="{num(params.max_wheel_speed_radps)}"/>\n  </joint>\n')
    if params.drive == 'caster':
        r_c = params.caster_radius_m
        i_c = 0.4 * CASTER_MASS_KG * r_c * r_c
        sphere = f'<sphere radius="{num(r_c)}"/>'
        parts.append(f'  <link name="{prefix}caster_link">\n'
                     + inertial(CASTER_MASS_KG, i_c, i_c, i_c)
                     + geometry_block('visual', (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), sphere)
                     + geometry_block('collision', (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), sphere)
                     + '  </link>\n')
        parts.append(
            f'  <joint name="{prefix}caster_joint" type="fixed">\n'
            f'    <parent link="{base}"/>\n    <child link="{prefix}caster_link"/>\n'
            f'    <origin xyz="{vec((params.caster_offset_m, 0.0, r_c))}" rpy="0 0 0"/>\n'
            f'  </joint>\n')
    parts.append('</robot>\n')
    return ''.join(parts)


@dataclass(frozen=True)
class RobotReading:
    """
    One reading of the driven wheels, in ``wheel_joints`` order (left side first).

    Positions are unwrapped joint angles [rad]; velocities [rad/s], positive = rolling forward.
    ``left_radps``/``right_radps`` are the side means.
    """

    wheel_position_rad: Tuple[float, ...]
    wheel_velocity_radps: Tuple[float, ...]
    left_radps: float
    right_radps: float


class DiffRobotBody(VehicleBody):
    """A differential-drive robot in a World, driven by wheel velocity motors."""

    OUTLINE = staticmethod(robot_outline)
    SPAWN_CLEARANCE_M = SPAWN_CLEARANCE_M

    def __init__(self, world, params, position=(0.0, 0.0, 0.0), name=None, register=True):
        """
        Load the robot into the world.

        :param world: the World to live in.
        :param params: RobotParams, or a preset name / YAML path (see load_robot).
        :param position: base_link pose: (x [m], y [m], yaw [rad]) on the ground, or the full
            (x, y, z, qx, qy, qz, qw) in the world frame.
        :param name: robot name in the URDF; the preset's model name when None.
        :param register: register with the world's step hooks (kept for symmetry with CarBody;
            the motors are implicit, so no per-step hook is needed).
        """
        params = load_robot(params)
        name = name or params.model
        self._load(world, params, robot_urdf(params, name=name), position, name)
        self.wheel_joints = params.wheel_joints
        joints = self._joint
        self._wheels = [joints[n] for n in self.wheel_joints]
        self._left = [i for i, n in enumerate(self.wheel_joints) if 'left' in n]
        self._right = [i for i, n in enumerate(self.wheel_joints) if 'right' in n]
        self._configure()
        if register:
            world.add_body(self)

    def _configure(self):
        # A freshly loaded body: no command in force, the dynamics set.
        self._command_radps = (0.0,) * len(self._wheels)
        self._configure_dynamics()

    def _configure_dynamics(self):
        cid, body, params = self._cid, self.body_id, self.params
        pybullet.changeDynamics(body, -1, linearDamping=0.0, angularDamping=0.0,
                                lateralFriction=BODY_FRICTION, physicsClientId=cid)
        for joint in self._wheels:
            pybullet.changeDynamics(body, joint, linearDamping=0.0, angularDamping=0.0,
                                    lateralFriction=params.wheel_friction, jointDamping=0.0,
                                    physicsClientId=cid)
        if 'caster_joint' in self._joint:
            pybullet.changeDynamics(body, self._joint['caster_joint'], lateralFriction=0.0,
                                    rollingFriction=0.0, spinningFriction=0.0,
                                    linearDamping=0.0, angularDamping=0.0, physicsClientId=cid)
        self._apply()

    def _apply(self):
        pybullet.setJointMotorControlArray(
            self.body_id, self._wheels, pybullet.VELOCITY_CONTROL,
            targetVelocities=list(self._command_radps),
            forces=[self.params.wheel_motor_torque_nm] * len(self._wheels),
            physicsClientId=self._cid)

    # ---------------------------------------------------------------- commands
    def _check_radps(self, name, value):
        if isinstance(value, bool) or not isinstance(value, (int, float)) \
                or not math.isfinite(value):
            raise InvalidCommandError(f'{name} = {value!r} rad/s: must be a finite number')
        limit = self.params.max_wheel_speed_radps
        if abs(value) > limit:
            raise InvalidCommandError(
                f'{name} = {value!r} rad/s: outside [-{limit:g}, {limit:g}] rad/s '
                '(max_wheel_speed)')
        return float(value)

    def set_wheel_velocities(self, left_radps, right_radps):
        """
        Command the left and right wheel speeds (every wheel of a side gets its side's value).

        :param left_radps: left wheel angular speed [rad/s], positive = forward.
        :param right_radps: right wheel angular speed [rad/s], positive = forward.
        :raises InvalidCommandError: for a non-finite value or |value| > max_wheel_speed; the
            command in force is then unchanged (no clamping at this API).
        """
        left = self._check_radps('left_radps', left_radps)
        right = self._check_radps('right_radps', right_radps)
        command = [0.0] * len(self._wheels)
        for i in self._left:
            command[i] = left
        for i in self._right:
            command[i] = right
        self._command_radps = tuple(command)
        self._apply()

    def set_joint_velocities(self, velocities_radps):
        """
        Command every driven wheel joint, in ``wheel_joints`` order.

        :param velocities_radps: one angular speed per joint [rad/s].
        :raises InvalidCommandError: for a wrong length, a non-finite value or |value| >
            max_wheel_speed; the command in force is then unchanged.
        """
        values = list(velocities_radps)
        if len(values) != len(self._wheels):
            raise InvalidCommandError(
                f'{len(values)} wheel velocities given, {len(self._wheels)} expected '
                f'({", ".join(self.wheel_joints)})')
        checked = tuple(self._check_radps(name, value)
                        for name, value in zip(self.wheel_joints, values))
        self._command_radps = checked
        self._apply()

    @property
    def command_radps(self):
        """The wheel speeds in force, in ``wheel_joints`` order [rad/s]."""
        return self._command_radps

    def _teleport_joints(self):
        # The wheels keep their angles; every velocity becomes 0.
        return (), self._wheels

    # ---------------------------------------------------------------- measurement
    def read(self):
        """Return a RobotReading of the driven wheels."""
        states = pybullet.getJointStates(self.body_id, self._wheels, physicsClientId=self._cid)
        positions = tuple(s[0] for s in states)
        velocities = tuple(s[1] for s in states)
        left = sum(velocities[i] for i in self._left) / len(self._left)
        right = sum(velocities[i] for i in self._right) / len(self._right)
        return RobotReading(positions, velocities, left, right)

    def joint_states(self):
        """
        Return the driven wheel joints for sensor_msgs/JointState.

        :return: (names, positions [rad], velocities [rad/s]) as tuples.
        """
        reading = self.read()
        return self.wheel_joints, reading.wheel_position_rad, reading.wheel_velocity_radps
