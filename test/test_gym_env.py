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
The Gymnasium environment vehicle_sim/Drive-v0.

Gymnasium's own checker, determinism, episode ends (collision, goal, scenario criteria), reward
terms, refused input, registration and Gymnasium's vector wrappers (rendering:
test_gym_render.py).
"""

import json
import warnings

import numpy as np
import pytest

gymnasium = pytest.importorskip('gymnasium', reason="needs the 'gym' extra (gymnasium)")

from gymnasium.utils.env_checker import check_env  # noqa: E402

from vehicle_sim.core.sensors.labels import LABEL_IDS  # noqa: E402
from vehicle_sim.core.specs.errors import InvalidParameterError  # noqa: E402
import vehicle_sim.gym  # noqa: E402,F401  (registers the ids)
from vehicle_sim.gym import DriveEnv  # noqa: E402

ROOT = __import__('pathlib').Path(__file__).resolve().parents[1]
ROBOT = {'robot': 'caster_robot', 'start': [0.0, 3.0, 0.0]}

CASES = {
    'car': {},
    'car_lidar': {'lidar': True},
    'car_throttle': {'control': 'throttle_steering'},
    'robot': dict(ROBOT),
    'robot_lidar': dict(ROBOT, lidar={'horizontal_resolution': 360, 'max_range': 10.0}),
}


@pytest.mark.parametrize('case', sorted(CASES))
def test_gymnasium_check_env_passes(make, case):
    env = make(**CASES[case])
    with warnings.catch_warnings():
        # advisory only: unbounded odometry entries and physical (not [-1, 1]) action units
        warnings.filterwarnings('ignore', message='.*(infinity|symmetric and normalized).*')
        check_env(env.unwrapped, skip_render_check=True)
    obs, _ = env.reset(seed=0)
    assert set(obs) == ({'pose', 'twist', 'lidar'} if 'lidar' in CASES[case]
                        else {'pose', 'twist'})


def test_the_lidar_observation_reads_the_wall_and_maps_no_return_to_max_range(make):
    env = make(lidar={'fov': 3.14159, 'horizontal_resolution': 181, 'max_range': 50.0,
                      'pose': {'x': 1.0, 'z': 1.5}})
    obs, _ = env.reset(seed=0)
    ranges = obs['lidar']
    assert ranges.shape == (181,) and ranges.dtype == np.float32
    assert ranges[90] == pytest.approx(18.5, abs=0.01)      # the wall's face at x = 19.5 m
    assert ranges[0] == pytest.approx(50.0)                 # nothing to the right: max_range
    assert env.observation_space['lidar'].contains(ranges)


def _rollout(env, seed, actions):
    obs, _ = env.reset(seed=seed)
    out = [obs]
    for action in actions:
        obs, reward, terminated, truncated, info = env.step(action)
        out.append((obs, reward, terminated, truncated))
        if terminated or truncated:
            break
    return out


def _same(a, b):
    for x, y in zip(a, b, strict=True):
        x = x if isinstance(x, tuple) else (x,)
        y = y if isinstance(y, tuple) else (y,)
        for u, v in zip(x, y, strict=True):
            if isinstance(u, dict):
                assert set(u) == set(v)
                for key in u:
                    assert u[key].tobytes() == v[key].tobytes(), key
            else:
                assert u == v


def test_one_seed_and_one_action_list_give_bit_identical_episodes(make):
    options = dict(lidar={'horizontal_resolution': 90, 'noise': 0.05}, start_noise=[0.5, 0.5, 0.1])
    rng = np.random.default_rng(7)
    actions = [np.array([rng.uniform(-0.4, 0.4), rng.uniform(0.0, 12.0)], dtype=np.float32)
               for _ in range(150)]
    env = make(**options)
    first = _rollout(env, 3, actions)
    _rollout(env, 4, actions[:40])               # another episode in between
    again = _rollout(env, 3, actions)
    fresh = _rollout(make(**options), 3, actions)
    _same(first, again)
    _same(first, fresh)
    other = _rollout(env, 5, actions)
    assert other[0]['pose'].tobytes() != first[0]['pose'].tobytes()   # the seed matters


def test_resets_load_no_body_so_a_long_run_does_not_grow(make, monkeypatch):
    # PyBullet keeps a loaded body's collision shapes until its simulation is reset: an env
    # reset that loaded the ego's URDF again grew the process by ~18 KiB (60 KiB per 1000
    # steps with a reset every 300; benchmarks/bench_gym_soak.py). With traffic, start noise
    # (a start pose drawn, maybe several times, each reset) and a lidar.
    import pybullet
    env = make(world='highway_traffic', start_noise=[2.0, 0.5, 0.1],
               lidar={'horizontal_resolution': 90})
    env.reset(seed=0)
    sim = env.unwrapped.sim
    ego = sim.ego.body.body_id
    bodies = pybullet.getNumBodies(physicsClientId=sim.world.client_id)
    loads = []
    load = pybullet.loadURDF
    monkeypatch.setattr(pybullet, 'loadURDF', lambda *a, **k: loads.append(a) or load(*a, **k))
    for episode in range(10):
        for _ in range(20):
            env.step([0.2, 10.0])
        env.reset(seed=episode)
    assert loads == []
    assert sim.ego.body.body_id == ego
    assert pybullet.getNumBodies(physicsClientId=sim.world.client_id) == bodies


def test_start_noise_never_puts_the_ego_inside_an_obstacle(make):
    # the wall's face is at x = 19.5 m and the car 4.5 m long: offsets up to 18 m reach into it
    env = make(start_noise=[18.0, 2.0, 0.2])
    sim = env.unwrapped.sim
    starts = set()
    for seed in range(30):
        obs, _ = env.reset(seed=seed)
        assert sim.world.overlaps(sim.ego.body.body_id) == []
        starts.add(round(float(obs['pose'][0]), 3))
    assert len(starts) == 30 and max(starts) > 10.0


def test_a_collision_ends_the_episode_with_its_penalty_in_the_terms(make):
    env = make()
    env.reset(seed=0)
    for _ in range(1000):
        obs, reward, terminated, truncated, info = env.step([0.0, 8.0])
        if terminated or truncated:
            break
    assert terminated and not truncated
    assert info['collision'] and info['collided_with'] == 'wall'
    assert info['reward_terms']['collision'] == -10.0
    assert reward == pytest.approx(sum(info['reward_terms'].values()))
    assert 14.0 < obs['pose'][0] < 15.5      # front bumper (4.5 m ahead) at the wall (19.5 m)


def test_reaching_the_goal_ends_the_episode_with_the_goal_reward(make):
    env = make(goal=[10.0, 0.0], goal_radius=2.0)
    obs, _ = env.reset(seed=0)
    total_progress = 0.0
    for _ in range(1000):
        obs, reward, terminated, truncated, info = env.step([0.0, 8.0])
        total_progress += info['reward_terms']['progress']
        if terminated or truncated:
            break
    assert terminated and info['goal_reached'] and info['reward_terms']['goal'] == 10.0
    assert 7.9 < obs['pose'][0] < 8.3            # entered the 2 m circle around x = 10 m
    assert total_progress == pytest.approx(10.0 - 2.0, abs=0.3)   # distance to the goal shrank


def test_the_episode_is_truncated_at_max_episode_s(make):
    env = make(max_episode_s=0.5, action_repeat=5)
    env.reset(seed=0)
    results = [env.step([0.0, 0.0]) for _ in range(10)]
    assert [r[3] for r in results] == [False] * 9 + [True]
    assert results[-1][4]['time_s'] == pytest.approx(0.5)


def test_a_path_gives_progress_along_it(make):
    env = make(path=[[0.0, 0.0], [5.0, 0.0], [5.0, 10.0]], world='default')
    env.reset(seed=0)
    progress = sum(env.step([0.0, 5.0])[4]['progress_m'] for _ in range(100))
    x = env.unwrapped.sim.ego.body.pose()[0]
    assert progress == pytest.approx(min(x, 5.0), abs=1e-6)


def test_a_scenario_gives_the_ego_its_criteria_and_ends_on_them(make):
    env = make(scenario=str(ROOT / 'scenarios' / 'drive_into_obstacle.yaml'))
    obs, info = env.reset(seed=0)
    assert set(info['criteria']) == {'no_collision', 'reach_goal', 'max_speed'}
    for _ in range(2000):
        obs, reward, terminated, truncated, info = env.step([0.0, 5.0])
        if terminated or truncated:
            break
    # every reach_goal criterion passed: the goal circle (12, 0) r = 3 m is entered at x = 9 m
    assert terminated and info['criteria']['reach_goal'] == 'passed'
    assert info['goal_reached'] and 8.9 < obs['pose'][0] < 9.2
    assert info['criteria']['no_collision'] == 'undecided'


def test_a_scenario_criterion_that_fails_ends_the_episode(make):
    env = make(scenario=str(ROOT / 'scenarios' / 'drive_into_obstacle.yaml'))
    env.reset(seed=0)
    for _ in range(2000):
        obs, reward, terminated, truncated, info = env.step([0.0, 7.0])    # limit 6 m/s
        if terminated or truncated:
            break
    assert terminated and info['criteria']['max_speed'] == 'failed'
    assert not info['goal_reached']


def test_a_robot_scenario_gives_its_robot_as_ego_and_leaves_out_topic_criteria(make):
    with pytest.warns(UserWarning, match=r"criteria 'topic' \(topic\) read ROS messages"):
        env = make(scenario=str(ROOT / 'scenarios' / 'bridge_s_curve.yaml'))
    obs, info = env.reset(seed=0)
    assert env.unwrapped.sim.ego_name == 'diff_robot'
    assert set(info['criteria']) == {'stay_on_path', 'reach_goal', 'max_speed'}
    assert env.action_space.shape == (2,)            # twist
    for _ in range(1000):
        obs, reward, terminated, truncated, info = env.step([0.9, 0.0])
        if terminated:
            break
    # straight on: the S-curve path turns left after 1.3 m, so stay_on_path (0.15 m) fails
    assert terminated and info['criteria']['stay_on_path'] == 'failed'
    assert 1.3 < obs['pose'][0] < 3.0


def test_a_user_reward_replaces_the_default_and_sees_the_terms(make):
    seen = []

    def reward(obs, action, info):
        seen.append(info['reward_terms']['progress'])
        return float(obs['twist'][0])

    env = make(reward_fn=reward)
    env.reset(seed=0)
    obs, value, *_ = env.step([0.0, 5.0])
    assert value == float(obs['twist'][0]) and len(seen) == 1


def test_an_action_outside_the_space_is_refused_naming_the_entry(make):
    env = make()
    env.reset(seed=0)
    before = env.unwrapped.sim.world.step_count
    with pytest.raises(ValueError, match=r'action\[1\] \(speed\) = 25.0 m/s: outside'):
        env.step([0.0, 25.0])
    with pytest.raises(ValueError, match=r'action\[0\] \(steering_angle\) = nan'):
        env.step([float('nan'), 1.0])
    with pytest.raises(ValueError, match=r'shape \(3,\)'):
        env.step([0.0, 1.0, 2.0])
    assert env.unwrapped.sim.world.step_count == before       # nothing stepped
    # float rounding at a bound (RescaleAction's -1 gives -5.0000002 m/s) is the bound
    rescaled = gymnasium.wrappers.RescaleAction(env, -1.0, 1.0)
    rescaled.step(np.array([-1.0, -1.0], dtype=np.float32))
    assert env.unwrapped.sim.world.step_count == before + 1


@pytest.mark.parametrize('kwargs, message', [
    ({'action_repeat': 0}, "option 'action_repeat' = 0: must be in 1 .. 10000"),
    ({'colour': 'red'}, "unknown option 'colour'"),
    ({'control': 'twist'}, "control 'twist' does not fit the ego 'Car', a car; valid: "
                           'speed_steering, braking_speed_steering, guarded_speed_steering, '
                           'lane_speed, throttle_steering'),
    (dict(ROBOT, control='speed_steering'), 'does not fit the ego .ego., a robot'),
    ({'vehicle': 'Bus'}, "option 'vehicle' = 'Bus': no such vehicle in the world; vehicles: "
                         'Car'),
    ({'lidar': 'front'}, "option 'lidar' = 'front': the ego 'Car' has no lidar of that name; "
                         'its lidars: lidar'),
    ({'lidar': {'max_range': -1.0}}, "option 'lidar'.*max_range"),
    ({'world': 'no_such_world'}, 'no_such_world'),
])
def test_bad_options_are_refused_before_anything_is_built(kwargs, message):
    with pytest.raises((InvalidParameterError, ValueError), match=message):
        DriveEnv(**kwargs)


def test_step_before_reset_is_refused():
    env = DriveEnv()
    try:
        with pytest.raises(RuntimeError, match='reset'):
            env.unwrapped.sim.step([0.0, 0.0])
    finally:
        env.close()


def test_the_id_resolves_through_the_module_prefix_and_the_entry_point_is_declared():
    env = gymnasium.make('vehicle_sim.gym:vehicle_sim/Drive-v0', world='default')
    try:
        assert isinstance(env.unwrapped, DriveEnv)
    finally:
        env.close()
    setup = (ROOT / 'setup.py').read_text()
    assert "'gymnasium.envs': ['vehicle_sim = vehicle_sim.gym.registration:register_envs']" \
        in setup


def test_gymnasium_sync_and_async_vector_envs_run_it(make):
    def factory():
        return gymnasium.make('vehicle_sim/Drive-v0', world='default')

    for vector in (gymnasium.vector.SyncVectorEnv([factory] * 2),
                   gymnasium.vector.AsyncVectorEnv([factory] * 2)):
        try:
            obs, _ = vector.reset(seed=1)
            assert obs['pose'].shape == (2, 3)
            for _ in range(5):
                obs, reward, terminated, truncated, info = vector.step(
                    np.array([[0.0, 3.0], [0.0, 0.0]], dtype=np.float32))
            assert obs['twist'][0][0] > obs['twist'][1][0] >= -1e-3
        finally:
            vector.close()


def test_the_docs_show_the_options_table():
    from vehicle_sim.gym.options import options_markdown
    assert options_markdown() in (ROOT / 'docs' / 'gym.md').read_text()


def test_registering_again_or_inside_a_plugin_namespace_keeps_one_id():
    from gymnasium.envs.registration import namespace, registry

    from vehicle_sim.gym.registration import register_envs
    before = dict(registry)
    with warnings.catch_warnings():
        warnings.simplefilter('error')         # gymnasium warns when an id is overridden
        register_envs()
        with namespace('vehicle_sim'):          # how plugin-loading Gymnasium releases call it
            register_envs()
    assert dict(registry) == before and 'vehicle_sim/Drive-v0' in registry
    spec = registry.pop('vehicle_sim/Drive-v0')
    try:
        with namespace('vehicle_sim'):
            register_envs()
        assert registry['vehicle_sim/Drive-v0'].entry_point == spec.entry_point
    finally:
        registry['vehicle_sim/Drive-v0'] = spec


@pytest.mark.parametrize('speed_control, hits', [(None, False), ('waypoints', True)])
def test_a_scenario_actor_keeps_its_idm_gap_to_the_standing_ego_unless_told_otherwise(
        make, tmp_path, speed_control, hits):
    # the actor drives at 8 m/s towards the standing ego 40 m ahead: IDM (the default) stops it
    # behind the ego, the waypoints' speed drives it into the ego
    actor = {'vehicle': 'other', 'speed': 8.0, 'waypoints': [[120.0, 0.0]]}
    if speed_control is not None:
        actor['speed_control'] = speed_control
    text = (
        'world:\n  vehicles:\n'
        '    - {name: ego, model: Car, pose: {x: 40.0, y: 0.0, yaw: 0.0}}\n'
        '    - {name: other, namespace: other, model: ToyotaPrius, '
        'pose: {x: 0.0, y: 0.0, yaw: 0.0}}\n'
        f'actors: [{json.dumps(actor)}]\n'
        'duration: 12.0\n'
        'driver: {commands: [{t: 0.0, cruising_speed: 0.0}]}\n'
        'criteria: [{kind: no_collision}]\n')
    path = tmp_path / 'actor_behind.yaml'
    path.write_text(text, encoding='utf-8')
    env = make(scenario=str(path))
    env.reset(seed=0)
    for _ in range(3000):
        obs, reward, terminated, truncated, info = env.step([0.0, 0.0])
        if terminated or truncated:
            break
    assert info['collision'] is hits
    assert (info['collided_with'] == 'other') is hits
    assert truncated is not hits and info['time_s'] > (5.0 if hits else 11.9)


def test_a_segmenting_camera_gives_the_semantic_observation(make):
    env = make(camera={'width': 32, 'height': 24, 'pose': {'x': 1.5, 'z': 1.3},
                       'segmentation': True})
    obs, _ = env.reset(seed=0)
    semantic = obs['semantic']
    assert semantic.shape == (24, 32) and semantic.dtype == np.uint8
    assert env.observation_space['semantic'].contains(semantic)
    # obstacle_course: the wall ahead at the centre (an obstacle), the sky above, the ground
    # below
    assert semantic[0, 16] == LABEL_IDS['none']
    assert semantic[-1, 16] == LABEL_IDS['ground']
    assert semantic[12, 16] in (LABEL_IDS['obstacle'], LABEL_IDS['wall'])
    assert 'semantic' not in make(camera=True).reset(seed=0)[0]


def _mean_speed_scenario(tmp_path, min_mps):
    path = tmp_path / 'mean_speed.yaml'
    path.write_text('name: mean_speed\nworld: default\nduration: 2.0\n'
                    'driver:\n  commands: [{t: 0.0, cruising_speed: 0.0}]\n'
                    f'criteria:\n  - kind: mean_speed\n    min: {min_mps}\n', encoding='utf-8')
    return str(path)


@pytest.mark.parametrize('min_mps, verdict', [(0.5, 'passed'), (50.0, 'failed')])
def test_a_criterion_judged_at_the_end_has_its_verdict_in_the_last_info(make, tmp_path,
                                                                       min_mps, verdict):
    # mean_speed is decided only when the scenario's time is up: the truncating step's info
    # gives its verdict (not 'undecided'), so that an evaluation reads the outcome from info
    env = make(scenario=_mean_speed_scenario(tmp_path, min_mps), action_repeat=10)
    _, info = env.reset(seed=0)
    assert info['criteria'] == {'mean_speed': 'undecided'}
    for _ in range(100):
        _, _, terminated, truncated, info = env.step([0.0, 5.0])
        if terminated or truncated:
            break
    assert truncated and not terminated and info['time_s'] == pytest.approx(2.0)
    assert info['criteria'] == {'mean_speed': verdict}
    result = env.unwrapped.sim.criteria_results()['mean_speed']     # the measured value too
    assert result.passed == (verdict == 'passed') and 0.5 < result.value < 5.0


def test_braking_speed_steering_brakes_for_a_speed_well_below_the_cars_and_cruises_else(make):
    from vehicle_sim.core.car.drivetrain import ControlMode, SPEED_100_KMH_MPS
    from vehicle_sim.core.specs.units import mps_to_kmh
    options = dict(world='highway', max_speed=20.0, max_steering=0.02, action_repeat=10)
    env = make(control='braking_speed_steering', **options)
    plain = make(control='speed_steering', **options)
    assert env.action_space == plain.action_space       # the entries and bounds of speed_steering
    assert list(env.action_space.high) == pytest.approx([0.02, 20.0])
    obs, _ = env.reset(seed=0)
    logic = env.unwrapped.sim.control.logic
    while obs['twist'][0] < 14.0:                       # cruising up: never braking
        obs, *_ = env.step([0.0, 15.0])
        assert logic.control_mode == ControlMode.SPEED and logic.brake_intensity == 0.0
        assert env.unwrapped.sim.elapsed_s < 20.0
    # 2.5 m/s slower than the car: throttle released, half the brake
    speed = float(obs['twist'][0])
    obs, *_ = env.step([0.0, speed - 2.5])
    assert logic.control_mode == ControlMode.TORQUE and logic.throttle == 0.0
    assert logic.brake_intensity == pytest.approx(0.5, abs=1e-5)
    assert logic.target_cruising_speed_kmh == pytest.approx(mps_to_kmh(15.0))    # untouched
    # speed 0: full brake, faster than the cruise control's ramp (time0To100) slows the car
    before = float(obs['twist'][0])
    for _ in range(10):                                 # 1 s
        obs, *_ = env.step([0.0, 0.0])
        assert logic.brake_intensity == 1.0
    ramp_mps2 = SPEED_100_KMH_MPS / logic.params.time_0_to_100_s
    assert before - float(obs['twist'][0]) > 1.5 * ramp_mps2
    # within 1 m/s of the car's speed: the brake released, cruise control takes the speed
    speed = float(obs['twist'][0])
    env.step([0.0, speed - 0.9])
    assert logic.control_mode == ControlMode.SPEED and logic.brake_intensity == 0.0
    assert logic.target_cruising_speed_kmh == pytest.approx(mps_to_kmh(speed - 0.9))
    # outside the Box: refused naming the entry, nothing stepped or commanded
    steps = env.unwrapped.sim.world.step_count
    with pytest.raises(ValueError, match=r'action\[1\] \(speed\) = 25.0 m/s: outside '
                                         r'\[-5, 20\]'):
        env.step([0.0, 25.0])
    with pytest.raises(ValueError, match=r'action\[1\] \(speed\) = nan'):
        env.step([0.0, float('nan')])
    assert env.unwrapped.sim.world.step_count == steps
    assert logic.target_cruising_speed_kmh == pytest.approx(mps_to_kmh(speed - 0.9))


def test_max_steering_narrows_the_steering_actions_and_refuses_more_than_the_car_has(make):
    env = make(max_steering=0.05)
    assert env.action_space.low[0] == pytest.approx(-0.05)
    assert env.action_space.high[0] == pytest.approx(0.05)
    env.reset(seed=0)
    with pytest.raises(ValueError, match=r'action\[0\] \(steering_angle\) = 0.06'):
        env.step([0.06, 1.0])
    throttle = make(max_steering=0.05, control='throttle_steering')
    assert list(throttle.action_space.low[:1]) == pytest.approx([-0.05])
    wide = make()
    limit = float(min(-wide.action_space.low[0], wide.action_space.high[0]))
    with pytest.raises(InvalidParameterError, match=rf'max_steering = 2.0 rad: more than the '
                       rf"car's steering limit \({limit:g} rad\)"):
        make(max_steering=2.0)
    with pytest.raises(InvalidParameterError, match=r'max_steering = 0.1 rad: .* is a robot'):
        make(max_steering=0.1, **ROBOT)
