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
Registries of kinds: a table of rows by name, each name added once.

Map kinds, obstacle shapes, traffic models, scene parts and sweep backends are each a dict of
rows keyed by the row's ``name``; every layer registers its part under that name and
test/test_repo_kind_registries.py checks that the layers agree.
"""

from typing import Iterable, Mapping, TypeVar

Row = TypeVar('Row')


def register(registry: dict, row: Row, what: str, taken: Iterable[Mapping] = ()) -> Row:
    """
    Add ``row`` to ``registry`` under ``row.name`` and return it.

    :param registry: the table of rows by name.
    :param row: a row with a ``name``.
    :param what: what a row is, for the error (e.g. 'map kind').
    :param taken: other tables whose names this one must not reuse either.
    :raises ValueError: for a name registered already (nothing added).
    """
    if any(row.name in table for table in (registry, *taken)):
        raise ValueError(f'{what} {row.name!r} is registered already')
    registry[row.name] = row
    return row
