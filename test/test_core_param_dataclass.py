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
Frozen dataclasses made from ParamSpec tables: each default written once, in its row.

``table_dataclass(specs)`` turns a class into a frozen dataclass with one field per row (the
row's attribute, type and default) and ``from_dict(data, source)``, the table's validator. The
IDM and MOBIL parameters are made this way.
"""

from dataclasses import fields, FrozenInstanceError
import re

import pytest

from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.param_spec import ParamSpec, REQUIRED, table_dataclass
from vehicle_sim.core.traffic import idm, mobil

TABLE = (
    ParamSpec('gap', 'gap_m', 'float', 2.0, 'm', 'a gap', gt=0.0),
    ParamSpec('count', 'count', 'int', 3, '', 'a count', ge=1, le=9),
    ParamSpec('mode', 'mode', 'enum', 'a', choices=('a', 'b')),
)


@table_dataclass(TABLE)
class Toy:
    """A toy parameter set."""

    def twice_gap(self):
        return 2.0 * self.gap_m


def test_the_class_has_one_field_per_row_with_its_attribute_type_and_default():
    assert [(f.name, f.type, f.default) for f in fields(Toy)] == [
        ('gap_m', float, 2.0), ('count', int, 3), ('mode', str, 'a')]
    toy = Toy(count=5)
    assert (toy.gap_m, toy.count, toy.mode, toy.twice_gap()) == (2.0, 5, 'a', 4.0)
    assert Toy.SPECS is TABLE
    with pytest.raises(FrozenInstanceError):
        toy.count = 6


def test_from_dict_validates_with_the_table_and_names_source_key_and_value():
    assert Toy.from_dict({'gap': 1.5, 'mode': 'b'}, 'w.yaml') == Toy(gap_m=1.5, mode='b')
    assert Toy.from_dict(None, 'w.yaml') == Toy()
    with pytest.raises(InvalidParameterError,
                       match=r"w.yaml: field 'count' = 10: must be in 1 .. 9"):
        Toy.from_dict({'count': 10}, 'w.yaml')


def test_a_row_without_a_default_is_refused():
    with pytest.raises(InvalidParameterError, match="'name' has no default"):
        table_dataclass((ParamSpec('name', kind='str', default=REQUIRED),))(type('T', (), {}))


@pytest.mark.parametrize('module, cls, specs', [
    (idm, idm.IdmParams, idm.IDM_SPECS), (mobil, mobil.MobilParams, mobil.MOBIL_SPECS)])
def test_idm_and_mobil_parameters_are_made_from_their_tables(module, cls, specs):
    assert cls.SPECS is specs
    assert [(f.name, f.default) for f in fields(cls)] == [(s.attr, s.default) for s in specs]
    # No default is written a second time in the module: a field line 'name: float = value'.
    source = open(module.__file__, encoding='utf-8').read()
    assert re.findall(r'^\s+\w+: float = [-.0-9]', source, re.MULTILINE) == []
