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
The range finder (a depth camera): the metric depth of the world's renderer from the mount.

It asks the world's renderer (physics/sensors/render.py) for the View of its size, vertical
field of view and clip planes (near = ``min_range``, far = ``max_range``), so a camera with the
same view at the same mount and step costs no second render. The depth is Webots'
RangeFinder's: the distance of each pixel's surface from the image plane along the optical
axis (planar depth, not the length of the pixel's ray), from Bullet's depth buffer; nothing
drawn within ``max_range`` reads +inf. Gaussian noise of sigma ``noise`` [m] (seeded as the
other range sensors) is added to the finite depths; a noisy depth beyond ``max_range`` then
reads +inf, one under ``min_range`` -inf (REP 118). The frame and intrinsics are those of a
camera of the same size and fov (the optical frame ``<p><name>_optical``).
"""

import numpy as np

from vehicle_sim.core.sensors.noise import GaussianNoise
from vehicle_sim.core.sensors.readings import camera_matrices, DepthReading
from vehicle_sim.physics.sensors.render import View
from vehicle_sim.physics.sensors.sensor import Sensor


class RangeFinderSensor(Sensor):
    """
    A range finder on a vehicle body.

    :param world: the World.
    :param body: the vehicle body.
    :param spec: core RangeFinderSpec.
    :param plane: unused (the one constructor shape of physics/sensors/sensor.py).
    """

    def __init__(self, world, body, spec, plane=None):
        super().__init__(world, body, spec, plane)
        world.show_ground()        # the same scene as a camera's, so that they share renders
        self.view = View(spec.width, spec.height, spec.vertical_fov_rad, spec.min_range_m,
                         spec.max_range_m)
        self._k, self._p = camera_matrices(*spec.intrinsics)
        self._noise = GaussianNoise(spec.noise_m, spec.seed, spec.name)

    def sample(self, time_s):
        """Render (or reuse this step's render of) the view now; return a DepthReading."""
        spec = self.spec
        position, rotation, _ = self.mount.world_frame()
        depth = self.world.renderer.render(self.view, position, rotation).depth_m
        if self._noise:
            finite = np.isfinite(depth)
            noisy = self._noise.add(depth[finite])
            depth = depth.copy()
            depth[finite] = np.where(noisy > spec.max_range_m, np.inf,
                                     np.where(noisy < spec.min_range_m, -np.inf, noisy))
        return DepthReading(spec.name, time_s, spec.width, spec.height, depth, self._k, self._p,
                            spec.min_range_m, spec.max_range_m)
