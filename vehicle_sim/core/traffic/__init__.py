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
Traffic: other vehicles that drive the lanes of a LaneGraph (ROS-free, PyBullet-free).

One module per model: :mod:`~vehicle_sim.core.traffic.idm` (the Intelligent Driver Model, the
speed) and :mod:`~vehicle_sim.core.traffic.mobil` (MOBIL, the lane changes), registered in
:mod:`~vehicle_sim.core.traffic.models` (chosen by ``traffic: model:``); the ``traffic:``
key of world files (:mod:`~vehicle_sim.core.traffic.params`), where the vehicles start
(:mod:`~vehicle_sim.core.traffic.spawn`, their state in :mod:`~vehicle_sim.core.traffic.vehicles`),
the manager that moves them along the lanes (:mod:`~vehicle_sim.core.traffic.manager`) and
their ground truth as objects (:mod:`~vehicle_sim.core.traffic.objects`).

May import (core): specs, geometry, sensors, map.
"""
