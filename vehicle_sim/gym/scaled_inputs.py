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
A policy's input scaling, inside the policy: a stable-baselines3 features extractor.

Drive-v0's observations are in physical units (docs/gym.md): a lane's arc length runs to
hundreds of metres while a heading error that matters is a hundredth of a radian. A network
learns badly from inputs of such different sizes; :class:`ScaledInputs` multiplies each entry
of each Dict key by a fixed factor, clips the result to [-clip, clip] and concatenates the keys
(stable-baselines3's CombinedExtractor without learned parts). The factors are the policy's
``features_extractor_kwargs``, saved in the model file: a policy loaded elsewhere (``vehicle-sim
policy run``, reading the same keys from ROS topics) scales its inputs the same way, and the
observations themselves stay in the units the environment and the topics give.

With ``closing``, the extractor also derives, for each row of an objects table (highway-env's
Kinematics layout, core/learning/objects_table.py: presence, x, y, vx, vy, ...), the rate at
which that object closes in along the ego's axis: its relative speed towards the ego over its
longitudinal distance, the inverse of the time to collision [1/s] (0 for an object that opens
the gap or an empty row). A small network computes sums and products of its inputs well and a
quotient badly; a car 30 m ahead closing at 12 m/s and one 60 m ahead closing at 24 m/s read the
same (2.5 s) only as this quotient.

With ``lane_lateral``, it derives for each row the object's lateral position across the ego's
lane, in lane widths (0: on the ego's lane centre line, +1: the centre of the next lane to the
left), from the row and the ego's lane state (Drive-v0's ``lane`` key: offset, heading error and
width): offset + x sin(heading error) + y cos(heading error), over the width. The table's x and y
are in the ego's axes, so a car ahead in the ego's own lane reads y of a metre or two whenever
the ego's heading is a degree or two off its lane's; the policy would need the product of x and
the heading error to tell it from a car in the next lane. A straight lane is assumed: on an arc
of radius R, an object x metres ahead reads x^2 / 2R further out (0.5 m at 40 m on R = 1500 m).

