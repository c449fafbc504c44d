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
URDF of a car generated from CarParams: one description for PyBullet and ROS ``robot_description``.

Frames (REP 103, FLU): the root link ``base_link`` lies on the ground below the rear-axle centre
(Autoware). The Webots vehicle frame (origin at the rear-axle centre) is ``base_link`` raised by
the rear tyre radius, so every CarParams position (centre of mass, collision boxes, wheel anchors)
is written with ``z + rearTireRadius``.

Per wheel (prefix ``front_right``, ``front_left``, ``rear_right``, ``rear_left``):
``<w>_suspension`` prismatic along +z (position = wheel travel upwards relative to the body, i.e.
compression positive), front wheels ``<w>_steer`` revolute about -z (positive = RIGHT, Webots
sign), then ``<w>_wheel`` continuous about +y (positive = forward rolling on both sides, as in
Webots). Joint position 0 of the suspension is the static equilibrium: see docs/physics.md.
"""

import math
from xml.sax.saxutils import escape

import numpy as np

from vehicle_sim.core.car.vehicle_io import WHEEL_NAMES

# Intermediate links (suspension carrier, steering knuckle): small but not tiny, so the
# articulated-body solver stays well conditioned next to 5-150 kg wheels.
KNUCKLE_MASS_KG = 0.5
KNUCKLE_INERTIA_KGM2 = 0.005
# Suspension travel either side of the static position (joint limit).
SUSPENSION_TRAVEL_M = 0.25
# Steering motor speed limit of Webots' default RotationalMotor (Webots' RotationalMotor).
STEER_MAX_VELOCITY_RADPS = 10.0


def wheel_is_front(index):
    """Tell whether a wheel index is a front wheel (Webots indices 0 FR and 1 FL)."""
    return index < 2


def wheel_anchor_m(params, index):
    """
    Wheel joint anchor in the Webots vehicle frame (FLU, origin at the rear-axle centre).

    :param params: CarParams.
    :param index: wheel index (FR, FL, RR, RL).
    :return: (x, y, z) [m]: front (wheelbase, -/+trackFront/2, 0), rear (0, -/+trackRear/2, 0).
    """
    front = wheel_is_front(index)
    track = params.track_front_m if front else params.track_rear_m
    side = -1.0 if index % 2 == 0 else 1.0   # right wheels at -y
    return (params.wheelbase_m if front else 0.0, side * track / 2.0, 0.0)


def joint_names(prefix=''):
    """
    Names of the movable joints of the car URDF, grouped by kind.

    :param prefix: string put in front of every name (e.g. a robot namespace ``car1/``).
    :return: dict with keys 'wheel' (4, FR FL RR RL), 'steer' (2, right left), 'suspension' (4).
    """
    return {
        'wheel': tuple(f'{prefix}{w}_wheel' for w in WHEEL_NAMES),
        'steer': tuple(f'{prefix}{w}_steer' for w in WHEEL_NAMES[:2]),
        'suspension': tuple(f'{prefix}{w}_suspension' for w in WHEEL_NAMES),
    }


def box_inertia_kgm2(params):
    """
    Chassis inertia about its centre of mass: the preset's, or computed from the collision boxes.

    Webots computes a missing inertia from the bounding objects; here the boxes are given a
    uniform density (total mass = ``mass``), each box's own inertia (rotated by its pitch) is
    moved to the boxes' common centroid (parallel axes), and the result is used at the
    preset's centre of mass.

    :return: (ixx, iyy, izz, ixy, ixz, iyz) [kg*m^2].
    """
    if params.inertia_kgm2 is not None:
        return tuple(params.inertia_kgm2)
    volumes = [b.size_m[0] * b.size_m[1] * b.size_m[2] for b in params.collision_boxes]
    total = sum(volumes)
    centres = np.array([b.position_m for b in params.collision_boxes])
    centroid = (centres * np.array(volumes)[:, None]).sum(axis=0) / total
    tensor = np.zeros((3, 3))
    for box, volume in zip(params.collision_boxes, volumes):
        mass = params.mass_kg * volume / total
        lx, ly, lz = box.size_m
        local = np.diag([ly ** 2 + lz ** 2, lx ** 2 + lz ** 2, lx ** 2 + ly ** 2]) * mass / 12.0
        c, s = math.cos(box.pitch_rad), math.sin(box.pitch_rad)
        rot = np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])
        d = np.array(box.position_m) - centroid
        tensor += rot @ local @ rot.T + mass * (np.dot(d, d) * np.eye(3) - np.outer(d, d))
    return tuple(float(tensor[i, j]) for i, j in ((0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)))


def wheel_inertia_kgm2(mass_kg, radius_m, width_m):
    """Solid-cylinder inertia (ixx, iyy, izz) of a wheel spinning about y [kg*m^2]."""
    radial = mass_kg * (3.0 * radius_m ** 2 + width_m ** 2) / 12.0
    return (radial, 0.5 * mass_kg * radius_m ** 2, radial)


def num(value):
    """Format a number for a URDF attribute."""
    return f'{float(value):.9g}'


def vec(values):
    """Format a vector for a URDF attribute."""
    return ' '.join(num(v) for v in values)


def inertial(mass, ixx, iyy, izz, ixy=0.0, ixz=0.0, iyz=0.0, xyz=(0.0, 0.0, 0.0)):
    return (f'    <inertial>\n      <origin xyz="{vec(xyz)}" rpy="0 0 0"/>\n'
            f'      <mass value="{num(mass)}"/>\n'
            f'      <inertia ixx="{num(ixx)}" ixy="{num(ixy)}" ixz="{num(ixz)}" iyy="{num(iyy)}" '
            f'iyz="{num(iyz)}" izz="{num(izz)}"/>\n    </inertial>\n')


def geometry_block(tag, xyz, rpy, geometry):
    return (f'    <{tag}>\n      <origin xyz="{vec(xyz)}" rpy="{vec(rpy)}"/>\n'
            f'      <geometry>{geometry}</geometry>\n    </{tag}>\n')


def _knuckle(name):
    i = KNUCKLE_INERTIA_KGM2
    return f'  <link name="{name}">\n' + inertial(KNUCKLE_MASS_KG, i, i, i) + '  </link>\n'


def _joint(name, kind, parent, child, xyz, axis, limit='', dynamics=''):
    return (f'  <joint name="{name}" type="{kind}">\n    <parent link="{parent}"/>\n'
            f'    <child link="{child}"/>\n    <origin xyz="{vec(xyz)}" rpy="0 0 0"/>\n'
            f'    <axis xyz="{vec(axis)}"/>\n{limit}{dynamics}  </joint>\n')


def car_urdf(params, name=None, prefix='', wheel_shape='sphere'):
    """
    Generate the URDF of a car.

    :param params: CarParams.
    :param name: robot name; the preset's model name when None.
    :param prefix: put in front of every link and joint name (e.g. ``'car1/'``); '' by default.
    :param wheel_shape: wheel collision shape: 'sphere' (radius; default) or 'cylinder'
        (radius, width; Webots' VehicleWheel). Bullet's cylinder-plane contact wanders across
        the tread and steers the car off a straight line (20-120 m of drift in a 0-100 km/h run
        of the two-wheel-drive presets), so the sphere is the default. The visual is always
        the cylinder.
    :return: URDF text.
    :raises ValueError: for an unknown wheel_shape.
    """
    if wheel_shape not in ('cylinder', 'sphere'):
        raise ValueError(f"wheel_shape {wheel_shape!r}: must be 'cylinder' or 'sphere'")
    lift = params.rear_tire_radius_m     # base_link -> Webots vehicle frame
    base = f'{prefix}base_link'
    parts = [f'<?xml version="1.0"?>\n<robot name="{escape(name or params.model)}">\n',
             f'  <link name="{base}">\n']
    com = params.center_of_mass_m
    parts.append(inertial(params.mass_kg, *box_inertia_kgm2(params),
                           xyz=(com[0], com[1], com[2] + lift)))
    for box in params.collision_boxes:
        x, y, z = box.position_m
        geometry = f'<box size="{vec(box.size_m)}"/>'
        for tag in ('visual', 'collision'):
            parts.append(geometry_block(tag, (x, y, z + lift), (0.0, box.pitch_rad, 0.0),
                                         geometry))
    parts.append('  </link>\n')
    names = joint_names(prefix)
    for index, wheel in enumerate(WHEEL_NAMES):
        front = wheel_is_front(index)
        anchor = wheel_anchor_m(params, index)
        susp_link = f'{prefix}{wheel}_suspension_link'
        parts.append(_knuckle(susp_link))
        travel = SUSPENSION_TRAVEL_M
        spring = (params.suspension_front_spring_n_per_m if front
                  else params.suspension_rear_spring_n_per_m)
        damper = (params.suspension_front_damping_ns_per_m if front
                  else params.suspension_rear_damping_ns_per_m)
        parts.append(_joint(
            names['suspension'][index], 'prismatic', base, susp_link,
            (anchor[0], anchor[1], anchor[2] + lift), (0.0, 0.0, 1.0),
            f'    <limit lower="{num(-travel)}" upper="{num(travel)}" effort="1e6" '
            f'velocity="100"/>\n',
            f'    <dynamics damping="{num(damper)}" friction="0"/>\n'))
        # The spring has no URDF field; it is realised by the body's joint motor
        # (docs/physics.md). spring [N/m] kept in a comment for readers of the description.
        parts.append(f'  <!-- {names["suspension"][index]}: spring {num(spring)} N/m -->\n')
        carrier = susp_link
        if front:
            steer_link = f'{prefix}{wheel}_steer_link'
            parts.append(_knuckle(steer_link))
            parts.append(_joint(
                names['steer'][index], 'revolute', susp_link, steer_link, (0.0, 0.0, 0.0),
                (0.0, 0.0, -1.0),
                f'    <limit lower="{num(params.min_steering_angle_rad)}" '
                f'upper="{num(params.max_steering_angle_rad)}" '
                f'effort="{num(params.max_steering_torque_nm)}" '
                f'velocity="{num(STEER_MAX_VELOCITY_RADPS)}"/>\n'))
            carrier = steer_link
        radius = params.front_tire_radius_m if front else params.rear_tire_radius_m
        width = params.front_tire_width_m if front else params.rear_tire_width_m
        mass = params.wheel_mass_kg(front)
        wheel_link = f'{prefix}{wheel}_wheel_link'
        ixx, iyy, izz = wheel_inertia_kgm2(mass, radius, width)
        cylinder = f'<cylinder radius="{num(radius)}" length="{num(width)}"/>'
        collision = cylinder if wheel_shape == 'cylinder' else f'<sphere radius="{num(radius)}"/>'
        parts.append(f'  <link name="{wheel_link}">\n' + inertial(mass, ixx, iyy, izz))
        for tag, geometry in (('visual', cylinder), ('collision', collision)):
            parts.append(geometry_block(tag, (0.0, 0.0, 0.0), (math.pi / 2, 0.0, 0.0),
                                         geometry))
        parts.append('  </link>\n')
        parts.append(_joint(
            names['wheel'][index], 'continuous', carrier, wheel_link, (0.0, 0.0, 0.0),
            (0.0, 1.0, 0.0), '',
            f'    <dynamics damping="{num(params.wheels_damping_nms_per_rad)}"/>\n'))
    parts.append('</robot>\n')
    return ''.join(parts)
