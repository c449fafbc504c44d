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
Drive-v0's lane_speed action on the physics car: a lane change and lane keeping on the motorway.

The car (the Prius of config/worlds/highway.yaml, 3.75 m lanes, 1 500 m arcs) accelerates in its
lane at offset 0, asks for one lane to the left until it is over the dashed line, then for 0: it
ends in the left neighbour's centre, having crossed no solid line and never left a lane, and on
the arcs stays within the law's documented curve offset. A world without lanes refuses the
action.
"""

import gymnasium as gym
import numpy as np
import pytest

from vehicle_sim.core.car import lane_keeping as lk
from vehicle_sim.core.specs.errors import InvalidParameterError
import vehicle_sim.gym  # noqa: F401  (registers Drive-v0)

LIMIT = 33.3
LANE_M = 3.75


def _env(world):
    return gym.make('vehicle_sim/Drive-v0', world=world, control='lane_speed', max_steering=0.02,
                    max_speed=LIMIT, action_repeat=20, max_episode_s=80.0)


def test_a_lane_change_to_the_left_and_lane_keeping_on_the_arcs():
    env = _env('highway')
    try:
        assert np.array_equal(env.action_space.low, np.float32((-4.0, 0.0)))
        assert np.array_equal(env.action_space.high, np.float32((4.0, LIMIT)))
        obs, _ = env.reset(seed=1)
        graph = env.unwrapped.sim.scene.lanes
        start = int(obs['lane_id'][0])
        left = graph.lane(start).left_lane
        assert left is not None and graph.lane(start).left_change
        phase, previous, crossed_at, rows = 'keep', 0.0, None, []
        for k in range(350):          # 70 s: the 2.3 km road ends at about 75 s
            t = 0.2 * k
            offset = float(obs['lane'][1])
            if phase == 'keep' and t >= 16.0:
                phase = 'change'
            elif phase == 'change' and previous > 1.0 and offset < -1.0:
                phase, crossed_at = 'stay', t          # over the line: the left lane's state
            previous = offset
            target = LANE_M if phase == 'change' else 0.0
            obs, _, terminated, truncated, info = env.step(np.float32((target, LIMIT)))
            assert not terminated, info
            assert not truncated
            rows.append((t + 0.2, int(obs['lane_id'][0]), float(obs['lane'][1]),
                         float(obs['twist'][0])))
        # over the dashed line within 2 s of asking at the limit
        assert crossed_at is not None and crossed_at - 16.0 < 2.0
        assert rows[-1][3] == pytest.approx(LIMIT, abs=0.2)
        # in the left neighbour's lanes from then on (the road's later lanes continue it)
        after = [row for row in rows if row[0] > crossed_at + 0.2]
        assert graph.lane(after[0][1]).id == left
        assert all(lane_id != 0 for _, lane_id, _, _ in rows)
        # centred on the straights, within the law's curve offset (0.30 m at the limit on the
        # 1 500 m arcs) plus 0.05 m everywhere after settling
        curve = LIMIT ** 2 * lk.LATERAL_TIME_S * lk.HEADING_TIME_S / 1500.0
        settled = [offset for t, _, offset, _ in after if t > crossed_at + 3.0]
        assert max(abs(offset) for offset in settled) < curve + 0.05
        assert min(abs(offset) for offset in settled) < 0.01
    finally:
        env.close()


def test_a_world_without_lanes_refuses_the_action():
    with pytest.raises(InvalidParameterError, match="control 'lane_speed' reads the lane "
                                                    'state: the world has no lanes'):
        _env('default')
