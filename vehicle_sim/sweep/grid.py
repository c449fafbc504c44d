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
The variants of a sweep: ``--set`` and ``--seeds`` parsed, applied, validated.

``--set key=v1,v2`` and ``--seeds`` are parsed and applied to the scenario's data by dotted
path, and every combination is validated before anything runs.

A key is a dotted path into the scenario file (``actors.0.speed``, ``criteria.2.limit``,
``duration``): mappings by key, lists by index. Every part but the last must be in the file; the
last may be a key the file leaves at its default (the scenario's validation refuses keys that
are not in its tables). Values are YAML scalars (``4``, ``4.5``, ``true``, ``text``).
"""

import copy
from dataclasses import dataclass
import hashlib
import itertools
import json
from typing import Any, Dict, List, Optional, Tuple

import yaml

from vehicle_sim.core.specs.value_text import brief

MAX_CASES = 100000          # one sweep's combinations: so that a typo cannot ask for billions
# Every combination is validated up front when there are at most this many (7 ms each); beyond,
# each value alone is (a combination that only fails together is then that case's error).
MAX_CHECKED_COMBINATIONS = 2000


class SweepError(Exception):
    """Bad sweep input (a ``--set``, ``--seeds``, the scenario, the output folder): nothing ran."""


@dataclass(frozen=True)
class Axis:
    """One swept key and its values, in the order given."""

    key: str
    path: Tuple[Any, ...]
    values: Tuple[Any, ...]


@dataclass(frozen=True)
class Case:
    """
    One variant: the scenario with ``overrides`` ({key: value}) applied, run with ``seed``.

    :param index: its place in the grid (the order of the merged results).
    :param case_id: a name that stays the same for the same overrides and seed (file names).
    """

    index: int
    overrides: Tuple[Tuple[str, Any], ...]
    seed: int
    case_id: str

    @property
    def label(self):
        parts = [f'{key}={_text(value)}' for key, value in self.overrides]
        return ' '.join(parts + [f'seed={self.seed}'])


def _text(value):
    return yaml.safe_dump(value, default_flow_style=True).strip().removesuffix('...').strip()


def parse_set(text):
    """
    Parse one ``--set key=v1,v2,...`` into an Axis.

    :raises SweepError: no ``=``, an empty key or value, a value that is not a YAML scalar, a
        value given twice.
    """
    key, sep, values_text = text.partition('=')
    key = key.strip()
    if not sep or not key:
        raise SweepError(f'--set {brief(text)}: give key=value[,value...] (e.g. '
                         'actors.0.speed=4,6)')
    path = key_path(key)
    if any(part == '' for part in path):
        raise SweepError(f'--set {key}: an empty part in the dotted key')
    values = []
    for item in values_text.split(','):
        item = item.strip()
        if not item:
            raise SweepError(f'--set {key}: an empty value in {brief(values_text)}')
        try:
            value = yaml.safe_load(item)
        except yaml.YAMLError:
            raise SweepError(f'--set {key}: value {brief(item)} is not a YAML scalar') from None
        if isinstance(value, (list, dict)) or value is None and item not in ('null', '~'):
            raise SweepError(f'--set {key}: value {brief(item)} is not a YAML scalar')
        if not isinstance(value, (str, int, float, bool, type(None))):
            value = item        # a date, a timestamp: the text as written
        if any(type(v) is type(value) and v == value for v in values):
            raise SweepError(f'--set {key}: value {brief(item)} given twice')
        values.append(value)
    return Axis(key, path, tuple(values))


def key_path(key):
    """Split a dotted key: list indices as ints (``actors.0.speed`` -> actors, 0, speed)."""
    return tuple(int(part) if part.lstrip('-').isdigit() else part for part in key.split('.'))


def parse_seeds(text):
    """
    Parse ``--seeds``: ``A:B`` (A, A+1, ... B-1, as a Python range) or ``N[,N...]``.

    :raises SweepError: not integers, negative, an empty range, a seed given twice.
    """
    text = str(text).strip()
    try:
        if ':' in text:
            start, _, stop = text.partition(':')
            span = range(int(start), int(stop))
            if len(span) > MAX_CASES:
                raise SweepError(f'--seeds {text}: {len(span)} seeds; at most {MAX_CASES} in one '
                                 'sweep')
            seeds = list(span)
        else:
            seeds = [int(item) for item in text.split(',')]
    except ValueError:
        raise SweepError(f'--seeds {brief(text)}: give A:B (seeds A to B-1) or N[,N...], '
                         'integers') from None
    if not seeds:
        raise SweepError(f'--seeds {text}: no seeds (A:B holds A to B-1)')
    if min(seeds) < 0:
        raise SweepError(f'--seeds {text}: seeds must be >= 0')
    if len(set(seeds)) != len(seeds):
        raise SweepError(f'--seeds {text}: a seed given twice')
    return seeds


def apply_override(data, axis, value):
    """
    Set ``axis.path`` to ``value`` in ``data`` (changed in place).

    :raises SweepError: a part of the path that the scenario does not have.
    """
    node = data
    for depth, part in enumerate(axis.path):
        last = depth == len(axis.path) - 1
        where = '.'.join(str(p) for p in axis.path[:depth + 1])
        if isinstance(node, dict):
            if last:
                node[part] = value
                return
            if part not in node:
                raise SweepError(f'--set {axis.key}: the scenario has no {where!r}; keys there: '
                                 + ', '.join(str(k) for k in node))
            node = node[part]
        elif isinstance(node, list):
            if not isinstance(part, int) or not 0 <= part < len(node):
                raise SweepError(f'--set {axis.key}: {where!r}: a list of {len(node)} entries '
                                 f'(index 0 .. {len(node) - 1})')
            if last:
                node[part] = value
                return
            node = node[part]
        else:
            parent = '.'.join(str(p) for p in axis.path[:depth]) or 'the scenario'
            raise SweepError(f'--set {axis.key}: {parent!r} is a value ({brief(node)}), not a '
                             'mapping or list')


def case_id(overrides, seed):
    """Name one variant stably (the same overrides and seed give the same name)."""
    text = json.dumps([[k, v] for k, v in overrides] + [seed], sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def build_cases(axes: List[Axis], seeds: Optional[List[int]], file_seed: int) -> List[Case]:
    """Every combination of the axes' values (the first axis slowest), then the seeds."""
    keys = [axis.key for axis in axes]
    if len(set(keys)) != len(keys):
        twice = sorted({k for k in keys if keys.count(k) > 1})
        raise SweepError(f'--set {twice[0]}: given twice (give its values in one --set)')
    if 'seed' in keys and seeds is not None:
        raise SweepError('--set seed=... and --seeds: give the seeds once')
    total = len(seeds or [0])
    for axis in axes:
        total *= len(axis.values)
    if total > MAX_CASES:
        raise SweepError(f'{total} variants: at most {MAX_CASES} in one sweep')
    cases = []
    for index, combo in enumerate(itertools.product(*(a.values for a in axes), seeds or [None])):
        overrides = tuple(zip(keys, combo[:-1]))
        seed = combo[-1]
        if seed is None:
            seed = dict(overrides).get('seed', file_seed)
        cases.append(Case(index, overrides, seed, case_id(overrides, seed)))
    return cases


