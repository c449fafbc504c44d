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
Seeded Gaussian sensor noise (default: none, so that readings are exact and reproducible).

Each sensor owns one generator seeded from its ``seed`` and its name, so two sensors with the
same seed draw different but reproducible sequences, and adding a sensor does not change the
noise of the others.
"""

import zlib

import numpy as np


class GaussianNoise:
    """
    Zero-mean Gaussian noise of a fixed standard deviation.

    :param sigma: standard deviation (in the unit of the values it is added to), >= 0; 0 adds
        nothing and draws nothing.
    :param seed: non-negative integer seed.
    :param stream: a name mixed into the seed (the sensor's name and quantity).
    """

    def __init__(self, sigma, seed=0, stream=''):
        if not sigma >= 0.0:
            raise ValueError(f'sigma = {sigma!r}: must be >= 0')
        self.sigma = float(sigma)
        self._rng = np.random.default_rng([int(seed), zlib.crc32(stream.encode('utf-8'))])

    def __bool__(self):
        return self.sigma > 0.0

    def add(self, values):
        """
        Return ``values`` plus noise (a new array; ``values`` itself when sigma = 0).

        :param values: a number or an array of numbers.
        """
        if self.sigma == 0.0:
            return values
        values = np.asarray(values, dtype=float)
        return values + self._rng.normal(0.0, self.sigma, values.shape)

    def add_relative(self, value, relative_sigma):
        """
        Return ``value`` with noise of standard deviation ``relative_sigma * |value|``.

        Webots' lookup-table noise: the third column is a fraction of the response value. Uses
        this generator whatever ``sigma`` is.
        """
        if relative_sigma == 0.0:
            return value
        return float(value + self._rng.normal(0.0, abs(relative_sigma * value)))
