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
The contract of a simulated sensor: one constructor shape, ``sample``, motion tracking.

Every sensor class is built as ``cls(world, body, spec, plane)`` by SensorSuite, whatever its
type, and registered under its core type name in ``SENSOR_CLASSES`` (suite.py). A sensor that
differentiates motion over the step before a sample (the IMU) sets ``tracks_motion`` and
overrides ``track`` and ``restart``; the others inherit no-ops.
"""

from vehicle_sim.core.geometry.geodesy import LocalTangentPlane
from vehicle_sim.physics.sensors.mount import Mount


class Sensor:
    """
    A sensor of one core SensorSpec on a vehicle body.

    :param world: the World.
    :param body: the vehicle body (CarBody, DiffRobotBody).
    :param spec: the core SensorSpec of the sensor's type.
    :param plane: the world's LocalTangentPlane (geodetic readings); None = the default
        geodetic origin.
    """

    tracks_motion = False

    def __init__(self, world, body, spec, plane=None):
        self.world = world
        self.spec = spec
        self.mount = Mount(body, spec.pose)
        self.plane = plane if plane is not None else LocalTangentPlane()

    def sample(self, time_s):
        """Return the reading (core/sensors/readings.py) of the state now, stamped ``time_s``."""
        raise NotImplementedError

    def track(self):
        """Record what the next sample differentiates (``tracks_motion`` sensors)."""

    def restart(self):
        """After a reset or teleport: differentiate nothing across the jump."""
