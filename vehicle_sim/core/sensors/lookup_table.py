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
Webots' DistanceSensor lookup table: distance -> response value, with relative noise.

Each row is (distance [m], value, noise); the distances are >= 0 and strictly increasing.
Between rows the value and the noise are interpolated linearly; outside the table they are those
of the nearest end row (a sensor saturates). The noise column is a standard deviation relative
to the value (0.1 = 10 %). ``getMaxValue`` / ``getMinValue`` are the largest / smallest values
of the second column (Webots' distance_sensor.md, "Lookup Table").
"""

from typing import Sequence, Tuple

import numpy as np

Row = Tuple[float, float, float]


class LookupTable:
    """
    A validated lookup table.

    :param rows: at least two (distance, value, noise) rows.
    :raises ValueError: for fewer than two rows, non-increasing or negative distances, or a
        negative noise.
    """

    def __init__(self, rows: Sequence[Row]):
        table = np.asarray(rows, dtype=float)
        if table.ndim != 2 or table.shape[1] != 3 or table.shape[0] < 2:
            raise ValueError('a lookup table needs at least two rows of (distance, value, noise)')
        if not np.all(np.isfinite(table)):
            raise ValueError('every lookup table entry must be finite')
        distances = table[:, 0]
        if distances[0] < 0.0 or np.any(np.diff(distances) <= 0.0):
            raise ValueError('lookup table distances must be >= 0 and strictly increasing')
        if np.any(table[:, 2] < 0.0):
            raise ValueError('lookup table noise must be >= 0')
        self.rows = tuple(tuple(float(v) for v in row) for row in table)
        self._distance = distances
        self._value = table[:, 1]
        self._noise = table[:, 2]

    @classmethod
    def identity(cls, max_range_m):
        """Return the table that gives the distance itself up to ``max_range_m``, without noise."""
        return cls(((0.0, 0.0, 0.0), (float(max_range_m), float(max_range_m), 0.0)))

    @property
    def max_value(self):
        """Largest value of the second column (Webots getMaxValue)."""
        return float(self._value.max())

    @property
    def min_value(self):
        """Smallest value of the second column (Webots getMinValue)."""
        return float(self._value.min())

    @property
    def max_distance_m(self):
        """The last row's distance: the range of the sensor."""
        return float(self._distance[-1])

    @property
    def has_noise(self):
        return bool(np.any(self._noise > 0.0))

    def value(self, distance_m):
        """Return the response value at a distance (interpolated; saturated outside)."""
        return float(np.interp(distance_m, self._distance, self._value))

    def relative_noise(self, distance_m):
        """Return the relative noise standard deviation at a distance."""
        return float(np.interp(distance_m, self._distance, self._noise))
