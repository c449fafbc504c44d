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
Lanes in the Gym environment.

The ``lane`` observation, progress along the lanes, the ``lane`` reward term, ending off the
road, determinism; worlds without lanes unchanged.
"""

import math
from pathlib import Path
import warnings

import numpy as np
import pytest

from vehicle_sim.core.learning.progress import LaneProgress
from vehicle_sim.core.learning.reward import lane_term, LANE_TERMS, RewardWeights, TERMS
from vehicle_sim.core.map.lane_state import LaneState, OFF_LANE
from vehicle_sim.core.map.lane_travel import lane_distance
from vehicle_sim.core.map.road_segments import lane_graph_from_roads, roads_from_list
from vehicle_sim.core.specs.errors import InvalidParameterError

gymnasium = pytest.importorskip('gymnasium', reason="needs the 'gym' extra (gymnasium)")

from gymnasium.utils.env_checker import check_env  # noqa: E402

import vehicle_sim.gym  # noqa: E402,F401  (registers the ids)
from vehicle_sim.gym import DriveVectorEnv  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
# One road, one lane each way, 3.5 m lanes: 20 m straight east, a quarter circle of radius
# 30 m to the left, 30 m straight north. Forward lanes 100001, 100101, 100201 (docs/lanes.md).
ROAD = {'name': 'bend', 'lanes': 1, 'backward_lanes': 1, 'lane_width': 3.5,
        'speed_limit': 13.9, 'edge_line': 'solid', 'centre_line': 'solid',
        'segments': [{'type': 'straight', 'length': 20.0},
                     {'type': 'arc', 'radius': 30.0, 'angle': 90.0},
                     {'type': 'straight', 'length': 30.0}]}
ARC_M = 30.0 * math.pi / 2.0        # the arc's length along the reference line


def bend_world(lanelet, s_m, offset_m=0.0):
    return {'vehicles': [{'name': 'Car', 'model': 'ToyotaPrius',
                          'pose': {'lanelet': lanelet, 's': s_m, 'offset': offset_m}}],
            'roads': [ROAD]}


def bend_graph():
    return lane_graph_from_roads(roads_from_list([ROAD], 'w.yaml: roads'), 'w.yaml: roads')


def on(lane_id, s_m):
    return LaneState(True, lane_id, s_m, 0.0, 0.0, 3.5, 13.9)


def test_check_env_passes_on_the_highway_with_the_lane_part(make):
    env = make(world='highway')
    with warnings.catch_warnings():
        warnings.filterwarnings('ignore', message='.*(infinity|symmetric and normalized).*')
        check_env(env.unwrapped, skip_render_check=True)
    obs, info = env.reset(seed=0)
    assert set(obs) == {'pose', 'twist', 'lane', 'lane_id'}
    assert obs['lane'].dtype == np.float32 and obs['lane'].shape == (6,)
    assert obs['lane_id'].dtype == np.int64 and obs['lane_id'].shape == (1,)
    # the car starts in the middle forward lane of the first segment, 20 m from its start
    assert obs['lane_id'][0] == 100002 and info['lane_id'] == 100002 and info['on_lane']
    s, offset, heading, width, limit, on_lane = obs['lane']
    assert s == pytest.approx(20.0, abs=1e-4) and offset == pytest.approx(0.0, abs=1e-4)
    assert width == pytest.approx(3.75) and limit == pytest.approx(33.3) and on_lane == 1.0
    assert tuple(info['reward_terms']) == LANE_TERMS
    assert 100002 in env.unwrapped.sim.lane_ids


def test_a_car_placed_at_s_10_on_a_lane_reads_that_lane_and_no_offset(make):
    env = make(world=bend_world(100001, 10.0))
    obs, _ = env.reset(seed=0)
    assert obs['lane_id'][0] == 100001
    s, offset, heading, width, limit, on_lane = obs['lane'].tolist()
    assert s == pytest.approx(10.0, abs=1e-3) and abs(offset) < 1e-3 and abs(heading) < 1e-3
    assert width == pytest.approx(3.5) and limit == pytest.approx(13.9, rel=1e-6)
    assert on_lane == 1.0
    assert env.observation_space.contains(obs)


def test_placed_on_the_arc_with_an_offset_the_observation_reads_it(make):
    env = make(world=bend_world(100101, 10.0, offset_m=0.5))
    obs, _ = env.reset(seed=0)
    assert obs['lane_id'][0] == 100101
    assert obs['lane'][0] == pytest.approx(10.0, abs=0.02)
    assert obs['lane'][1] == pytest.approx(0.5, abs=0.02)


def test_driving_straight_off_a_curved_lane_makes_the_lane_penalty_appear(make):
    env = make(world=bend_world(100101, 2.0), action_repeat=10,
               off_lane_penalty=4.0, solid_line_penalty=2.0)
    env.reset(seed=0)
    straight = np.array([0.0, 8.0], dtype=np.float32)
    lane_terms, crossed, off = [], 0, False
    for _ in range(60):
        _, reward, terminated, truncated, info = env.step(straight)
        lane_terms.append(info['reward_terms']['lane'])
        crossed += info['solid_crossings']
        off = off or not info['on_lane']
        assert reward == pytest.approx(sum(info['reward_terms'].values()))
        assert not terminated      # leaving the road ends nothing by default
    # the car leaves the lane on the outside of the bend: it crosses the solid edge line
    # (-2 once) and then is off every lane (-4/s x 0.1 s per step)
    assert crossed >= 1 and off
    assert min(lane_terms) <= -2.0
    assert lane_terms[-1] == pytest.approx(-0.4)
    assert lane_terms[0] == 0.0     # still on the lane at the start


def test_terminate_off_road_ends_the_episode_when_the_car_leaves_every_lane(make):
    env = make(world=bend_world(100101, 2.0), action_repeat=10, terminate_off_road=True)
    env.reset(seed=0)
    for step in range(60):
        _, _, terminated, _, info = env.step(np.array([0.0, 8.0], dtype=np.float32))
        if terminated:
            break
    assert terminated and not info['on_lane'] and info['lane_id'] == 0


def test_progress_follows_the_lane_and_replaces_the_heading_default(make):
    env = make(world=bend_world(100001, 2.0), action_repeat=10)
    obs, _ = env.reset(seed=0)
    total, s_before = 0.0, float(obs['lane'][0])
    for _ in range(10):
        obs, _, _, _, info = env.step(np.array([0.0, 5.0], dtype=np.float32))
        total += info['reward_terms']['progress']
    assert obs['lane_id'][0] == 100001 and total > 1.0
    assert total == pytest.approx(float(obs['lane'][0]) - s_before, abs=1e-3)


def test_determinism_with_lanes_same_seed_same_actions_bit_identical(make):
    options = dict(world='highway', action_repeat=5, start_noise=[1.0, 0.5, 0.05])
    rng = np.random.default_rng(7)
    actions = [np.array([rng.uniform(-0.1, 0.1), rng.uniform(0.0, 20.0)], dtype=np.float32)
               for _ in range(30)]

    def run(env):
        obs, _ = env.reset(seed=3)
        out = [obs]
        for action in actions:
            out.append(env.step(action)[0])
        return out

    first = make(**options)
    a = run(first)
    run(first)                      # another episode in between
    b = run(first)
    c = run(make(**options))
    for x, y, z in zip(a, b, c):
        for key in x:
            assert x[key].tobytes() == y[key].tobytes() == z[key].tobytes(), key
    assert a[-1]['lane'][0] > a[0]['lane'][0]       # it did move along the lane


def test_worlds_without_lanes_keep_their_observation_keys_and_terms(make):
    env = make(world='obstacle_course')
    obs, info = env.reset(seed=0)
    assert set(obs) == {'pose', 'twist'}
    assert tuple(info['reward_terms']) == TERMS
    assert 'on_lane' not in info and env.unwrapped.sim.lanes is None
    _, _, _, _, info = env.step(np.array([0.0, 1.0], dtype=np.float32))
    assert tuple(info['reward_terms']) == TERMS


def test_the_lane_penalty_options_are_validated(make):
    with pytest.raises(InvalidParameterError, match='off_lane_penalty'):
        make(world='highway', off_lane_penalty=-1.0)
    with pytest.raises(InvalidParameterError, match='solid_line_penalty'):
        make(world='highway', solid_line_penalty=float('nan'))


# ------------------------------------------------------------------- core: lanes and reward
def test_lane_distance_follows_successors_predecessors_and_neighbours():
    graph = bend_graph()
    first, arc = graph.lanes[100001], graph.lanes[100101]
    assert lane_distance(graph, 100001, 5.0, 100001, 7.5) == pytest.approx(2.5)
    assert lane_distance(graph, 100001, 18.0, 100101, 1.0) == pytest.approx(
        first.length_m - 18.0 + 1.0)
    # two lanes ahead: the arc counted whole
    assert lane_distance(graph, 100001, 19.0, 100201, 2.0) == pytest.approx(
        1.0 + arc.length_m + 2.0)
    assert lane_distance(graph, 100101, 1.0, 100001, 18.0) == pytest.approx(
        -(first.length_m - 18.0 + 1.0))
    # the backward lane of the same segment is no neighbour of the same direction: unrelated
    assert lane_distance(graph, 100001, 5.0, 100051, 5.0) is None
    # a lane change onto the same-direction neighbour, on the arc where the two differ in
    # length: s carried over at the same fraction of the length
    two = lane_graph_from_roads(roads_from_list([dict(ROAD, lanes=2)], 'w'), 'w')
    inner, outer = two.lanes[100101], two.lanes[100102]
    assert inner.right_lane == 100102 and outer.length_m > inner.length_m
    moved = lane_distance(two, 100101, 10.0, 100102, 12.0)
    assert moved == pytest.approx(12.0 - 10.0 / inner.length_m * outer.length_m)


def test_lane_progress_counts_after_coming_back_and_nothing_off_the_lane():
    progress = LaneProgress(bend_graph())
    progress.start(on(100001, 5.0))
    assert progress.advance(on(100001, 6.0)) == pytest.approx(1.0)
    assert progress.advance(OFF_LANE) == 0.0
    assert progress.advance(on(100001, 9.0)) == pytest.approx(3.0)
    assert progress.advance(on(100051, 3.0)) == 0.0      # a jump onto the other direction
    assert progress.advance(on(100051, 4.0)) == pytest.approx(1.0)


def test_lane_term_weights_time_off_the_lane_and_solid_lines():
    weights = RewardWeights(off_lane_penalty=10.0, solid_line_penalty=1.5)
    assert lane_term(weights, True, 0, 0.1) == 0.0
    assert lane_term(weights, False, 0, 0.1) == pytest.approx(-1.0)
    assert lane_term(weights, True, 2, 0.1) == pytest.approx(-3.0)
    with pytest.raises(InvalidParameterError, match='off_lane_penalty'):
        RewardWeights(off_lane_penalty=-1.0)


def test_a_scenarios_lane_criteria_are_judged_on_the_worlds_lane_map(make):
    scenario = ROOT / 'scenarios' / 'highway_stay_in_lane.yaml'
    env = make(scenario=str(scenario), action_repeat=10)
    _, info = env.reset(seed=0)
    assert set(info['criteria'].values()) == {'undecided'}
    for _ in range(20):         # straight along the middle lane: nothing decided yet
        _, _, terminated, _, info = env.step(np.array([0.0, 15.0], dtype=np.float32))
        assert not terminated
    assert set(info['criteria'].values()) == {'undecided'}
    for _ in range(100):        # steer left across the lanes: stay_in_lane fails
        _, _, terminated, _, info = env.step(np.array([0.2, 15.0], dtype=np.float32))
        if terminated:
            break
    assert terminated
    verdicts = info['criteria']
    stay = [name for name in verdicts if 'stay_in_lane' in name]
    assert len(stay) == 1 and verdicts[stay[0]] == 'failed', verdicts


def test_on_a_lanelet2_map_the_lane_part_reads_the_lanelet_and_progress_follows_successors(
        make, tmp_path):
    pytest.importorskip('lanelet2', reason="needs the 'lanelet2' extra (Lanelet2's Python "
                        'package) to read the .osm map')
    from lane_helpers import write_world
    world = write_world(tmp_path, [{'name': 'Car', 'model': 'ToyotaPrius',
                                    'pose': {'lanelet': 2001, 's': 10.0, 'offset': 0.0}}])
    env = make(world=str(world), action_repeat=10)
    obs, _ = env.reset(seed=0)
    assert obs['lane_id'][0] == 2001
    assert obs['lane'][0] == pytest.approx(10.0, abs=1e-3) and abs(obs['lane'][1]) < 1e-3
    x0, total = float(obs['pose'][0]), 0.0
    for _ in range(80):          # straight on at 10 m/s, past the lanelet's end at x = 50 m
        obs, _, _, _, info = env.step(np.array([0.0, 10.0], dtype=np.float32))
        total += info['progress_m']
        if obs['pose'][0] > 60.0:
            break
    assert obs['lane_id'][0] == 2003 and info['on_lane']       # 2001's successor
    assert obs['lane'][0] == pytest.approx(float(obs['pose'][0]) - 50.0, abs=0.05)
    assert total == pytest.approx(float(obs['pose'][0]) - x0, abs=0.05)


def test_the_vector_env_batches_the_lane_keys():
    env = DriveVectorEnv(3, world='highway', action_repeat=5)
    try:
        obs, info = env.reset(seed=[0, 1, 2])
        assert obs['lane'].shape == (3, 6) and obs['lane_id'].shape == (3, 1)
        assert obs['lane_id'].dtype == np.int64 and (obs['lane_id'][:, 0] == 100002).all()
        action = np.tile(np.array([0.0, 10.0], dtype=np.float32), (3, 1))
        obs, reward, _, _, info = env.step(action)
        assert info['lane_id'].tolist() == [100002] * 3 and info['on_lane'].all()
        assert info['reward_terms']['lane'].shape == (3,)
        assert env.single_observation_space.contains({k: v[0] for k, v in obs.items()})
    finally:
        env.close()


def test_a_reset_after_leaving_the_lane_is_neither_a_crossing_nor_progress(make):
    env = make(world=bend_world(100101, 2.0), action_repeat=10)
    first, _ = env.reset(seed=0)
    crossed = 0
    for _ in range(40):
        _, _, _, _, info = env.step(np.array([0.0, 8.0], dtype=np.float32))
        crossed += info['lane_crossings']
    assert crossed >= 1 and not info['on_lane']
    again, info = env.reset(seed=0)
    assert info['lane_crossings'] == 0 and info['on_lane'] and info['lane_id'] == 100101
    assert again['lane'].tobytes() == first['lane'].tobytes()
    _, _, _, _, info = env.step(np.array([0.0, 1.0], dtype=np.float32))
    # the jump back is not counted: the first step's progress is what the car drove
    assert info['lane_crossings'] == 0 and 0.0 <= info['progress_m'] < 0.1
    assert info['reward_terms']['lane'] == 0.0


def test_lane_term_weights_the_distance_from_the_lane_centre():
    weights = RewardWeights(lane_centre_penalty=2.0)
    # 0.5 m off a 3.5 m lane's centre: 0.5 / 1.75 of the half width, 2 /s, for 0.1 s
    assert lane_term(weights, True, 0, 0.1, 0.5 / 1.75) == pytest.approx(-2.0 * 0.1 / 3.5)
    assert lane_term(weights, True, 0, 0.1, 0.0) == 0.0
    assert lane_term(RewardWeights(), True, 0, 0.1, 0.9) == 0.0      # off by default
    with pytest.raises(InvalidParameterError, match='lane_centre_penalty'):
        RewardWeights(lane_centre_penalty=-1.0)


def test_the_lane_centre_penalty_follows_the_observed_offset(make):
    env = make(world=bend_world(100101, 10.0, offset_m=0.5), action_repeat=10,
               lane_centre_penalty=3.0)
    env.reset(seed=0)
    obs, _, _, _, info = env.step(np.array([0.0, 2.0], dtype=np.float32))
    _, offset, _, width, _, on_lane = obs['lane'].tolist()
    assert on_lane == 1.0 and abs(offset) > 0.3
    assert info['reward_terms']['lane'] == pytest.approx(-3.0 * abs(offset) / (width / 2) * 0.1,
                                                         rel=1e-5)
    with pytest.raises(InvalidParameterError, match='lane_centre_penalty'):
        make(world='highway', lane_centre_penalty=-0.5)