Needs the ``learn`` extra (stable-baselines3 and PyTorch).
"""

import numpy as np

from vehicle_sim.gym.learn_require import BaseFeaturesExtractor, torch


class ScaledInputs(BaseFeaturesExtractor):
    """
    Each Dict key flattened, times its fixed factors, clipped, concatenated.

    :param observation_space: the policy's Dict of Boxes.
    :param scales: {key: factor}: a number, or an array broadcast to the key's shape (one
        factor per column of a table: ``[1, 2, 10, ...]``); a key left out keeps factor 1.
    :param clip: the scaled entries are clipped to [-clip, clip].
    :param closing: None, or {'key': the objects table's key, 'range': its range [m],
        'speed_scale': its speed scale [m/s] (the table's own ``range`` and ``speed_scale``),
        'min_distance': the distance [m] under which an object counts as that close (a car
        beside the ego has x near 0), 'factor': the rate's factor [s]}: one more input per row,
        the closing rate times ``factor``, clipped to [0, clip].
    :param lane_lateral: None, or {'key': the objects table's key, 'lane_key': the key of the
        ego's lane state in Drive-v0's layout (s, offset, heading error, width, speed limit,
        on_lane), 'range': the table's range [m]}: one more input per row, the object's
        lateral position in the ego's lane widths, clipped to [-clip, clip] (0 for an empty row,
        or off every lane).
    :raises ValueError: naming a key of ``scales`` not in the space, or factors whose shape
        does not fit the key's; a ``closing`` or ``lane_lateral`` key that is not a table of at
        least 5 columns (a lane key of fewer than 6 entries), or a missing or non-positive
        entry.
    """

    def __init__(self, observation_space, scales=None, clip=5.0, closing=None,
                 lane_lateral=None):
        spaces = observation_space.spaces
        scales = dict(scales or {})
        unknown = sorted(set(scales) - set(spaces))
        if unknown:
            raise ValueError(f'scales for keys {unknown}: not in the observation space '
                             f'(keys {sorted(spaces)})')
        self.keys = list(spaces)
        factors = []
        for key in self.keys:
            shape = spaces[key].shape
            try:
                factor = np.broadcast_to(np.asarray(scales.get(key, 1.0), dtype=np.float32),
                                         shape)
            except ValueError:
                raise ValueError(f'scales[{key!r}] of shape '
                                 f"{np.shape(scales[key])} does not fit the key's shape "
                                 f'{shape}') from None
            factors.append(factor.reshape(-1))
        self.closing = _derived('closing', closing, CLOSING_ENTRIES, spaces)
        self.lane_lateral = _derived('lane_lateral', lane_lateral, LANE_LATERAL_ENTRIES, spaces)
        extra = sum(spaces[d['key']].shape[0] for d in (self.closing, self.lane_lateral)
                    if d is not None)
        super().__init__(observation_space,
                         features_dim=int(sum(f.size for f in factors)) + extra)
        self.clip = float(clip)
        for i, factor in enumerate(factors):
            self.register_buffer(f'factor_{i}', torch.as_tensor(np.array(factor)))

    def forward(self, observations):
        parts = []
        for i, key in enumerate(self.keys):
            value = observations[key].reshape(observations[key].shape[0], -1)
            parts.append(torch.clamp(value * getattr(self, f'factor_{i}'),
                                     -self.clip, self.clip))
        if self.closing is not None:
            parts.append(self._closing_rates(observations[self.closing['key']]))
        if self.lane_lateral is not None:
            d = self.lane_lateral
            parts.append(self._lane_laterals(observations[d['key']], observations[d['lane_key']]))
        return torch.cat(parts, dim=1)

    def _closing_rates(self, table):
        c = self.closing
        x = table[..., 1] * c['range']
        towards = -table[..., 3] * c['speed_scale'] * torch.sign(x)
        rate = table[..., 0] * torch.relu(towards) / torch.clamp(torch.abs(x),
                                                                 min=c['min_distance'])
        return torch.clamp(rate * c['factor'], 0.0, self.clip)

    def _lane_laterals(self, table, lane):
        r = self.lane_lateral['range']
        offset, heading = lane[:, 1:2], lane[:, 2:3]
        width = torch.clamp(lane[:, 3:4], min=MIN_LANE_WIDTH_M)
        across = offset + r * (table[..., 1] * torch.sin(heading)
                               + table[..., 2] * torch.cos(heading))
        value = table[..., 0] * lane[:, 5:6] * across / width
        return torch.clamp(value, -self.clip, self.clip)


# The entries of each derived input's mapping: a key of the space, or a positive number.
CLOSING_ENTRIES = ('key', 'range', 'speed_scale', 'min_distance', 'factor')
LANE_LATERAL_ENTRIES = ('key', 'lane_key', 'range')
# A lane key whose width reads less (0 off every lane) divides by this [m].
MIN_LANE_WIDTH_M = 1.0
# The least columns of an objects table (presence, x, y, vx, vy) and entries of a lane state.
_TABLE_COLUMNS, _LANE_ENTRIES = 5, 6


def _derived(what, mapping, entries, spaces):
    """Return the checked mapping of a derived input (numbers as floats), or None."""
    if mapping is None:
        return None
    mapping = dict(mapping)
    if sorted(mapping) != sorted(entries):
        raise ValueError(f'{what}: entries {sorted(mapping)}, expected {list(entries)}')
    checked = {}
    for name in entries:
        value = mapping[name]
        if name.endswith('key'):
            shape = spaces[value].shape if isinstance(value, str) and value in spaces else None
            table = name == 'key'
            fits = shape is not None and (
                len(shape) == 2 and shape[1] >= _TABLE_COLUMNS if table
                else len(shape) == 1 and shape[0] >= _LANE_ENTRIES)
            if not fits:
                kind = (f'an objects table of the space (rows of at least {_TABLE_COLUMNS} '
                        'columns' if table else
                        f'a lane state of the space (at least {_LANE_ENTRIES} entries')
                raise ValueError(f'{what}: {name} {value!r} is not {kind}; keys '
                                 f'{sorted(spaces)}, its shape {shape})')
            checked[name] = value
        elif isinstance(value, bool) or not isinstance(value, (int, float)) or not value > 0:
            raise ValueError(f'{what}: {name} must be a positive number, got {value!r}')
        else:
            checked[name] = float(value)
    return checked
