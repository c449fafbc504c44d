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
A map's own signal programs (a SUMO network's ``tlLogic``), and the controller that runs them.

A :class:`SignalProgram` is one traffic light system of the map: its id (SUMO's traffic light
id), the traffic light group of each of its link indices (``links[i]``: the group id of link
``i``, None for a link with no group, e.g. a pedestrian crossing's), its phases (duration [s],
SUMO state string: one character per link index) and its offset: the cycle position at time
``t`` is ``(t - offset) mod cycle``, as SUMO runs it (a phase that starts at ``t`` is in effect
from ``t`` on: SUMO switches at the start of its step at ``t``, and TraCI, asked at ``t``,
still reads the state before that step). :data:`SUMO_STATES` maps SUMO's state
characters onto the groups' states (core/map/lane_rules.py SIGNAL_STATES): ``G`` (priority
green), ``g`` (permissive green: the vehicle yields to the conflicting priority flows; here, as
everywhere in the simulator, the conflict zones are served first come first served) and ``s``
(green right-turn arrow, stop first) are green; ``y`` yellow; ``r`` red and ``u`` (red-yellow,
about to turn green) red; ``o`` and ``O`` (off, blinking or not) off.

:class:`ProgramController` is the world's signal controller of a map with programs
(physics/signal_part.py builds it instead of the fixed-time SignalController of
core/map/signal_plan.py, with the same interface: ``update(time_s)``, ``state``, ``states``,
``force``, ``release``). Without a traffic engine it runs the programs on the world's clock:
SUMO is not needed, and the built-in traffic obeys them. Actuated and delay-based programs run
their phases' ``duration`` as a fixed-time program (their detectors are SUMO's). A traffic
engine that runs the signals itself (SUMO) calls :meth:`ProgramController.drive` at each of its
steps with the states it has: from then on the groups show the driven states (the programs no
longer advance) until :meth:`ProgramController.stop_driving`. A state a scenario forces
(:meth:`force`) wins over both; the engine reads :meth:`ProgramController.forced` to push it to
its own signals.
"""

from dataclasses import dataclass
import math
from typing import Dict, Optional, Sequence, Tuple

from vehicle_sim.core.map.signal_plan import check_signal_state, GroupStates
from vehicle_sim.core.specs.errors import InvalidParameterError

# SUMO's link state characters (its tlLogic phase states) -> the groups' states.
SUMO_STATES = {'G': 'green', 'g': 'green', 's': 'green', 'y': 'yellow', 'Y': 'yellow',
               'r': 'red', 'u': 'red', 'o': 'off', 'O': 'off'}


@dataclass(frozen=True)
class SignalProgram:
    """
    One traffic light system's program.

    :param tls_id: the traffic light system's id (SUMO's).
    :param links: per link index, the id of its traffic light group (None: no group).
    :param phases: ((duration [s], state string), ...): each string has a character per link.
    :param offset_s: the cycle's shift: position ``(t - offset_s) mod cycle`` at time t [s].
    :param program_id: the program's id in the map (SUMO's programID).
    """

    tls_id: str
    links: Tuple[Optional[int], ...]
    phases: Tuple[Tuple[float, str], ...]
    offset_s: float = 0.0
    program_id: str = '0'

    def __post_init__(self):
        where = f'signal program {self.tls_id!r}'
        if not self.phases:
            raise InvalidParameterError(f'{where}: has no phases')
        for duration, state in self.phases:
            if not (isinstance(duration, (int, float)) and math.isfinite(duration)
                    and duration >= 0.0):
                raise InvalidParameterError(f'{where}: phase duration {duration!r} must be a '
                                            'finite number >= 0 [s]')
            unknown = sorted(set(state) - set(SUMO_STATES))
            if unknown:
                raise InvalidParameterError(
                    f'{where}: state {state!r}: unknown character(s) {"".join(unknown)} (known: '
                    f'{"".join(SUMO_STATES)})')
            if len(state) < len(self.links):
                raise InvalidParameterError(
                    f'{where}: state {state!r} has {len(state)} links, the program '
                    f'{len(self.links)}')
        if not math.isfinite(self.offset_s):
            raise InvalidParameterError(f'{where}: offset {self.offset_s!r} must be finite')
        if self.cycle_s <= 0.0:
            raise InvalidParameterError(f'{where}: its phases last 0 s in all')

    @property
    def cycle_s(self) -> float:
        """The cycle's length: the phases' durations summed [s]."""
        return float(sum(duration for duration, _ in self.phases))

    def phase_at(self, time_s: float) -> Tuple[int, float]:
        """Return (phase index, time to its end [s]) at simulation time ``time_s``."""
        position = (time_s - self.offset_s) % self.cycle_s
        for index, (duration, _) in enumerate(self.phases):
            if position < duration:
                return index, duration - position
            position -= duration
        return len(self.phases) - 1, 0.0        # rounding at the cycle's end

    def state_at(self, time_s: float) -> str:
        """Return the SUMO state string at simulation time ``time_s``."""
        return self.phases[self.phase_at(time_s)[0]][1]

    def group_states(self, state: str) -> Dict[int, str]:
        """Return {group id: state} of a SUMO state string (the links with groups)."""
        return {group: SUMO_STATES[state[index]] for index, group in enumerate(self.links)
                if group is not None}


class ProgramController(GroupStates):
    """
    The state of every traffic light group of a map with signal programs, at the world's time.

    :param graph: the map's LaneGraph (its ``rules``: the groups and ``programs``).
    :param programs: the programs to run; None = the map's (``graph.rules.programs``).
    :raises InvalidParameterError: a program names a group not in the map.
    """

    def __init__(self, graph, programs: Optional[Sequence[SignalProgram]] = None):
        self.rules = graph.rules
        self.programs = tuple(self.rules.programs if programs is None else programs)
        for program in self.programs:
            for group_id in program.links:
                if group_id is not None:
                    self.rules.group(group_id)
        self.time_s = 0.0
        self._forced: Dict[int, str] = {}
        self._driven: Optional[Dict[int, str]] = None
        self._states: Dict[int, str] = {}
        self._planned: Dict[int, str] = {}
        self._next_change_s = -math.inf
        self.update(0.0)

    @property
    def driven(self) -> bool:
        """Whether an engine drives the states (:meth:`drive`) instead of the programs."""
        return self._driven is not None

    def update(self, time_s: float) -> None:
        """Set every group's state for simulation time ``time_s`` [s]."""
        previous, self.time_s = self.time_s, time_s
        if self._driven is not None:
            return
        if previous <= time_s < self._next_change_s:   # no phase boundary since
            return
        states = {group.id: 'off' for group in self.rules.groups}
        next_change = math.inf
        for program in self.programs:
            index, left_s = program.phase_at(time_s)
            states.update(program.group_states(program.phases[index][1]))
            next_change = min(next_change, time_s + left_s)
        self._planned = states
        self._states = dict(states)
        self._states.update(self._forced)
        self._next_change_s = next_change - 1e-9 * max(1.0, abs(next_change))

    def drive(self, states: Dict[int, str]) -> None:
        """
        Set groups' states from a traffic engine (the groups not given keep theirs).

        From the first call on, the programs no longer advance the states: the engine drives
        them (until :meth:`stop_driving`). A forced state still wins.

        :raises InvalidParameterError: a group not in the map or a state not in
            SIGNAL_STATES (nothing is changed).
        """
        for group_id, state in states.items():
            check_signal_state(self.rules, group_id, state)
        if self._driven is None:
            self._driven = dict(self._planned)
        self._driven.update(states)
        self._states = dict(self._driven)
        self._states.update(self._forced)

    def stop_driving(self) -> None:
        """Return the groups to the programs (at the controller's time)."""
        self._driven = None
        self._next_change_s = -math.inf
        self.update(self.time_s)

    def force(self, group_id, state: str) -> None:
        """Hold a group in ``state`` (one of SIGNAL_STATES) until :meth:`release`."""
        check_signal_state(self.rules, group_id, state)
        self._forced[group_id] = state
        self._states[group_id] = state

    def release(self, group_id=None) -> None:
        """Return a group (None: every group) to its program (or to the engine's state)."""
        if group_id is None:
            self._forced.clear()
        else:
            self.rules.group(group_id)
            self._forced.pop(group_id, None)
        if self._driven is not None:
            self._states = dict(self._driven)
            self._states.update(self._forced)
        else:
            self._next_change_s = -math.inf
            self.update(self.time_s)
