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
(core/sensors/sampling.py: the first step at or after each k / rate) and keeps the readings:
``fresh`` (those sampled at the last step, one per sensor) and ``latest(key)``.

Schedules have keys: ``start()`` schedules each sensor under its own name at its ``rate_hz``
(the ROS nodes); ``set_period_ms(name, ms, key)`` schedules it under another key, counted from
the current step (each Webots device: an IMU serves an InertialUnit, a Gyro and an
Accelerometer, each with its own sampling period). A sensor due under several keys at one step
is sampled once.
"""

from typing import Dict, List

from vehicle_sim.core.geometry.geodesy import GeodeticOrigin, LocalTangentPlane
from vehicle_sim.core.sensors.params import check_layer
from vehicle_sim.core.sensors.sampling import SampleSchedule, Scheduler
from vehicle_sim.core.sensors.sets import mounted
from vehicle_sim.physics.sensors.camera import CameraSensor
from vehicle_sim.physics.sensors.distance import RayDistanceSensor
from vehicle_sim.physics.sensors.inertial import GnssSensor, ImuSensor
from vehicle_sim.physics.sensors.lidar import LidarSensor
from vehicle_sim.physics.sensors.radar import RadarSensor
from vehicle_sim.physics.sensors.range_finder import RangeFinderSensor

# The physics registration: core sensor type -> its Sensor class (physics/sensors/sensor.py),
# built as cls(world, body, spec, plane); checked against the core types when imported.
SENSOR_CLASSES = {
    'lidar': LidarSensor,
    'imu': ImuSensor,
    'gnss': GnssSensor,
    'distance': RayDistanceSensor,
    'camera': CameraSensor,
    'range_finder': RangeFinderSensor,
    'radar': RadarSensor,
}
check_layer('physics SENSOR_CLASSES (physics/sensors/suite.py)', SENSOR_CLASSES)


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
            self.sensors[name] = SENSOR_CLASSES[spec.sensor_type](world, body, spec, plane)
        self._trackers = {name for name, sensor in self.sensors.items()
                          if sensor.tracks_motion}
        self._scheduler = Scheduler()
        self._sensor_of: Dict[str, str] = {}      # schedule key -> sensor name
        self._latest: Dict[str, object] = {}      # schedule key or sensor name -> reading
        self.fresh: List = []
        self._registered = False

    # ---------------------------------------------------------------- scheduling
    def start(self, names=None):
        """
        Sample sensors at their ``rate_hz`` from now on, each under its name (ROS).

        :param names: sensor names; all mounted sensors when None.
        :raises KeyError: for a sensor that is not mounted.
        """
        for name in self._check(names):
            self._schedule(name, name, SampleSchedule.from_rate(
                self.specs[name].rate_hz, self.world.time_step_s, self.world.step_count))

    def set_period_ms(self, name, period_ms, key=None):
        """
        Sample a sensor every ``period_ms`` from now on (Webots ``enable``); 0 stops it.

        :param name: the sensor.
        :param period_ms: sampling period [ms], > 0; 0 or None stops this key.
        :param key: the schedule's key (a Webots device name); the sensor's name when None.
        :raises KeyError: for a sensor that is not mounted.
        """
        self._check([name])
        key = name if key is None else key
        if not period_ms:
            self.stop(key)
            return
        self._schedule(key, name, SampleSchedule.from_period_ms(
            period_ms, self.world.time_step_s * 1000.0, self.world.step_count))

    def stop(self, key):
        """Stop a schedule (a sensor name or a key); its latest reading is kept."""
        self._scheduler.set(key, None)
        self._sensor_of.pop(key, None)
        self._update_registration()

    def scheduled(self, key):
        """Tell whether a schedule (a sensor name or a key) is running."""
        return self._scheduler.get(key) is not None

    def _check(self, names):
        names = list(self.specs) if names is None else list(names)
        for name in names:
            if name not in self.specs:
                raise KeyError(f'no mounted sensor {name!r}; mounted: '
                               f'{", ".join(self.specs) or "none"}')
        return names

    def _schedule(self, key, name, schedule):
        self._scheduler.set(key, schedule)
        self._sensor_of[key] = name
        self._update_registration()
        self._track(self.world.step_count)

    def _update_registration(self):
        active = bool(self._scheduler)
        if active and not self._registered:
            self.world.add_body(self)
        elif not active and self._registered and not self.world.closed:
            self.world.remove(self)
        self._registered = active

    def _track(self, step):
        # an IMU differentiates the velocity over the step before its sample: record it now
        if not self._trackers:
            return
        tracked = set()
        for key, name in self._sensor_of.items():
            if name in self._trackers and name not in tracked and \
                    self._scheduler.get(key).next_step == step + 1:
                self.sensors[name].track()
                tracked.add(name)

    # ---------------------------------------------------------------- sampling
    def post_step(self):
        """World hook: sample the sensors due at this step."""
        world = self.world
        step = world.step_count
        due = self._scheduler.due(step)
        fresh = []
        if due:
            time_s = world.time_s
            sampled = {}
            for key in due:
                name = self._sensor_of[key]
                if name not in sampled:
                    sampled[name] = self.sensors[name].sample(time_s)
                    self._latest[name] = sampled[name]
                    fresh.append(sampled[name])
                self._latest[key] = sampled[name]
        self.fresh = fresh
        self._track(step)

    def restart_motion(self):
        """After a reset or teleport: no sensor differentiates across the jump (IMU)."""
        for name in self._trackers:
            self.sensors[name].restart()

    def sample(self, name):
        """Sample a sensor now, whatever its schedules; return the reading (also ``latest``)."""
        self._check([name])
        reading = self.sensors[name].sample(self.world.time_s)
        self._latest[name] = reading
        return reading

    def latest(self, key):
        """Return the last reading under a key (or sensor name), None before the first."""
        return self._latest.get(key)

    def close(self):
        """Stop every schedule and leave the world's hooks."""
        for key in list(self._sensor_of):
            self._scheduler.set(key, None)
        self._sensor_of.clear()
        self._update_registration()
