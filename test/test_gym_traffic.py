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
The Gymnasium environment in worlds with traffic: every reset starts the traffic afresh.

Each shipped world with builtin ``traffic:`` (config/worlds) is reset 500 times, unseeded after the
first, with random actions stepped between the resets (the traffic moves): no reset raises,
the traffic starts afresh, none of ours starts inside anything and no traffic vehicle inside
another, in a lone environment and in the vector environment. The reported run (action_repeat
100, the ego crashing into traffic) resets after every crash. The same seed gives the same
traffic after other episodes as in a new environment; a reset that raises leaves no episode
running, and the next one works.
"""

import math

import numpy as np
import pytest

gymnasium = pytest.importorskip('gymnasium', reason="needs the 'gym' extra (gymnasium)")

from vehicle_sim.config import read_yaml  # noqa: E402
from vehicle_sim.gym import DriveVectorEnv  # noqa: E402

ROOT = __import__('pathlib').Path(__file__).resolve().parents[1]
# the worlds of the builtin engine (whose manager this test reads); SUMO's reset is
# test_physics_sumo_traffic.py's
TRAFFIC_WORLDS = sorted(path.stem for path in (ROOT / 'config' / 'worlds').glob('*.yaml')
                        if (read_yaml(path) or {}).get('traffic', {'engine': 'sumo'}).get(
                            'engine', 'builtin') == 'builtin')
RESETS = 500
STEPS = 3               # env steps between two resets (at most), ACTION_REPEAT basic steps each
ACTION_REPEAT = 10      # 0.1 s: one traffic update per env step
EPISODES = 5            # of the reported run


def _corners(x, y, yaw, length, width):
    c, s = math.cos(yaw), math.sin(yaw)
    return [(x + c * u - s * v, y + s * u + c * v)
            for u, v in ((-length / 2, -width / 2), (length / 2, -width / 2),
                         (length / 2, width / 2), (-length / 2, width / 2))]


def _overlap(a, b):
    # separating axes of two convex polygons (touching counts as apart)
    for polygon in (a, b):
        for (x0, y0), (x1, y1) in zip(polygon, polygon[1:] + polygon[:1]):
            nx, ny = y1 - y0, x0 - x1
            pa = [nx * x + ny * y for x, y in a]
            pb = [nx * x + ny * y for x, y in b]
            if max(pa) <= min(pb) or max(pb) <= min(pa):
                return False
    return True


def _traffic_inside_another(sim):
    """Return the pairs of traffic vehicles whose footprints overlap (manager poses)."""
    manager = sim.scene.parts['traffic'].manager
    boxes = [(v.name, _corners(*manager.pose(v), v.length_m, v.width_m))
             for v in manager.vehicles if v.active]
    centres = np.array([np.mean(corners, axis=0) for _, corners in boxes])
    found = []
    for i, j in zip(*np.nonzero(np.triu(
            np.hypot(*(centres[:, None] - centres[None]).transpose(2, 0, 1)) < 8.0, 1))):
        if _overlap(boxes[i][1], boxes[j][1]):
            found.append((boxes[i][0], boxes[j][0]))
    return found


def _check_start(sim, where):
    # the traffic started afresh (none stopped, not stepped yet); none of our vehicles starts
    # inside anything (Bullet's own overlap test), the traffic included; no traffic vehicle
    # inside another
    manager = sim.scene.parts['traffic'].manager
    assert manager.steps == 0 and not any(v.stopped for v in manager.vehicles), where
    for name, vehicle in sim.scene.vehicles.items():
        inside = sim.world.overlaps(vehicle.body.body_id)
        assert inside == [], f'{where}: {name!r} starts inside {inside}'
    assert _traffic_inside_another(sim) == [], where


def test_the_traffic_worlds_are_found():
    assert 'highway_traffic' in TRAFFIC_WORLDS


def _places(sim):
    manager = sim.scene.parts['traffic'].manager
    return tuple((v.lane, v.s_m) for v in manager.vehicles)


@pytest.mark.parametrize('world', TRAFFIC_WORLDS)
def test_unseeded_resets_between_random_steps_always_start_clear_of_the_traffic(world):
    env = gymnasium.make('vehicle_sim/Drive-v0', world=world, action_repeat=ACTION_REPEAT)
    sim = env.unwrapped.sim
    env.action_space.seed(0)
    starts = set()
    try:
        env.reset(seed=0)
        for k in range(RESETS):
            start = _places(sim)
            for _ in range(STEPS):
                _, _, terminated, truncated, _ = env.step(env.action_space.sample())
                if terminated or truncated:
                    break
            assert _places(sim) != start        # the traffic moved in the episode
            env.reset()                         # unseeded: the generator goes on
            _check_start(sim, f'reset {k + 1}')
            starts.add(_places(sim))
    finally:
        env.close()
    assert len(starts) == RESETS    # each reset drew the traffic afresh


@pytest.mark.parametrize('world', TRAFFIC_WORLDS)
def test_the_vector_env_resets_its_traffic_worlds_clear_of_the_traffic(world):
    env = DriveVectorEnv(2, world=world, action_repeat=ACTION_REPEAT)
    env.action_space.seed(0)
    starts = set()
    try:
        env.reset(seed=0)
        for k in range(RESETS // 2):      # two worlds: RESETS world resets
            for _ in range(STEPS):
                env.step(env.action_space.sample())
            env.reset()
            for i, sim in enumerate(env.sims):
                _check_start(sim, f'reset {k + 1}, world {i}')
                starts.add(_places(sim))
    finally:
        env.close()
    assert len(starts) == RESETS


def test_the_reported_run_resets_after_every_crash_into_traffic(make):
    # The report: action_repeat 100, random actions, a reset after each episode. The ego is
    # hit by traffic, which stops for good where it hit; the next reset used to put the ego
    # back inside it (InvalidPoseError), and every reset after.
    env = make(world='highway_traffic', action_repeat=100, max_episode_s=10.0)
    sim = env.unwrapped.sim
    env.action_space.seed(0)
    env.reset(seed=0)
    crashes = 0
    for episode in range(EPISODES):
        for _ in range(10):
            _, _, terminated, truncated, info = env.step(env.action_space.sample())
            if terminated or truncated:
                break
        crashes += info['collided_with'].startswith('traffic_')
        env.reset()
        assert sim.world.overlaps(sim.ego.body.body_id) == [], episode
    assert crashes >= 2


def _episode(env, seed, actions):
    # the observations, rewards, ends, infos and every traffic vehicle's lane and s
    sim = env.unwrapped.sim
    obs, info = env.reset(seed=seed)
    out = [obs, info, _places(sim)]
    for action in actions:
        obs, reward, terminated, truncated, info = env.step(action)
        out.append((obs, reward, terminated, truncated, info, _places(sim)))
        if terminated or truncated:
            break
    return out


def _same(a, b):
    if isinstance(a, dict):
        return a.keys() == b.keys() and all(_same(a[k], b[k]) for k in a)
    if isinstance(a, (list, tuple)):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b))
    if isinstance(a, np.ndarray):
        return a.dtype == b.dtype and np.array_equal(a, b)
    return a == b


def test_a_seed_gives_the_same_traffic_episode_after_other_episodes_and_in_a_new_env(make):
    # The traffic starts from the seeded generator and updates on its period from the reset:
    # after steps that end between two updates (7 basic steps each, the traffic's period 10),
    # the same seed and actions give the same episode, bit for bit, as in a new environment.
    kwargs = {'world': 'highway_traffic', 'action_repeat': 7}
    used = make(**kwargs)
    used.action_space.seed(3)
    actions = [used.action_space.sample() for _ in range(30)]
    used.reset(seed=0)
    for action in actions[:11]:
        used.step(action)                  # 77 basic steps
    assert used.unwrapped.sim.world.step_count % 10 != 0
    first = _episode(make(**kwargs), 5, actions)
    assert len(first) > 5
    assert _same(_episode(used, 5, actions), first)
    assert _episode(used, 6, actions)[2] != first[2]    # another seed, other traffic


def test_a_reset_that_raises_leaves_no_episode_and_the_next_reset_works(make, monkeypatch):
    env = make(world='highway_traffic', action_repeat=ACTION_REPEAT)
    sim = env.unwrapped.sim
    env.reset(seed=0)
    for _ in range(5):
        env.step(env.action_space.sample())
    body = sim.ego.body
    rebuild = body.rebuild

    def fails(position):
        monkeypatch.setattr(body, 'rebuild', rebuild)       # once
        raise RuntimeError('injected')

    monkeypatch.setattr(body, 'rebuild', fails)
    with pytest.raises(RuntimeError, match='injected'):
        env.reset(seed=1)
    with pytest.raises(RuntimeError, match=r'reset\(\) first'):
        env.step(env.action_space.sample())                 # no half-reset episode runs on
    actions = [np.array([0.05, 8.0], dtype=np.float32)] * 20
    assert _same(_episode(env, 2, actions),
                 _episode(make(world='highway_traffic', action_repeat=ACTION_REPEAT), 2,
                          actions))


def test_start_noise_keeps_the_ego_clear_of_the_traffic_and_of_a_placed_vehicle(make):
    # A placed traffic vehicle 9 m ahead of the ego's spawn in its lane, the ego's start drawn
    # within 10 m along the road: a draw on the placed vehicle is drawn again, the random
    # traffic starts around the ego wherever it is.
    data = read_yaml(ROOT / 'config' / 'worlds' / 'highway_traffic.yaml')
    data['traffic']['placed'] = [{'model': 'BmwX5', 'lanelet': 100002, 's': 29.0,
                                  'speed': 0.0, 'speed_factor': 0.01}]
    env = make(world=data, action_repeat=ACTION_REPEAT, start_noise=[10.0, 1.0, 0.2])
    sim = env.unwrapped.sim
    env.reset(seed=0)
    xs = []
    for k in range(60):
        env.step(np.array([0.0, 5.0], dtype=np.float32))
        env.reset()
        _check_start(sim, f'reset {k + 1}')
        manager = sim.scene.parts['traffic'].manager
        assert manager.pose(manager.vehicles[0])[0] == pytest.approx(29.0)    # placed: there
        xs.append(sim.observe()['pose'][0])
    # drawn over 10 .. 30 m; from about 22 m on the ego's front would be within 1 m of the
    # placed vehicle's back (26.6 m): drawn again
    assert min(xs) < 12.0 and 20.0 < max(xs) < 22.5
