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
An RGB picture from a chase camera behind a vehicle, by PyBullet's CPU renderer.

The camera sits where core/geometry/chase_camera.py puts the GUI's chase camera (behind and above
the vehicle, looking along its heading), so ``render_mode='rgb_array'`` of the Gym environment
shows what the window would show, without a window (ER_TINY_RENDERER works in DIRECT worlds).
"""

import math

import numpy as np
import pybullet

from vehicle_sim.core.geometry.chase_camera import chase_view, ChaseSettings, eye_position
from vehicle_sim.physics.sensors.render import LIGHT_DIRECTION

VERTICAL_FOV_DEG = 60.0
NEAR_M = 0.1
FAR_M = 200.0


class ChaseImage:
    """
    Renders a vehicle body from behind.

    :param world: the World.
    :param body: the vehicle body followed (``pose()``, ``yaw_rad()``).
    :param width: picture width [px], >= 1.
    :param height: picture height [px], >= 1.
    :param settings: distance, pitch, target height (core ChaseSettings; no heading lag here).
    """

    def __init__(self, world, body, width, height, settings=None):
        for name, value in (('width', width), ('height', height)):
            if isinstance(value, bool) or not isinstance(value, int) or value < 1:
                raise ValueError(f'chase image {name} = {value!r}: must be an integer >= 1')
        self.world = world
        self.body = body
        self.width = width
        self.height = height
        self.settings = settings or ChaseSettings(heading_lag_s=0.0)
        world.show_ground()
        self._projection = pybullet.computeProjectionMatrixFOV(
            VERTICAL_FOV_DEG, width / height, NEAR_M, FAR_M, physicsClientId=world.client_id)

    def render(self):
        """Return the picture now: (height, width, 3) uint8, rows top to bottom."""
        pose = self.body.pose()
        view = chase_view(pose[:3], self.body.yaw_rad(), self.settings)
        eye = eye_position(view)
        if not all(math.isfinite(v) for v in eye):
            return np.zeros((self.height, self.width, 3), dtype=np.uint8)
        cid = self.world.client_id
        self.world.prepare_render()       # lamps made, placed bodies (traffic) where they are
        matrix = pybullet.computeViewMatrix(list(eye), list(view.target_m), [0.0, 0.0, 1.0],
                                            physicsClientId=cid)
        _, _, rgba, _, _ = pybullet.getCameraImage(
            self.width, self.height, matrix, self._projection, lightDirection=LIGHT_DIRECTION,
            renderer=pybullet.ER_TINY_RENDERER, flags=pybullet.ER_NO_SEGMENTATION_MASK,
            physicsClientId=cid)
        rgb = np.asarray(rgba, dtype=np.uint8).reshape(self.height, self.width, 4)[:, :, :3]
        return np.ascontiguousarray(rgb)
