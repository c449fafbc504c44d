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
One driving world for learning: the scene, its ego vehicle, and an episode's step and reset.

:class:`DriveSim` holds what a Gym environment needs of the simulator, without Gymnasium: the
world built by the scene builder (physics/scene.py) from a world or scenario file, the ego's
action layout (controls.py), observation parts (observations.py), progress measure and reward
terms (core/learning), collisions and a scenario's criteria (episode.py), and in a world with a
lane map the ego's lane state (core/map/vehicle_lanes.py, updated once per env step; lanes.py).
``DriveEnv`` wraps one, ``DriveVectorEnv`` holds several, each with its own physics client, in
one process.

A reset puts every vehicle back at its spawn pose (each body as built, in place,
``VehicleBody.reset``) and every movable obstacle at its start: no new physics client, a few
milliseconds. Simulated time goes on across episodes (the World's clock never goes back); the
episode's time is counted from its reset. With the same seed and the same actions two episodes
give bit-identical observations (test/test_gym_env.py).
"""

import numpy as np

from vehicle_sim.config import read_yaml, world_from_data, world_path
from vehicle_sim.core.learning.reward import total
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.simulation import TIME_STEP_MS
from vehicle_sim.core.world.params import RobotSpec, WorldSpec
from vehicle_sim.gym.ego import Ego, mounted_parts
from vehicle_sim.gym.episode import CriteriaWatch, judged_criteria
from vehicle_sim.gym.options import SOURCE, validate_options
from vehicle_sim.physics.scene import build_scene
from vehicle_sim.scenarios.actors import make_actors
from vehicle_sim.scenarios.schema import load_scenario, ScenarioSpec
from vehicle_sim.scenarios.sim import VehicleHandle

DEFAULT_WORLD = 'obstacle_course'
DEFAULT_EPISODE_S = 60.0
EGO_ROBOT_NAME = 'ego'
# Start poses drawn at most per reset when start_noise puts the ego inside another body.
START_DRAWS = 100
# A reset draws the traffic's seed in [0, TRAFFIC_SEEDS) from the environment's generator.
TRAFFIC_SEEDS = 2 ** 31


def draw_traffic_seed(rng):
    """Return the traffic's seed of a reset: the first draw of the environment's generator."""
    return int(rng.integers(TRAFFIC_SEEDS))


def episode_traffic_seed(seed):
    """
    Return the traffic's seed of ``reset(seed=seed)`` (start_noise 0): what the world needs.

    Gymnasium seeds the environment's generator from ``seed`` (``np_random``); the reset's
    first draw is the traffic's seed. A scenario run whose world has ``traffic: seed`` set to
    this value starts the same traffic as that reset (``vehicle-sim policy evaluate``).
    """
    from gymnasium.utils.seeding import np_random
    return draw_traffic_seed(np_random(int(seed))[0])


class _ActorHook:
    """World hook registered before the vehicles: the scenario's actors act each basic step."""

    def __init__(self):
        self.actors = []

    def pre_step(self):
        for actor in self.actors:
            actor.control()


def _world_spec(world, vehicles_required):
    if isinstance(world, WorldSpec):
        return world
    if isinstance(world, dict):
        return world_from_data(world, f'{SOURCE}: world mapping',
                               vehicles_required=vehicles_required)
    path = world_path(world)
    return world_from_data(read_yaml(path), str(path), vehicles_required=vehicles_required)


def _load(world, scenario, robot):
    # -> (WorldSpec, robots, ScenarioSpec or None)
    if world is not None and scenario is not None:
        raise InvalidParameterError(f'{SOURCE}: give a world or a scenario, not both')
    if scenario is not None:
        spec = scenario if isinstance(scenario, ScenarioSpec) else load_scenario(scenario)
        return spec.world, tuple(spec.robots), spec
    return _world_spec(DEFAULT_WORLD if world is None else world, not robot), (), None


def reset_world(scene, rng, bodies, start_noise, what):
    """
    Put every vehicle and movable obstacle of a scene back as built, the traffic and signals too.

    :param rng: the environment's seeded generator: the traffic's seed and the start offsets are
        drawn from it.
    :param bodies: the ego bodies that ``start_noise`` offsets, in order.
    :param start_noise: half-widths [x, y, yaw] of a uniform offset of each ego's start pose.
    :param what: the egos' names as an error names them.
    :raises InvalidParameterError: when no start poses of ``start_noise`` fit.
    """
    for vehicle in scene.vehicles.values():
        vehicle.vehicle.reset()
    scene.world.reset_obstacles()
    traffic = scene.parts.get('traffic')
    traffic_seed = None if traffic is None else draw_traffic_seed(rng)
    if any(start_noise):
        _offset_starts(scene, rng, bodies, start_noise, what, traffic, traffic_seed)
    elif traffic is not None:
        traffic.reset(traffic_seed)
    signals = scene.parts.get('signals')
    if signals is not None:         # the plan from its start, nothing forced
        signals.reset()


def _offset_starts(scene, rng, bodies, start_noise, what, traffic, traffic_seed):
    # Each ego at its spawn pose plus a uniform offset, then the traffic started around them;
    # offsets that put an ego inside another body (the traffic, started afresh after, aside) or
    # where the traffic does not fit around them are drawn again (the same draws for the same
    # seed).
    half = np.asarray(start_noise)
    world = scene.world
    moving = set() if traffic is None else traffic.moving_names()
    for _ in range(START_DRAWS):
        for body in bodies:
            x, y, yaw = body.spawn[:3]
            dx, dy, dyaw = rng.uniform(-half, half)
            body.rebuild((x + dx, y + dy, yaw + dyaw))
        if any(name not in moving for body in bodies
               for name in world.overlaps(body.body_id)):
            continue
        if traffic is not None:
            try:
                traffic.reset(traffic_seed)
            except InvalidParameterError:    # a placed vehicle there, too few places
                continue
        return
    raise InvalidParameterError(
        f"{SOURCE}: option 'start_noise' = {list(half)}: {START_DRAWS} start poses drawn "
        f'around the spawn pose of {what} were all inside another body'
        + ('' if traffic is None else ' or where the traffic does not fit around it'))


class DriveSim:
    """
    One world with an ego vehicle, stepped by actions (see the module text).

    :param world: a world name (config/worlds), a path to a world .yaml, a world mapping or a
        WorldSpec; None = 'obstacle_course' (unless ``scenario``).
    :param scenario: a scenario .yaml path or a ScenarioSpec (its world, robots, vehicle under
        test as the ego, actors, criteria, duration and time step).
    :param options: the environment's options (options.py), validated here.
    :param gui: build the world in PyBullet's window (render_mode 'human').
    :param observation_parts: more observation parts (observations.py), after the built-in.
    :raises InvalidParameterError: for a bad option, world or scenario; nothing is built.
    """

    def __init__(self, world=None, scenario=None, options=None, gui=False,
                 observation_parts=()):
        opts = self.options = validate_options(options or {})
        world_spec, robots, self.scenario = _load(world, scenario, opts['robot'])
        if opts['robot']:
            x, y, yaw = opts['start']
            robots = robots + (RobotSpec(EGO_ROBOT_NAME, opts['robot'], x, y, yaw),)
        self.ego_name = self._ego_name(world_spec, robots, opts)
        step_ms = opts['time_step_ms'] or (self.scenario.time_step_ms if self.scenario
                                           else TIME_STEP_MS.default)
        criteria = ()
        if self.scenario is not None:
            criteria = judged_criteria([c for c in self.scenario.criteria
                                        if c.vehicle in ('', self.ego_name)],
                                       self.scenario.source)
        self._criteria_specs = criteria
        self.episode_s = opts['max_episode_s'] or (self.scenario.duration_s if self.scenario
                                                   else DEFAULT_EPISODE_S)
        self._hook = _ActorHook()
        self._mounted = []
        self.scene = build_scene(world_spec, time_step_s=step_ms / 1000.0, gui=gui,
                                 robots=robots, hooks=(self._hook,), mount=self._mount)
        try:
            self.world = self.scene.world
            lanes = self.scene.lanes
            self.agent = Ego(self.scene, self.ego_name, opts, self._mounted,
                             observation_parts, self._scenario_goal(), self._scenario_path())
            self.ego = self.agent.ego
            self.lanes = self.agent.lanes
            self.lane_ids = () if lanes is None else tuple(sorted(lanes.lanes))
            self.control = self.agent.control
            self.spaces = self.agent.spaces
            self.weights = self.agent.weights
            self._handles = {name: VehicleHandle(name, v.body, v.car)
                             for name, v in self.scene.vehicles.items()}
            self._watch = None
            self._started = False
            self._step0 = self.world.step_count
        except BaseException:
            self.close()
            raise

    # ---------------------------------------------------------------- building
    @staticmethod
    def _ego_name(world_spec, robots, opts):
        names = [v.name for v in world_spec.vehicles] + [r.name for r in robots]
        wanted = opts['vehicle']
        if not wanted:
            if opts['robot']:
                wanted = EGO_ROBOT_NAME
            elif names:
                wanted = names[0]
        if wanted not in names:
            raise InvalidParameterError(
                f"{SOURCE}: option 'vehicle' = {wanted!r}: no such vehicle in the world; "
                f'vehicles: {", ".join(names) or "none"}')
        return wanted

    def _mount(self, vehicle, scene):
        # The scene builder's mount step: the ego's observation parts (sensors) only.
        if vehicle.name != self.ego_name:
            return None
        self._mounted = mounted_parts(vehicle, scene, self.options)
        return self._mounted

    def _scenario_goal(self):
        for spec in self._criteria_specs:
            if spec.kind == 'reach_goal':
                return spec.values['goal'], spec.values['radius_m']
        return None

    def _scenario_path(self):
        for spec in self._criteria_specs:
            if spec.kind == 'stay_on_path':
                return spec.values['path']
        return None

    # ---------------------------------------------------------------- episode
    @property
    def elapsed_s(self):
        """Simulated time since the last reset [s]."""
        return (self.world.step_count - self._step0) * self.world.time_step_s

    def criteria_results(self):
        """
        Return the scenario's criteria on the episode so far: {name: CriterionResult}.

        Each result as the scenario runner's report gives it (measured value, unit, detail:
        ``mean_speed``'s mean, ``no_collision``'s first contact); {} without a scenario.
        """
        watch = self._watch
        return {} if watch is None else {c.name: c.result() for c in watch.criteria}

    def reset(self, rng):
        """
        Start an episode: every vehicle and movable obstacle as built; return (obs, info).

        :param rng: numpy Generator (the environment's seeded ``np_random``): the traffic's
            seed, the ego's start offset (option start_noise) and the lidar noise seed are drawn
            from it.
        :raises InvalidParameterError: when no start pose of option start_noise fits; the
            environment is then not reset (``step`` refuses until a reset succeeds).
        """
        agent = self.agent
        self._started = False           # no episode until this reset is through
        agent.stop()
        reset_world(self.scene, rng, (agent.body,), self.options['start_noise'],
                    repr(self.ego_name))
        agent.reseed(rng)
        self._hook.actors = self._actors()
        self._step0 = self.world.step_count
        if self._criteria_specs:
            signals = self.scene.parts.get('signals')
            self._watch = CriteriaWatch(self._criteria_specs, self.episode_s, self.world,
                                        self._handles, self.scene.spec.obstacles,
                                        self.scene.lanes, None if signals is None
                                        else signals.controller)
        obs = agent.start()
        self._started = True
        return obs, self._info(0.0, dict.fromkeys(agent.terms, 0.0), '', False)

    def _actors(self):
        if self.scenario is None:
            return []
        traffic = self.scene.parts.get('traffic')
        return make_actors(self.scenario.actors, self._handles, traffic)

    def observe(self):
        """Return the observation dict now."""
        return self.agent.observe()

    def step(self, action, action_repeat=None):
        """
        Apply an action for ``action_repeat`` basic steps.

        :return: (obs, reward terms, terminated, truncated, info).

        :raises ValueError: for an action outside the action space (nothing stepped).
        :raises RuntimeError: before the first reset.
        """
        self.apply(self.check(action))
        self.advance(action_repeat)
        return self.finish()

    # The three phases of a step, for DriveVectorEnv: it checks every world's action, then
    # applies and advances every world, then finishes every world, so that the basic steps of
    # its worlds run one after another without the rest of a step between them (each world's
    # physics data then stays in the processor's cache more often).
    def check(self, action):
        """Return ``action`` checked against the action space (ValueError naming the entry)."""
        if not self._started:
            raise RuntimeError('step() before reset() (or after a reset that raised): call '
                               'reset() first')
        return self.control.check(action)

    def apply(self, values):
        """Command the ego with a checked action (:meth:`check`)."""
        self.control.apply(values)

    def advance(self, action_repeat=None):
        """Run the ``action_repeat`` basic steps of a step (after :meth:`apply`)."""
        repeat = action_repeat or self.options['action_repeat']
        world = self.world
        agent = self.agent
        watch = self._watch
        # the goal circle: the option's, else the scenario's when it has no reach_goal
        # criterion to judge it
        agent.begin(own_goal=not (watch is not None and watch.goals))
        stop_on_hit = self.options['terminate_on_collision']
        repeat_done = 0
        for _ in range(repeat):
            world.step()
            repeat_done += 1
            # (the elapsed time is the watch's only: not worked out at every basic step)
            hit = agent.after_basic_step(watch, 0.0 if watch is None else self.elapsed_s)
            if hit and stop_on_hit:
                break
        self._repeat_done = repeat_done

    def finish(self):
        """Return (obs, reward terms, terminated, truncated, info) of the step just advanced."""
        obs, terms, terminated, truncated, facts = self._outcome()
        return obs, terms, terminated, truncated, self._info(*facts)

    def finish_row(self):
        """
        Return :meth:`finish`'s step as DriveVectorEnv takes it, without an info dict.

        :return: (obs, terminated, truncated, default reward, row): the info as the flat list
            of its values (``Ego.info_row``).
        """
        obs, terms, terminated, truncated, facts = self._outcome()
        reward = total(terms)
        return obs, terminated, truncated, reward, self.agent.info_row(
            self.elapsed_s, *facts, reward, self._watch)

    def _outcome(self):
        # (obs, reward terms, terminated, truncated, the info's facts) of the step just advanced
        return self.agent.outcome(self.elapsed_s, self.episode_s, self._repeat_done,
                                  self._watch)

    def _info(self, progress_m, terms, collided_with, collision):
        return self.agent.info(self.elapsed_s, progress_m, terms, collided_with, collision,
                               self._watch)

    def close(self):
        """Disconnect the physics client (idempotent)."""
        self.scene.world.close()
