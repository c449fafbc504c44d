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
The ``automobile`` node: Webots' ``ros_automobile`` interface (docs/ros_interface.md).

This module is the executable; the node class, :class:`~vehicle_sim.ros.automobile.
AutomobileNode`, lives in :mod:`.automobile` because ``autoware_automobile`` composes it too and
node modules never import each other.

Run: ``ros2 run vehicle_sim automobile --ros-args -p car_model:=ToyotaPrius`` or
``python -m vehicle_sim.ros.automobile_node --ros-args --params-file config/automobile.yaml``.
"""

import sys

from vehicle_sim.ros.automobile import AutomobileNode, NODE_NAME
from vehicle_sim.ros.node_support import run_main

__all__ = ['main']


def main(args=None):
    """Entry point ``automobile``: build the node and spin it (Jazzy main shape)."""
    return run_main(NODE_NAME, AutomobileNode, args)


if __name__ == '__main__':
    sys.exit(main())
