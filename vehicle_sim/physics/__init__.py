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
PyBullet physics: World, car bodies, URDF generation (the only place pybullet is imported).

May import: core, config, maps.
"""

# First: pybullet without its start-up banner (the modules below import it too).
from vehicle_sim.physics import _pybullet  # noqa: F401
from vehicle_sim.physics.car_body import CarBody
from vehicle_sim.physics.simulated_car import SimulatedCar
from vehicle_sim.physics.urdf import car_urdf, joint_names
from vehicle_sim.physics.world import DEFAULT_FRICTION, World

__all__ = ['CarBody', 'SimulatedCar', 'car_urdf', 'DEFAULT_FRICTION', 'joint_names', 'World']
