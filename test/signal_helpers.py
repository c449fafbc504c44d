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
A road with signals the tests make by hand: its world file, its rules and a 'signals' part.

The road (``roads:``, two straight 60 m segments, one lane each way, 3.5 m wide)::

      y = 1.75   <--- 100151 (x 120 -> 60) ---  <--- 100051 (x 60 -> 0) ---
      y = -1.75  --- 100001 (x 0 -> 60) --->    --- 100101 (x 60 -> 120) --->

Rules (:func:`road_rules`): traffic light group 7001 (red, yellow, green circles and a green
left arrow) stops lane 100001 at its stop line 9001 (s 50 m, x = 50); group 7002 (no bulbs)
stops lane 100151 at 9002 (s 50 m, x = 70); a stop sign's line 9003 on lane 100101 (s 30 m,
x = 90). :class:`HandSignals` is a scene part named 'signals' (as the world's own): it attaches
the rules to the world's lane graph and advances a SignalController (7001 and 7002 in two
phases of :data:`PLAN`) to the world's time after every step.
"""

from vehicle_sim.core.map.lane_rules import Bulb, LaneRules, StopLine, TrafficLightGroup
from vehicle_sim.core.map.signal_plan import FixedTimePlan, SignalController

ROADS = [{'name': 'main', 'start': {'x': 0.0, 'y': 0.0, 'yaw': 0.0}, 'lanes': 1,
          'backward_lanes': 1, 'speed_limit': 13.9,
          'segments': [{'type': 'straight', 'length': 60.0},
                       {'type': 'straight', 'length': 60.0}]}]
EAST, EAST_NEXT, WEST, WEST_NEXT = 100001, 100101, 100151, 100051
# green 0.55 s, yellow 0.2 s, all red 0.3 s: changes between the 10 Hz publishing instants
PLAN = FixedTimePlan(green_s=0.55, yellow_s=0.2, all_red_s=0.3)
PHASES = (((7001,), (7002,)),)


def world_data(x_m=20.0, y_m=-1.75, yaw_rad=0.0):
    """Return the world file's data: the road and one car (default: lane 100001 at s 20 m)."""
    return {'vehicles': [{'name': 'Car', 'model': 'ToyotaPrius',
                          'pose': {'x': x_m, 'y': y_m, 'yaw': yaw_rad}}],
            'roads': ROADS}


def write_world(tmp_path, name='signals_road', **pose):
    """Write the world file of :func:`world_data`; return its path."""
    import yaml
    path = tmp_path / f'{name}.yaml'
    path.write_text(yaml.safe_dump(world_data(**pose)), encoding='utf-8')
    return path


def road_rules():
    """Return the LaneRules of the module docstring."""
    bulbs = (Bulb('red', 52.0, -4.0, 5.0), Bulb('yellow', 52.0, -4.0, 4.7),
             Bulb('green', 52.0, -4.0, 4.4), Bulb('green', 52.0, -4.3, 4.4, 'left_arrow'))
    return LaneRules(
        stop_lines=(StopLine(9001, EAST, 50.0, [(50.0, -3.5), (50.0, 0.0)], 'traffic_light',
                             7001),
                    StopLine(9002, WEST, 50.0, [(70.0, 0.0), (70.0, 3.5)], 'traffic_light',
                             7002),
                    StopLine(9003, EAST_NEXT, 30.0, [(90.0, -3.5), (90.0, 0.0)],
                             'stop_sign')),
        groups=(TrafficLightGroup(7001, (EAST,), (9001,), bulbs, 'east'),
                TrafficLightGroup(7002, (WEST,), (9002,))))


class HandSignals:
    """A 'signals' scene part made by hand: the rules attached, a controller on world time."""

    name = 'signals'

    def __init__(self, plan=PLAN, phases=PHASES):
        self.plan, self.phases = plan, phases
        self.controller = None
        self.world = None

    def build(self, world, spec):
        spec.lanes.set_rules(road_rules())
        self.controller = SignalController(spec.lanes, self.plan, self.phases)
        self.controller.update(world.time_s)
        self.world = world
        world.add_body(self)
        return self

    def post_step(self):
        self.controller.update(self.world.time_s)


def with_hand_signals(monkeypatch, module):
    """Make ``module``'s ``build_scene`` add a :class:`HandSignals` part to every scene."""
    real = module.build_scene

    def build_scene(spec, *args, parts=(), **kwargs):
        return real(spec, *args, parts=tuple(parts) + (HandSignals(),), **kwargs)
    monkeypatch.setattr(module, 'build_scene', build_scene)
