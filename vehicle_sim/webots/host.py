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
Controller hosting: ``Driver()`` binds to a vehicle the simulation already has.

Webots starts a controller for a robot of a running world, and the controller's ``Driver()``
connects to that robot. The scenario runner does the same in-process: inside
``with hosting(ControllerHost(...)):`` every ``Driver()`` (or ``Car()``) drives the host's car in
the host's world instead of building its own, ``step()`` advances the host's world (so the
runner's per-step hooks run) and returns -1 at the host's end time. A controller that keeps
calling ``step()`` after -1 is stopped with :class:`ControllerStopped`.
"""

from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any, Callable, List, Optional

from vehicle_sim.core.geometry.geodesy import GeodeticOrigin

# step() calls tolerated after it returned -1 before the controller is stopped.
CALLS_AFTER_END = 10


class ControllerStopped(BaseException):
    """
    Stop a hosted controller that keeps stepping after the end.

    A BaseException, so that a controller's ``except Exception`` does not swallow it.
    """


@dataclass
class ControllerHost:
    """
    What a hosted ``Driver()`` binds to.

    :param world: the World.
    :param car: the SimulatedCar the controller drives.
    :param sensors: the car's SensorSpecs (the mounted ones become devices).
    :param origin: GeodeticOrigin of the world (GNSS).
    :param duration_s: ``step()`` returns -1 from this simulated time on [s].
    :param step: advances the world one basic step (and serves it, when the host publishes it);
        None = ``world.step``.
    :param lanes: the world's lane map (a core LaneGraph; ``Driver.getLaneState``), or None.
    :param signals: the world's SignalController (the signal state in ``getLaneState``), or None.
    """

    world: Any
    car: Any
    sensors: tuple = ()
    origin: GeodeticOrigin = field(default_factory=GeodeticOrigin)
    duration_s: Optional[float] = None
    step: Optional[Callable[[], Any]] = None
    drivers: List[Any] = field(default_factory=list)
    calls_after_end: int = 0
    lanes: Any = None
    signals: Any = None

    def after_end(self):
        """Return -1 for a step() at or after the end; stop a controller that insists."""
        self.calls_after_end += 1
        if self.calls_after_end > CALLS_AFTER_END:
            raise ControllerStopped(f'the controller called step() {CALLS_AFTER_END} times '
                                    'after it returned -1 (end of the simulation)')
        return -1


_hosts: List[ControllerHost] = []


def current_host() -> Optional[ControllerHost]:
    """Return the active host, or None outside :func:`hosting`."""
    return _hosts[-1] if _hosts else None


@contextmanager
def hosting(host: ControllerHost):
    """Make ``Driver()`` bind to ``host`` inside the block."""
    _hosts.append(host)
    try:
        yield host
    finally:
        _hosts.remove(host)
