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
A seeded episode with traffic gives the trajectory recorded before the step was made faster.

The configuration of bench_gym's equal work (highway_traffic, 20 traffic vehicles updated at
5 Hz, 10 ms steps, full physics) at 5 Hz decisions, with random steering that drives the ego
into a traffic vehicle (traffic_4, which then stops for good: the contact reads of the collision
monitor and the traffic): every observation, reward and traffic pose of 60 env steps, hashed,
equals the digest the code gave before the per-step work was cut (the speed-ups change no
result). Bullet's results are bit-exact on one build and platform only: the digest is checked
with the pybullet release and processor it was recorded with, the events everywhere. numpy's
vector math (sin, cos, exp, ...) rounds the last bit differently in its AVX-512 paths than in
its AVX2 ones, which it picks at run time by the processor (seen: a Sapphire Rapids machine gave
another digest until they were off); the digest was recorded with the AVX2 paths, so the trace
runs in a child process with numpy's AVX-512 dispatch turned off (numpy's
``NPY_DISABLE_CPU_FEATURES``, read when numpy loads).
"""

import hashlib
import json
import os
import platform
import struct
import subprocess
import sys

import numpy as np
import pytest

gymnasium = pytest.importorskip('gymnasium', reason="needs the 'gym' extra (gymnasium)")

from vehicle_sim.config import read_yaml, world_path  # noqa: E402
import vehicle_sim.gym  # noqa: E402, F401

STEPS = 60
# recorded with pybullet 3.2.7 on x86_64 from the code before the speed-ups
RECORDED = 'fb202f5c8bbe4cc4b85205025ae2593cab7d4a11b92a515d8894c6bae0722187'
RECORDED_ON = ('3.2.7', 'x86_64')
CRASH_STEP = 34         # the env step in which the ego hits traffic_4


def _pybullet_version():
    from importlib.metadata import version
    return version('pybullet')


def _trace():
    # -> (sha256 of the episode, [(env step, collided with, stopped traffic indices)])
    world = read_yaml(world_path('highway_traffic'))
    world['traffic']['vehicles'] = 20
    world['traffic']['update_period'] = 0.2
    env = gymnasium.make('vehicle_sim/Drive-v0', world=world, max_speed=33.3, action_repeat=20,
                         terminate_on_collision=False)
    try:
        traffic = env.unwrapped.sim.scene.parts['traffic']
        rng = np.random.default_rng(3)
        digest = hashlib.sha256()
        events = []
        env.reset(seed=5)
        for index in range(STEPS):
            action = np.array([rng.uniform(-0.3, 0.3), rng.uniform(15.0, 33.0)],
                              dtype=np.float32)
            obs, reward, terminated, truncated, info = env.step(action)
            for key in sorted(obs):
                digest.update(np.ascontiguousarray(obs[key]).tobytes())
            digest.update(struct.pack('<d', reward))
            for agent in traffic.agents():
                digest.update(repr(agent).encode())
            stopped = [v.index for v in traffic.manager.vehicles if v.stopped]
            if info['collision'] or stopped:
                events.append((index, info['collided_with'], stopped))
            if terminated or truncated:
                env.reset()
        return digest.hexdigest(), events
    finally:
        env.close()


def _avx512_features():
    # numpy's run-time dispatched features this processor has beyond AVX2 (names of numpy 2.4:
    # X86_V4, AVX512_*; earlier releases: AVX512F, AVX512_SKX, ...)
    from numpy._core._multiarray_umath import __cpu_dispatch__, __cpu_features__
    return [name for name in __cpu_dispatch__ if __cpu_features__.get(name)
            and (name.startswith('AVX512') or name == 'X86_V4')]


def _trace_in_a_child():
    env = dict(os.environ)
    disabled = _avx512_features()
    if disabled:
        env['NPY_DISABLE_CPU_FEATURES'] = ' '.join(disabled)
    else:
        env.pop('NPY_DISABLE_CPU_FEATURES', None)
    done = subprocess.run([sys.executable, __file__], env=env, capture_output=True, text=True,
                          timeout=600, check=False)
    assert done.returncode == 0, done.stderr[-3000:]
    digest, events = json.loads(done.stdout.strip().splitlines()[-1])
    return digest, [(index, name, stopped) for index, name, stopped in events]


def test_seeded_episode_with_traffic_gives_the_recorded_trajectory():
    digest, events = _trace_in_a_child()
    assert events[0] == (CRASH_STEP, 'traffic_4', [4])
    assert all(stopped == [4] for _, _, stopped in events)
    if (_pybullet_version(), platform.machine()) != RECORDED_ON:
        pytest.skip(f'the digest was recorded with pybullet {RECORDED_ON[0]} on '
                    f'{RECORDED_ON[1]}: the events were checked')
    assert digest == RECORDED


if __name__ == '__main__':      # the child of _trace_in_a_child: its result as JSON
    print(json.dumps(_trace()))
