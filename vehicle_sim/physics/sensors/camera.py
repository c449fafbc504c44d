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
The camera: a colour frame of the world's renderer (physics/sensors/render.py) from the mount.

The mount's x axis is the viewing direction and its z axis is up in the picture. PyBullet's
projection takes the VERTICAL field of view; the spec gives the horizontal one in radians, so
fov_v = 2 atan(tan(fov_h / 2) * height / width) (square pixels). The image rows run top to
bottom, the columns left to right; its frame is the optical one (z forward, x right, y down) and
the intrinsics are those of CameraSpec.intrinsics. The ground gets a visual as soon as a camera
exists (World.show_ground). A 320 x 240 frame costs several milliseconds, so cameras are off
unless mounted. With segmentation or recognition the frame is rendered with its body mask, which
physics/sensors/recognition.py turns into the label and object images and the objects.
"""

from vehicle_sim.core.sensors.readings import camera_matrices, CameraReading
from vehicle_sim.physics.sensors.recognition import recognise, segment
from vehicle_sim.physics.sensors.render import View
from vehicle_sim.physics.sensors.sensor import Sensor


class CameraSensor(Sensor):
    """
    An RGB camera on a vehicle body.

    :param world: the World.
    :param body: the vehicle body.
    :param spec: core CameraSpec.
    :param plane: unused (the one constructor shape of physics/sensors/sensor.py).
    """

    def __init__(self, world, body, spec, plane=None):
        super().__init__(world, body, spec, plane)
        world.show_ground()
        self.view = View(spec.width, spec.height, spec.vertical_fov_rad, spec.near_m, spec.far_m)
        self._k, self._p = camera_matrices(*spec.intrinsics)

    def sample(self, time_s):
        """Render a frame now; return a CameraReading stamped ``time_s``."""
        spec = self.spec
        position, rotation, _ = self.mount.world_frame()
        frame = self.world.renderer.render(self.view, position, rotation, mask=spec.masked)
        if not spec.masked:
            return CameraReading(spec.name, time_s, spec.width, spec.height, frame.rgb, self._k,
                                 self._p)
        semantic, instance = segment(self.world, frame, self.mount.body.body_id)
        objects = (recognise(self.world, spec, frame, semantic, instance, position, rotation)
                   if spec.recognition else None)
        return CameraReading(spec.name, time_s, spec.width, spec.height, frame.rgb, self._k,
                             self._p, semantic=semantic, instance=instance, objects=objects)
