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
The objects around the ego in the Gym environment: the ``objects`` observation key.

Present when the option ``objects`` asks for it (true: the default table; a mapping: its keys,
core/learning/objects_table.py ``OBJECTS_TABLE_SPECS``): :func:`objects_part` is in
observations.PART_FACTORIES and returns None otherwise.

- ``objects``: (count, 7) float32 in [-1, 1]: the nearest traffic bodies and obstacles, one
  row each (presence, x, y, vx, vy, cos_h, sin_h, relative to the ego, normalised:
  core/learning/objects_table.py), read as ``/perception/object_recognition/objects``
  carries them: the traffic's objects now and the world's obstacles where they are.
"""

import numpy as np

from vehicle_sim.core.geometry.angles import yaw_from_quaternion
from vehicle_sim.core.learning.objects_table import Neighbour, objects_table, ObjectsTableSpec
from vehicle_sim.core.traffic.objects import obstacle_objects

OBJECTS = 'objects'


def objects_spec(option, source):
    """Return the ObjectsTableSpec of the ``objects`` option (None/False: None)."""
    if option is None or option is False:
        return None
    if option is True:
        return ObjectsTableSpec()
    return ObjectsTableSpec.from_dict(option, f"{source}: option 'objects'")


class ObjectsPart:
    """
    The ``objects`` key, read from the scene's traffic and obstacles at each observation.

    :param scene: the Scene (its ``traffic`` part and obstacles are read).
    :param body: the ego's body.
    :param spec: the table's ObjectsTableSpec.
    """

    def __init__(self, scene, body, spec):
        self.scene = scene
        self.world = scene.world
        self.body = body
        self.spec = spec
        self._table = None

    def spaces(self):
        return {OBJECTS: (-1.0, 1.0, self.spec.shape, np.float32)}

    def reset(self):
        self._table = None

    def _obstacle_pose(self, name):
        (position, (qx, qy, qz, qw)), _, _ = self.world.body_state(self.world.obstacles[name])
        return (*position, yaw_from_quaternion(qx, qy, qz, qw))

    def neighbours(self):
        """Return the traffic's objects and the obstacles now, as Neighbours."""
        traffic = self.scene.parts.get('traffic')
        found = [] if traffic is None else [Neighbour(o.x_m, o.y_m, o.yaw_rad, o.speed_mps)
                                            for o in traffic.objects(paths=False)]
        found.extend(Neighbour(o.x_m, o.y_m, o.yaw_rad) for o in obstacle_objects(
            self.scene.spec.obstacles, self._obstacle_pose))
        return found

    def read(self, out):
        x, y, z, qx, qy, qz, qw = self.body.pose()
        yaw = yaw_from_quaternion(qx, qy, qz, qw)
        (vx, vy, _), _ = self.world.base_link_velocity(self.body.body_id, (x, y, z))
        forward = vx * np.cos(yaw) + vy * np.sin(yaw)
        left = -vx * np.sin(yaw) + vy * np.cos(yaw)
        self._table = objects_table(self.spec, x, y, yaw, forward, left, self.neighbours())
        out[OBJECTS] = self._table

    def last_table(self):
        """Return the table of the last observation (read now if there was none)."""
        if self._table is None:
            self.read({})
        return self._table


def objects_part(ego):
    """Return the ego's ObjectsPart when its options ask for one, else None (PART_FACTORIES)."""
    spec = objects_spec(ego.options['objects'], 'vehicle_sim/Drive-v0')
    return None if spec is None else ObjectsPart(ego.scene, ego.body, spec)
