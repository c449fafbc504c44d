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
Learning math without ROS or PyBullet: progress measures, reward terms, action layouts.

The Gym environment (``vehicle_sim.gym``) reads the ego vehicle's pose after each step and asks
this package how far it got (:mod:`.progress`) and what that is worth (:mod:`.reward`); it and
the policy node (``vehicle_sim.ros.policy_node``) turn a policy's action into the vehicle's
setters by one table (:mod:`.actions`).

May import (core): specs, geometry, sensors, map, traffic, diffdrive, car, commands, autoware,
bridge, world.
"""
