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
The sensors of one vehicle: built from its mounted SensorSpecs, sampled after world steps.

The suite registers a ``post_step`` hook with the World only while a sensor is scheduled, so a
vehicle without sensors costs nothing. After each basic step n it samples the sensors due at n
(core/sampling.py: the first step at or after each k / rate) and keeps the readings:
``fresh`` (those of the last step) and ``latest(name)``.

Two ways to schedule: ``start()`` at each sensor's ``rate_hz`` (the ROS nodes), or
``set_period_ms(name, ms)`` (Webots ``enable(samplingPeriod)``), counted from the current step.
"""

from typing import Dict, List

from vehicle_sim.core.geodesy import GeodeticOrigin, LocalTangentPlane
from vehicle_sim.core.sampling import SampleSchedule, Scheduler
from vehicle_sim.core.sensor_sets import mounted
from vehicle_sim.physics.sensors.camera import CameraSensor
from vehicle_sim.physics.sensors.distance import DistanceSensor
from vehicle_sim.physics.sensors.inertial import GnssSensor, ImuSensor
from vehicle_sim.physics.sensors.lidar import LidarSensor

SENSOR_CLASSES = {
    'lidar': LidarSensor,
    'imu': ImuSensor,
    'gnss': GnssSensor,
    'distance': DistanceSensor,
    'camera': CameraSensor,
}


class SensorSuite:
    """
    The mounted sensors of a vehicle body.

    :param world: the World.
    :param body: the vehicle body (CarBody, DiffRobotBody; a SimulatedCar's ``body``).
    :param specs: the vehicle's SensorSpecs; only the mounted (``enabled``) ones are built.
    :param origin: the world's GeodeticOrigin (GNSS).
    """

    def __init__(self, world, body, specs, origin=GeodeticOrigin()):
        self.world = world
        self.body = body
        self.specs = {spec.name: spec for spec in mounted(specs)}
        plane = LocalTangentPlane(origin)
        self.sensors = {}
        for name, spec in self.specs.items():
            cls = SENSOR_CLASSES[spec.sensor_type]
            self.sensors[name] = (cls(world, body, spec, plane) if cls is GnssSensor
                                  else cls(world, body, spec))
        self._trackers = {name: s for name, s in self.sensors.items() if hasattr(s, 'track')}
        self._scheduler = Scheduler()
        self._latest: Dict[str, object] = {}
        self.fresh: List = []
        self._registered = False

    # ---------------------------------------------------------------- scheduling
    def start(self, names=None):
        """
        Sample sensors at their ``rate_hz`` from now on (ROS).

        :param names: sensor names; all mounted sensors when None.
        """
        for name in self._names(names):
            self._schedule(name, SampleSchedule.from_rate(
                self.specs[name].rate_hz, self.world.time_step_s, self.world.step_count))

    def set_period_ms(self, name, period_ms):
        """
        Sample a sensor every ``period_ms`` from now on (Webots ``enable``); 0 stops it.

        :raises KeyError: for an unknown sensor.
        """
        self._names([name])
        if not period_ms:
            self.stop(name)
            return
        self._schedule(name, SampleSchedule.from_period_ms(
            period_ms, self.world.time_step_s * 1000.0, self.world.step_count))

    def stop(self, name):
        """Stop sampling a sensor (its latest reading is kept)."""
        self._scheduler.set(name, None)
        self._update_registration()

    def scheduled(self, name):
        """Tell whether a sensor is being sampled."""
        return self._scheduler.get(name) is not None

    def _names(self, names):
        names = list(self.specs) if names is None else list(names)
        for name in names:
            if name not in self.specs:
                raise KeyError(f'no mounted sensor {name!r}; mounted: '
                               f'{", ".join(self.specs) or "none"}')
        return names

    def _schedule(self, name, schedule):
        self._scheduler.set(name, schedule)
        self._track_if_due_next(name, schedule, self.world.step_count)
        self._update_registration()

    def _update_registration(self):
        active = bool(self._scheduler)
        if active and not self._registered:
            self.world.add_body(self)
        elif not active and self._registered and not self.world.closed:
            self.world.remove(self)
        self._registered = active

    def _track_if_due_next(self, name, schedule, step):
        tracker = self._trackers.get(name)
        if tracker is not None and schedule.next_step == step + 1:
            tracker.track()

    # ---------------------------------------------------------------- sampling
    def post_step(self):
        """World hook: sample the sensors due at this step."""
        world = self.world
        step = world.step_count
        due = self._scheduler.due(step)
        if due:
            time_s = world.time_s
            fresh = [self._take(name, time_s) for name in due]
        else:
            fresh = []
        self.fresh = fresh
        for name in self._trackers:
            schedule = self._scheduler.get(name)
            if schedule is not None:
                self._track_if_due_next(name, schedule, step)

    def _take(self, name, time_s):
        reading = self.sensors[name].sample(time_s)
        self._latest[name] = reading
        return reading

    def sample(self, name):
        """Sample a sensor now, whatever its schedule; return the reading (also ``latest``)."""
        self._names([name])
        return self._take(name, self.world.time_s)

    def latest(self, name):
        """Return the last reading of a sensor, or None before its first sample."""
        return self._latest.get(name)

    def close(self):
        """Stop every sensor and leave the world's hooks."""
        for name in list(self.specs):
            self._scheduler.set(name, None)
        self._update_registration()