def variant_data(data, axes, case):
    """Return the scenario data of one variant (a copy; ``data`` is not changed)."""
    variant = copy.deepcopy(data)
    by_key = {axis.key: axis for axis in axes}
    for key, value in case.overrides:
        apply_override(variant, by_key[key], value)
    return variant


def check_variants(data, lines, source, axes, cases, validate) -> Dict[str, Any]:
    """
    Validate the variants before anything runs.

    Each value alone first (the error names its key), then every combination (up to
    MAX_CHECKED_COMBINATIONS of them).

    :param validate: ``validate(data, lines, source)`` -> ScenarioSpec, raising ScenarioError.
    :return: {case_id: ScenarioSpec} of the combinations checked.
    :raises SweepError: naming the ``--set`` values of the first invalid variant.
    """
    def named(overrides, error):
        given = ', '.join(f'{k}={_text(v)}' for k, v in overrides) or 'no --set'
        return SweepError(f'--set {given}: {error}')

    for axis in axes:       # each value alone first: the error names its key
        for value in axis.values:
            variant = copy.deepcopy(data)
            apply_override(variant, axis, value)
            try:
                validate(variant, lines, source)
            except Exception as error:   # noqa: BLE001 - ScenarioError, named with the key
                raise named(((axis.key, value),), error) from None
    specs = {}
    for case in cases if len(cases) <= MAX_CHECKED_COMBINATIONS else ():
        variant = variant_data(data, axes, case)
        try:
            specs[case.case_id] = validate(variant, lines, source)
        except Exception as error:   # noqa: BLE001 - ScenarioError, named with the variant
            raise named(case.overrides, error) from None
    return specs
