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
SUMO's signal programs driving the world's signal controller (the SUMO engine's signal bridge).

After each SUMO step each program's state string, link by link, gives the state of the lane
graph's group of that link (core/map/signal_programs.py SignalProgram ``links``; SUMO_STATES
maps SUMO's characters to ours) and drives the world's controller (``drive(states)``); a group a
scenario forces is pushed to SUMO (``trafficlight.setLinkState``) and given back to its program
when released.
"""

from vehicle_sim.core.map.signal_programs import SUMO_STATES

# SUMO's state character of each of our signal states (what a forced state is pushed as)
SUMO_CHARACTER = {'green': 'G', 'yellow': 'y', 'red': 'r', 'off': 'O'}

__all__ = ['SUMO_CHARACTER', 'SumoSignals']


class SumoSignals:
    """
    The signal bridge of one started SUMO (made again at each start).

    :param session: the started SumoSession.
    :param controller: the world's SignalController, or None.
    :param programs: the lane map's SignalPrograms.
    :param constants: TraCI's constants.
    """

    def __init__(self, session, controller, programs, constants):
        self.session = session
        self.signals = controller
        self._constants = constants
        self._strings = {}                 # {tls id: its state string at the last drive}
        self._pushed = {}                  # {group id: state} forced states pushed to SUMO
        self._tls_links = {}               # {group id: (tls id, link index)}
        self._groups_of = {}               # {tls id: ((link index, group id), ...)}
        for program in programs:
            self._groups_of[program.tls_id] = tuple(
                (link, group) for link, group in enumerate(program.links) if group is not None)
            for link, group in self._groups_of[program.tls_id]:
                self._tls_links[group] = (program.tls_id, link)
        self._programs_of = {program.tls_id: program.program_id for program in programs}

    def begin(self, api):
        """Subscribe to the lights' states and drive the controller with SUMO's first ones."""
        if self._tls_links:
            c = self._constants
            for tls in {tls for tls, _ in self._tls_links.values()}:
                api.trafficlight.subscribe(tls, (c.TL_RED_YELLOW_GREEN_STATE,))
            self.drive(api, {tls: api.trafficlight.getRedYellowGreenState(tls)
                             for tls in self._programs_of})

    def drive(self, api, strings=None, subscribed=None):
        """
        Give the world's signal controller SUMO's states ({tls: state string}: now).

        :param subscribed: the lights' subscription results when read elsewhere (a SUMO
            worker's readings); None: read here (``strings`` None).
        """
        controller = self.signals
        if controller is None or not self._tls_links:
            return
        if strings is None:
            if subscribed is None:
                subscribed = api.trafficlight.getAllSubscriptionResults()
            c = self._constants
            strings = {tls: values[c.TL_RED_YELLOW_GREEN_STATE]
                       for tls, values in subscribed.items()}
        states, last = {}, self._strings
        for tls, text in strings.items():
            if last.get(tls) == text:
                continue                          # no change at this light
            last[tls] = text
            for link, group in self._groups_of[tls]:
                if link < len(text):
                    states[group] = SUMO_STATES[text[link]]
        if states or not controller.driven:     # the changes (checking a group costs)
            controller.drive(states)

    def push(self):
        """Push the states a scenario forces on the world's controller to SUMO (and releases)."""
        controller = self.signals
        if controller is None or not self._tls_links:
            return
        api = self.session.api
        forced = controller.forced()
        for group, state in forced.items():
            where = self._tls_links.get(group)
            if where is not None and self._pushed.get(group) != state:
                api.trafficlight.setLinkState(where[0], where[1], SUMO_CHARACTER[state])
                self._pushed[group] = state
        released = {self._tls_links[g][0] for g in self._pushed if g not in forced}
        if released:
            self._pushed = {g: s for g, s in self._pushed.items() if g in forced}
            for tls in released:
                api.trafficlight.setProgram(tls, self._programs_of[tls])
                for group, state in self._pushed.items():    # still forced at that light
                    if self._tls_links[group][0] == tls:
                        api.trafficlight.setLinkState(tls, self._tls_links[group][1],
                                                      SUMO_CHARACTER[state])
