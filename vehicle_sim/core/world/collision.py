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
Collision events from per-step contacts, debounced.

A vehicle's contacts flicker while it rests against or scrapes along something. An event is
reported when the vehicle starts touching a body (anything but the ground); the same pair
reports again only after it was apart for at least ``min_apart_s`` (0.1 s by default).
"""

from dataclasses import dataclass
from typing import Dict, List, Mapping, Optional, Tuple

DEFAULT_MIN_APART_S = 0.1
# Simulated times are multiples of the step; a tiny tolerance keeps 10 steps of 0.01 s = 0.1 s.
_TIME_TOLERANCE_S = 1e-9


@dataclass(frozen=True)
class CollisionEvent:
    """
    The vehicle started touching another body.

    :param time_s: simulated time of the step of first contact [s].
    :param other: the other body's name (an obstacle's or a vehicle's name).
    :param normal_force_n: sum of the contact normal forces at that step [N].
    :param position_m: where they touched: the mean of that step's contact points on the other
        body [x, y, z] in the world [m]; None where not known.
    """

    time_s: float
    other: str
    normal_force_n: float
    position_m: Optional[Tuple[float, float, float]] = None


class CollisionDebouncer:
    """
    Turn per-step contact sets into collision events.

    :param min_apart_s: how long a pair must be apart before it can report again [s], >= 0.
    """

    def __init__(self, min_apart_s=DEFAULT_MIN_APART_S):
        if not min_apart_s >= 0.0:
            raise ValueError(f'min_apart_s = {min_apart_s!r}: must be >= 0')
        self.min_apart_s = float(min_apart_s)
        self._touching = set()
        self._apart_since: Dict[str, float] = {}

    @property
    def idle(self):
        """True when no pair is touching: an update without contacts changes nothing then."""
        return not self._touching

    def update(self, now_s, contacts: Mapping[str, float]) -> List[CollisionEvent]:
        """
        Feed the contacts of one step.

        :param now_s: simulated time of the step [s].
        :param contacts: {other body's name: sum of normal forces [N]} of the bodies touching now.
        :return: the new events, in the order of ``contacts``.
        """
        events = []
        for other, force in contacts.items():
            if other in self._touching:
                continue
            since = self._apart_since.get(other)
            if since is None or now_s - since >= self.min_apart_s - _TIME_TOLERANCE_S:
                events.append(CollisionEvent(now_s, other, float(force)))
            self._touching.add(other)
            self._apart_since.pop(other, None)
        for other in self._touching - set(contacts):
            self._touching.discard(other)
            self._apart_since[other] = now_s
        return events
