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
The ``overtake`` criterion of scenarios: the vehicle passes traffic vehicles driving its way.

A traffic vehicle counts as passed once it has been wholly ahead of the vehicle's front and
later wholly behind its rear, both measured along the vehicle's heading, while it drove the
same way (headings within 90 degrees) and near it (its centre within ``lateral`` of the
vehicle's axis), and the vehicle never touched it (a collision with it, at any time: driving on
past a car it has hit is no overtake). It reads the traffic from the run's scene
(``scene.traffic``) like ``min_gap``.
Importing this module registers it in ``criteria.CRITERIA`` (schema.py imports it).
"""

import math

from vehicle_sim.core.geometry.angles import wrap_angle_rad
from vehicle_sim.core.specs.param_spec import ParamSpec
from vehicle_sim.scenarios.criteria import CRITERIA, Criterion


class Overtake(Criterion):
    """The vehicle passes traffic vehicles driving its way: each ahead of it, later behind it."""

    KIND = 'overtake'
    UNIT = 'vehicles'
    UNIT_OF_ONE = 'vehicle'
    SPECS = (
        ParamSpec('min', 'min_count', 'int', 1, doc='traffic vehicles it must pass (one it '
                  'touched, a collision, does not count)', ge=1),
        ParamSpec('lateral', 'lateral_m', 'float', 8.0, 'm', "counts traffic vehicles whose "
                  "centre is within this of the vehicle's axis (about two lanes)", gt=0.0),
        ParamSpec('within', 'within_s', 'float', None, 's', 'deadline; null = the duration',
                  gt=0.0, optional=True),
    )

    def __init__(self, *args):
        super().__init__(*args)
        self.outline = None
        self.traffic = None
        self.ahead = set()          # names seen wholly ahead of the vehicle's front
        self.passed = {}            # name -> time it was wholly behind the vehicle's rear
        self.touched = {}           # name -> time of the vehicle's first collision with it

    def bind(self, scene):
        self.outline = scene.outline(self.vehicle)
        self.traffic = getattr(scene, 'traffic', None)

    def collision(self, event):
        if self.traffic is None or event.other in self.touched:
            return
        if any(name == event.other for name, *_ in self.traffic()):
            self.touched[event.other] = event.time_s

    def observe(self, sample):
        if self.traffic is None:
            return
        within = self.values['within_s'] or self.duration_s
        if sample.time_s > within + 1e-9:
            return
        c, s = math.cos(sample.yaw_rad), math.sin(sample.yaw_rad)
        for name, x, y, yaw, length, width in self.traffic():
            if name in self.passed:
                continue
            turn = wrap_angle_rad(yaw - sample.yaw_rad)
            dx, dy = x - sample.x_m, y - sample.y_m
            along, side = c * dx + s * dy, -s * dx + c * dy   # in the vehicle's frame
            if abs(turn) >= 0.5 * math.pi or abs(side) > self.values['lateral_m']:
                continue
            half = 0.5 * (abs(math.cos(turn)) * length + abs(math.sin(turn)) * width)
            if along - half > self.outline.x_max_m:
                self.ahead.add(name)
            elif along + half < self.outline.x_min_m and name in self.ahead:
                self.passed[name] = sample.time_s

    def result(self):
        bound = self.values['min_count']
        if self.traffic is None:
            return self._result(False, None, 'the world has no traffic (traffic: in the world)')
        passed = {name: time_s for name, time_s in self.passed.items()
                  if name not in self.touched}
        count = len(passed)
        if passed:
            order = sorted(passed.items(), key=lambda item: item[1])
            listed = ', '.join(f'{name} at {time_s:.2f} s' for name, time_s in order)
        else:
            listed = f'none of the {len(self.ahead)} seen ahead'
        touched = sorted(self.touched.items(), key=lambda item: item[1])
        if touched:
            listed += '; not counted: ' + ', '.join(f'{name} touched at {time_s:.2f} s'
                                                    for name, time_s in touched)
        within = self.values['within_s'] or self.duration_s
        return self._result(count >= bound, count, f'passed {count} (at least {bound} within '
                                                   f'{within:g} s): {listed}')


CRITERIA[Overtake.KIND] = Overtake
