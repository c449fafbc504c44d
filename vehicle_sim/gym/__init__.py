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
Gymnasium environments of vehicle_sim (the ``gym`` extra: ``pip install 'vehicle_sim[gym]'``).

Importing this package registers ``vehicle_sim/Drive-v0`` (registration.py)::

    import gymnasium
    import vehicle_sim.gym
    env = gymnasium.make('vehicle_sim/Drive-v0', world='obstacle_course', lidar=True)

:class:`DriveEnv` is one world; :class:`DriveVectorEnv` holds N worlds in one process and steps
them in one call. docs/gym.md describes actions, observations, reward and options.

May import: core, config, maps, physics, scenarios.
"""

from vehicle_sim.gym.drive_env import DriveEnv
from vehicle_sim.gym.registration import register_envs
from vehicle_sim.gym.vector_env import DriveVectorEnv

register_envs()

__all__ = ['DriveEnv', 'DriveVectorEnv', 'register_envs']
