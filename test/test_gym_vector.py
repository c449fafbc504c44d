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
The native vector environment: N worlds in one process, independent, stepped in one call.

A crash in world 0 changes nothing in world 1 (bit-identical to a lone run); episodes end on a
collision and on the goal; autoreset in Gymnasium's modes; the id's vector entry point.
"""

from pathlib import Path

import numpy as np
import pytest

gymnasium = pytest.importorskip('gymnasium', reason="needs the 'gym' extra (gymnasium)")

from gymnasium.vector import AutoresetMode  # noqa: E402

from vehicle_sim.gym import DriveEnv, DriveVectorEnv  # noqa: E402

SCENARIOS = Path(__file__).resolve().parents[1] / 'scenarios'

FAST = np.array([0.0, 10.0], dtype=np.float32)     # into the wall at x = 19.5 m
GENTLE = np.array([0.2, 2.0], dtype=np.float32)


@pytest.fixture
def vector():
    made = []

    def _make(num_envs, **kwargs):
        env = DriveVectorEnv(num_envs, **kwargs)
        made.append(env)
        return env

    yield _make
    for env in made:
        env.close()


def test_a_crash_in_world_0_changes_nothing_in_world_1(vector):
    env = vector(2, lidar={'horizontal_resolution': 120})
    lone = DriveEnv(lidar={'horizontal_resolution': 120})
    try:
        obs, _ = env.reset(seed=[11, 22])
        alone, _ = lone.reset(seed=22)
        crashed = False
        for _ in range(400):
            obs, reward, terminated, truncated, info = env.step(np.stack([FAST, GENTLE]))
            alone, *_ = lone.step(GENTLE)
            crashed = crashed or bool(terminated[0] and info['collision'][0])
            for key in ('pose', 'twist', 'lidar'):
                assert obs[key][1].tobytes() == alone[key].tobytes(), key
            assert not terminated[1] and not info['collision'][1]
        assert crashed          # world 0 hit its wall (and was reset by the next step)
    finally:
        lone.close()


def test_episodes_end_on_a_collision_and_on_the_goal(vector):
    turn = np.array([-0.3, 5.0], dtype=np.float32)          # a right turn
    lone = DriveEnv()
    try:
        lone.reset(seed=0)
        for _ in range(400):
            obs, *_ = lone.step(turn)
    finally:
        lone.close()
    goal = [float(obs['pose'][0]), float(obs['pose'][1])]      # on the turning car's way only
    assert abs(goal[1]) > 4.0
    env = vector(2, goal=goal, goal_radius=1.0)
    env.reset(seed=0)
    ends = {}
    for _ in range(1000):
        obs, reward, terminated, truncated, info = env.step(np.stack([FAST, turn]))
        for i in np.flatnonzero(terminated):
            ends.setdefault(int(i), (bool(info['collision'][i]), bool(info['goal_reached'][i]),
                                     float(reward[i])))
        if len(ends) == 2:
            break
    assert ends[0][:2] == (True, False)          # world 0: the wall
    assert ends[1][:2] == (False, True)          # world 1: the goal
    assert ends[0][2] < -9.0 and ends[1][2] > 10.0


def test_next_step_autoreset_resets_an_ended_world_on_the_following_step(vector):
    env = vector(2, max_episode_s=0.05)
    obs, _ = env.reset(seed=0)
    start = obs['pose'].copy()
    for _ in range(5):
        obs, reward, terminated, truncated, _ = env.step(np.stack([FAST, FAST]))
    assert truncated.all() and not terminated.any()
    obs, reward, terminated, truncated, info = env.step(np.stack([FAST, FAST]))
    assert (reward == 0.0).all() and not truncated.any()
    assert np.array_equal(obs['pose'], start) and (info['time_s'] == 0.0).all()


def test_disabled_autoreset_refuses_an_ended_world_until_a_masked_reset(vector):
    env = vector(2, max_episode_s=0.05, autoreset_mode='disabled')
    obs, _ = env.reset(seed=0)
    start = obs['pose'].copy()
    for _ in range(5):
        obs, _, _, truncated, _ = env.step(np.stack([FAST, GENTLE]))
    assert truncated.all()
    moved = obs['pose'].copy()
    steps = [sim.world.step_count for sim in env.sims]
    with pytest.raises(RuntimeError, match='world 0 ended'):
        env.step(np.stack([FAST, GENTLE]))
    assert [sim.world.step_count for sim in env.sims] == steps     # no world stepped
    obs, info = env.reset(options={'reset_mask': np.array([True, False])})
    assert np.array_equal(obs['pose'][0], start[0]) and np.array_equal(obs['pose'][1], moved[1])
    assert info['_time_s'].tolist() == [True, False] and info['time_s'][0] == 0.0
    with pytest.raises(RuntimeError, match='world 1 ended'):
        env.step(np.stack([FAST, GENTLE]))
    obs, info = env.reset(options={'reset_mask': np.array([False, True])})
    obs, reward, terminated, truncated, info = env.step(np.stack([FAST, GENTLE]))
    assert info['time_s'].tolist() == pytest.approx([0.01, 0.01])
    assert not (terminated | truncated).any()


def test_same_step_autoreset_reports_the_final_observation(vector):
    env = vector(1, max_episode_s=0.05, autoreset_mode='same_step')
    obs, _ = env.reset(seed=0)
    start = obs['pose'].copy()
    for _ in range(5):
        obs, reward, terminated, truncated, info = env.step(FAST[None])
    assert truncated[0] and info['_final_obs'][0]
    assert np.array_equal(obs['pose'], start)
    assert info['final_obs'][0]['pose'][0] > start[0][0]
    # the final info is the ended step's info dict, as a lone env gives it; the step's own
    # info columns are the reset's
    final = info['final_info'][0]
    assert final['time_s'] == pytest.approx(0.05) and info['time_s'][0] == 0.0
    assert final['reward_default'] == pytest.approx(sum(final['reward_terms'].values()))
    lone = DriveEnv(max_episode_s=0.05)
    try:
        lone.reset(seed=0)
        for _ in range(5):
            *_, lone_info = lone.step(FAST)
        assert final == lone_info
    finally:
        lone.close()


def test_it_is_a_gymnasium_vector_env_made_by_the_vector_entry_point():
    env = gymnasium.make_vec('vehicle_sim/Drive-v0', num_envs=3,
                             vectorization_mode='vector_entry_point', world='default')
    try:
        assert isinstance(env.unwrapped, DriveVectorEnv)
        assert isinstance(env.unwrapped, gymnasium.vector.VectorEnv)
        obs, info = env.reset(seed=5)
        assert obs['pose'].shape == (3, 3) and env.action_space.shape == (3, 2)
        assert env.metadata['autoreset_mode'] == AutoresetMode.NEXT_STEP
        obs, reward, terminated, truncated, info = env.step(env.action_space.sample())
        assert reward.shape == (3,) and info['reward_terms']['progress'].shape == (3,)
        assert env.observation_space.contains(obs)
    finally:
        env.close()


def test_bad_arguments_are_refused(vector):
    with pytest.raises(ValueError, match='num_envs = 0'):
        DriveVectorEnv(0)
    with pytest.raises(ValueError, match="render_mode = 'human'"):
        DriveVectorEnv(1, render_mode='human')
    env = vector(2)
    env.reset(seed=0)
    with pytest.raises(ValueError, match=r'shape \(2,\)'):
        env.step(FAST)


def test_a_bad_action_for_one_world_moves_no_world(vector):
    # Every world's action is checked before any world is commanded or stepped.
    env = vector(3)
    env.reset(seed=0)
    before = env.step(np.stack([GENTLE] * 3))[0]
    times = [sim.world.time_s for sim in env.sims]
    bad = np.stack([GENTLE, np.array([0.0, np.nan], dtype=np.float32), GENTLE])
    with pytest.raises(ValueError, match=r'action\[1\] \(speed\) = nan'):
        env.step(bad)
    assert [sim.world.time_s for sim in env.sims] == times
    after = env.step(np.stack([GENTLE] * 3))[0]
    lone = DriveVectorEnv(3)
    try:
        lone.reset(seed=0)
        lone.step(np.stack([GENTLE] * 3))
        expected = lone.step(np.stack([GENTLE] * 3))[0]
    finally:
        lone.close()
    for key in before:
        assert after[key].tobytes() == expected[key].tobytes(), key


def test_worlds_give_the_same_results_whichever_way_round_a_step_walks_them(vector):
    # The phases of a step walk the worlds forwards and backwards by turns (for the cache):
    # world i's results are those of a lone environment, step after step.
    env = vector(3)
    lones = [DriveEnv() for _ in range(3)]
    try:
        obs, _ = env.reset(seed=[5, 6, 7])
        alone = [lone.reset(seed=5 + i)[0] for i, lone in enumerate(lones)]
        for i, one in enumerate(alone):
            assert obs['pose'][i].tobytes() == one['pose'].tobytes()
        actions = [GENTLE, FAST, np.array([-0.1, 4.0], dtype=np.float32)]
        for _ in range(6):
            obs, reward, *_ = env.step(np.stack(actions))
            for i, lone in enumerate(lones):
                one, lone_reward, *_ = lone.step(actions[i])
                assert obs['pose'][i].tobytes() == one['pose'].tobytes()
                assert reward[i] == lone_reward
    finally:
        for lone in lones:
            lone.close()


@pytest.mark.parametrize('where, shown', [
    ({'world': 'obstacle_course'}, 'collision=True'),           # a crash
    ({'world': 'highway'}, 'lane_crossings=1'),                 # lane keys, a crossing
    ({'scenario': str(SCENARIOS / 'highway_stay_in_lane.yaml')}, 'ended=True'),  # criteria
])
def test_step_infos_are_what_gymnasium_makes_of_each_world_s_info(vector, where, shown):
    # Gymnasium's own VectorEnv._add_info stacks lone environments' infos (as SyncVectorEnv
    # does, the lone ones reset as next_step autoreset does): the native vector env's table
    # must give the same keys, nesting, masks and values, and a reward_fn the same info dicts.
    def reward_fn(obs, action, info):
        return info['progress_m'] + 10.0 * len(info) + sum(info['reward_terms'].values())

    env = vector(3, reward_fn=reward_fn, action_repeat=10, **where)
    lones = [DriveEnv(reward_fn=reward_fn, action_repeat=10, **where) for _ in range(3)]
    actions = np.stack([FAST, GENTLE, np.array([-0.3, 5.0], dtype=np.float32)])
    seen = set()
    try:
        env.reset(seed=[1, 2, 3])
        for i, lone in enumerate(lones):
            lone.reset(seed=i + 1)
        ended = [False] * 3
        stacker = gymnasium.vector.VectorEnv()
        stacker.num_envs = 3
        for _ in range(45):
            _, rewards, terminated, truncated, info = env.step(actions)
            expected, expected_rewards = {}, []
            for i, lone in enumerate(lones):
                if ended[i]:
                    (_, lone_info), reward, ended[i] = lone.reset(), 0.0, False
                else:
                    _, reward, term, trunc, lone_info = lone.step(actions[i])
                    ended[i] = term or trunc
                expected = stacker._add_info(expected, lone_info, i)
                expected_rewards.append(reward)

            def same(ours, theirs):
                assert list(ours) == list(theirs)
                for key, value in theirs.items():
                    if isinstance(value, dict):
                        same(ours[key], value)
                    else:
                        assert np.array_equal(ours[key], value), key
            same(info, expected)
            assert rewards.tolist() == expected_rewards
            assert (terminated | truncated).tolist() == [bool(t) for t in ended]
            seen.update(f'{key}={value}' for key in ('collision', 'lane_crossings')
                        if key in info for value in info[key])
            seen.update(f'ended={value}' for value in ended)
        assert shown in seen, seen
    finally:
        for lone in lones:
            lone.close()
