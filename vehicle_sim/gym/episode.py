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
When an episode ends, from a scenario's criteria or the environment's own goal and collisions.

A scenario's criteria watch the ego during the episode as the scenario runner's do (each basic
step); :func:`verdict_now` says whether a criterion is already decided:

- ``no_collision``: failed at the first collision (with a body it does not ignore);
- ``reach_goal``: passed once the goal region is reached (at the speed asked), failed once its
  deadline passed without;
- ``max_speed``, ``stay_on_path``, ``clearance``: failed as soon as the bound is crossed;
- the lane criteria (a world with a lane map): ``stay_in_lane`` failed as soon as the ego is
  off every lane, beyond its offset or across a solid line; ``speed_limit`` as soon as the ego
  is faster than its lane's limit (plus the tolerance); ``reach_lanelet`` passed once the
  lanelet is reached (it ends nothing), failed once its deadline passed without; each failed
  from the start in a world without a lane map;
- the traffic rule criteria (``traffic_light``, ``stop_sign``, ``yield``): failed as soon as the
  ego breaks the rule (passes a red line, rolls through a stop line, enters a conflict zone in
  front of a vehicle with priority), and from the start when the world lacks what they watch;
- otherwise undecided until the end.

When the scenario's time is up (the step that reaches its duration), every criterion still
undecided takes the verdict of its result (:meth:`CriteriaWatch.decide`): ``mean_speed``,
``no_collision`` without one and the others that pass unless something happened give their
outcome in the last step's info, as the scenario runner's report would; such a verdict ends
nothing (the episode is truncated there).

The episode is *terminated* when a criterion failed, or when every ``reach_goal`` criterion
passed (there is at least one); it is *truncated* at the scenario's duration. ``topic``
criteria read ROS messages, which an environment without ROS has none of: left out, with a
warning naming them.
"""

import math
import warnings

from vehicle_sim.scenarios.criteria import build_criteria, Sample
from vehicle_sim.scenarios.rule_criteria import RULE_CRITERIA
from vehicle_sim.scenarios.scene import world_scene

PASSED, FAILED, UNDECIDED = 'passed', 'failed', 'undecided'
_EPS_S = 1e-9


def judged_criteria(specs, source):
    """
    Return the criteria an in-process episode judges: all but the ``topic`` ones.

    A topic criterion reads ROS messages, which an environment without ROS has none of: it is
    left out with a warning naming it (the scenario runner judges it).
    """
    skipped = [spec.name for spec in specs if spec.kind == 'topic']
    if skipped:
        warnings.warn(f'{source}: criteria {", ".join(repr(n) for n in skipped)} (topic) read '
                      'ROS messages: not judged in the Gym environment, which runs without ROS '
                      '(the scenario runner judges them)', stacklevel=3)
    return tuple(spec for spec in specs if spec.kind != 'topic')


def verdict_now(criterion, elapsed_s):
    """Return PASSED, FAILED or UNDECIDED for a criterion during the episode."""
    kind = criterion.KIND
    values = criterion.values
    if kind == 'no_collision':
        return FAILED if criterion.events else UNDECIDED
    if kind == 'reach_goal':
        if criterion.reached_s is not None:
            within = values['within_s']
            return PASSED if within is None or criterion.reached_s <= within + _EPS_S \
                else FAILED
        within = values['within_s']
        if within is not None and elapsed_s > within + _EPS_S:
            return FAILED
        return UNDECIDED
    if kind == 'max_speed':
        return FAILED if criterion.top_mps > values['limit_mps'] else UNDECIDED
    if kind == 'stay_on_path':
        return FAILED if criterion.worst_m > values['max_distance_m'] else UNDECIDED
    if kind in _LANE_KINDS:
        return _lane_verdict(criterion, elapsed_s)
    if kind in RULE_CRITERIA:
        return FAILED if criterion.violated else UNDECIDED
    if kind == 'clearance':
        nearest = min((d for d, _, _, _ in criterion.nearest.values()), default=math.inf)
        return FAILED if nearest < values['min_m'] else UNDECIDED
    return UNDECIDED


_LANE_KINDS = ('stay_in_lane', 'speed_limit', 'reach_lanelet')


def _lane_verdict(criterion, elapsed_s):
    values = criterion.values
    if criterion.error:
        return FAILED
    kind = criterion.KIND
    if kind == 'stay_in_lane':
        limit = values['max_offset_m']
        off = criterion.off_lane_s is not None or (values['solid_lines'] and criterion.crossed) \
            or (limit is not None and criterion.worst is not None
                and criterion.worst[0] > limit)
        return FAILED if off else UNDECIDED
    if kind == 'speed_limit':
        worst = criterion.worst
        return FAILED if worst is not None and worst[0] > values['tolerance_mps'] + 1e-12 \
            else UNDECIDED
    within = values['within_s'] or criterion.duration_s
    if criterion.reached_s is not None:
        return PASSED if criterion.reached_s <= within + _EPS_S else FAILED
    return FAILED if elapsed_s > within + _EPS_S else UNDECIDED


class CriteriaWatch:
    """
    A scenario's criteria on the ego for one episode (made afresh at each reset).

    :param specs: the ego's CriterionSpecs.
    :param duration_s: the scenario's duration [s].
    :param world: the World; ``handles``: {name: VehicleHandle} of the vehicles;
        ``obstacles``: the world's ObstacleSpecs (clearance); ``lanes``: the world's LaneGraph
        or None (the lane criteria); ``signals``: the world's SignalController or None (the
        traffic rule criteria).
    """

    def __init__(self, specs, duration_s, world, handles, obstacles, lanes=None, signals=None):
        self.criteria = build_criteria(specs, duration_s)
        self.duration_s = duration_s
        scene = world_scene(world, handles, obstacles, lanes=lanes, signals=signals)
        for criterion in self.criteria:
            criterion.bind(scene)
        self.goals = [c for c in self.criteria if c.KIND == 'reach_goal']
        self.verdicts = {c.name: UNDECIDED for c in self.criteria}

    def observe(self, elapsed_s, x_m, y_m, yaw_rad, speed_mps, collisions):
        """Take the ego's state after a basic step (episode time) and its new collisions."""
        sample = Sample(elapsed_s, x_m, y_m, yaw_rad, speed_mps)
        for criterion in self.criteria:
            for event in collisions:
                criterion.collision(event)
            criterion.observe(sample)

    def decide(self, elapsed_s):
        """
        Update ``verdicts``; return (terminated, reached every goal).

        At the scenario's duration a criterion still undecided takes its result's verdict;
        such a verdict ends nothing (the episode is truncated there).
        """
        for criterion in self.criteria:
            self.verdicts[criterion.name] = verdict_now(criterion, elapsed_s)
        failed = any(v == FAILED for v in self.verdicts.values())
        reached = bool(self.goals) and all(self.verdicts[c.name] == PASSED for c in self.goals)
        if elapsed_s >= self.duration_s - _EPS_S:
            for criterion in self.criteria:
                if self.verdicts[criterion.name] == UNDECIDED:
                    self.verdicts[criterion.name] = PASSED if criterion.result().passed \
                        else FAILED
        return failed or reached, reached
