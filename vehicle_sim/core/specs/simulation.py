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
The simulation parameters several entry points share: one ParamSpec row each, one default.

``time_step_ms`` is taken by the automobile and robot nodes, scenario files, the Gymnasium
environment's options, the Webots facade (``Driver(time_step_ms=...)``) and the end-to-end
runner; ``friction`` by the automobile node and the physics World. Every one of them validates
with the row (an entry point may make it optional, nothing else), so the kind, the bounds, the
default and the refusal text are the same wherever the value is given.
"""

from vehicle_sim.core.specs.param_spec import ParamSpec

# Webots' basicTimeStep: an integer number of milliseconds (WorldInfo, default 32 there; 10 here,
# the step the car presets are tuned at). 1 ms is the shortest step; 1 s the longest that still
# steps a car's controllers sensibly.
TIME_STEP_MS = ParamSpec('time_step_ms', kind='int', default=10, unit='ms', ge=1, le=1000,
                         doc='basic time step of the world (Webots basicTimeStep)')
# The basic steps [ms] at which the physics car's checks run (docs/physics.md, World: the 0-100
# ramps, top speeds, braking, steady turns, static sag and the steering motor's law): the default
# and the coarsest step the car is shown to keep them at.
CHECKED_TIME_STEPS_MS = (TIME_STEP_MS.default, 20)

# Tyre-road friction coefficient of the ground (Bullet multiplies the two materials' values; car
# wheels have 1.0). 0-100 km/h in time0To100 needs about 1.1 on the driven axle (docs/physics.md
# "Grip"; TeslaModel3 is the hardest); Webots' vehicle worlds use coulombFriction 8.
FRICTION = ParamSpec('friction', kind='float', default=1.5, unit='1', gt=0.0,
                     doc='tyre-road friction coefficient of the ground')
