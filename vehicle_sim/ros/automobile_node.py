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
The ``automobile`` node: Webots' ``ros_automobile`` interface (docs/ros_interface.md).

:class:`AutomobileNode` owns one PyBullet :class:`~vehicle_sim.physics.World` and one or more
:class:`~vehicle_sim.physics.SimulatedCar` (a world file, or one default car), and serves each
car's ``/<ns>/automobile/*`` and ``/<ns>/robot/*`` endpoints from :mod:`.automobile_interfaces`.
It is written once against the transport port, so the same code runs on rclpy and on the
embedded Cyclone DDS transport. :func:`main` is the ``automobile`` executable; the
``autoware_automobile`` node composes :class:`AutomobileNode` on its own ROS node, the one node
module that imports another (declared in ``NODE_COMPOSITION`` of test/test_repo_layers.py).

Run: ``ros2 run vehicle_sim automobile --ros-args -p car_model:=ToyotaPrius`` or
``python -m vehicle_sim.ros.automobile_node --ros-args --params-file config/automobile.yaml``.

Time: in real-time mode a wall-clock timer of period ``time_step / real_time_factor`` steps the
world while the node spins between steps (services stay responsive); ``real_time_factor`` 0
steps on every non-blocking spin; ``synchronous`` steps only on ``robot/time_step`` calls, which
are queued and run in chunks from the node's loop (:mod:`.time_step`), so the node keeps
serving and honours signals however long a request is.

Reset, teleport and pause (``reset``, ``set_pose``, ``/sim/reset``,
``/sim/pause``, ``/initialpose``): :mod:`.sim_control`; a paused node skips its step timer.

