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
The lane criteria (stay_in_lane, reach_lanelet, speed_limit) fed by hand.

The lane map: one straight road along +x, 200 m, two lanes each way, 3.5 m wide; forward lane 0
(id 100001) is centred at y = -1.75, forward lane 1 (100002) at y = -5.25, separated by a dashed
line at y = -3.5; a solid centre line at y = 0; a solid edge at y = -7. The second half
(x 100 .. 200, lanes 100101, 100102) has a limit of 10 m/s, the first 20 m/s.
"""

from types import SimpleNamespace

import pytest

from vehicle_sim.core.map.road_segments import lane_graph_from_roads, roads_from_list
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.scenarios.criteria import CRITERIA, Sample, validate_criterion
from vehicle_sim.scenarios.lane_criteria import NO_MAP

DURATION_S = 20.0
LANES = lane_graph_from_roads(roads_from_list([{
    'lanes': 2, 'speed_limit': 20.0,
    'segments': [{'type': 'straight', 'length': 100.0},
                 {'type': 'straight', 'length': 100.0, 'speed_limit': 10.0}]}], 'roads'))


def _criterion(kind, lanes=LANES, **data):
    criterion = CRITERIA[kind](kind, 'ego', validate_criterion(kind, data), DURATION_S)
    criterion.bind(SimpleNamespace(lanes=lanes))
    return criterion


def _feed(criterion, points, dt_s=0.5):
    # points: (x, y, speed) per sample, heading +x, one sample every dt_s from t = 0
    for index, (x, y, speed) in enumerate(points):
        criterion.observe(Sample(index * dt_s, x, y, 0.0, speed))
    return criterion.result()


def test_stay_in_lane_passes_within_the_offset_and_reports_the_largest():
    result = _feed(_criterion('stay_in_lane', max_offset=0.5),
                   [(x, -1.75 + 0.01 * x, 5.0) for x in range(0, 40, 2)])
    assert result.passed and result.unit == 'm'
    assert result.value == pytest.approx(0.38)         # x = 38: 0.38 m left of centre
    assert 'max |offset| 0.380 m at 9.50 s on lane 100001 (limit 0.5 m)' in result.detail


def test_stay_in_lane_fails_beyond_the_offset_but_not_for_the_dashed_line():
    points = [(10.0 + x, -1.75 - 0.1 * x, 5.0) for x in range(0, 30)]   # into lane 100002
    assert not _feed(_criterion('stay_in_lane', max_offset=1.0), points).passed
    result = _feed(_criterion('stay_in_lane'), points)  # no offset bound; dashed is allowed
    assert result.passed and 'crossed no solid line' in result.detail


def test_stay_in_lane_fails_on_a_solid_line_naming_it():
    points = [(10.0 + x, -1.75 + 0.25 * x, 5.0) for x in range(0, 12)]   # over the centre
    result = _feed(_criterion('stay_in_lane'), points)
    assert not result.passed
    assert 'crossed 1 solid line(s): first solid 100030 at' in result.detail
    lenient = _feed(_criterion('stay_in_lane', solid_lines=False), points)
    assert lenient.passed    # the backward lane is a lane too; no offset bound


def test_stay_in_lane_fails_off_every_lane():
    result = _feed(_criterion('stay_in_lane', solid_lines=False),
                   [(10.0, -1.75, 1.0), (10.0, -7.5, 1.0)])
    assert not result.passed and 'off every lane at 0.50 s' in result.detail


def test_reach_lanelet_reports_the_first_time_on_it():
    result = _feed(_criterion('reach_lanelet', lanelet=100101, min_s=5.0),
                   [(95.0 + 2.0 * i, -1.75, 4.0) for i in range(10)])
    assert result.passed and result.unit == 's'
    assert result.value == pytest.approx(2.5)      # x = 105, s = 5 on 100101: 6th sample
    missed = _feed(_criterion('reach_lanelet', lanelet=100102, within=1.0),
                   [(95.0 + 2.0 * i, -1.75, 4.0) for i in range(10)])
    assert not missed.passed and 'lanelet 100102 not reached' in missed.detail


def test_reach_lanelet_naming_a_lane_not_in_the_map_fails_saying_so():
    result = _criterion('reach_lanelet', lanelet=42).result()
    assert not result.passed and result.detail == 'lanelet 42 is not in the lane map'


def test_speed_limit_takes_the_limit_of_the_lane_the_vehicle_is_on():
    # 15 m/s is below the first half's 20 m/s but above the second half's 10 m/s
    first_half = [(10.0 * i, -1.75, 15.0) for i in range(10)]
    result = _feed(_criterion('speed_limit'), first_half)
    assert result.passed and result.value == pytest.approx(-5.0)
    result = _feed(_criterion('speed_limit', tolerance=1.0),
                   first_half + [(110.0, -1.75, 10.5), (120.0, -1.75, 15.0)])
    assert not result.passed and result.value == pytest.approx(5.0)
    assert 'at 5.50 s on lane 100101: 5.000 m/s above its 10.000 m/s' in result.detail


@pytest.mark.parametrize('kind', ['stay_in_lane', 'reach_lanelet', 'speed_limit'])
def test_lane_criteria_fail_in_a_world_without_a_lane_map(kind):
    data = {'lanelet': 1} if kind == 'reach_lanelet' else {}
    criterion = _criterion(kind, lanes=None, **data)
    criterion.observe(Sample(0.0, 0.0, 0.0, 0.0, 1.0))
    result = criterion.result()
    assert not result.passed and result.detail == NO_MAP


@pytest.mark.parametrize('kind, data, match', [
    ('reach_lanelet', {}, "field 'lanelet' is required"),
    ('reach_lanelet', {'lanelet': 1.5}, "field 'lanelet' = 1.5: must be an integer"),
    ('stay_in_lane', {'max_offset': 0.0}, "field 'max_offset' = 0.0: must be > 0"),
    ('speed_limit', {'tolerance': -1.0}, "field 'tolerance' = -1.0: must be >= 0"),
])
def test_bad_lane_criteria_are_refused_naming_the_field(kind, data, match):
    with pytest.raises(InvalidParameterError, match=match):
        validate_criterion(kind, data)
