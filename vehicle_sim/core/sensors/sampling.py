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
When periodic sensors are due, on the integer grid of basic time steps.

A sensor at ``rate_hz`` is sampled at the first basic step at or after each k / rate_hz
(k = 1, 2, ...), counted from the step at which it was started. On a 10 ms step a 40 Hz sensor
is then due at steps 3, 5, 8, 10, 13, ... (alternately 3 and 2 steps apart), a 10 Hz one every
10 steps. Steps are counted with exact rational arithmetic: the rate and the step are read as
the decimal numbers they print as (``40.0`` Hz, ``0.01`` s), so no sample drifts or doubles
because 0.01 has no exact binary value. A rate above the step rate samples every step.
"""

from fractions import Fraction
from typing import Dict, Hashable, List, Tuple


def exact(value):
    """
    Return a number as the exact fraction of the decimal it prints as.

    :param value: an int, float or Fraction (``0.01`` gives 1/100, not the binary double).
    :return: Fraction.
    """
    if isinstance(value, Fraction):
        return value
    if isinstance(value, int):
        return Fraction(value)
    return Fraction(repr(float(value)))


def _ceil_div(numerator, denominator):
    return -(-numerator // denominator)


class SampleSchedule:
    """
    The due steps of one periodic sensor.

    :param steps_per_sample: basic steps per sample period (a positive Fraction: period / step).
    :param start_step: step at which the sensor was started; its first sample is one period
        later (Webots: "the first measurement will be available only after the first sampling
        period elapsed").
    """

    __slots__ = ('_num', '_den', '_start', '_k', 'next_step')

    def __init__(self, steps_per_sample, start_step=0):
        steps_per_sample = exact(steps_per_sample)
        if steps_per_sample <= 0:
            raise ValueError(f'steps_per_sample = {steps_per_sample}: must be > 0')
        self._num = steps_per_sample.numerator
        self._den = steps_per_sample.denominator
        self._start = int(start_step)
        self._k = 1
        self.next_step = self._step_of(1)

    @classmethod
    def from_rate(cls, rate_hz, time_step_s, start_step=0):
        """
        Schedule a sensor by its rate.

        :param rate_hz: samples per simulated second [Hz], > 0.
        :param time_step_s: the world's basic time step [s], > 0.
        :param start_step: see the class.
        """
        rate, step = exact(rate_hz), exact(time_step_s)
        if rate <= 0 or step <= 0:
            raise ValueError(f'rate_hz = {rate_hz!r}, time_step_s = {time_step_s!r}: must be > 0')
        return cls(1 / (rate * step), start_step)

    @classmethod
    def from_period_ms(cls, period_ms, time_step_ms, start_step=0):
        """Schedule a sensor by its sampling period (Webots ``enable(period)``) [ms]."""
        period, step = exact(period_ms), exact(time_step_ms)
        if period <= 0 or step <= 0:
            raise ValueError(f'period_ms = {period_ms!r}, time_step_ms = {time_step_ms!r}: '
                             'must be > 0')
        return cls(period / step, start_step)

    def _step_of(self, k):
        # first integer step n with n - start >= k * num / den
        return self._start + _ceil_div(k * self._num, self._den)

    def due(self, step):
        """
        Tell whether the sensor is due at a basic step; advance to the next sample if so.

        :param step: the world's step count after the step just taken.
        :return: True once per due step (also when several periods fell into it).
        """
        if step < self.next_step:
            return False
        # skip the periods that fell into this step (a rate above the step rate, or a caller
        # that skipped steps): the next sample is the first one after ``step``
        self._k = max(self._k + 1, (step - self._start) * self._den // self._num + 1)
        self.next_step = self._step_of(self._k)
        return True

    def steps(self, count):
        """Return the next ``count`` due steps without consuming them (for docs and tests)."""
        return [self._step_of(k) for k in range(self._k, self._k + count)]


class Scheduler:
    """
    The schedules of several sensors: which ones are due after a basic step.

    Keys are any hashables (sensor names). ``due(step)`` costs one integer comparison when
    nothing is due.
    """

    def __init__(self):
        self._schedules: Dict[Hashable, SampleSchedule] = {}
        self._next = None

    def set(self, key, schedule):
        """Add or replace a sensor's schedule; ``None`` removes it."""
        if schedule is None:
            self._schedules.pop(key, None)
        else:
            self._schedules[key] = schedule
        self._refresh()

    def get(self, key):
        return self._schedules.get(key)

    def __bool__(self):
        return bool(self._schedules)

    def _refresh(self):
        self._next = min((s.next_step for s in self._schedules.values()), default=None)

    def due(self, step) -> List[Hashable]:
        """
        Return the keys of the sensors due at a step, in insertion order.

        :param step: the world's step count after the step just taken.
        """
        if self._next is None or step < self._next:
            return []
        keys = [key for key, schedule in self._schedules.items() if schedule.due(step)]
        self._refresh()
        return keys

    def next_step(self):
        """Return the earliest step at which some sensor is due, or None."""
        return self._next


def due_steps(rate_hz, time_step_s, count) -> Tuple[int, ...]:
    """Return the first ``count`` due steps of a sensor started at step 0."""
    return tuple(SampleSchedule.from_rate(rate_hz, time_step_s).steps(count))
