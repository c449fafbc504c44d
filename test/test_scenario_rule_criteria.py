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
The traffic rule criteria (traffic_light, stop_sign, yield) fed by hand.

The lane map: two roads of one lane each way crossing at a 12 m intersection centred on the
origin (``roads:``): east along y = -1.75 (approach lane 100001 from x = -60 to -6, then 100101
through the intersection), north along x = 1.75 (approach 200001 from y = -60 to -6, then
200101). Stop lines 1 (east, x = -7) and 2 (north, y = -7) lie 1 m before the intersection
(s = 53 m of their approach). 100101 and 200101 cross: x 0 .. 3.5 on 100101 (s 6 .. 9.5), y -3.5
.. 0 on 200101 (s 2.5 .. 6). The vehicle's front is 4 m ahead of its reference point.
"""

import math
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
import yaml

from vehicle_sim.core.geometry.footprint import Outline
from vehicle_sim.core.map.lane_rules import (
    Conflict,
    LaneRules,
    RightOfWay,
    StopLine,
    TrafficLightGroup,
)
from vehicle_sim.core.map.priority import priority_conflicts
from vehicle_sim.core.map.road_segments import lane_graph_from_roads, roads_from_list
from vehicle_sim.core.map.signal_plan import SignalController
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.scenarios import schema  # noqa: F401  (registers every criterion kind)
from vehicle_sim.scenarios.criteria import CRITERIA, Sample, validate_criterion
from vehicle_sim.scenarios.lane_criteria import NO_MAP
from vehicle_sim.scenarios.rule_criteria import NO_SIGNALS
from vehicle_sim.scenarios.runner import run_scenario

DURATION_S = 30.0
OUTLINE = Outline(-1.0, 4.0, -0.9, 0.9)
EAST, NORTH = 0.0, 0.5 * math.pi
CROSSING = Conflict(100101, 200101, (6.0, 9.5), (2.5, 6.0))


def _road(name, x, y, yaw):
    return {'name': name, 'start': {'x': x, 'y': y, 'yaw': yaw}, 'lanes': 1,
            'backward_lanes': 1, 'lane_width': 3.5, 'speed_limit': 13.9,
            'segments': [{'type': 'straight', 'length': 54.0},
                         {'type': 'intersection', 'length': 12.0},
                         {'type': 'straight', 'length': 54.0}]}


def _graph(rules):
    graph = lane_graph_from_roads(roads_from_list([_road('east', -60.0, 0.0, EAST),
                                                   _road('north', 0.0, -60.0, NORTH)], 'roads'))
    graph.set_rules(rules)
    return graph


def _line(line_id, kind, group=None):
    if line_id == 1:
        return StopLine(1, 100001, 53.0, [(-7.0, -3.5), (-7.0, 0.0)], kind, group)
    return StopLine(2, 200001, 53.0, [(0.0, -7.0), (3.5, -7.0)], kind, group)


def signalised():
    """Return the crossing with signal groups 10 (east) and 20 (north) and their controller."""
    graph = _graph(LaneRules(
        stop_lines=(_line(1, 'traffic_light', 10), _line(2, 'traffic_light', 20)),
        groups=(TrafficLightGroup(10, (100001,), (1,)), TrafficLightGroup(20, (200001,), (2,))),
        conflicts=(CROSSING,)))
    return graph, SignalController(graph)


def with_stop_sign(right_of_way=False):
    """Return the crossing with a stop sign line on the north approach (or a yield rule)."""
    if right_of_way:
        return _graph(LaneRules(stop_lines=(_line(2, 'yield'),), conflicts=(CROSSING,),
                                right_of_way=(RightOfWay(5, (100001,), (200001,), (2,)),)))
    return _graph(LaneRules(stop_lines=(_line(2, 'stop_sign'),), conflicts=(CROSSING,)))


def _criterion(kind, lanes, **scene):
    data = scene.pop('data', {})
    criterion = CRITERIA[kind](kind, 'ego', validate_criterion(kind, data), DURATION_S)
    criterion.bind(SimpleNamespace(lanes=lanes, outline=lambda name: OUTLINE, **scene))
    return criterion


def _drive(criterion, moves, dt_s=0.1, clock=None):
    # moves: (x, y, yaw, speed) of the reference point per sample, every dt_s from t = 0
    for index, (x, y, yaw, speed) in enumerate(moves):
        if clock is not None:
            clock['t'] = index * dt_s
        criterion.observe(Sample(index * dt_s, x, y, yaw, speed))
    return criterion.result()


def east_at(speed, x0=-40.0, steps=60):
    """Return the moves of a car driving east at a constant speed from x0."""
    return [(x0 + speed * 0.1 * i, -1.75, EAST, speed) for i in range(steps)]


def east_stopping(stop_x=-12.0, x0=-40.0):
    """Return the moves of a car braking evenly from 10 m/s to a stop at stop_x."""
    a = 100.0 / (2.0 * (stop_x - x0))
    moves, t = [], 0.0
    while t < 8.0:
        speed = max(10.0 - a * t, 0.0)
        travelled = (100.0 - speed ** 2) / (2.0 * a)
        moves.append((x0 + travelled, -1.75, EAST, speed))
        t += 0.1
    return moves


# ------------------------------------------------------------------------- traffic_light
def test_stopping_before_a_red_line_passes_saying_how_close_it_came():
    graph, signals = signalised()
    signals.force(10, 'red')
    result = _drive(_criterion('traffic_light', graph, signals=signals), east_stopping())
    assert result.passed and result.value == 0
    # the front stops at x = -8: 1 m before line 1 (x = -7)
    assert 'passed no traffic light stop line; closest to a red line: 1.00 m before line 1 ' \
           '(group 10)' in result.detail


def test_driving_through_a_red_line_fails_with_the_time_line_group_and_speed():
    graph, signals = signalised()
    signals.force(10, 'red')
    result = _drive(_criterion('traffic_light', graph, signals=signals), east_at(10.0))
    assert not result.passed and result.value == 1 and result.unit == 'crossing'
    # the front (x + 4) reaches the line (x = -7) at x = -11: t = 2.9 s
    assert result.detail == ('passed stop line 1 (lane 100001, group 10) on red at 2.90 s at '
                             '10.00 m/s')
    assert result.at_s == pytest.approx(2.9)
    assert result.points_m[0] == pytest.approx((-7.0, -1.75))


@pytest.mark.parametrize('state', ['green', 'yellow', 'off'])
def test_passing_on_green_yellow_or_off_is_allowed(state):
    graph, signals = signalised()
    signals.force(10, state)
    result = _drive(_criterion('traffic_light', graph, signals=signals), east_at(10.0))
    assert result.passed and result.value == 0
    assert f'passed line 1 (group 10) on {state} at 2.90 s' in result.detail
    assert '(yellow and off are allowed)' in result.detail


def test_the_state_counts_at_the_moment_the_front_passes_the_line():
    graph, signals = signalised()
    signals.force(10, 'green')
    criterion = _criterion('traffic_light', graph, signals=signals)
    for index, (x, y, yaw, speed) in enumerate(east_at(10.0)):
        if index == 35:                 # red once the front is past the line (2.9 s)
            signals.force(10, 'red')
        criterion.observe(Sample(index * 0.1, x, y, yaw, speed))
    assert criterion.result().passed
    # the other group's line is not on its way; a watched group list leaves group 10 out
    signals.force(10, 'red')
    only_north = _drive(_criterion('traffic_light', graph, signals=signals,
                                   data={'groups': [20]}), east_at(10.0))
    assert only_north.passed and 'passed no traffic light stop line' in only_north.detail


def test_traffic_light_fails_without_signals_a_map_or_lines_saying_so():
    graph, _ = signalised()
    assert _drive(_criterion('traffic_light', graph, signals=None),
                  east_at(10.0)).detail == NO_SIGNALS
    assert _drive(_criterion('traffic_light', None), east_at(10.0)).detail == NO_MAP
    result = _drive(_criterion('traffic_light', with_stop_sign(), signals=None), east_at(10.0))
    assert not result.passed
    assert result.detail == 'the lane map has no traffic light stop line to watch'
    _, signals = signalised()
    result = _criterion('traffic_light', graph, signals=signals, data={'groups': [10, 99]})
    assert result.result().detail == 'traffic light group(s) [99] not in the lane map (its ' \
                                     'groups: 10, 20)'


# ----------------------------------------------------------------------------- stop_sign
def north_moves(speeds, y0=-30.0):
    """Return the moves of a car driving north from y0 at the given speed per 0.1 s step."""
    moves, y = [], y0
    for speed in speeds:
        moves.append((1.75, y, NORTH, speed))
        y += 0.1 * speed
    return moves


def test_a_full_stop_before_the_stop_line_passes():
    # 5 m/s from y = -30 to a stop at y = -12 (3.6 s): the front 1 m before the line, then on
    approach = [5.0] * 36 + [0.0] * 10 + [3.0] * 40
    result = _drive(_criterion('stop_sign', with_stop_sign()), north_moves(approach))
    assert result.passed and result.value == 0.0 and result.unit == 'm/s'
    assert result.detail == ('stopped before all 1 stop sign line(s) passed; the least full '
                             'stop: line 2: slowest 0.000 m/s within 3 m before it at 3.60 s '
                             '(a stop: <= 0.1 m/s)')


def test_rolling_through_a_stop_line_fails_with_the_time_and_the_slowest_speed():
    # 5 m/s to y = -15 (3 s), then 1 m/s: the front passes the line (y = -7) at about 7 s
    result = _drive(_criterion('stop_sign', with_stop_sign()),
                    north_moves([5.0] * 30 + [1.0] * 60))
    assert not result.passed and result.value == pytest.approx(1.0)
    assert result.detail.startswith('rolled through stop line 2 (lane 200001) at 7.')
    assert ' s at 1.00 m/s: slowest 1.000 m/s within 3 m before it at 4.0' in result.detail
    assert result.detail.endswith('(a stop: <= 0.1 m/s)')


def test_a_stop_further_back_than_the_distance_does_not_count():
    # stopped with its front 4 m before the line, then creeping on at 0.5 m/s
    approach = [5.0] * 30 + [0.0] * 10 + [0.5] * 100
    lenient = _drive(_criterion('stop_sign', with_stop_sign(), data={'stop_within': 4.5}),
                     north_moves(approach))
    strict = _drive(_criterion('stop_sign', with_stop_sign()), north_moves(approach))
    assert lenient.passed and lenient.value == 0.0
    assert not strict.passed and 'slowest 0.500 m/s within 3 m before it' in strict.detail


# --------------------------------------------------------------------------------- yield
def test_priority_comes_from_a_right_of_way_rule_or_a_stop_sign_on_one_way_only():
    expected = {200101: (CROSSING.reversed(),)}
    assert priority_conflicts(with_stop_sign(right_of_way=True)) == expected
    assert priority_conflicts(with_stop_sign()) == expected
    graph, _ = signalised()
    assert priority_conflicts(graph) == {}          # signalised: the lights decide


def _traffic(clock, x0, speed):
    # one traffic car driving east on the priority lane (its box centre; 4.5 m long)
    return {'traffic': lambda: [('traffic_0', x0 + speed * clock['t'], -1.75, EAST, 4.5, 1.8)],
            'traffic_speeds': lambda: {'traffic_0': speed}}


def test_entering_in_front_of_a_priority_vehicle_within_the_gap_fails_naming_it():
    # the front enters the zone (y = -3.5) when y = -7.5: t = 4.5 s at 5 m/s from y = -30
    clock = {'t': 0.0}
    criterion = _criterion('yield', with_stop_sign(right_of_way=True),
                           **_traffic(clock, -70.0, 10.0))
    result = _drive(criterion, north_moves([5.0] * 60), clock=clock)
    assert not result.passed and result.unit == 's'
    # at 4.5 s the traffic car's front is at x = -22.75, 22.75 m from the zone (x = 0)
    assert result.value == pytest.approx(2.275, abs=0.01)
    assert result.detail == ('entered the conflict zone of lane 200101 with priority lane '
                             '100101 at 4.50 s while traffic_0 was 2.27 s from it (22.8 m at '
                             '10.00 m/s); gap 3 s')
    assert result.others == ('traffic_0',) and result.at_s == pytest.approx(4.5)


def test_entering_well_ahead_of_or_after_the_priority_vehicle_passes():
    clock = {'t': 0.0}
    early = _drive(_criterion('yield', with_stop_sign(right_of_way=True),
                              **_traffic(clock, -90.0, 8.0)),
                   north_moves([5.0] * 60), clock=clock)
    # at 4.5 s its front is at x = -51.75: 6.47 s from the zone at 8 m/s
    assert early.passed and early.value == pytest.approx(51.75 / 8.0)
    assert "the nearest priority vehicle traffic_0 6.47 s from lane 100101's zone at 4.50 s " \
           '(gap 3 s)' in early.detail
    # it waits at the line until the traffic car has gone by, then crosses
    clock = {'t': 0.0}
    waited = _drive(_criterion('yield', with_stop_sign(right_of_way=True),
                               **_traffic(clock, -70.0, 10.0)),
                    north_moves([5.0] * 42 + [0.0] * 40 + [5.0] * 20), clock=clock)
    assert waited.passed and waited.value is None
    assert waited.detail == 'entered 1 conflict zone(s) of a priority lane, no priority ' \
                            'vehicle coming (gap 3 s)'


def test_one_of_our_vehicles_in_the_zone_counts_and_the_gap_is_a_parameter():
    other = {'car2': Sample(0.0, -1.0, -1.75, EAST, 0.0)}     # standing in the zone
    result = _drive(_criterion('yield', with_stop_sign(),
                               samples=lambda: dict(other, ego=None)),
                    north_moves([5.0] * 60))
    assert not result.passed and result.value == 0.0
    assert 'while car2 was in it; gap 3 s' in result.detail
    clock = {'t': 0.0}
    short = _drive(_criterion('yield', with_stop_sign(), data={'gap': 2.0},
                              **_traffic(clock, -70.0, 10.0)),
                   north_moves([5.0] * 60), clock=clock)
    assert short.passed and short.value == pytest.approx(2.275, abs=0.01)


def test_yield_fails_on_a_map_without_priorities():
    graph, _ = signalised()
    result = _drive(_criterion('yield', graph), north_moves([5.0] * 10))
    assert not result.passed and 'gives no lane priority over another' in result.detail


@pytest.mark.parametrize('kind, data, match', [
    ('traffic_light', {'groups': 10}, "field 'groups' = 10: must be a list of group ids"),
    ('traffic_light', {'groups': ['a']}, "field 'groups'.*must be a list of group ids"),
    ('stop_sign', {'stop_speed': 0.0}, "field 'stop_speed' = 0.0: must be > 0"),
    ('stop_sign', {'stop_within': -1.0}, "field 'stop_within' = -1.0: must be > 0"),
    ('yield', {'gap': 0.0}, "field 'gap' = 0.0: must be > 0"),
    ('yield', {'gap': 'long'}, "field 'gap'"),
    ('yield', {'within': 3.0}, "unknown field 'within'"),
])
def test_bad_rule_criteria_are_refused_naming_the_field(kind, data, match):
    with pytest.raises(InvalidParameterError, match=match):
        validate_criterion(kind, data)


# ----------------------------------------------------------------- through the runner
# test/scenarios/red_light.yaml and yield_crossing.yaml: the same crossing as a world's roads:
# (its rules from the intersection's signals: or stop_signs:, docs/signals.md): the eastbound
# group 4000100101 and its stop line 3000100001 across the end of lane 100001 (x = -6); the
# northbound stop sign line 3000200001 across the end of lane 200001 (y = -6).
SCENARIOS = Path(__file__).resolve().parent / 'scenarios'
RED_LIGHT = SCENARIOS / 'red_light.yaml'
YIELD_CROSSING = SCENARIOS / 'yield_crossing.yaml'


def _variant(tmp_path, source, change):
    data = yaml.safe_load(source.read_text(encoding='utf-8'))
    change(data)
    path = tmp_path / source.name
    path.write_text(yaml.safe_dump(data), encoding='utf-8')
    return path


def _no_brake(data):
    data['driver']['commands'] = data['driver']['commands'][:1]


def test_a_car_braking_to_a_stop_before_a_red_light_passes():
    result = run_scenario(RED_LIGHT)
    assert result.passed and result.error is None
    light = result.criterion('traffic_light')
    # at 30 km/h, full brake at 5.3 s: its front stops 2.5 m before the line (x = -6)
    assert light.value == 0
    assert light.detail.startswith('passed no traffic light stop line; closest to a red line: '
                                   '2.5')
    assert 'm before line 3000100001 (group 4000100101) at 7.' in light.detail
    track = result.tracks['Car']
    front = track.x_m[-1] + track.outline.x_max_m
    assert front == pytest.approx(-6.0 - 2.51, abs=0.05)


def test_a_car_driving_through_a_red_light_fails_with_the_time_and_the_line(tmp_path):
    result = run_scenario(_variant(tmp_path, RED_LIGHT, _no_brake))
    assert not result.passed
    light = result.criterion('traffic_light')
    assert light.value == 1 and light.unit == 'crossing'
    # the moment: the first step with its front at or beyond the line (x = -6), from the track
    track = result.tracks['Car']
    crossed = next(t for t, x in zip(track.time_s, track.x_m)
                   if x + track.outline.x_max_m >= -6.0)
    assert light.at_s == pytest.approx(crossed) and 6.0 < crossed < 7.0
    assert light.detail == (f'passed stop line 3000100001 (lane 100001, group 4000100101) on '
                            f'red at {crossed:.2f} s at 8.33 m/s')
    assert light.points_m[0] == pytest.approx((-6.0, -1.75), abs=0.1)


def test_served_over_ros_the_criterion_reads_the_automobile_nodes_signals(tmp_path):
    # a topic criterion serves the world (the automobile node builds it, with its signals part;
    # the signal command forces that one), the commands one step later than in a local run
    def served(data):
        _no_brake(data)
        data['criteria'].append({'kind': 'topic', 'topic': '/automobile/current_speed',
                                 'type': 'vehicle_msgs/msg/Float64Stamped', 'field': 'data',
                                 'op': '>', 'value': 25.0, 'mode': 'eventually'})

    result = run_scenario(_variant(tmp_path, RED_LIGHT, served))
    light = result.criterion('traffic_light')
    assert not light.passed and result.criterion('topic').passed
    track = result.tracks['Car']
    crossed = next(t for t, x in zip(track.time_s, track.x_m)
                   if x + track.outline.x_max_m >= -6.0)
    assert light.at_s == pytest.approx(crossed)
    assert light.detail == (f'passed stop line 3000100001 (lane 100001, group 4000100101) on '
                            f'red at {crossed:.2f} s at 8.33 m/s')


@pytest.mark.parametrize('green_s, passed, passing', [
    (5.0, True, 'passed line 3000100001 (group 4000100101) on yellow at 6.'),
    (3.0, False, 'passed stop line 3000100001 (lane 100001, group 4000100101) on red at 6.'),
])
def test_the_plan_decides_when_no_command_forces_the_group(tmp_path, green_s, passed, passing):
    # no forced state: the plan's first phase is the eastbound group's: green, yellow 3 s,
    # all red 2 s; the car's front reaches the line at about 6.5 s
    def plan_only(data):
        _no_brake(data)
        data['driver']['commands'][0].pop('signal')
        data['world']['signals'] = {'green': green_s}

    light = run_scenario(_variant(tmp_path, RED_LIGHT, plan_only)).criterion('traffic_light')
    assert light.passed is passed and light.detail.startswith(passing)


def test_a_car_that_stops_and_waits_for_the_priority_car_passes():
    result = run_scenario(YIELD_CROSSING)
    assert result.passed, [c.detail for c in result.criteria]
    stop = result.criterion('stop_sign')
    assert stop.value < 0.01
    assert stop.detail.startswith('stopped before all 1 stop sign line(s) passed; the least '
                                  'full stop: line 3000200001: slowest 0.000 m/s within 3 m '
                                  'before it at ')
    assert result.criterion('yield').detail.endswith('no priority vehicle coming (gap 3 s)')


def test_a_car_that_rolls_through_the_stop_sign_in_front_of_the_priority_car_fails(tmp_path):
    result = run_scenario(_variant(tmp_path, YIELD_CROSSING, _no_brake))
    stop = result.criterion('stop_sign')
    assert not stop.passed and stop.value == pytest.approx(8.33, abs=0.01)
    track = result.tracks['Car']
    crossed = next(t for t, y in zip(track.time_s, track.y_m)
                   if y + track.outline.x_max_m >= -6.0)
    assert stop.detail.startswith(f'rolled through stop line 3000200001 (lane 200001) at '
                                  f'{crossed:.2f} s at 8.33 m/s: slowest 8.333 m/s within 3 m '
                                  f'before it at ')
    given = result.criterion('yield')
    assert not given.passed and given.others == ('other',)
    # both at 30 km/h from 40 m: its front enters the first priority lane's zone (y = -3.5)
    # about half a second before 'other' (8 m/s) would reach it; they collide
    assert given.value == pytest.approx(0.53, abs=0.05)
    entered = next(t for t, y in zip(track.time_s, track.y_m)
                   if y + track.outline.x_max_m >= -3.5)
    assert given.at_s == pytest.approx(entered)
    assert given.detail.startswith('entered the conflict zone of lane 200101 with priority '
                                   f'lane 100101 at {entered:.2f} s while other was 0.5')
    assert ' m at 8.00 m/s); gap 3 s' in given.detail
    assert result.criterion('no_collision').others == ('other',)


def test_going_in_front_of_a_traffic_car_with_priority_fails_with_its_speed(tmp_path):
    def traffic_instead(data):
        _no_brake(data)
        data['world']['vehicles'] = data['world']['vehicles'][:1]
        del data['actors']
        # a traffic car (docs/traffic.md) going straight over the crossing at 0.6 x 13.9 m/s
        data['world']['traffic'] = {'placed': [{
            'model': 'ToyotaPrius', 'lanelet': 100001, 's': 5.0, 'speed': 8.0,
            'speed_factor': 0.6, 'route': [100101, 100201]}]}

    result = run_scenario(_variant(tmp_path, YIELD_CROSSING, traffic_instead))
    given = result.criterion('yield')
    assert not given.passed and given.others == ('traffic_0',)
    assert 0.0 < given.value < 1.5
    # its speed is the traffic's own (its pose changes only at the traffic's 0.1 s updates)
    speed = float(given.detail.split(' m at ')[1].split(' m/s')[0])
    assert speed == pytest.approx(8.34, abs=0.2)


def test_in_the_gym_env_driving_through_the_red_light_ends_the_episode(make, tmp_path):
    pytest.importorskip('gymnasium', reason="needs the 'gym' extra (gymnasium)")
    import vehicle_sim.gym  # noqa: F401  (registers the ids)

    def red_by_the_plan(data):
        # the agent drives (the scenario's commands do not run): the plan's cycle shifted so
        # that the eastbound group's phase is 25 s away: red from the start
        data['world']['signals'] = {'offset': 25.0}

    env = make(scenario=str(_variant(tmp_path, RED_LIGHT, red_by_the_plan)), action_repeat=10)
    _, info = env.reset(seed=0)
    controller = env.unwrapped.sim.scene.parts['signals'].controller
    assert controller.state(4000100101) == 'red'
    assert info['criteria'] == {'traffic_light': 'undecided'}
    for _ in range(150):
        _, _, terminated, _, info = env.step(np.array([0.0, 8.0], dtype=np.float32))
        if terminated:
            break
    assert terminated and info['criteria'] == {'traffic_light': 'failed'}
    front = env.unwrapped.sim.scene.vehicles['Car'].body.pose()[0] + 3.585
    assert -6.0 <= front < -6.0 + 0.8 * 1.0 + 0.1     # the env step (0.1 s) that passed it
