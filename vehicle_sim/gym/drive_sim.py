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

A reset puts every vehicle back at its spawn pose (each body loaded afresh in the same client,
``VehicleBody.reset``) and every movable obstacle at its start: no new physics client, a few
milliseconds. Simulated time goes on across episodes (the World's clock never goes back); the
episode's time is counted from its reset. With the same seed and the same actions two episodes
give bit-identical observations (test/test_gym_env.py).
"""

import math

import numpy as np

from vehicle_sim.config import read_yaml, world_from_data, world_path
from vehicle_sim.core.geometry.angles import yaw_from_quaternion
from vehicle_sim.core.learning.progress import (
    GoalProgress,
    HeadingProgress,
    LaneProgress,
    PathProgress,
)
from vehicle_sim.core.learning.reward import (
    lane_term,
    LANE_TERMS,
    reward_terms,
    RewardWeights,
    solid_crossings,
    TERMS,
    total,
)
from vehicle_sim.core.map.vehicle_lanes import VehicleLanes
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.simulation import TIME_STEP_MS
from vehicle_sim.core.world.params import RobotSpec, WorldSpec
from vehicle_sim.gym.controls import make_control
from vehicle_sim.gym.episode import CriteriaWatch, judged_criteria
from vehicle_sim.gym.observations import ego_parts, PART_FACTORIES, sensor_spec
from vehicle_sim.gym.options import CAMERA, LIDAR, RANGE_FINDER, SOURCE, validate_options
from vehicle_sim.physics.scene import build_scene
from vehicle_sim.physics.sensors.collisions import CollisionMonitor
from vehicle_sim.scenarios.actors import make_actor
from vehicle_sim.scenarios.schema import load_scenario, ScenarioSpec
from vehicle_sim.scenarios.sim import VehicleHandle

DEFAULT_WORLD = 'obstacle_course'
DEFAULT_EPISODE_S = 60.0
EGO_ROBOT_NAME = 'ego'
# Start poses drawn at most per reset when start_noise puts the ego inside another body.
START_DRAWS = 100
# A reset draws the traffic's seed in [0, TRAFFIC_SEEDS) from the environment's generator.
TRAFFIC_SEEDS = 2 ** 31


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
        self.weights = RewardWeights(opts['progress_weight'], opts['collision_penalty'],
                                     opts['goal_reward'], opts['off_lane_penalty'],
                                     opts['solid_line_penalty'])
        self._hook = _ActorHook()
        self._parts = []
        self.scene = build_scene(world_spec, time_step_s=step_ms / 1000.0, gui=gui,
                                 robots=robots, hooks=(self._hook,), mount=self._mount)
        try:
            self.world = self.scene.world
            self.ego = self.scene.vehicles[self.ego_name]
            graph = self.scene.lanes
            # the ego's lane state and the markings it crosses (None: a world without lanes)
            signals = getattr(self.scene.parts.get('signals'), 'controller', None)
            self.lanes = None if graph is None else VehicleLanes(graph, signals)
            self.lane_ids = () if graph is None else tuple(sorted(graph.lanes))
            self._terms = TERMS if graph is None else LANE_TERMS
            self._crossed = ()
            self.control = make_control(opts['control'], self.ego, opts['max_speed'],
                                        opts['max_reverse_speed'])
            self._parts.extend(p for p in (factory(self) for factory in PART_FACTORIES)
                               if p is not None)
            self._parts.extend(observation_parts)
            self.spaces = {}
            for part in self._parts:
                self.spaces.update(part.spaces())
            self._handles = {name: VehicleHandle(name, v.body, v.car)
                             for name, v in self.scene.vehicles.items()}
            self._progress, self._goal = self._measures()
            self._monitor = None
            self._watch = None
            self._step0 = self.world.step_count
            self._goal_reached = False
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
        opts = self.options
        lidar = sensor_spec(opts[LIDAR], LIDAR, vehicle, SOURCE)
        camera = sensor_spec(opts[CAMERA], CAMERA, vehicle, SOURCE)
        depth = sensor_spec(opts[RANGE_FINDER], RANGE_FINDER, vehicle, SOURCE)
        self._parts = ego_parts(scene.world, vehicle, lidar, camera, depth)
        return self._parts

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

    def _measures(self):
        # -> (progress measure, GoalProgress or None)
        opts = self.options
        goal = None
        if opts['goal'] is not None:
            goal = GoalProgress(opts['goal'], opts['goal_radius'])
        elif self._scenario_goal() is not None:
            goal = GoalProgress(*self._scenario_goal())
        path = opts['path'] if opts['path'] is not None else self._scenario_path()
        if path is not None:
            try:
                return PathProgress(path), goal
            except InvalidParameterError as error:
                raise InvalidParameterError(f"{SOURCE}: option 'path': {error}") from None
        if goal is None and self.lanes is not None:
            return LaneProgress(self.lanes.graph), goal
        return (goal if goal is not None else HeadingProgress()), goal

    # ---------------------------------------------------------------- episode
    @property
    def elapsed_s(self):
        """Simulated time since the last reset [s]."""
        return (self.world.step_count - self._step0) * self.world.time_step_s

    def _ego_state(self):
        x, y, _, qx, qy, qz, qw = self.ego.body.pose()
        return x, y, yaw_from_quaternion(qx, qy, qz, qw)

    def reset(self, rng):
        """
        Start an episode: every vehicle and movable obstacle as built; return (obs, info).

        :param rng: numpy Generator (the environment's seeded ``np_random``): the traffic's
            seed, the ego's start offset (option start_noise) and the lidar noise seed are drawn
            from it.
        :raises InvalidParameterError: when no start pose of option start_noise fits; the
            environment is then not reset (``step`` refuses until a reset succeeds).
        """
        if self._monitor is not None:   # no episode until this reset is through
            self._monitor.close()
            self._monitor = None
        for vehicle in self.scene.vehicles.values():
            vehicle.vehicle.reset()
        self.world.reset_obstacles()
        traffic = self.scene.parts.get('traffic')
        traffic_seed = None if traffic is None else int(rng.integers(TRAFFIC_SEEDS))
        if any(self.options['start_noise']):
            self._offset_start(rng, traffic, traffic_seed)
        elif traffic is not None:
            traffic.reset(traffic_seed)
        signals = self.scene.parts.get('signals')
        if signals is not None:         # the plan from its start, nothing forced
            signals.reset()
        for part in self._parts:
            reseed = getattr(part, 'reseed', None)
            if reseed is not None:
                reseed(rng.integers(2 ** 31))
            part.reset()
        self._hook.actors = self._actors()
        self._step0 = self.world.step_count
        if self._criteria_specs:
            self._watch = CriteriaWatch(self._criteria_specs, self.episode_s, self.world,
                                        self._handles, self.scene.spec.obstacles,
                                        self.scene.lanes, None if signals is None
                                        else signals.controller)
        x, y, yaw = self._ego_state()
        if self.lanes is not None:       # after the teleport: the jump is no crossing
            self.lanes.reset()
            self.lanes.update(x, y, yaw, self.world.time_s)
            self._crossed = ()
        self._start_progress(x, y, yaw)
        self._goal_reached = False
        obs = self.observe()
        self._monitor = CollisionMonitor(self.world, self.ego.body)
        return obs, self._info(0.0, dict.fromkeys(self._terms, 0.0), '', False)

    def _start_progress(self, x, y, yaw):
        if isinstance(self._progress, LaneProgress):
            self._progress.start(self.lanes.state)
        else:
            self._progress.start(x, y, yaw)

    def _offset_start(self, rng, traffic, traffic_seed):
        # The ego at its spawn pose plus a uniform offset, then the traffic started around it;
        # an offset that puts the ego inside another body (the traffic, started afresh after,
        # aside) or where the traffic does not fit around it is drawn again (the same draws for
        # the same seed).
        half = np.asarray(self.options['start_noise'])
        body = self.ego.body
        x, y, yaw = body.spawn[:3]
        moving = set() if traffic is None else traffic.moving_names()
        for _ in range(START_DRAWS):
            dx, dy, dyaw = rng.uniform(-half, half)
            body.rebuild((x + dx, y + dy, yaw + dyaw))
            if any(name not in moving for name in self.world.overlaps(body.body_id)):
                continue
            if traffic is not None:
                try:
                    traffic.reset(traffic_seed)
                except InvalidParameterError:    # a placed vehicle there, too few places
                    continue
            return
        raise InvalidParameterError(
            f"{SOURCE}: option 'start_noise' = {list(half)}: {START_DRAWS} start poses drawn "
            f'around the spawn pose of {self.ego_name!r} were all inside another body'
            + ('' if traffic is None else ' or where the traffic does not fit around it'))

    def _actors(self):
        if self.scenario is None:
            return []
        traffic = self.scene.parts.get('traffic')
        return [make_actor(spec, self._handles, traffic) for spec in self.scenario.actors]

    def observe(self):
        """Return the observation dict now."""
        out = {}
        for part in self._parts:
            part.read(out)
        return out

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
        if self._monitor is None:
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
        monitor = self._monitor
        watch = self._watch
        # the goal circle checked each basic step: the option's, else the scenario's when
        # it has no reach_goal criterion to judge it; none once reached
        circle = None if self._goal_reached or (watch is not None and watch.goals) \
            else self._goal
        hits = []
        reached_now = False
        repeat_done = 0
        for _ in range(repeat):
            world.step()
            repeat_done += 1
            if monitor.fresh:
                hits.extend(monitor.fresh)
            if watch is not None or circle is not None:
                x, y, yaw = self._ego_state()
                if watch is not None:
                    watch.observe(self.elapsed_s, x, y, yaw, self.ego.body.forward_speed_mps(),
                                  monitor.fresh)
                if circle is not None and math.hypot(x - circle.goal[0],
                                                     y - circle.goal[1]) <= circle.radius_m:
                    reached_now = True
            if hits and self.options['terminate_on_collision']:
                break
        self._advanced = (hits, reached_now, repeat_done)

    def finish(self):
        """Return (obs, reward terms, terminated, truncated, info) of the step just advanced."""
        obs, terms, terminated, truncated, facts = self._outcome()
        return obs, terms, terminated, truncated, self._info(*facts)

    def finish_row(self):
        """
        Return :meth:`finish`'s step as DriveVectorEnv takes it, without an info dict.

        :return: (obs, terminated, truncated, default reward, row): the info as the flat list
            of its values (``_info_row``).
        """
        obs, terms, terminated, truncated, facts = self._outcome()
        reward = total(terms)
        return obs, terminated, truncated, reward, self._info_row(*facts, reward)

    def _outcome(self):
        # (obs, reward terms, terminated, truncated, the info's facts) of the step just advanced
        hits, reached_now, repeat_done = self._advanced
        world = self.world
        watch = self._watch
        x, y, yaw = self._ego_state()
        terminated = bool(hits) and self.options['terminate_on_collision']
        if self.lanes is not None:
            state, self._crossed = self.lanes.update(x, y, yaw, world.time_s)
            if self.options['terminate_off_road'] and not state.on_lane:
                terminated = True
        if isinstance(self._progress, LaneProgress):
            progress_m = self._progress.advance(self.lanes.state)
        else:
            progress_m = self._progress.advance(x, y, yaw)
        if watch is not None:
            ended, reached_all = watch.decide(self.elapsed_s)
            terminated = terminated or ended
            if watch.goals:     # the scenario's reach_goal criteria say when (speed, deadline)
                reached_now = reached_all and not self._goal_reached
        terminated = terminated or reached_now
        self._goal_reached = self._goal_reached or reached_now
        terms = reward_terms(self.weights, progress_m, bool(hits), reached_now)
        if self.lanes is not None:
            terms['lane'] = lane_term(self.weights, self.lanes.state.on_lane,
                                      solid_crossings(self._crossed),
                                      repeat_done * world.time_step_s)
        truncated = not terminated and self.elapsed_s >= self.episode_s - 1e-9
        other = ','.join(sorted({event.other for event in hits}))
        return self.observe(), terms, terminated, truncated, (progress_m, terms, other, bool(hits))

    def _info(self, progress_m, terms, collided_with, collision):
        info = {'time_s': self.elapsed_s, 'progress_m': float(progress_m),
                'reward_terms': dict(terms), 'reward_default': total(terms),
                'collision': collision, 'collided_with': collided_with,
                'goal_reached': self._goal_reached}
        if self.lanes is not None:
            state = self.lanes.state
            info['on_lane'] = state.on_lane
            info['lane_id'] = state.lane_id
            info['lane_crossings'] = len(self._crossed)
            info['solid_crossings'] = solid_crossings(self._crossed)
        if self._watch is not None:
            info['criteria'] = dict(self._watch.verdicts)
        return info

    def _info_row(self, progress_m, terms, collided_with, collision, reward):
        # _info's values in its order, a nested dict's values in its place, for DriveVectorEnv's
        # info table (test_gym_vector compares the vector's infos with lone environments').
        row = [self.elapsed_s, float(progress_m), *terms.values(), reward, collision,
               collided_with, self._goal_reached]
        if self.lanes is not None:
            state = self.lanes.state
            row += (state.on_lane, state.lane_id, len(self._crossed),
                    solid_crossings(self._crossed))
        if self._watch is not None:
            row += self._watch.verdicts.values()
        return row

    def close(self):
        """Disconnect the physics client (idempotent)."""
        self.scene.world.close()
