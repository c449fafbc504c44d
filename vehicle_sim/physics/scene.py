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
The scene builder: the one place a WorldSpec becomes a filled World.

Every world of the simulator is built here: the automobile node's, the robot node's, the Webots
Driver's, the scenario runner's (and the coming Gym environment's). :func:`build_scene` adds, in
this order (the world calls its step hooks in registration order, so the order is part of the
contract):

1. the World (its own physics client and the ground), or the given World to add to;
2. ``hooks``: step hooks that act before every vehicle (a scenario's director);
3. the obstacles (ObstacleSpec), then the cars (SimulatedCar, in file order), then the robots
   (DiffRobotBody); the World refuses a vehicle that starts inside an obstacle;
4. the scene ``parts``, in order (see below);
5. each vehicle's sensors, through ``mount`` (SensorSuite or SensorFeed, as the caller needs).

Extension points: a *scene part* is any object with ``name`` and ``build(world, spec)``; it adds
what the WorldSpec asks of it (a map layer's ground and walls, traffic vehicles) once the
obstacles and vehicles are in, and returns what callers read later, kept in
:attr:`Scene.parts` under its name (a part with ``reads_parts = True`` is built with
``build(world, spec, parts)``: the scene's parts by name, those built before it in, e.g. the
lamps reading ``parts['signals'].controller``). The parts a world gets by itself are the rows of
:data:`SCENE_PARTS`, one per world key the obstacles and vehicles leave (a test checks them
against core/world/params.py's ``WORLD_KEYS``) and those with ``world_key=False`` that draw what
other parts made, each added when the WorldSpec asks for it: a
``map`` gets the map layer (physics/map_layer.py), ``scene.parts['map']``; ``roads:`` the road
layer (physics/lane_layer.py), ``scene.parts['roads']``; a lane map with traffic lights (or a
``signals:`` key) the world's one SignalController (physics/signal_part.py),
``scene.parts['signals'].controller``; a lane map with traffic light bulbs the lamps
(physics/signal_lamps.py), ``scene.parts['signal_lamps']``, after the signals, whose
controller they show; these before the caller's ``parts``; ``traffic:`` the traffic part
(physics/traffic_bodies.py), on its lane map, after them. A part of the caller's with a row's
name takes that row's place; a world that asks for none gets no part and pays nothing.

Lanes: before anything is built, the world's lane map (a lanelet2 map, a SUMO network or its
roads) is loaded and the vehicles placed by lane get their pose (vehicle_sim/maps/
lane_maps.py), so a bad file or a vehicle off every lane is refused with nothing built;
:attr:`Scene.lanes` is that LaneGraph (None without a lane map), ``scene.spec`` the WorldSpec
with it.

It returns a :class:`Scene`: the World, the vehicles by name (:class:`SceneVehicle`: body, car,
sensors), the obstacles by name and the geodetic origin, which callers read instead of building
anything themselves (a test over the package checks that nothing outside ``physics`` loads a body
or adds an obstacle).
"""

from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Callable, Dict, Mapping, Optional, Protocol, Sequence

from vehicle_sim.config import load_car, load_robot
from vehicle_sim.core.geometry.geodesy import GeodeticOrigin
from vehicle_sim.core.specs.errors import InvalidParameterError, InvalidPoseError
from vehicle_sim.core.specs.registry import register
from vehicle_sim.core.world.params import RobotSpec, used_twice, WorldSpec
from vehicle_sim.maps.lane_maps import with_lanes
from vehicle_sim.physics.diff_robot import DiffRobotBody
from vehicle_sim.physics.gui import GuiClosedError
from vehicle_sim.physics.kinematic_car import KinematicCar
from vehicle_sim.physics.lane_layer import RoadLayer
from vehicle_sim.physics.map_layer import MapLayer
from vehicle_sim.physics.sensors import SensorSuite
from vehicle_sim.physics.signal_lamps import SignalLampsPart, wants_lamps
from vehicle_sim.physics.signal_part import SignalPart, signals_wanted
from vehicle_sim.physics.simulated_car import SimulatedCar
from vehicle_sim.physics.traffic_bodies import TrafficPart
from vehicle_sim.physics.vehicle_body import VehicleBody
from vehicle_sim.physics.world import DEFAULT_FRICTION, DEFAULT_TIME_STEP_S, World


class ScenePart(Protocol):
    """An extension of the scene (a map layer, traffic): built after the vehicles."""

    name: str

    def build(self, world: World, spec: WorldSpec) -> object:
        """Add this part's bodies to ``world`` as ``spec`` asks; return what callers read."""


@dataclass(frozen=True)
class ScenePartRow:
    """
    A scene part every world that asks for it gets: one row of :data:`SCENE_PARTS`.

    :param name: its name (``scene.parts[name]``; the world key it builds).
    :param wanted: ``wanted(spec)`` -> whether a WorldSpec asks for it.
    :param make: ``make()`` -> the part (a ScenePart of that name).
    :param before_given: built before the caller's ``parts`` (True), or after them.
    :param world_key: its name is the world key it builds (True), or it draws what other
        parts made (False: the lamps of a lane map's traffic lights).
    """

    name: str
    wanted: Callable[[WorldSpec], bool]
    make: Callable[[], ScenePart]
    before_given: bool = True
    world_key: bool = True


SCENE_PARTS: Dict[str, ScenePartRow] = {}


def register_scene_part(row: ScenePartRow) -> ScenePartRow:
    """Add a row to :data:`SCENE_PARTS` (its name must be new); rows build in this order."""
    return register(SCENE_PARTS, row, 'scene part')


register_scene_part(ScenePartRow('map', lambda spec: spec.map is not None, MapLayer))
register_scene_part(ScenePartRow('roads', lambda spec: bool(spec.roads), RoadLayer))
register_scene_part(ScenePartRow('signals', signals_wanted, SignalPart))
register_scene_part(ScenePartRow('signal_lamps', wants_lamps, SignalLampsPart,
                                 world_key=False))
register_scene_part(ScenePartRow(
    'traffic', lambda spec: getattr(spec, 'traffic', None) is not None, TrafficPart,
    before_given=False))


def scene_parts(spec: WorldSpec, given: Sequence[ScenePart] = ()) -> tuple:
    """Return the parts of a WorldSpec in build order: the rows it asks for and ``given``."""
    names = {part.name for part in given}
    rows = [row for row in SCENE_PARTS.values() if row.name not in names and row.wanted(spec)]
    return (tuple(row.make() for row in rows if row.before_given) + tuple(given)
            + tuple(row.make() for row in rows if not row.before_given))


@dataclass
class SceneVehicle:
    """
    One vehicle of a scene.

    :param name: its name in the world.
    :param spec: its VehicleSpec (a car) or RobotSpec (a robot).
    :param body: its VehicleBody (CarBody, DiffRobotBody): pose, twist, reset, outline.
    :param car: the SimulatedCar driving a car's body (None for a robot).
    :param sensors: what ``mount`` returned for it (SensorSuite, SensorFeed), or None.
    """

    name: str
    spec: object
    body: VehicleBody
    car: Optional[SimulatedCar] = None
    sensors: object = None

    @property
    def vehicle(self):
        """What the world steps and a reset resets: the SimulatedCar, or the robot's body."""
        return self.car if self.car is not None else self.body


@dataclass
class Scene:
    """A built world: the World, its vehicles and obstacles by name, the geodetic origin."""

    world: World
    spec: WorldSpec
    vehicles: Dict[str, SceneVehicle] = field(default_factory=dict)
    obstacles: Dict[str, int] = field(default_factory=dict)
    parts: Dict[str, object] = field(default_factory=dict)

    @property
    def lanes(self):
        """The world's lane map (a core LaneGraph), or None when it has none."""
        return self.spec.lanes

    @property
    def origin(self) -> GeodeticOrigin:
        """The geodetic origin of the world frame (GNSS)."""
        return self.spec.origin

    @property
    def cars(self) -> Dict[str, SimulatedCar]:
        """{name: SimulatedCar} of the cars, in world file order."""
        return {name: v.car for name, v in self.vehicles.items() if v.car is not None}


Mount = Callable[[SceneVehicle, Scene], object]


def mount_suite(vehicle: SceneVehicle, scene: Scene) -> SensorSuite:
    """Mount a car's sensors (its spec's mounted SensorSpecs) as a SensorSuite."""
    return SensorSuite(scene.world, vehicle.body, vehicle.spec.sensors, scene.origin)


def build_scene(spec: WorldSpec, world: Optional[World] = None, *,
                time_step_s: float = DEFAULT_TIME_STEP_S, friction: float = DEFAULT_FRICTION,
                gui: bool = False, robots: Sequence[RobotSpec] = (), params: Mapping = None,
                hooks: Sequence = (), mount: Optional[Mount] = None,
                parts: Sequence[ScenePart] = ()) -> Scene:
    """
    Build a WorldSpec into a World (see the module text for the order).

    :param spec: the WorldSpec: origin, obstacles, cars (VehicleSpec).
    :param world: a World to add to (shared); None = a new one from ``time_step_s``,
        ``friction`` and ``gui``, closed again if the building fails.
    :param robots: RobotSpecs of differential-drive robots to add after the cars.
    :param params: {vehicle name: CarParams or RobotParams} taking the place of the spec's
        model (a Driver given CarParams, a robot node given a preset file).
    :param hooks: step hooks registered before every body.
    :param mount: (SceneVehicle, Scene) -> its sensors, for each vehicle once every body is in;
        None mounts none.
    :param parts: scene parts, built in order after the vehicles, after the rows of
        :data:`SCENE_PARTS` that build first (map, roads) and before the others (traffic); one
        with a row's name takes the row's place.
    :raises InvalidPoseError: for a vehicle that starts inside an obstacle.
    :raises InvalidParameterError: for two vehicles (cars or robots) of one name, a lane map
        that cannot be read, a vehicle placed off every lane; nothing is built.
    """
    twice = used_twice([v.name for v in spec.vehicles] + [r.name for r in robots])
    if twice:   # names are how getDevice, /initialpose and scenarios find a vehicle
        raise InvalidParameterError(f'vehicle name(s) used twice: {twice}')
    params = params or {}
    spec = with_lanes(spec)     # lanes loaded and vehicles placed on them, before any body
    parts = scene_parts(spec, parts)
    owned = world is None
    if owned:
        world = World(time_step_s=time_step_s, friction=friction, gui=gui)
    scene = Scene(world, spec)
    try:
        with world.rendering_paused():     # a GUI window draws the whole scene once, after
            with _naming_the_file(spec):
                _build_bodies(scene, spec, robots, params, hooks, parts)
            if mount is not None:
                for vehicle in scene.vehicles.values():
                    vehicle.sensors = mount(vehicle, scene)
    except BaseException as error:
        if not owned:
            raise
        # The window closed while the world was being built: say so, not PyBullet's error.
        window_closed = world.gui_closed
        world.close()
        if window_closed and not isinstance(error, GuiClosedError):
            raise GuiClosedError('the PyBullet window was closed during start-up') from None
        raise
    return scene


@contextmanager
def _naming_the_file(spec):
    # A vehicle refused for its start pose (inside an obstacle, a wall, a barrier): the refusal
    # names the world file it comes from.
    try:
        yield
    except InvalidPoseError as error:
        if spec.source and not str(error).startswith(f'{spec.source}: '):
            raise InvalidPoseError(f'{spec.source}: {error}') from None
        raise


def _build_bodies(scene, spec, robots, params, hooks, parts):
    # The hooks, obstacles, cars, robots and parts of build_scene, in that order.
    world = scene.world
    for hook in hooks:
        world.add_body(hook)
    for obstacle in spec.obstacles:
        scene.obstacles[obstacle.name] = world.add_obstacle(obstacle)
    for car_spec in spec.vehicles:
        car_params = params.get(car_spec.name) or load_car(car_spec.model)
        pose = (car_spec.x_m, car_spec.y_m, car_spec.yaw_rad)
        if car_spec.vehicle_model is None:
            car = SimulatedCar(world, car_params, pose, name=car_spec.name)
        else:       # moved by a simple_planning_simulator model (docs/physics.md)
            car = KinematicCar(world, car_params, car_spec.vehicle_model, pose,
                               name=car_spec.name)
        scene.vehicles[car_spec.name] = SceneVehicle(car_spec.name, car_spec, car.body, car)
    for robot in robots:
        body = DiffRobotBody(world, params.get(robot.name) or load_robot(robot.model),
                             (robot.x_m, robot.y_m, robot.yaw_rad), name=robot.name)
        scene.vehicles[robot.name] = SceneVehicle(robot.name, robot, body)
    for part in parts:
        if getattr(part, 'reads_parts', False):     # it reads the parts built before it
            scene.parts[part.name] = part.build(world, spec, scene.parts)
        else:
            scene.parts[part.name] = part.build(world, spec)
