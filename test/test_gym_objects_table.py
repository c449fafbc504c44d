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

"""The objects table (core/learning/objects_table.py) and the Gym env's ``objects`` key."""

import math

import numpy as np
import pytest

from vehicle_sim.core.learning.objects_table import (
    FEATURES,
    Neighbour,
    objects_table,
    ObjectsTableSpec,
)
from vehicle_sim.core.specs.errors import InvalidParameterError

SPEC = ObjectsTableSpec(count=3, range_m=50.0, speed_scale_mps=10.0)


def test_a_car_ahead_in_the_ego_frame_normalised():
    # ego at (10, 5) heading +y (90 deg) at 5 m/s; a car 20 m ahead (at y = 25) at 9 m/s, same
    # heading, and one 10 m to the ego's left (x = 0) at rest, facing -x.
    table = objects_table(SPEC, 10.0, 5.0, math.pi / 2, 5.0, 0.0,
                          [Neighbour(10.0, 25.0, math.pi / 2, 9.0),
                           Neighbour(0.0, 5.0, math.pi, 0.0)])
    assert table.shape == (3, len(FEATURES)) and table.dtype == np.float32
    # nearest first: the one on the left (10 m), then the one ahead (20 m)
    np.testing.assert_allclose(table[0], (1.0, 0.0, 10 / 50, -5 / 10, 0.0, 0.0, 1.0),
                               atol=1e-6)
    np.testing.assert_allclose(table[1], (1.0, 20 / 50, 0.0, 4 / 10, 0.0, 1.0, 0.0), atol=1e-6)
    np.testing.assert_array_equal(table[2], np.zeros(len(FEATURES)))


def test_far_objects_left_out_extra_ones_cut_and_speeds_saturated():
    others = [Neighbour(float(d), 0.0, math.pi, 30.0) for d in (60.0, 40.0, 30.0, 20.0, 10.0)]
    table = objects_table(SPEC, 0.0, 0.0, 0.0, 0.0, 0.0, others)
    np.testing.assert_allclose(table[:, 1], (0.2, 0.4, 0.6), atol=1e-6)   # 60 m: beyond range
    np.testing.assert_allclose(table[:, 3], (-1.0, -1.0, -1.0))           # -30 m/s: saturated
    assert np.all(np.abs(table) <= 1.0)


def test_bad_keys_are_refused_naming_them():
    with pytest.raises(InvalidParameterError, match="'range'.*-1"):
        ObjectsTableSpec.from_dict({'range': -1.0}, 'here')
    with pytest.raises(InvalidParameterError, match="unknown key 'rows'"):
        ObjectsTableSpec.from_dict({'rows': 3}, 'here')
    assert ObjectsTableSpec.from_dict(SPEC.as_dict(), 'here') == SPEC


def test_the_gym_key_is_the_table_of_the_traffic_objects():
    gymnasium = pytest.importorskip('gymnasium', reason='the gym extra is not installed')
    import vehicle_sim.gym  # noqa: F401
    env = gymnasium.make('vehicle_sim/Drive-v0', world='highway_traffic', objects={'count': 4},
                         action_repeat=10)
    try:
        obs, _ = env.reset(seed=3)
        obs, *_ = env.step(np.array([0.1, 15.0], dtype=np.float32))
        sim = env.unwrapped.sim
        part = next(p for p in sim.agent.parts if type(p).__name__ == 'ObjectsPart')
        x, y, _, qx, qy, qz, qw = sim.agent.body.pose()
        yaw = math.atan2(2 * (qw * qz + qx * qy), 1 - 2 * (qy * qy + qz * qz))
        forward, left = obs['twist'][0], obs['twist'][1]
        expected = objects_table(ObjectsTableSpec(count=4), x, y, yaw, forward, left,
                                 part.neighbours())
        assert obs['objects'].shape == (4, len(FEATURES))
        assert obs['objects'][0, 0] == 1.0          # the highway's traffic is around the ego
        np.testing.assert_allclose(obs['objects'], expected, atol=1e-4)
    finally:
        env.close()
