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
Sensor links in the published robot description (URDF), never in the simulated body.

Each mounted sensor becomes a link ``<p><name>`` on a fixed joint ``<p><name>_joint`` from
``<p>base_link`` at its mount pose, and a camera also ``<p><name>_optical`` (rpy -pi/2, 0,
-pi/2). The links have no inertial: loaded into PyBullet they would each weigh 1 kg (PyBullet's
default for a link without mass), so the body a World simulates is always generated without
them (CarBody, DiffRobotBody), and only ``robot_description`` carries them.
"""

from xml.sax.saxutils import escape

from vehicle_sim.core.geometry.frames import OPTICAL_RPY
from vehicle_sim.core.sensors.sets import mounted
from vehicle_sim.physics.urdf import vec

_END = '</robot>'


def _fixed_joint(name, parent, child, xyz, rpy):
    return (f'  <link name="{escape(child)}"/>\n'
            f'  <joint name="{escape(name)}" type="fixed">\n'
            f'    <parent link="{escape(parent)}"/>\n    <child link="{escape(child)}"/>\n'
            f'    <origin xyz="{vec(xyz)}" rpy="{vec(rpy)}"/>\n  </joint>\n')


def sensor_links_urdf(sensors, prefix=''):
    """
    Return the URDF elements (links and fixed joints) of the mounted sensors.

    :param sensors: SensorSpecs (unmounted ones are skipped).
    :param prefix: frame prefix of the vehicle (``'car1/'``).
    """
    base = f'{prefix}base_link'
    parts = []
    for spec in mounted(sensors):
        frame = spec.frame_id(prefix)
        parts.append(_fixed_joint(f'{frame}_joint', base, frame, spec.pose.xyz, spec.pose.rpy))
        optical = spec.optical_frame_id(prefix)
        if optical is not None:
            parts.append(_fixed_joint(f'{optical}_joint', frame, optical, (0.0, 0.0, 0.0),
                                      OPTICAL_RPY))
    return ''.join(parts)


def with_sensor_links(urdf, sensors, prefix=''):
    """
    Return a robot description with the mounted sensors' links added.

    :param urdf: the body's URDF (car_urdf, robot_urdf) with the same ``prefix``.
    :param sensors: the vehicle's SensorSpecs.
    :param prefix: frame prefix of the vehicle.
    :raises ValueError: when ``urdf`` has no closing robot tag.
    """
    links = sensor_links_urdf(sensors, prefix)
    if not links:
        return urdf
    cut = urdf.rfind(_END)
    if cut < 0:
        raise ValueError('the URDF has no </robot> end tag')
    return urdf[:cut] + links + urdf[cut:]
