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
One ego vehicle of a driving world: what a learning agent acts on, sees and is rewarded for.

:class:`Ego` holds one vehicle's action layout (controls.py), observation parts
(observations.py), lane state (core/map/vehicle_lanes.py, updated once per env step; lanes.py),
progress measure and reward terms (core/learning), collisions and goal circle. ``DriveSim``
(drive_sim.py) has one, with a scenario's criteria beside it; ``MultiDriveSim`` (multi_sim.py)
has one per agent, all in one world. Stepping the world is theirs: an Ego is told before the
basic steps of an env step (:meth:`begin`), after each (:meth:`after_basic_step`) and at the end
(:meth:`outcome`).
"""

import math

from vehicle_sim.core.geometry.angles import yaw_from_quaternion
from vehicle_sim.core.learning.gap import Box, gap_fractions, gap_term, GapWeights
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
from vehicle_sim.core.traffic.objects import obstacle_objects
from vehicle_sim.gym.controls import make_control
from vehicle_sim.gym.objects import ObjectsPart
from vehicle_sim.gym.observations import ego_parts, PART_FACTORIES, sensor_spec
from vehicle_sim.gym.options import CAMERA, LIDAR, RANGE_FINDER, SOURCE
from vehicle_sim.physics.sensors.collisions import CollisionMonitor


def mounted_parts(vehicle, scene, options, source=SOURCE):
    """Return the built-in observation parts of an ego (the scene builder's mount step)."""
    lidar = sensor_spec(options[LIDAR], LIDAR, vehicle, source)
    camera = sensor_spec(options[CAMERA], CAMERA, vehicle, source)
    depth = sensor_spec(options[RANGE_FINDER], RANGE_FINDER, vehicle, source)
    return ego_parts(scene.world, vehicle, lidar, camera, depth)


def reward_weights(options):
    """Return the RewardWeights of the environment's options."""
    return RewardWeights(options['progress_weight'], options['collision_penalty'],
                         options['goal_reward'], options['off_lane_penalty'],
                         options['solid_line_penalty'], options['lane_centre_penalty'])


def gap_weights(options):
    """Return the GapWeights of the environment's options (the ``gap`` term)."""
    return GapWeights(options['headway_penalty'], options['headway_s'], options['ttc_penalty'],
                      options['ttc_s'], options['side_gap_penalty'], options['gap_margin'])


def road_users(scene):
    """Return the traffic's vehicles and the world's obstacles now, as gap Boxes."""
    traffic = scene.parts.get('traffic')
    found = [] if traffic is None else [Box(o.x_m, o.y_m, o.yaw_rad, o.speed_mps, *o.size_m[:2])
                                        for o in traffic.objects(paths=False)]
    world = scene.world

    def pose_of(name):
        (position, (qx, qy, qz, qw)), _, _ = world.body_state(world.obstacles[name])
        return (*position, yaw_from_quaternion(qx, qy, qz, qw))

    found.extend(Box(o.x_m, o.y_m, o.yaw_rad, 0.0, *o.size_m[:2])
                 for o in obstacle_objects(scene.spec.obstacles, pose_of))
    return found


def progress_measures(options, lanes, scenario_goal=None, scenario_path=None):
    """
    Return (progress measure, GoalProgress or None) of an ego.

    The option ``goal`` (else the scenario's reach_goal) gives the goal; progress is along the
    option ``path`` (else the scenario's stay_on_path), else along the lanes when there is no
    goal and the world has lanes, else toward the goal, else the distance driven forward.
    """
    goal = None
    if options['goal'] is not None:
        goal = GoalProgress(options['goal'], options['goal_radius'])
    elif scenario_goal is not None:
        goal = GoalProgress(*scenario_goal)
    path = options['path'] if options['path'] is not None else scenario_path
    if path is not None:
        try:
            return PathProgress(path), goal
        except InvalidParameterError as error:
            raise InvalidParameterError(f"{SOURCE}: option 'path': {error}") from None
    if goal is None and lanes is not None:
        return LaneProgress(lanes.graph), goal
    return (goal if goal is not None else HeadingProgress()), goal


class Ego:
    """
    One ego vehicle of a built scene (see the module text).

    :param scene: the Scene (physics/scene.py).
    :param name: the vehicle's name in it.
    :param options: the environment's validated options (options.py).
    :param parts: its built-in observation parts (:func:`mounted_parts`).
    :param observation_parts: more parts, after those of ``PART_FACTORIES``.
    :param goal: a scenario's reach_goal ((x, y), radius) or None; ``path``: its stay_on_path
        points or None (:func:`progress_measures`).
    """

    def __init__(self, scene, name, options, parts, observation_parts=(), goal=None,
                 path=None):
        self.scene = scene
        self.world = scene.world
        self.name = name
        self.ego = scene.vehicles[name]
        self.body = self.ego.body
        self.options = options
        self.weights = reward_weights(options)
        self.gap = gap_weights(options)
        graph = scene.lanes
        # the ego's lane state and the markings it crosses (None: a world without lanes)
        signals = getattr(scene.parts.get('signals'), 'controller', None)
        self.lanes = None if graph is None else VehicleLanes(graph, signals)
        self.terms = (TERMS if graph is None else LANE_TERMS) + (
            ('gap',) if self.gap.enabled else ())
        self.crossed = ()
        self.parts = list(parts)
        self.parts.extend(p for p in (factory(self) for factory in PART_FACTORIES)
                          if p is not None)
        self.parts.extend(observation_parts)
        objects = next((p for p in self.parts if isinstance(p, ObjectsPart)), None)
        self.control = make_control(options['control'], self.ego, options['max_speed'],
                                    options['max_reverse_speed'], options['max_steering'],
                                    self.lanes, objects)
        self.spaces = {}
        for part in self.parts:
            self.spaces.update(part.spaces())
        self.progress, self.goal = progress_measures(options, self.lanes, goal, path)
        self.monitor = None
        self.goal_reached = False
        self._hits = []
        self._reached_now = False
        self._circle = None

    def state(self):
        """Return the body's (x, y, yaw) now."""
        x, y, _, qx, qy, qz, qw = self.body.pose()
        return x, y, yaw_from_quaternion(qx, qy, qz, qw)

    def reseed(self, rng):
        """Draw its observation parts' noise seeds from a reset's generator."""
        for part in self.parts:
            reseed = getattr(part, 'reseed', None)
            if reseed is not None:
                reseed(rng.integers(2 ** 31))

    def start(self):
        """
        Start an episode after the world was reset (and the ego placed).

        :return: its first observation.
        """
        for part in self.parts:
            part.reset()
        x, y, yaw = self.state()
        if self.lanes is not None:       # after the teleport: the jump is no crossing
            self.lanes.reset()
            self.lanes.update(x, y, yaw, self.world.time_s)
            self.crossed = ()
        if isinstance(self.progress, LaneProgress):
            self.progress.start(self.lanes.state)
        else:
            self.progress.start(x, y, yaw)
        self.goal_reached = False
        obs = self.observe()
        self.monitor = CollisionMonitor(self.world, self.body)
        return obs

    def stop(self):
        """End its episode: its collisions are no longer watched."""
        if self.monitor is not None:
            self.monitor.close()
            self.monitor = None

    def observe(self):
        """Return the observation dict now."""
        out = {}
        for part in self.parts:
            part.read(out)
        return out

    # ---------------------------------------------------------------- a step
    def begin(self, own_goal=True):
        """
        Start an env step's basic steps.

        :param own_goal: check the goal circle each basic step (False where a scenario's
            reach_goal criteria judge the goal).
        """
        self._hits = []
        self._reached_now = False
        # the goal circle checked each basic step; none once reached
        self._circle = None if self.goal_reached or not own_goal else self.goal

    def after_basic_step(self, watch=None, elapsed_s=0.0):
        """Take a basic step's collisions (and goal); return True once it collided this step."""
        fresh = self.monitor.fresh
        if fresh:
            self._hits.extend(fresh)
        circle = self._circle
        if watch is not None or circle is not None:
            x, y, yaw = self.state()
            if watch is not None:
                watch.observe(elapsed_s, x, y, yaw, self.body.forward_speed_mps(), fresh)
            if circle is not None and math.hypot(x - circle.goal[0],
                                                 y - circle.goal[1]) <= circle.radius_m:
                self._reached_now = True
        return bool(self._hits)

    def outcome(self, elapsed_s, episode_s, repeat_done, watch=None):
        """
        Return the env step's (obs, reward terms, terminated, truncated, the info's facts).

        :param elapsed_s: the episode's time now; ``episode_s``: its truncation time.
        :param repeat_done: the basic steps this env step ran.
        :param watch: a scenario's CriteriaWatch (episode.py) or None.
        """
        hits = self._hits
        reached_now = self._reached_now
        opts = self.options
        x, y, yaw = self.state()
        terminated = bool(hits) and opts['terminate_on_collision']
        if self.lanes is not None:
            state, self.crossed = self.lanes.update(x, y, yaw, self.world.time_s)
            if opts['terminate_off_road'] and not state.on_lane:
                terminated = True
        if isinstance(self.progress, LaneProgress):
            progress_m = self.progress.advance(self.lanes.state)
        else:
            progress_m = self.progress.advance(x, y, yaw)
        if watch is not None:
            ended, reached_all = watch.decide(elapsed_s)
            terminated = terminated or ended
            if watch.goals:     # the scenario's reach_goal criteria say when (speed, deadline)
                reached_now = reached_all and not self.goal_reached
        terminated = terminated or reached_now
        self.goal_reached = self.goal_reached or reached_now
        weights = self.weights
        terms = reward_terms(weights, progress_m, bool(hits), reached_now)
        if self.lanes is not None:
            state = self.lanes.state
            centre = min(1.0, abs(state.offset_m) / (0.5 * state.width_m)) \
                if state.on_lane and state.width_m > 0.0 else 0.0
            terms['lane'] = lane_term(weights, state.on_lane, solid_crossings(self.crossed),
                                      repeat_done * self.world.time_step_s, centre)
        if self.gap.enabled:
            terms['gap'] = gap_term(self.gap, self.gap_fractions(x, y, yaw),
                                    repeat_done * self.world.time_step_s)
        truncated = not terminated and elapsed_s >= episode_s - 1e-9
        other = ','.join(sorted({event.other for event in hits}))
        return self.observe(), terms, terminated, truncated, (progress_m, terms, other,
                                                              bool(hits))

    def gap_fractions(self, x, y, yaw):
        """Return the gap term's (headway, ttc, side) fractions at the pose (x, y, yaw) now."""
        return gap_fractions(self.gap, self.body.outline, x, y, yaw,
                             self.body.forward_speed_mps(), road_users(self.scene))

    def info(self, elapsed_s, progress_m, terms, collided_with, collision, watch=None):
        """Return the info dict of a step (docs/gym.md)."""
        info = {'time_s': elapsed_s, 'progress_m': float(progress_m),
                'reward_terms': dict(terms), 'reward_default': total(terms),
                'collision': collision, 'collided_with': collided_with,
                'goal_reached': self.goal_reached}
        if self.lanes is not None:
            state = self.lanes.state
            info['on_lane'] = state.on_lane
            info['lane_id'] = state.lane_id
            info['lane_crossings'] = len(self.crossed)
            info['solid_crossings'] = solid_crossings(self.crossed)
        if watch is not None:
            info['criteria'] = dict(watch.verdicts)
        return info

    def info_row(self, elapsed_s, progress_m, terms, collided_with, collision, reward,
                 watch=None):
        """Return :meth:`info`'s values in its order, a nested dict's values in its place."""
        row = [elapsed_s, float(progress_m), *terms.values(), reward, collision,
               collided_with, self.goal_reached]
        if self.lanes is not None:
            state = self.lanes.state
            row += (state.on_lane, state.lane_id, len(self.crossed),
                    solid_crossings(self.crossed))
        if watch is not None:
            row += watch.verdicts.values()
        return row
