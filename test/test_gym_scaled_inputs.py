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
The policy's input scaling (vehicle_sim/gym/scaled_inputs.py) against values worked out by hand.

Factors, clipping, and the inputs derived from an objects table (closing rates; lateral
positions in the ego's lane widths); bad settings refused by name. Skipped, saying why, without
the ``learn`` extra (PyTorch), which CI does not install.
"""

import math

import numpy as np
import pytest

pytest.importorskip('gymnasium', reason="needs the 'gym' extra (gymnasium)")
pytest.importorskip('stable_baselines3',
                    reason="needs the 'learn' extra (stable-baselines3 and PyTorch): "
                           "pip install 'vehicle_sim[learn]', docs/learning.md")
torch = pytest.importorskip('torch', reason="needs the 'learn' extra (PyTorch): docs/learning.md")

from gymnasium import spaces  # noqa: E402

from vehicle_sim.gym.scaled_inputs import ScaledInputs  # noqa: E402

RANGE, SPEED = 80.0, 40.0
CLOSING = {'key': 'objects', 'range': RANGE, 'speed_scale': SPEED, 'min_distance': 5.0,
           'factor': 4.0}
LANE_LATERAL = {'key': 'objects', 'lane_key': 'lane', 'range': RANGE}
SPACE = spaces.Dict({'twist': spaces.Box(-50.0, 50.0, (3,), np.float32),
                     'objects': spaces.Box(-1.0, 1.0, (5, 7), np.float32)})
LANE_SPACE = spaces.Dict({'lane': spaces.Box(-1e3, 1e3, (6,), np.float32),
                          'objects': spaces.Box(-1.0, 1.0, (3, 7), np.float32)})


def _row(x_m, vx_mps, presence=1.0):
    return [presence, x_m / RANGE, 0.0, vx_mps / SPEED, 0.0, 1.0, 0.0]


def _features(extractor, twist, table):
    batch = {'twist': torch.as_tensor(np.array([twist], dtype=np.float32)),
             'objects': torch.as_tensor(np.array([table], dtype=np.float32))}
    return extractor(batch)[0].numpy()


def test_factors_and_clip():
    extractor = ScaledInputs(SPACE, {'twist': [0.1, 1.0, 5.0]}, clip=2.0)
    assert extractor.features_dim == 3 + 35
    out = _features(extractor, [30.0, 0.5, 1.0], [_row(40.0, -8.0)] + [[0.0] * 7] * 4)
    # the keys in the space's order (gymnasium sorts a Dict's keys): objects, then twist
    assert out[35:] == pytest.approx([2.0, 0.5, 2.0])     # 3.0 and 5.0 clipped to 2
    assert out[:7] == pytest.approx(_row(40.0, -8.0), abs=1e-6)


def test_closing_rates_against_hand_values():
    extractor = ScaledInputs(SPACE, closing=CLOSING)
    assert extractor.features_dim == 3 + 35 + 5
    table = [_row(30.0, -12.0),     # ahead, closing 12 m/s over 30 m: 0.4 /s, x 4 s = 1.6
             _row(-20.0, 10.0),     # behind, catching up 10 m/s over 20 m: 0.5 /s -> 2.0
             _row(30.0, 5.0),       # ahead and pulling away: 0
             _row(1.0, -10.0),      # beside: 10 m/s over the 5 m floor, 2 /s -> 8, clipped 5
             _row(30.0, -12.0, presence=0.0)]   # an empty row reads 0
    out = _features(extractor, [0.0, 0.0, 0.0], table)
    assert out[-5:] == pytest.approx([1.6, 2.0, 0.0, 5.0, 0.0], abs=1e-5)


def _seen_from_ego(along_m, across_m, offset_m, heading_rad):
    """Return the row of an object at (along, across) in the ego's lane, in the ego's axes."""
    dx, dy = along_m, across_m - offset_m     # from the ego, in the lane's axes
    c, s = math.cos(heading_rad), math.sin(heading_rad)
    return [1.0, (c * dx + s * dy) / RANGE, (-s * dx + c * dy) / RANGE, 0.0, 0.0, 1.0, 0.0]


def test_lane_lateral_undoes_the_egos_heading():
    extractor = ScaledInputs(LANE_SPACE, lane_lateral=LANE_LATERAL)
    assert extractor.features_dim == 6 + 21 + 3
    offset, heading, width = 0.5, 0.05, 3.5
    lane = [100.0, offset, heading, width, 33.3, 1.0]
    # 40 m ahead on the ego's lane centre, 25 m ahead in the lane to its left, 10 m behind in
    # the lane to its right: 0, +1, -1 lane widths, though the ego's y reads them -2.5, +1.75
    # and -3.5 m (its heading 0.05 rad and its offset 0.5 m)
    table = [_seen_from_ego(40.0, 0.0, offset, heading),
             _seen_from_ego(25.0, width, offset, heading),
             _seen_from_ego(-10.0, -width, offset, heading)]
    assert [row[2] * RANGE for row in table] == pytest.approx([-2.499, 1.747, -3.495], abs=1e-3)
    batch = {'lane': torch.as_tensor(np.array([lane], dtype=np.float32)),
             'objects': torch.as_tensor(np.array([table], dtype=np.float32))}
    assert extractor(batch)[0].numpy()[-3:] == pytest.approx([0.0, 1.0, -1.0], abs=1e-5)
    # by hand: offset 0.5 + 30 sin 0.1 - 2.5 cos 0.1 = 1.00749 m, over 3.5 m
    lane = [100.0, 0.5, 0.1, 3.5, 33.3, 1.0]
    table = [[1.0, 30.0 / RANGE, -2.5 / RANGE, 0.0, 0.0, 1.0, 0.0],
             [0.0, 30.0 / RANGE, -2.5 / RANGE, 0.0, 0.0, 1.0, 0.0],     # an empty row
             [1.0, 30.0 / RANGE, 60.0 / RANGE, 0.0, 0.0, 1.0, 0.0]]     # 17.5 lanes: clipped
    batch = {'lane': torch.as_tensor(np.array([lane, [0.0] * 6], dtype=np.float32)),
             'objects': torch.as_tensor(np.array([table, table], dtype=np.float32))}
    out = extractor(batch).numpy()
    assert out[0, -3:] == pytest.approx([0.28785, 0.0, 5.0], abs=1e-4)
    assert out[1, -3:] == pytest.approx([0.0, 0.0, 0.0])       # off every lane: all 0


def test_bad_settings_refused_by_name():
    with pytest.raises(ValueError, match=r"scales for keys \['lane'\]"):
        ScaledInputs(SPACE, {'lane': 1.0})
    with pytest.raises(ValueError, match=r"scales\['twist'\] of shape \(2,\)"):
        ScaledInputs(SPACE, {'twist': [1.0, 2.0]})
    with pytest.raises(ValueError, match="closing: key 'twist' is not an objects table"):
        ScaledInputs(SPACE, closing=dict(CLOSING, key='twist'))
    with pytest.raises(ValueError, match="key 'lane' is not an objects table"):
        ScaledInputs(SPACE, closing=dict(CLOSING, key='lane'))
    with pytest.raises(ValueError, match="lane_lateral: lane_key 'twist' is not a lane state"):
        ScaledInputs(SPACE, lane_lateral=dict(LANE_LATERAL, lane_key='twist'))
    with pytest.raises(ValueError, match=r"closing: key \['objects'\] is not an objects table"):
        ScaledInputs(SPACE, closing=dict(CLOSING, key=['objects']))
    with pytest.raises(ValueError, match='min_distance must be a positive number, got 0'):
        ScaledInputs(SPACE, closing=dict(CLOSING, min_distance=0))
    with pytest.raises(ValueError, match=r"expected \['key', 'range'"):
        ScaledInputs(SPACE, closing={'key': 'objects'})