Pacing: each step feeds a :class:`~vehicle_sim.core.world.pacing.RealTimeMeter` (simulated
time per wall time, over 1 s windows); in real-time mode a window below the asked factor logs a
throttled warning with the achieved factor, and :attr:`AutomobileNode.achieved_real_time_factor`
gives it to the ``vehicle-sim run`` status line.
"""

from dataclasses import replace
import sys
import time
from types import SimpleNamespace
from typing import Callable, Dict, List, Optional

from vehicle_sim.core.commands.drive_input import CarDriveInput
from vehicle_sim.core.geometry.angles import yaw_from_quaternion
from vehicle_sim.core.sensors.sampling import SampleSchedule
from vehicle_sim.core.specs.errors import InvalidCommandError
from vehicle_sim.core.traffic.objects import obstacle_objects
from vehicle_sim.core.world.pacing import RealTimeMeter
from vehicle_sim.physics import SimulatedCar
from vehicle_sim.physics.gui import ChaseCamera, GuiClosedError, shortcuts_text
from vehicle_sim.physics.scene import build_scene
from vehicle_sim.physics.sensors import SensorFeed
from vehicle_sim.ros import automobile_interfaces as itf
from vehicle_sim.ros.car_context import CarContext
from vehicle_sim.ros.car_lanes import publish_car_lanes, wire_car_lanes
from vehicle_sim.ros.descriptions import mounted_sensors
from vehicle_sim.ros.endpoints import (
    EACH_PUBLISH,
    EACH_SAMPLE,
    EACH_STEP,
    ON_EVENT,
    ONCE_LATCHED,
    Outputs,
    serve,
    subscribe,
)
from vehicle_sim.ros.map_interfaces import (
    fixed_frame,
    map_in_world,
    map_static_transform,
    MapOutputs,
)
from vehicle_sim.ros.messages import stamp_builder
from vehicle_sim.ros.node_support import run_main
from vehicle_sim.ros.sensor_interfaces import check_names, sensor_rows
from vehicle_sim.ros.sim_control import serve_vehicle, WorldControl
from vehicle_sim.ros.sim_params import (
    declare_parameters,
    initialpose_index,
    parameter_names,
    world_spec,
)
from vehicle_sim.ros.time_step import TimeStepService
from vehicle_sim.ros.traffic_interfaces import (
    AT_OBJECTS_RATE,
    AT_SIGNAL_CHANGES,
    AT_SIGNALS,
    object_topics,
    objects_rate_hz,
    signal_topics,
)
from vehicle_sim.ros.traffic_messages import signal_groups_reader
from vehicle_sim.transport import create_node
from vehicle_sim.transport.logger import ThrottledWarning
from vehicle_sim.transport.names import resolve_name

NODE_NAME = 'automobile'

# Timer period standing for "as fast as possible" (the port's timers need a period > 0).
AS_FAST_AS_POSSIBLE_PERIOD_S = 1e-6
# Wall time between two "behind real time" warnings [s] (each counts the ones it held back).
BEHIND_WARNING_PERIOD_S = 5.0

_FROM_CORE = {'float': float, 'int': int, 'bool': bool}


def start_live_view(node, settings):
    """Start the Foxglove live view of the ``foxglove`` parameter (docs/foxglove.md)."""
    from vehicle_sim.foxglove.live_view import LiveView
    return LiveView(node, host=settings.foxglove_host, port=settings.foxglove,
                    parameter_names=parameter_names())


def live_transform(parent, child, xyz, q):
    """Return one transform of the tree for the live view."""
    from vehicle_sim.foxglove.scene import Transform
    return Transform(parent, child, tuple(xyz), tuple(q))


def _to_core(kind, value):
    # The Webots-shaped services carry the core's own units (km/h, rad + = right), so only the
    # Python type is normalised; CarLogic does the validation.
    if kind == 'float':
        return float(value)
    if kind == 'bool':
        return bool(value)
    return int(value)


class AutomobileNode:
    """
    Simulated cars behind Webots' ros_automobile interface.

    In-process API (tests, benchmarks): :meth:`step_once`, :meth:`step`, :meth:`reset` (as
    /sim/reset), :attr:`paused`, :attr:`world`, :attr:`scene` (the Scene the scene builder
    made: vehicles by name with body, car and sensor feed), :attr:`vehicles` (namespace ->
    SimulatedCar), :attr:`settings`, :meth:`close`.
    """

    def __init__(self, args=None, *, transport: Optional[str] = None,
                 parameter_overrides: Optional[Dict] = None, node=None, drive_inputs=True,
                 wall_clock: Callable[[], float] = time.monotonic):
        """
        Build the world, the cars and every endpoint.

        :param args: command line (its ``--ros-args`` part: parameters, remaps).
        :param transport: 'auto', 'rclpy' or 'dds' (default: VEHICLE_SIM_TRANSPORT).
        :param parameter_overrides: parameter values winning over the command line.
        :param node: an existing NodePort to use instead of creating one.
        :param drive_inputs: wire each car's cmd_vel and drive (False: a composing node drives
            the cars itself, as autoware_automobile does).
        :param wall_clock: the monotonic wall clock [s] the pacing is measured with (tests
            inject one).
        :raises InvalidParameterError: for a refused parameter or an invalid world file.
        :raises TransportError: for a refused parameter override.
        """
        self.node = node if node is not None else create_node(
            NODE_NAME, args=args, transport=transport,
            parameter_overrides=parameter_overrides)
        self.world = None
        self._drive_inputs = drive_inputs
        self._wall_clock = wall_clock
        self._pace = None
        self._timer = None
        self._time_step = None
        self._control = None
        self._sensing = []
        self._traffic = None
        self._objects_due = None
        self._signals = None
        self._gui_closed = False
        self._live = None
        try:
            self._build()
        except BaseException as error:
            # The window closed while the world was being built: say so, not PyBullet's error.
            window_closed = self.world is not None and self.world.gui_closed
            self.close()
            if window_closed and not isinstance(error, GuiClosedError):
                raise GuiClosedError('the PyBullet window was closed during start-up') from None
            raise

    def _build(self):
        node = self.node
        self._logger = node.get_logger()
        self._warn_setter_note = ThrottledWarning(self._logger)
        self.settings = settings = declare_parameters(node)
        if settings.foxglove:
            # Before any endpoint: the live view sees every publisher and service created.
            self._live = start_live_view(node, settings)
        spec = self._with_sensor_parameter(world_spec(settings))
        # Collisions are watched when there is something besides the ground to hit: obstacles,
        # other vehicles, map walls, traffic (and a lane map's barriers: curbstones, walls).
        collisions = (bool(spec.obstacles) or len(spec.vehicles) > 1 or spec.map is not None
                      or spec.traffic is not None)

        def feed(vehicle, scene):
            # Each vehicle's sensors at their rates, and its collisions (ros: their topics).
            watch = collisions or any(getattr(part, 'barrier_count', 0)
                                      for part in scene.parts.values())
            return SensorFeed(scene.world, vehicle.body, vehicle.spec.sensors, scene.origin,
                              watch)

        self.scene = build_scene(spec, time_step_s=settings.time_step_s,
                                 friction=settings.friction, gui=settings.gui, mount=feed)
        self.world = self.scene.world
        if self._live is not None:
            self._live.show(self.scene)
        self._publish_every = settings.publish_every_steps
        # Synchronous stepping has no target: the factor is measured (status line), never behind.
        self._pace = RealTimeMeter(0.0 if settings.synchronous else settings.real_time_factor)
        self._warn_behind = ThrottledWarning(self._logger, BEHIND_WARNING_PERIOD_S)
        self._stamp = stamp_builder(node.msg)
        # One queue for every vehicle's robot/time_step: they all advance the one world.
        self._time_step = TimeStepService(node, settings.time_step_ms, self.step_once,
                                          settings.synchronous)
        self._vehicles: List[CarContext] = []
        self._taken_names = self._interface_names(spec)
        self._scene_source = spec.source or node.get_fully_qualified_name()
        for built in self.scene.vehicles.values():
            vehicle = CarContext(built.spec, built.car, built.spec.sensors)
            vehicle.feed = built.sensors
            self._wire_vehicle(vehicle)
            self._vehicles.append(vehicle)
        self._sensing = [v for v in self._vehicles if v.feed.active]
        if settings.gui and self._vehicles:
            ChaseCamera(self.world, [v.car for v in self._vehicles])
            self._logger.info(f'PyBullet window open; keys: {shortcuts_text()}')
        self._wire_world()
        # /sim/reset, /sim/pause, /initialpose (ros/sim_control.py).
        # the traffic and the signals start again with the world
        resets = tuple(part for part in (self.scene.parts.get(name)
                                         for name in ('traffic', 'signals')) if part is not None)
        self._control = WorldControl(
            node, self.world, self._vehicles, settings.synchronous,
            self._vehicles[initialpose_index(settings, spec)],
            map_in_world=None if spec.map is None else map_in_world(spec.map), resets=resets)
        self._publish_latched()
        self._publish_step(self.world.time_s)
        if not settings.synchronous:
            period = (settings.time_step_s / settings.real_time_factor
                      if settings.real_time_factor > 0.0 else AS_FAST_AS_POSSIBLE_PERIOD_S)
            self._timer = node.create_timer(period, self._on_step_timer)
        mode = ('synchronous (robot/time_step)' if settings.synchronous else
                f'real_time_factor {settings.real_time_factor:g}')
        node_ns = node.get_namespace().rstrip('/')   # a `-r __ns:=/x` remap moves everything
        names = ', '.join(f'{v.spec.name} ({v.spec.model}) under '
                          f'{node_ns}/{itf.vehicle_name("automobile", v.spec.namespace)}'
                          for v in self._vehicles)
        node.announce_ready(f'automobile ready: {names}; step {settings.time_step_ms} ms, {mode}')

    # ------------------------------------------------------------------------------ wiring

    def _with_sensor_parameter(self, spec):
        # The world's vehicles with their sensors: the world's, plus the presets' the sensors
        # parameter mounts.
        fqn = self.node.get_fully_qualified_name()
        return replace(spec, vehicles=tuple(
            replace(vehicle, sensors=mounted_sensors(
                vehicle, self.settings.sensors,
                f'{fqn}: parameter sensors, vehicle {vehicle.name!r}'))
            for vehicle in spec.vehicles))

    def _full_name(self, vehicle_namespace):
        # row name -> its fully-qualified name on this node (remaps aside).
        namespace, name = self.node.get_namespace(), self.node.get_name()
        return lambda row_name: resolve_name(itf.vehicle_name(row_name, vehicle_namespace),
                                             namespace, name)

    def _interface_names(self, scene):
        # {fully-qualified name: what has it} of every table row of the node.
        global_name = self._full_name('')
        taken = {global_name(row.name): 'a topic of the node'
                 for row in itf.WORLD_TOPICS + object_topics(bool(scene.traffic),
                                                             bool(scene.obstacles))
                 + signal_topics(self.signal_controller)}
        taken.update({global_name(row.name): 'an endpoint of the node'
                      for row in itf.WORLD_SERVICES + itf.WORLD_INPUTS})
        for spec in scene.vehicles:
            full_name = self._full_name(spec.namespace)
            for row in (itf.VEHICLE_TOPICS + itf.LANE_TOPICS + itf.INPUT_TOPICS + itf.SERVICES
                        + itf.LANE_SERVICES):
                taken[full_name(row.name)] = f'{row.name!r} of vehicle {spec.name!r}'
        return taken

    def _sensor_rows(self, vehicle):
        # The vehicle's sensor rows, refused when a name is taken in the node's interface.
        rows = sensor_rows(vehicle.sensors)
        where = f'{self._scene_source}: vehicle {vehicle.spec.name!r}'
        check_names(rows, self._taken_names, self._full_name(vehicle.spec.namespace), where)
        return rows

    def _wire_vehicle(self, vehicle):
        node = self.node
        ns = vehicle.spec.namespace

        def resolve(name):
            return itf.vehicle_name(name, ns)

        vehicle.outputs = Outputs(node, itf.VEHICLE_TOPICS + self._sensor_rows(vehicle),
                                  vehicle, resolve)
        handlers = {
            itf.SETTER: self._handle_setter,
            itf.GETTER: self._handle_getter,
            itf.DIMENSIONS: self._handle_get_dimensions,
            itf.TIME_STEP: self._handle_time_step,
            itf.WORLD_TIME: self._handle_get_time,
            itf.BASIC_TIME_STEP: self._handle_get_basic_time_step,
        }
        vehicle.services = list(serve(node, {
            spec: self._bind(handlers[spec.kind], spec, vehicle, resolve(spec.name))
            for spec in itf.SERVICES if spec.kind in handlers}, resolve).values())
        vehicle.services += serve_vehicle(node, itf.POSE_SERVICES, vehicle, resolve).values()
        if self.scene.lanes is not None:    # lane_state, lane_invasion, set_lane_pose
            wire_car_lanes(node, vehicle, self.scene.lanes, fixed_frame(self.scene.spec),
                           resolve, self.signal_controller)
        vehicle.drive = CarDriveInput(vehicle.logic, self.settings.cmd_vel_timeout_s)
        if self._drive_inputs:
            self._wire_inputs(vehicle, resolve)

    def _wire_inputs(self, vehicle, resolve):
        # cmd_vel and drive (docs/drive.md): commands on receipt, the watchdog in step_once.
        settings, drive = self.settings, vehicle.drive
        logger = self.node.get_logger()
        dropped, saturated = ThrottledWarning(logger), ThrottledWarning(logger)

        def callback(row, apply):
            name, read = resolve(row.name), row.converter

            def on_message(msg):
                try:
                    target = apply(*read(msg), self.world.time_s)
                except InvalidCommandError as error:
                    dropped.warn(f'{name}: {error}')
                    return
                for note in target.notes:
                    saturated.warn(f'{name}: {note}')
            return on_message

        cmd_vel = itf.CMD_VEL_INPUTS[settings.cmd_vel_stamped]
        vehicle.inputs = subscribe(self.node, {
            cmd_vel: callback(cmd_vel, drive.twist),
            itf.DRIVE: callback(itf.DRIVE, drive.ackermann)}, resolve)

    def _wire_world(self):
        # The global rows (/clock, /tf, /tf_static): once for the node, all vehicles in one
        # message.
        vehicles = self._vehicles
        self._fleet = SimpleNamespace(
            tf_frames=[(v.odom_frame, v.base_frame) for v in vehicles],
            static_transforms=[t for v in vehicles for t in v.static_transforms()],
            stamp=None, tf_poses=None)
        world_map = self.scene.spec.map
        if world_map is not None:     # map -> world, the root of the tree (docs/maps.md)
            self._fleet.static_transforms.insert(0, map_static_transform(world_map))
        self._fleet_outputs = Outputs(self.node, itf.WORLD_TOPICS, self._fleet)
        # /map, /map/lanes and their kin (ros/map_interfaces.py), for a world with a map.
        parts = self.scene.parts
        self._map_outputs = MapOutputs(self.node, parts.get('map'), parts.get('roads'),
                                       fixed_frame(self.scene.spec))
        if self._map_outputs.summary:
            self._logger.info(self._map_outputs.summary)
        # The traffic rows (ros/traffic_interfaces.py): the objects for a world with traffic
        # or obstacles, the markers with traffic.
        bodies = self.scene.parts.get('traffic')
        rows = object_topics(bodies is not None, bool(self.scene.spec.obstacles))
        self._traffic = None if not rows else SimpleNamespace(
            frame=fixed_frame(self.scene.spec),
            colours=() if bodies is None else bodies.colours, bodies=bodies, stamp=None,
            objects=None, obstacles=())
        self._traffic_outputs = None if not rows else Outputs(self.node, rows, self._traffic)
        if rows:     # at their own rate on simulated time (docs/traffic.md), from now on
            spec = self.scene.spec
            rate_hz = objects_rate_hz(self.settings.objects_rate_hz, spec.traffic)
            self._objects_due = SampleSchedule.from_rate(rate_hz, self.settings.time_step_s,
                                                         self.world.step_count)
            if rate_hz != self.settings.objects_rate_hz:
                self._logger.info(f'{spec.traffic.source}: objects_rate {rate_hz:g} Hz (the '
                                  f"world's; parameter objects_rate "
                                  f'{self.settings.objects_rate_hz:g} Hz not used)')
        # The signals' rows, for a world whose lane map has traffic light groups: the states at
        # the objects' rate and at the step a group changes state, the lamps' markers at the
        # changes (ros/traffic_interfaces.py).
        controller = self.signal_controller
        rows = signal_topics(controller)
        if rows:
            rate_hz = objects_rate_hz(self.settings.objects_rate_hz, self.scene.spec.traffic)
            self._signals = SimpleNamespace(
                controller=controller, read=signal_groups_reader(controller.rules),
                frame=fixed_frame(self.scene.spec), lanes=self.scene.lanes,
                outputs=None, stamp=None, groups=None, states=None,
                due=SampleSchedule.from_rate(rate_hz, self.settings.time_step_s,
                                             self.world.step_count))
            self._signals.outputs = Outputs(self.node, rows, self._signals)


    @staticmethod
    def _bind(handler, spec, vehicle, name):
        def callback(request, response):
            return handler(spec, vehicle, name, request, response)
        return callback

    # ------------------------------------------------------------------------------ services

    def _handle_setter(self, spec, vehicle, name, request, response):
        value = request.value
        try:
            note = getattr(vehicle.logic, spec.core)(_to_core(spec.value, value))
        except InvalidCommandError as error:
            # Odd input, ROS column (docs/deviations.md): success=false, nothing changed, the
            # reason logged.
            self._logger.warn(f'{name}: refused {value!r}: {error}; nothing changed')
            response.success = False
        else:
            response.success = True
            if note is not None:    # taken, but without effect now (e.g. a brake in SPEED mode)
                self._warn_setter_note.warn(f'{name}: {note}')
            if spec.name in itf.LONGITUDINAL_SERVICES:
                # A later service call wins over the last cmd_vel/drive command: the watchdog
                # lets it stand until the next command arrives (docs/drive.md, precedence).
                vehicle.drive.service_override()
        return response

    def _handle_getter(self, spec, vehicle, name, request, response):
        response.value = _FROM_CORE[spec.value](getattr(vehicle.logic, spec.core))
        return response

    def _handle_get_dimensions(self, spec, vehicle, name, request, response):
        dims = vehicle.logic.dimensions()
        response.track_front = float(dims.track_front_m)
        response.track_rear = float(dims.track_rear_m)
        response.wheel_base = float(dims.wheelbase_m)
        response.front_wheel_radius = float(dims.front_wheel_radius_m)
        response.rear_wheel_radius = float(dims.rear_wheel_radius_m)
        return response

    def _handle_time_step(self, spec, vehicle, name, request, response):
        # A deferred reply: answered once this request's own steps are done.
        return self._time_step.handle(name, request, response)

    def _handle_get_time(self, spec, vehicle, name, request, response):
        response.value = float(self.world.time_s)
        return response

    def _handle_get_basic_time_step(self, spec, vehicle, name, request, response):
        response.value = float(self.settings.time_step_ms)
        return response

    # ------------------------------------------------------------------------------ stepping

    def _on_step_timer(self):
        if not self._control.paused:     # /sim/pause
            self.step_once()
        else:                            # held time is not falling behind
            self._pace.restart()

    def step_once(self) -> float:
        """
        Advance the world by one basic step and publish; return the simulated time [s].

        /clock is published every step, the other topics every publish period. Requests that
        came in during the physics step are served before the publishing (they take effect at
        the next step), so none waits for the whole step.
        """
        if self._gui_closed:
            return self.world.time_s
        try:
            time_s = self.world.step()
            for vehicle in self._vehicles:
                if vehicle.drive.tick(time_s):
                    self._logger.warn(
                        f'{itf.vehicle_name("cmd_vel", vehicle.spec.namespace)}: no cmd_vel or '
                        f'drive command for {vehicle.drive.watchdog.timeout_s:g} s: safety '
                        'stop (cruising speed 0, throttle released, brake 1)')
            self.node.serve_pending()
            self._publish_step(time_s)
            if self._pace.update(self._wall_clock(), time_s):
                self._report_behind()
        except Exception:
            # The window closes asynchronously: whichever PyBullet call comes next fails.
            if not self.world.gui_closed:
                raise
            self._gui_closed = True
            self._logger.info('the PyBullet window was closed: shutting down')
            self.node.request_shutdown()
            return self.world.time_s
        return time_s

    def _report_behind(self):
        pace = self._pace
        self._warn_behind.warn(
            f'behind real time: {pace.factor:.2f}x achieved over the last '
            f'{pace.window_wall_s:.1f} s of wall time, real_time_factor {pace.target:g} asked; '
            'a step and its publishing take longer than its period (fewer subscribers, a '
            'larger publish_period_ms or a lower objects_rate lighten it)')

    def step(self, count: int = 1) -> float:
        """Advance the world by ``count`` basic steps; return the simulated time [s]."""
        time_s = self.world.time_s
        for _ in range(count):
            time_s = self.step_once()
        return time_s

    # ------------------------------------------------------------------------------ publishing

    def _publish_step(self, time_s):
        fleet = self._fleet
        fleet.stamp = stamp = self._stamp(time_s)
        outputs = self._fleet_outputs
        outputs.publish(EACH_STEP, fleet)
        if self.world.step_count % self._publish_every == 0:
            vehicles = self._vehicles
            serve_pending = self.node.serve_pending if len(vehicles) > 1 else None
            # /tf's poses are taken with each car's sample, before a request can move it.
            tf_poses = [] if outputs.wanted(EACH_PUBLISH) else None
            for vehicle in vehicles:
                vehicle.sample(stamp)
                vehicle.outputs.publish(EACH_PUBLISH, vehicle)
                if vehicle.lanes is not None:
                    publish_car_lanes(vehicle, time_s, self._stamp)
                if tf_poses is not None:
                    tf_poses.append(vehicle.odom[:2])
                if serve_pending is not None:   # a request waits for one car's burst at most
                    serve_pending()
            fleet.tf_poses = tf_poses
            outputs.publish(EACH_PUBLISH, fleet)
            if self._live is not None:
                self._live.publish(time_s, self._transforms)
        traffic = self._traffic
        if (traffic is not None and self._objects_due.due(self.world.step_count)
                and self._traffic_outputs.wanted(AT_OBJECTS_RATE)):
            traffic.stamp = stamp
            bodies = traffic.bodies
            traffic.objects = () if bodies is None else bodies.objects()
            traffic.obstacles = obstacle_objects(self.scene.spec.obstacles,
                                                 self._obstacle_pose, self.world.labels.instance)
            self._traffic_outputs.publish(AT_OBJECTS_RATE, traffic)
        signals = self._signals
        if signals is not None and (signals.outputs.wanted(AT_SIGNALS)
                                    or signals.outputs.wanted(AT_SIGNAL_CHANGES)):
            due = signals.due.due(self.world.step_count)
            states = signals.controller.states()
            changed = states != signals.states
            if due or changed:
                signals.stamp, signals.states = stamp, states
                signals.groups = signals.read(states)
                signals.outputs.publish(AT_SIGNALS, signals)
                if changed:         # the lamps' markers (RViz): only when a light changes
                    signals.outputs.publish(AT_SIGNAL_CHANGES, signals)
        for vehicle in self._sensing:
            self._publish_sensors(vehicle)

    def _obstacle_pose(self, name):
        # (x, y, z, yaw) of a movable obstacle now (PredictedObjects).
        (position, (qx, qy, qz, qw)), _, _ = self.world.body_state(self.world.obstacles[name])
        return (*position, yaw_from_quaternion(qx, qy, qz, qw))

    def _publish_sensors(self, vehicle):
        # Every reading and collision event since the last call, stamped with its own
        # simulated time (the feed keeps them across steps published together).
        samples, events = vehicle.feed.take()
        outputs, stamp = vehicle.outputs, self._stamp
        for time_s, readings in samples:
            vehicle.sample_stamp, vehicle.readings = stamp(time_s), readings
            outputs.publish(EACH_SAMPLE, vehicle)
        for event in events:
            vehicle.event_stamp, vehicle.event = stamp(event.time_s), event
            outputs.publish(ON_EVENT, vehicle)

    def _publish_latched(self):
        fleet = self._fleet
        fleet.stamp = self._stamp(self.world.time_s)
        self._fleet_outputs.publish(ONCE_LATCHED, fleet)
        self._map_outputs.publish_latched(fleet.stamp)
        for vehicle in self._vehicles:
            vehicle.sample(fleet.stamp)
            vehicle.outputs.publish(ONCE_LATCHED, vehicle)

    def _transforms(self):
        # The tree /tf_static and /tf carry (world -> odom -> base_link -> sensors), for the
        # live view's FrameTransforms.
        found = [live_transform(*t) for t in self._fleet.static_transforms]
        found += [live_transform(v.odom_frame, v.base_frame, *v.odom[:2])
                  for v in self._vehicles]
        return found

    # ------------------------------------------------------------------------------ access

    def reset(self) -> str:
        """Reset every vehicle and movable obstacle (as /sim/reset); return what was reset."""
        return self._control.reset()

    def reset_vehicle(self, namespace: str) -> str:
        """Reset one vehicle (as its ``<ns>/reset``); return what was reset."""
        return self._vehicle(namespace).reset()

    def add_reset_listener(self, namespace: str, callback: Callable[[], None]) -> None:
        """
        Call ``callback()`` after each reset of a vehicle (its ``<ns>/reset``, /sim/reset).

        For a node composing this one that keeps state of its own about the car (as
        autoware_automobile does): it runs after the car is back in its start state and before
        the reset is reported.
        """
        self._vehicle(namespace).reset_listeners.append(callback)

    def _vehicle(self, namespace):
        for vehicle in self._vehicles:
            if vehicle.spec.namespace == namespace:
                return vehicle
        raise KeyError(f'no vehicle {namespace!r}; known: '
                       f'{sorted(v.spec.namespace for v in self._vehicles)}')

    @property
    def achieved_real_time_factor(self) -> Optional[float]:
        """Simulated time per wall time over the last second of wall time; None before one."""
        return self._pace.factor

    @property
    def paused(self) -> bool:
        """True while /sim/pause holds simulated time (real-time mode)."""
        return self._control.paused

    @property
    def signal_controller(self):
        """The world's SignalController (its 'signals' scene part), or None."""
        return getattr(self.scene.parts.get('signals'), 'controller', None)

    @property
    def live_view(self):
        """The Foxglove LiveView of the ``foxglove`` parameter, or None."""
        return self._live

    @property
    def vehicles(self) -> Dict[str, SimulatedCar]:
        """Namespace ('' for the default car) -> SimulatedCar."""
        return {v.spec.namespace: v.car for v in self._vehicles}

    def close(self):
        """Stop stepping, leave the graph and free the physics (idempotent)."""
        if self._live is not None:
            self._live.close()
        if self._timer is not None:
            self._timer.cancel()
            self._timer = None
        if self._time_step is not None:
            self._time_step.close()
        if self.node is not None:
            self.node.shutdown()
        if self.world is not None:
            self.world.close()


def main(args=None):
    """Entry point ``automobile``: build the node and spin it (Jazzy main shape)."""
    return run_main(NODE_NAME, AutomobileNode, args)


if __name__ == '__main__':
    sys.exit(main())
