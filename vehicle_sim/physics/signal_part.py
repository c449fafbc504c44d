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
The world's traffic lights at run time: the one SignalController of a world.

:class:`SignalPart` is the scene part (physics/scene.py) ``'signals'``: a world whose lane map has
traffic light groups (``roads:`` intersections with ``signals: true``, a Lanelet2 map's traffic
lights), or that has a ``signals:`` key, gets it. It builds the core SignalController
(core/map/signal_plan.py) of the lane map's rules with the world file's plan
(core/map/signal_params.py) and returns :class:`WorldSignals`: ``scene.parts['signals']``, whose
``controller`` everything that reads signals reads (the traffic, the lane state, the criteria,
the ROS topic, the lamps, the Gym environment, the Webots facade), so that they all see the same
states.

A lane map with signal programs of its own (a SUMO network's: ``LaneRules.programs``) gets the
core ProgramController (core/map/signal_programs.py) instead, which runs those programs (and
which a traffic engine that runs the signals itself drives, ``drive(states)``); such a world's
``signals:`` key is refused, naming it: the map's programs are the plan (edit them in the
network, or force states from a scenario).

The plan runs on the world's clock from the moment the part is built: a world step hook
(``post_step``, the time advanced) sets every group's state for that time before anything reads
the world after the step. :meth:`WorldSignals.reset` (with the world's reset) starts the plan
again from the time of the reset and releases every forced state.
"""

from vehicle_sim.core.map.signal_params import SignalSpec
from vehicle_sim.core.map.signal_plan import SignalController
from vehicle_sim.core.map.signal_programs import ProgramController
from vehicle_sim.core.specs.errors import InvalidParameterError


def signals_wanted(spec) -> bool:
    """Return whether a WorldSpec gets the signals part: a ``signals:`` key or groups."""
    lanes = getattr(spec, 'lanes', None)
    return getattr(spec, 'signals', None) is not None or (
        lanes is not None and bool(lanes.rules.groups))


class SignalPart:
    """The scene part of a world's traffic lights (``scene.parts['signals']``)."""

    name = 'signals'

    def build(self, world, spec) -> 'WorldSignals':
        """Return the WorldSignals of ``spec``'s lane map and plan, advanced by ``world``."""
        graph = spec.lanes
        if graph is not None and graph.rules.programs:
            if spec.signals is not None:
                raise InvalidParameterError(
                    f'{spec.signals.source}: the lane map {graph.source} has signal programs '
                    'of its own, which its traffic lights run: remove the signals: key (edit '
                    "the programs in the map, or force a group's state from a scenario)")
            return WorldSignals(world, ProgramController(graph))
        settings = spec.signals or SignalSpec(source=f"{spec.source or 'world'}: signals")
        if graph is None or not graph.rules.groups:
            raise InvalidParameterError(
                f'{settings.source}: the lane map has no traffic light groups to plan (roads: '
                'intersections with signals: true, or a Lanelet2 map with traffic lights)')
        phases = None if settings.phases is None else (settings.phases,)   # one cycle
        try:
            controller = SignalController(graph, settings.fixed_time_plan(), phases)
        except InvalidParameterError as error:     # a group not in the map, conflicting greens
            raise InvalidParameterError(f"{settings.source}: field 'phases': {error}") from None
        if settings.intersections:
            try:
                controller = SignalController(graph, settings.fixed_time_plan(), phases,
                                              settings.intersection_plans())
            except InvalidParameterError as error:     # a group not in the map, given twice
                raise InvalidParameterError(
                    f"{settings.source}: field 'intersections': {error}") from None
        if phases is not None:
            listed = {group for phase in settings.phases for group in phase}
            missing = sorted(g.id for g in graph.rules.groups if g.id not in listed)
            if missing:
                raise InvalidParameterError(
                    f"{settings.source}: field 'phases': group(s) {missing} of the map are in "
                    'no phase (each group must be in one)')
        return WorldSignals(world, controller)


class WorldSignals:
    """
    The SignalController of a world, advanced to the world's time every step.

    :param world: the World (its step hook).
    :param controller: the core SignalController, or ProgramController of a map's programs.
    """

    def __init__(self, world, controller):
        self.world = world
        self.controller = controller
        self._start_step = world.step_count
        controller.update(0.0)
        world.add_body(self)

    @property
    def plan_time_s(self) -> float:
        """The plan's time now: the world's time since the build or the last reset [s]."""
        return (self.world.step_count - self._start_step) * self.world.time_step_s

    def post_step(self):
        """World hook: every group's state for the world's time now."""
        self.controller.update(self.plan_time_s)

    def reset(self):
        """Start the plan again now, every forced state released; say so in words."""
        self._start_step = self.world.step_count
        self.controller.release()
        self.controller.update(0.0)
        return f'signals: their {len(self.controller.states())} groups back at the plan start'
