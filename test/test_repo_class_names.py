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
One name per class: no two classes of the package (and the tests' shared helpers) share a name.

Two classes named alike (two ``Scene``, two ``ScenarioResult``) make every reader check which
one a line means; the scan parses the source (ast), classes inside functions included.
"""

import ast
from collections import defaultdict
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
TEST_DIR = REPO / 'test'


def scanned_files():
    """Return the package's modules and the tests' shared helper modules (not test_*.py)."""
    files = sorted((REPO / 'vehicle_sim').rglob('*.py')) + \
        sorted((REPO / 'vehicle_msgs_py').rglob('*.py'))
    return files + sorted(path for path in TEST_DIR.glob('*.py')
                          if not path.name.startswith('test_'))


def classes_by_name(sources):
    """Return {class name: [where defined]} for {where: source}."""
    found = defaultdict(list)
    for where, source in sources.items():
        for node in ast.walk(ast.parse(source)):
            if isinstance(node, ast.ClassDef):
                found[node.name].append(f'{where}:{node.lineno}')
    return found


def shared_names(sources):
    """Return {class name: places} of the names more than one class has."""
    return {name: places for name, places in classes_by_name(sources).items()
            if len(places) > 1}


def test_no_two_classes_share_a_name():
    sources = {str(path.relative_to(REPO)): path.read_text(encoding='utf-8')
               for path in scanned_files()}
    assert len(sources) > 200
    assert shared_names(sources) == {}


def test_the_scan_finds_a_shared_name_also_inside_a_function():
    sources = {'a.py': 'class Scene:\n    pass\n',
               'b.py': 'def f():\n    class Scene:\n        pass\n',
               'c.py': 'class Other:\n    pass\n'}
    assert shared_names(sources) == {'Scene': ['a.py:1', 'b.py:2']}
