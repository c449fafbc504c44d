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
Interface definitions of vehicle_sim and their Python / DDS types.

The ``.msg`` / ``.srv`` files under ``definitions/`` are the single source of every interface
(docs/ros_interface.md); :mod:`vehicle_msgs_py.types` builds cyclonedds-python types from them for
the
embedded transport, and :mod:`vehicle_msgs_py.export` writes the ``vehicle_msgs`` ament package
for ROS machines.

The names below are imported from :mod:`vehicle_msgs_py.types` on first use, so that the
exporter (``vehicle_msgs_py.export``) runs with the standard library only: on a ROS machine it
runs before cyclonedds or rosbags are installed, if they ever are.

May import: no other layer.
"""

import importlib

__all__ = [
    'dds_type_name',
    'from_rosbags',
    'known_services',
    'known_types',
    'message_definition',
    'message_type',
    'service_types',
    'ServiceTypes',
    'to_rosbags',
    'type_hash',
    'typestore',
]


def __getattr__(name):
    if name in __all__:
        return getattr(importlib.import_module('vehicle_msgs_py.types'), name)
    raise AttributeError(f'module {__name__!r} has no attribute {name!r}')


def __dir__():
    return sorted(set(globals()) | set(__all__))
