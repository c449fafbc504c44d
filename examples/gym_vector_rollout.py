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
Many worlds in one process: DriveVectorEnv steps N independent worlds in one call.

Run: ``.venv/bin/python examples/gym_vector_rollout.py [--worlds 16] [--steps 2000]``. Each
world drives its car with a steering that differs per world; worlds that crash are reset by the
next step (Gymnasium's next-step autoreset). Prints the episodes that ended and the throughput.
Also made by ``gymnasium.make_vec('vehicle_sim/Drive-v0', num_envs=N,
vectorization_mode='vector_entry_point')``.
"""

import argparse
import time

import numpy as np

from vehicle_sim.gym import DriveVectorEnv


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--worlds', type=int, default=16)
    parser.add_argument('--steps', type=int, default=2000)
    args = parser.parse_args(argv)
    start = time.perf_counter()
    env = DriveVectorEnv(args.worlds, world='obstacle_course', goal=[30.0, 0.0])
    made_s = time.perf_counter() - start
    obs, info = env.reset(seed=0)
    steering = np.linspace(-0.3, 0.3, args.worlds, dtype=np.float32)
    actions = np.stack([steering, np.full(args.worlds, 8.0, dtype=np.float32)], axis=1)
    returns = np.zeros(args.worlds)
    ended = {'collision': 0, 'goal': 0, 'time limit': 0}
    start = time.perf_counter()
    for _ in range(args.steps):
        obs, reward, terminated, truncated, info = env.step(actions)
        returns += reward
        for i in np.flatnonzero(terminated | truncated):
            why = ('collision' if info['collision'][i] else
                   'goal' if info['goal_reached'][i] else 'time limit')
            ended[why] += 1
            print(f'world {i:2d} (steering {steering[i]:+.2f} rad): return '
                  f'{returns[i]:7.2f}, {why}')
            returns[i] = 0.0
    elapsed = time.perf_counter() - start
    env.close()
    print(f'{args.worlds} worlds made in {made_s:.2f} s ({made_s / args.worlds * 1000:.0f} ms '
          f'each); {args.steps * args.worlds / elapsed:.0f} world steps/s; episodes ended: '
          + ', '.join(f'{k} {v}' for k, v in ended.items()))


if __name__ == '__main__':
    main()
