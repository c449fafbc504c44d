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
A vehicle's sensors and collision monitor, with what they produced since it was last read.

The ROS nodes publish after each basic step, but a reading must not be lost when they publish
less often (or after several steps): the feed is a world ``post_step`` hook, registered after
the suite's and the monitor's (so it runs after theirs), that keeps every step's fresh readings
and collision events until :meth:`SensorFeed.take`. A feed with no mounted sensor and no monitor
registers nothing: a vehicle without sensors steps as fast as before.
"""

from vehicle_sim.core.geometry.geodesy import GeodeticOrigin
from vehicle_sim.physics.sensors.collisions import CollisionMonitor
from vehicle_sim.physics.sensors.suite import SensorSuite


class SensorFeed:
    """
    The mounted sensors (each at its ``rate_hz``) and the collision monitor of one vehicle.

    :param world: the World.
    :param body: the vehicle body (a SimulatedCar's ``body``, a DiffRobotBody).
    :param specs: the vehicle's SensorSpecs; the mounted (``enabled``) ones are sampled.
    :param origin: the world's GeodeticOrigin (GNSS).
    :param collisions: watch the vehicle's contacts (CollisionMonitor); without a body to hit
        besides the ground, leave it off (it reads the contacts every step).
    """

    def __init__(self, world, body, specs, origin=GeodeticOrigin(), collisions=True):
        self.world = world
        self.monitor = CollisionMonitor(world, body) if collisions else None
        self.suite = SensorSuite(world, body, specs, origin)
        self.suite.start()
        self._samples = []
        self._events = []
        self.active = bool(self.suite.specs) or self.monitor is not None
        if self.active:
            world.add_body(self)

    @property
    def specs(self):
        """{name: SensorSpec} of the mounted sensors."""
        return self.suite.specs

    def post_step(self):
        """World hook: keep this step's readings and collision events."""
        fresh = self.suite.fresh
        if fresh:
            self._samples.append((fresh[0].time_s, {reading.name: reading for reading in fresh}))
        monitor = self.monitor
        if monitor is not None and monitor.fresh:
            self._events.extend(monitor.fresh)

    def take(self):
        """
        Return what was produced since the last call, oldest first, and forget it.

        :return: (samples, events): samples a list of (time_s, {sensor name: reading}), one per
            step that sampled a sensor (the readings carry that step's time); events the
            CollisionEvents.
        """
        samples, events = self._samples, self._events
        if samples:
            self._samples = []
        if events:
            self._events = []
        return samples, events

    def restart_motion(self):
        """After the body was reset or teleported: see SensorSuite.restart_motion."""
        self.suite.restart_motion()

    def close(self):
        """Stop sampling and watching, and leave the world's hooks."""
        self.suite.close()
        if self.monitor is not None:
            self.monitor.close()
        if not self.world.closed:
            self.world.remove(self)
