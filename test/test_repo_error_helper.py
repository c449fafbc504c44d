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


"""One error helper: a bad value is reported by ``param_spec.fail``, never by a private copy."""

import ast
from pathlib import Path

import pytest

from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.specs.param_spec import fail

ROOT = Path(__file__).resolve().parent.parent


def test_no_module_defines_its_own_fail_helper():
    copies = []
    for package in ('vehicle_sim', 'vehicle_msgs_py'):
        for path in sorted((ROOT / package).rglob('*.py')):
            for node in ast.parse(path.read_text(encoding='utf-8')).body:    # module level
                if isinstance(node, ast.FunctionDef) and node.name in ('_fail', 'fail') \
                        and path.name != 'param_spec.py':
                    copies.append(f'{path.relative_to(ROOT)}:{node.lineno}')
    assert copies == []


def test_the_helper_is_called_by_its_own_name():
    aliases = []
    for package in ('vehicle_sim', 'vehicle_msgs_py'):
        for path in sorted((ROOT / package).rglob('*.py')):
            for node in ast.walk(ast.parse(path.read_text(encoding='utf-8'))):
                if isinstance(node, ast.ImportFrom) \
                        and node.module == 'vehicle_sim.core.specs.param_spec':
                    aliases += [f'{path.relative_to(ROOT)}:{node.lineno}' for alias in node.names
                                if alias.name == 'fail' and alias.asname]
    assert aliases == []


def test_fail_names_source_key_value_and_reason():
    with pytest.raises(InvalidParameterError) as error:
        fail('car.yaml', 'mass', -1.0, 'must be > 0')
    assert str(error.value) == "car.yaml: field 'mass' = -1.0: must be > 0"
