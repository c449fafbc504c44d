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
The core imports only the standard library, numpy and vehicle_sim.core.

And numba: the compiled ray march of the ``fast`` extra (core/map/grid_rays_jit.py).
"""

import ast
from pathlib import Path
import sys

import pytest

CORE_DIR = Path(__file__).resolve().parent.parent / 'vehicle_sim' / 'core'
ALLOWED_THIRD_PARTY = {'numpy', 'numba'}
FORBIDDEN_EXAMPLES = ('rclpy', 'pybullet', 'yaml', 'cyclonedds', 'vehicle_msgs_py')


def _imported_modules(path):
    """Yield (line, absolute module name) for every import of a module file."""
    tree = ast.parse(path.read_text(encoding='utf-8'), filename=str(path))
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                yield node.lineno, alias.name
        elif isinstance(node, ast.ImportFrom):
            if node.level:      # relative import: stays inside vehicle_sim.core
                yield node.lineno, 'vehicle_sim.core'
            else:
                yield node.lineno, node.module
        elif isinstance(node, ast.Call) and getattr(node.func, 'id', '') == '__import__':
            yield node.lineno, '__import__(...)'


def _allowed(module):
    root = module.split('.')[0]
    return (module == 'vehicle_sim.core' or module.startswith('vehicle_sim.core.')
            or root in ALLOWED_THIRD_PARTY or root in sys.stdlib_module_names)


CORE_MODULES = sorted(CORE_DIR.rglob('*.py'))


def test_core_has_modules_to_check():
    assert len(CORE_MODULES) >= 8


@pytest.mark.parametrize('path', CORE_MODULES, ids=lambda p: p.name)
def test_core_module_imports_only_stdlib_numpy_and_core(path):
    bad = [f'{path.name}:{line}: {module}' for line, module in _imported_modules(path)
           if not _allowed(module)]
    assert not bad, 'core must stay ROS-free and PyBullet-free: ' + ', '.join(bad)


@pytest.mark.parametrize('module', FORBIDDEN_EXAMPLES + ('vehicle_sim.physics',
                                                         'vehicle_sim.config'))
def test_import_checker_rejects_forbidden_modules(module):
    assert not _allowed(module)
