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
The tests' same-shape set-ups are written once, in a helper, and the test modules use it.

- the automobile node recorded in process (``record_node`` then ``AutomobileNode``, stepped,
  closed): ``record_helpers.record_automobile``;
- the node in a subprocess, a client node and an ``VehicleClient`` waiting for its topics:
  ``automobile_helpers.automobile_fixtures``.
"""

import ast
from pathlib import Path

TEST_DIR = Path(__file__).resolve().parent


def _is_fixture(function):
    for decorator in function.decorator_list:
        target = decorator.func if isinstance(decorator, ast.Call) else decorator
        if ast.unparse(target) in ('pytest.fixture', 'fixture'):
            return True
    return False


def _fixtures_calling(name):
    """Return 'file:fixture' for each fixture of a test module that calls ``name``."""
    found = []
    for path in sorted(TEST_DIR.glob('test_*.py')):
        tree = ast.parse(path.read_text(encoding='utf-8'))
        for function in ast.walk(tree):
            if isinstance(function, ast.FunctionDef) and _is_fixture(function) and any(
                    isinstance(call, ast.Call) and ast.unparse(call.func) == name
                    for call in ast.walk(function)):
                found.append(f'{path.name}:{function.name}')
    return found


def _modules_calling(name):
    return sorted(path.name for path in TEST_DIR.glob('*.py')
                  if f'{name}(' in path.read_text(encoding='utf-8')
                  and path.name != Path(__file__).name)


def test_the_in_process_recording_is_set_up_once():
    assert _modules_calling('record_node') == ['record_helpers.py']


def test_no_module_builds_the_node_process_client_and_automobile_client_itself():
    assert _fixtures_calling('VehicleClient') == []
    assert _fixtures_calling('client_node') == []


def test_a_repository_script_is_loaded_by_path_in_one_place():
    assert _modules_calling('spec_from_file_location') == ['script_helpers.py']
