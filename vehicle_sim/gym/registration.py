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
The Gymnasium ids of vehicle_sim: registered when ``vehicle_sim.gym`` is imported.

``gymnasium.make('vehicle_sim/Drive-v0', ...)`` after ``import vehicle_sim.gym``, or without
the import: ``gymnasium.make('vehicle_sim.gym:vehicle_sim/Drive-v0', ...)`` (Gymnasium imports
the module named before the colon). setup.py also declares :func:`register_envs` under the
``gymnasium.envs`` entry point group, which Gymnasium releases that load plugins call.
``gymnasium.make_vec(..., vectorization_mode='vector_entry_point')`` gives DriveVectorEnv.
"""

from vehicle_sim.gym.require import gymnasium

NAMESPACE = 'vehicle_sim'
ENVS = {
    'Drive-v0': {
        'entry_point': 'vehicle_sim.gym.drive_env:DriveEnv',
        'vector_entry_point': 'vehicle_sim.gym.vector_env:DriveVectorEnv',
    },
}


def register_envs():
    """Register every id (idempotent); inside a plugin namespace the ids take it instead."""
    registry = gymnasium.envs.registration
    in_plugin = getattr(registry, 'current_namespace', None) is not None
    for name, kwargs in ENVS.items():
        if f'{NAMESPACE}/{name}' in registry.registry:
            continue
        gymnasium.register(id=name if in_plugin else f'{NAMESPACE}/{name}', **kwargs)
