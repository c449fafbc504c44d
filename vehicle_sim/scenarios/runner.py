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
Running a scenario: build its simulation, drive the vehicle under test, judge the criteria.

Time is synchronous: the world advances one basic step at a time, as fast as the driver keeps
up. Scripted commands and actors act in the world's ``pre_step`` (the runner's
:class:`Director` is a world body); after each step the Director records every vehicle's
ground-truth odometry and feeds the criteria. An in-process controller is run like Webots runs
one (its ``Driver()`` bound to the vehicle under test, :mod:`vehicle_sim.webots.host`); after
it returns the world steps on to the duration with its last commands. External processes get
the simulation served over ROS (:class:`~.served_sim.ServedSim`), paced at the driver's
``real_time_factor``; their timing is not reproducible, so such runs report
``deterministic = False`` (``repeat`` gives the spread of the measured values).

A run watched live (``foxglove``) can wait for a Foxglove client before its first step, and any
run can be paced at a real-time factor (:mod:`.pacing`): stepping stays synchronous, so the
results do not change.
"""

from dataclasses import dataclass, field, replace
import hashlib
import os
import random
import runpy
import sys
import time
import traceback
from typing import Dict, List, Optional, Tuple

from vehicle_sim.core.geometry.footprint import Footprint, Outline
from vehicle_sim.core.specs.errors import InvalidCommandError
from vehicle_sim.core.world.collision import CollisionEvent
from vehicle_sim.physics.sensors.collisions import CollisionMonitor
from vehicle_sim.scenarios.actors import make_actors
from vehicle_sim.scenarios.criteria import build_criteria, CriterionResult
from vehicle_sim.scenarios.external import run_processes, TopicWatcher
from vehicle_sim.scenarios.pacing import Pacer
from vehicle_sim.scenarios.scene import world_scene
from vehicle_sim.scenarios.schema import load_scenario, ScenarioSpec
from vehicle_sim.scenarios.served_sim import ServedSim
from vehicle_sim.scenarios.sim import LocalSim
from vehicle_sim.scenarios.yaml_lines import ScenarioError

_EPS_S = 1e-9
# How often the nodes are served while the run waits for a Foxglove client [s] (wall clock).
CLIENT_WAIT_SLICE_S = 0.05


@dataclass
class Track:
    """
    A vehicle's path: times [s], x, y [m] and yaw [rad] after every step (and at the start).

    :param outline: its footprint rectangle in base_link (core Outline), or None.
    """

    time_s: List[float] = field(default_factory=list)
    x_m: List[float] = field(default_factory=list)
    y_m: List[float] = field(default_factory=list)
    yaw_rad: List[float] = field(default_factory=list)
    outline: Optional[Outline] = None


@dataclass
class ScenarioResult:
    """
    The outcome of one run.

    :param criteria: one CriterionResult per criterion, in file order.
    :param error: why the run itself failed (a controller exception, a process that died), or
        None.
    :param odometry_sha256: hash of the vehicle under test's ground-truth odometry stream
        (ODOMETRY_ROW per step).
    :param deterministic: the same scenario and seed give the same run (False with external
        processes).
    :param spread: with repeated runs, {criterion name: (min, max)} of the measured values.
    :param collisions: {vehicle name: its CollisionEvents (with the contact point)}.
    :param notes: scripted commands that were taken but had no effect when given (a brake while
        cruise control holds a speed), each once per run, with its time and file line; a
        recording that stopped on a write error.
    :param recording: the MCAP file of the run's topics (``record``), or None.
    :param traffic_tracks: each traffic vehicle's path while it drove (its box centre; its
        outline its box).
    :param lanes: the world's lane map (a core LaneGraph), or None.
    :param walls: an occupancy map's walls (core Footprints), for plots.
    """

    spec: ScenarioSpec
    seed: int
    criteria: List[CriterionResult]
    sim_time_s: float
    wall_time_s: float
    tracks: Dict[str, Track]
    odometry_sha256: str
    deterministic: bool
    error: Optional[str] = None
    spread: Optional[Dict[str, tuple]] = None
    runs: int = 1
    collisions: Dict[str, List[CollisionEvent]] = field(default_factory=dict)
    notes: List[str] = field(default_factory=list)
    recording: Optional[str] = None
    traffic_tracks: Dict[str, Track] = field(default_factory=dict)
    lanes: Optional[object] = None
    walls: Tuple[Footprint, ...] = ()

    @property
    def passed(self):
        return self.error is None and all(c.passed for c in self.criteria)

    @property
    def failures(self):
        return [c for c in self.criteria if not c.passed]

    def criterion(self, name):
        """Return the CriterionResult called ``name``."""
        for result in self.criteria:
            if result.name == name:
                return result
        raise KeyError(f'no criterion {name!r}; criteria: '
                       + ', '.join(c.name for c in self.criteria))


class Director:
    """
    The runner's world body: commands and actors before each step, measurements after it.

    :param spec: ScenarioSpec.
    :param criteria: the Criterion objects.
    :param progress: ``progress(time_s, duration_s)`` after each step, or None.
    """

    def __init__(self, spec, criteria, progress=None):
        self.spec = spec
        self.criteria = criteria
        self.progress = progress
        self.world = None
        self.vehicles = {}
        self.actors = []
        self.monitors = {}
        self.tracks = {}
        self.traffic_tracks = {}
        self.scene = None
        self.collisions = {}
        self.digest = hashlib.sha256()
        self._commands = list(spec.driver.commands)
        self._next = 0
        self.signals = None         # the world's SignalController (a signals part), or None
        self.notes = []             # ScenarioResult.notes
        self._noted = set()         # the setters a note was taken of

    def attach(self, sim):
        """Bind to the built simulation: vehicles, actors, collision monitors."""
        self.world = sim.world
        self.vehicles = sim.vehicles
        signals = getattr(sim, 'signals', None)     # the world's one SignalController
        self.signals = None if signals is None else signals.controller
        traffic = getattr(sim, 'traffic', None)
        self.actors = make_actors(self.spec.actors, self.vehicles, traffic)
        for name, handle in self.vehicles.items():   # every vehicle: the plot marks them
            monitor = CollisionMonitor(self.world, handle.body)
            self.world.remove(monitor)      # stepped from post_step, after the physics
            self.monitors[name] = monitor
        self.collisions = {name: [] for name in self.vehicles}
        scene = world_scene(self.world, self.vehicles, self.spec.world.obstacles,
                            walls=getattr(sim, 'walls', ()), lanes=getattr(sim, 'lanes', None),
                            traffic=getattr(sim, 'traffic', None),
                            signals=self.signals)
        for criterion in self.criteria:
            criterion.bind(scene)
        self.scene = scene
        self.tracks = {name: Track(outline=scene.outline(name)) for name in self.vehicles}
        self._measure(self.world.time_s)

    @property
    def vut(self):
        return self.vehicles[self.spec.vehicle]

    def pre_step(self):
        """World hook: the scripted commands due now, then the actors."""
        if self.world is None:
            return
        now_s = self.world.time_s
        commands = self._commands
        while self._next < len(commands) and commands[self._next].t_s <= now_s + _EPS_S:
            self._apply(commands[self._next])
            self._next += 1
        for actor in self.actors:
            actor.control()

    def _apply(self, command):
        for group, state in command.signals:
            if self.signals is None:
                raise ScenarioError(self.spec.source, command.line,
                                    f'command at t = {command.t_s:g} s: signal {group}: the '
                                    'world has no traffic lights')
            if state == 'plan':
                self.signals.release(group)
            else:
                self.signals.force(group, state)
        if not command.setters:
            return
        logic = self.vut.car.logic
        for core_setter, value, webots_name in command.setters:
            try:
                note = getattr(logic, core_setter)(value)
            except InvalidCommandError as error:
                raise ScenarioError(self.spec.source, command.line,
                                    f'command at t = {command.t_s:g} s: {webots_name}'
                                    f'({value!r}) refused: {error}') from None
            if note is not None and webots_name not in self._noted:    # once per run
                self._noted.add(webots_name)
                self.notes.append(f'{self.spec.source}:{command.line}: command at t = '
                                  f'{command.t_s:g} s: {webots_name}({value!r}): {note}')

    def post_step(self):
        """World hook: collisions, odometry, criteria, progress."""
        if self.world is None:
            return
        now_s = self.world.time_s
        for name, monitor in self.monitors.items():
            monitor.post_step()
            self.collisions[name].extend(monitor.fresh)
            for event in monitor.fresh:
                for criterion in self.criteria:
                    if criterion.vehicle == name:
                        criterion.collision(event)
        self._measure(now_s)
        if self.progress is not None:
            self.progress(now_s, self.spec.duration_s)

    def _measure(self, now_s):
        vut = self.spec.vehicle
        for name, handle in self.vehicles.items():
            sample = handle.sample(now_s)
            track = self.tracks[name]
            track.time_s.append(now_s)
            track.x_m.append(sample.x_m)
            track.y_m.append(sample.y_m)
            track.yaw_rad.append(sample.yaw_rad)
            if name == vut:
                self.digest.update(handle.odometry_row(now_s))
            for criterion in self.criteria:
                if criterion.vehicle == name:
                    criterion.observe(sample)
        if self.scene.traffic is not None:
            for name, x, y, yaw, length, width in self.scene.traffic():
                track = self.traffic_tracks.get(name)
                if track is None:
                    track = self.traffic_tracks[name] = Track(outline=Outline(
                        -0.5 * length, 0.5 * length, -0.5 * width, 0.5 * width))
                track.time_s.append(now_s)
                track.x_m.append(x)
                track.y_m.append(y)
                track.yaw_rad.append(yaw)

    def close(self):
        self.world = None


def run_scenario(spec_or_path, seed=None, gui=False, progress=None, repeat=1,
                 transport=None, foxglove=None, record=None, real_time_factor=None,
                 wait_for_client=None) -> ScenarioResult:
    """
    Run a scenario and return its result.

    :param spec_or_path: a ScenarioSpec or the path of a scenario file.
    :param seed: overrides the file's seed.
    :param gui: open PyBullet's GUI (local simulations).
    :param progress: ``progress(time_s, duration_s)`` after each step.
    :param repeat: run this many times (external processes: the spread of the values).
    :param transport: the served nodes' transport (None = VEHICLE_SIM_TRANSPORT).
    :param foxglove: (host, port) of a live Foxglove view of the automobile node (the scenario
        is then served); None: none.
    :param record: an MCAP file to record every topic of the run into (the simulation is then
        served over ROS, so that its topics are published); with ``repeat``, the last run's.
    :param real_time_factor: simulated seconds per wall-clock second (0: as fast as possible);
        None: the scenario's own (an external driver's ``real_time_factor``, else as fast as
        possible). The results do not depend on it (stepping is synchronous).
    :param wait_for_client: with ``foxglove``: each run waits for a Foxglove client to connect
        before its first step, calling ``wait_for_client(url)`` when it starts waiting; None:
        no wait.
    :raises ScenarioError: for an invalid file or a refused scripted command.
    :raises RecordingError: when the recording cannot be created.
    """
    spec = spec_or_path if isinstance(spec_or_path, ScenarioSpec) else load_scenario(
        spec_or_path)
    if seed is not None:
        spec = spec.with_seed(seed)
    if repeat < 1:
        raise ValueError(f'repeat = {repeat!r}: must be >= 1')
    if real_time_factor is not None and not real_time_factor >= 0.0:
        raise ValueError(f'real_time_factor = {real_time_factor!r}: must be >= 0')
    if real_time_factor is not None and spec.driver.kind == 'processes':
        spec = replace(spec, driver=replace(spec.driver, real_time_factor=real_time_factor))
        real_time_factor = None         # the external driver's loop paces
    results = [_run_once(spec, gui, progress, transport, foxglove, record,
                         real_time_factor or 0.0, wait_for_client)
               for _ in range(repeat)]
    result = results[-1]
    if repeat > 1:
        result.runs = repeat
        result.spread = _spread(results)
        result.error = next((r.error for r in results if r.error), None)
        if not all(r.passed for r in results):
            failed = sum(not r.passed for r in results)
            result.error = result.error or f'{failed} of {repeat} runs failed'
    return result


def _spread(results):
    spread = {}
    for index, criterion in enumerate(results[0].criteria):
        values = [r.criteria[index].value for r in results
                  if r.criteria[index].value is not None]
        spread[criterion.name] = (min(values), max(values)) if values else (None, None)
    return spread


def _run_once(spec, gui, progress, transport, foxglove=None, record=None, pace=0.0,
              wait_for_client=None):
    criteria = build_criteria(spec.criteria, spec.duration_s)
    director = Director(spec, criteria, progress)
    # The live view shows the automobile node and a recording holds its topics: a scenario
    # watched or recorded is served.
    served = spec.served or foxglove is not None or record is not None
    start = time.monotonic()
    recorder = None
    if record is not None:
        from vehicle_sim.recording.bag_writer import BagWriter
        from vehicle_sim.recording.recorder import Recorder
        recorder = Recorder(BagWriter(record), use_sim_time=True,
                            on_error=lambda text: director.notes.append(text))
    try:
        sim = (ServedSim(spec, director, spec.seed, gui, transport, foxglove, recorder)
               if served else LocalSim(spec, director, spec.seed, gui))
    except BaseException:
        if recorder is not None:
            recorder.close()
        raise
    error = None
    watcher = None
    try:
        director.attach(sim)
        if wait_for_client is not None and foxglove is not None:
            _wait_for_client(sim, wait_for_client)
            start = time.monotonic()        # the run's wall time starts with its first step
        kind = spec.driver.kind
        if kind == 'processes':
            error = run_processes(spec, sim, criteria, transport)
        else:
            if served:
                watcher = TopicWatcher(sim, criteria, transport)
            pacer = Pacer(pace, sim.spin if watcher is None else watcher.spin)
            pacer.start(sim.world.time_s)

            def step():
                # one basic step; a served world also publishes and serves its nodes
                sim.step()
                if watcher is not None:
                    watcher.spin()
                pacer.wait(sim.world.time_s)

            if kind == 'controller':
                error = _run_controller(spec, sim, director, step)
            while sim.world.time_s < spec.duration_s - _EPS_S:
                step()
            if watcher is not None:
                watcher.drain()
        sim_time_s = sim.world.time_s
    finally:
        if watcher is not None:
            watcher.close()
        director.close()
        sim.close()
        if recorder is not None:
            recorder.close()
    return ScenarioResult(spec, spec.seed, [c.result() for c in criteria], sim_time_s,
                          time.monotonic() - start, director.tracks,
                          director.digest.hexdigest(), not served or kind != 'processes',
                          error, collisions=director.collisions, notes=director.notes,
                          recording=record, traffic_tracks=director.traffic_tracks,
                          lanes=director.scene.lanes, walls=director.scene.walls)


def _wait_for_client(sim, announce):
    """Serve the nodes until a Foxglove client has connected to the live view."""
    live_view = sim.live_view
    announce(live_view.url)
    while not live_view.wait_for_client(CLIENT_WAIT_SLICE_S):
        sim.spin()


# ---------------------------------------------------------------------------- in-process
def _run_controller(spec, sim, director, step):
    """Run the controller script with Driver() bound to the vehicle under test."""
    from vehicle_sim.webots.host import ControllerHost, ControllerStopped, hosting
    vut = director.vut
    host = ControllerHost(sim.world, vut.car, vut.sensors, spec.world.origin, spec.duration_s,
                          step, lanes=getattr(sim, 'lanes', None),
                          signals=director.signals)
    script = spec.driver.controller
    saved_argv, saved_path = sys.argv, list(sys.path)
    saved_seed = os.environ.get('VEHICLE_SIM_SEED')
    sys.argv = [script] + list(spec.driver.args)
    sys.path.insert(0, os.path.dirname(os.path.abspath(script)))
    os.environ['VEHICLE_SIM_SEED'] = str(spec.seed)
    _seed_random(spec.seed)
    try:
        with hosting(host):
            runpy.run_path(script, run_name='__main__')
    except ControllerStopped:
        pass
    except SystemExit as exit_:
        if exit_.code not in (None, 0):
            return f'controller {script} exited with status {exit_.code}'
    except ScenarioError:
        raise
    except Exception:  # noqa: BLE001 - the controller's failure is the run's error
        return f'controller {script} raised:\n{traceback.format_exc(limit=-3)}'
    finally:
        sys.argv, sys.path[:] = saved_argv, saved_path
        if saved_seed is None:
            os.environ.pop('VEHICLE_SIM_SEED', None)
        else:
            os.environ['VEHICLE_SIM_SEED'] = saved_seed
        for driver in host.drivers:
            driver.sensors.close()
    return None


def _seed_random(seed):
    random.seed(seed)
    try:
        import numpy
        numpy.random.seed(seed)
    except ImportError:     # pragma: no cover - numpy is a dependency
        pass
