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
The simulation a scenario runs in without ROS, and the handle of each of its vehicles.

- :class:`LocalSim`: the World, its obstacles, cars (SimulatedCar) and robots (DiffRobotBody),
  nothing on the network. Scripted commands and in-process controllers run here.
- :class:`VehicleHandle`: one vehicle of a scenario, as the runner, the criteria and the Gymnasium
  environment (which builds on this module, never on ROS) read it.

The same world served over ROS is :class:`~vehicle_sim.scenarios.served_sim.ServedSim`. Both
build their world through the scene builder (physics/scene.py; the served one inside the nodes),
give a :class:`VehicleHandle` per vehicle name and call a ``director`` (the runner's per-step
hooks) from the world's step.
"""

import struct

from vehicle_sim.core.geometry.angles import yaw_from_quaternion
from vehicle_sim.physics.scene import build_scene
from vehicle_sim.scenarios.criteria import Sample
from vehicle_sim.scenarios.scene import map_walls

# One odometry row: time, pose (x, y, z, qx, qy, qz, qw), linear and angular velocity (world).
ODOMETRY_ROW = struct.Struct('<14d')


class VehicleHandle:
    """
    One vehicle of a scenario: its body (the VehicleBody contract), and a car's SimulatedCar.

    :param name: its name in the scenario.
    :param body: its VehicleBody (CarBody, DiffRobotBody).
    :param car: the SimulatedCar of a car; None for a robot.
    :param sensors: its SensorSpecs (cars; the in-process controller's devices).
    """

    def __init__(self, name, body, car=None, sensors=()):
        self.name = name
        self.body = body
        self.car = car
        self.sensors = sensors

    @property
    def is_car(self):
        return self.car is not None

    @property
    def outline(self):
        """Return its footprint rectangle in base_link (core Outline), from its parameters."""
        return self.body.outline

    def odometry_row(self, time_s):
        """Return the packed ground-truth odometry row (ODOMETRY_ROW) at ``time_s``."""
        pose = self.body.pose()
        linear, angular = self.body.velocity()
        return ODOMETRY_ROW.pack(time_s, *pose, *linear, *angular)

    def sample(self, time_s):
        """Return the criteria's Sample: position, heading, forward speed."""
        x, y, _, qx, qy, qz, qw = self.body.pose()
        return Sample(time_s, x, y, yaw_from_quaternion(qx, qy, qz, qw),
                      self.body.forward_speed_mps())


def _seeded(sensors, seed):
    from dataclasses import replace
    return tuple(replace(spec, seed=seed) for spec in sensors)


class LocalSim:
    """
    The scenario's world without ROS.

    :param spec: ScenarioSpec.
    :param director: registered first, so its ``pre_step`` (scripted commands, actors) acts in
        the same step and its ``post_step`` sees the step's result.
    :param seed: the run's seed (every sensor's noise seed).
    :param gui: open PyBullet's window with a chase camera on the first vehicle.
    """

    served = False

    def __init__(self, spec, director, seed, gui=False):
        self.scene = scene = build_scene(spec.world, time_step_s=spec.time_step_ms / 1000.0,
                                         gui=gui, robots=spec.robots, hooks=(director,))
        self.world = world = scene.world
        self.lanes = scene.lanes        # the lane criteria's lane map (None: none)
        self.walls = map_walls(scene)   # an occupancy map's walls (Footprints)
        self.vehicles = {
            name: VehicleHandle(name, built.body, built.car,
                                _seeded(built.spec.sensors, seed) if built.car is not None else ())
            for name, built in scene.vehicles.items()}
        if gui:
            try:
                from vehicle_sim.physics.gui import ChaseCamera
                ChaseCamera(world, [built.vehicle for built in scene.vehicles.values()])
            except BaseException:
                world.close()
                raise

    @property
    def traffic(self):
        """The world's traffic (physics TrafficBodies), or None."""
        return self.scene.parts.get('traffic')

    @property
    def signals(self):
        """The world's signals (physics WorldSignals: ``controller``), or None."""
        return self.scene.parts.get('signals')

    def step(self):
        """Advance one basic step; return the time [s]."""
        return self.world.step()

    def spin(self):
        """Nothing to serve."""

    def close(self):
        self.world.close()
