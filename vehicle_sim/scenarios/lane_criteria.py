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
The lane criteria of scenarios: stay_in_lane, reach_lanelet and speed_limit.

They read the world's lane map (a Lanelet2 map or ``roads:``) from the run's scene
(``scene.lanes``, a core LaneGraph; None = the world has none, and each of them then fails
saying so) and follow the vehicle with a core LaneTracker (and a LaneInvasionDetector), from the
same ground-truth samples as the other criteria. Importing this module registers them in
``criteria.CRITERIA`` (schema.py imports it).
"""

from vehicle_sim.core.map.lane_graph import SOLID_TYPES
from vehicle_sim.core.map.lane_invasion import LaneInvasionDetector
from vehicle_sim.core.map.lane_state import LaneTracker
from vehicle_sim.core.specs.param_spec import ParamSpec, REQUIRED
from vehicle_sim.scenarios.criteria import CRITERIA, Criterion

NO_MAP = 'the world has no lane map (map: of type lanelet2, or roads:)'


class _LaneCriterion(Criterion):
    """Base: follows the vehicle's lane state; subclasses take ``observe_lane``."""

    def __init__(self, *args):
        super().__init__(*args)
        self.lanes = None
        self.tracker = None
        self.error = None

    def bind(self, scene):
        self.lanes = getattr(scene, 'lanes', None)
        if self.lanes is None:
            self.error = NO_MAP
            return
        self.tracker = LaneTracker(self.lanes)
        self.bind_lanes(self.lanes)

    def bind_lanes(self, lanes):
        """Take the lane map before the first step (check ids against it)."""

    def observe(self, sample):
        if self.tracker is not None:
            self.observe_lane(sample, self.tracker.update(sample.x_m, sample.y_m,
                                                          sample.yaw_rad))

    def observe_lane(self, sample, state):
        raise NotImplementedError


class StayInLane(_LaneCriterion):
    """The vehicle stays on a lane, within an offset of its centre, and crosses no solid line."""

    KIND = 'stay_in_lane'
    UNIT = 'm'
    SPECS = (
        ParamSpec('max_offset', 'max_offset_m', 'float', None, 'm', 'largest |offset| of the '
                  "vehicle's reference point from its lane's centreline; null = not checked",
                  gt=0.0, optional=True),
        ParamSpec('solid_lines', 'solid_lines', 'bool', True, doc='crossing a solid line '
                  '(solid, solid_solid, the mixed ones, curbstone, road_border, wall) fails'),
    )

    def __init__(self, *args):
        super().__init__(*args)
        self.detector = None
        self.worst = None           # (|offset|, time, lane)
        self.off_lane_s = None
        self.crossed = []           # solid-line LaneInvasions

    def bind_lanes(self, lanes):
        self.detector = LaneInvasionDetector(lanes)

    def observe_lane(self, sample, state):
        for event in self.detector.update(sample.x_m, sample.y_m, sample.time_s):
            if event.line_type in SOLID_TYPES:
                self.crossed.append(event)
        if not state.on_lane:
            if self.off_lane_s is None:
                self.off_lane_s = sample.time_s
            return
        if self.worst is None or abs(state.offset_m) > self.worst[0]:
            self.worst = (abs(state.offset_m), sample.time_s, state.lane_id)

    def result(self):
        if self.error:
            return self._result(False, None, self.error)
        limit = self.values['max_offset_m']
        parts, passed = [], True
        if self.worst is not None:
            offset, at_s, lane = self.worst
            within = limit is None or offset <= limit
            passed = within
            parts.append(f'max |offset| {offset:.3f} m at {at_s:.2f} s on lane {lane}'
                         + (f' (limit {limit:g} m)' if limit is not None else ''))
        if self.off_lane_s is not None:
            passed = False
            parts.append(f'off every lane at {self.off_lane_s:.2f} s')
        if self.values['solid_lines']:
            if self.crossed:
                passed = False
                first = self.crossed[0]
                parts.append(f'crossed {len(self.crossed)} solid line(s): first {first.line_type} '
                             f'{first.boundary_id} at {first.time_s:.2f} s')
            else:
                parts.append('crossed no solid line')
        return self._result(passed, None if self.worst is None else self.worst[0],
                            '; '.join(parts) or 'no step observed')


class ReachLanelet(_LaneCriterion):
    """The vehicle reaches a lanelet (a lane of the map, by id) within a time."""

    KIND = 'reach_lanelet'
    UNIT = 's'
    SPECS = (
        ParamSpec('lanelet', 'lanelet', 'int', REQUIRED, doc='the lane id: a Lanelet2 '
                  "lanelet's id, or a road segment lane's id"),
        ParamSpec('min_s', 'min_s_m', 'float', 0.0, 'm', 'counts from this arc length along '
                  'the lanelet', ge=0.0),
        ParamSpec('within', 'within_s', 'float', None, 's', 'deadline; null = the duration',
                  gt=0.0, optional=True),
    )

    def __init__(self, *args):
        super().__init__(*args)
        self.reached_s = None

    def bind_lanes(self, lanes):
        target = self.values['lanelet']
        if target not in lanes.lanes:
            self.error = f'lanelet {target} is not in the lane map'
        elif self.values['min_s_m'] > lanes.lanes[target].length_m:
            self.error = (f'min_s {self.values["min_s_m"]:g} m is beyond lanelet {target} '
                          f'({lanes.lanes[target].length_m:.3f} m long)')

    def observe_lane(self, sample, state):
        if self.reached_s is None and state.on_lane and state.lane_id == \
                self.values['lanelet'] and state.s_m >= self.values['min_s_m']:
            self.reached_s = sample.time_s

    def result(self):
        target = self.values['lanelet']
        if self.error:
            return self._result(False, None, self.error)
        within = self.values['within_s'] or self.duration_s
        if self.reached_s is None:
            return self._result(False, None, f'lanelet {target} not reached (deadline '
                                              f'{within:g} s)')
        return self._result(self.reached_s <= within + 1e-9, self.reached_s,
                            f'lanelet {target} reached at {self.reached_s:.2f} s (deadline '
                            f'{within:g} s)')


class SpeedLimit(_LaneCriterion):
    """The vehicle's speed never exceeds the speed limit of the lane it is on (the map's)."""

    KIND = 'speed_limit'
    UNIT = 'm/s'
    SPECS = (
        ParamSpec('tolerance', 'tolerance_mps', 'float', 0.0, 'm/s', 'allowed excess over '
                  "the lane's limit", ge=0.0),
    )

    def __init__(self, *args):
        super().__init__(*args)
        self.worst = None           # (excess, time, lane, limit)

    def observe_lane(self, sample, state):
        if not state.on_lane:
            return
        excess = abs(sample.speed_mps) - state.speed_limit_mps
        if self.worst is None or excess > self.worst[0]:
            self.worst = (excess, sample.time_s, state.lane_id, state.speed_limit_mps)

    def result(self):
        if self.error:
            return self._result(False, None, self.error)
        if self.worst is None:
            return self._result(True, None, 'never on a lane: no limit to keep')
        excess, at_s, lane, limit = self.worst
        tolerance = self.values['tolerance_mps']
        word = 'above' if excess > 0 else 'below'
        return self._result(excess <= tolerance + 1e-12, excess,
                            f'closest to the limit at {at_s:.2f} s on lane {lane}: '
                            f'{abs(excess):.3f} m/s {word} its {limit:.3f} m/s '
                            f'(tolerance {tolerance:g} m/s)')


LANE_CRITERIA = {cls.KIND: cls for cls in (StayInLane, ReachLanelet, SpeedLimit)}
CRITERIA.update(LANE_CRITERIA)
