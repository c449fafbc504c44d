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

"""A simulated car: the core CarLogic driving a PyBullet CarBody inside a World."""

from vehicle_sim.core.car.logic import CarLogic
from vehicle_sim.core.car.vehicle_io import Measurement
from vehicle_sim.physics.car_body import CarBody


class SimulatedCar:
    """
    CarLogic + CarBody, stepped by the World.

    Each world step, before the physics: read the joints, run the driver step (Webots'
    §3.1) with the time before the step, and apply the resulting commands.
    """

    drives_body = True      # the World counts it as the vehicle of ``body`` (world.py)

    def __init__(self, world, params, position=(0.0, 0.0, 0.0), name=None):
        """
        Place a car in the world.

        :param world: the World (several cars and robots may share it).
        :param params: CarParams.
        :param position: (x [m], y [m], yaw [rad]) on the ground, or a full pose.
        :param name: robot name (URDF); the preset's model name when None.
        """
        self.world = world
        self.params = params
        self.spawn = position
        self.logic = CarLogic(params)
        self.body = CarBody(world, params, position, name=name, register=False)
        self.measurement = Measurement()
        self._body_pre_step = self.body.pre_step
        self.pre_substep = self.body.pre_substep
        world.add_body(self)

    def pre_step(self):
        """World hook: sense, run the driver logic, actuate."""
        body = self.body
        world = self.world
        body.read(self.measurement)
        body.apply(self.logic.step(self.measurement, world.time_s, world.time_step_s))
        self._body_pre_step()

    def reset(self):
        """
        Put the car back as it was built: spawn pose, at rest, joints at 0, logic reset.

        The body is put back as built (CarBody.rebuild), so a reset repairs whatever state the
        physics left it in. CarLogic.reset gives the start state of every command and
        estimate; simulated time goes on.
        """
        self.body.reset()
        self.logic.reset()

    def teleport(self, position):
        """
        Put the car at rest at (x [m], y [m], yaw [rad]) on the ground; its commands stay.

        The wheels keep their angles, every velocity becomes 0 and the logic forgets the motion
        (CarLogic.come_to_rest).

        :raises InvalidPoseError: when the car would be inside another body (nothing moved).
        """
        self.body.teleport(position)
        self.logic.come_to_rest()

    def destroy(self):
        """Remove the car's bodies from the physics (World.remove calls this)."""
        self.body.destroy()
