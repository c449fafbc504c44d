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
Only vehicle_sim.transport.dds.cyclone_private touches cyclonedds-python internals.

A heuristic over the source of every vehicle_sim module (AST, nothing is imported): it flags

* imports of cyclonedds' private modules (``cyclonedds._clayer``, ``cyclonedds.internal``);
* ``X._name`` where ``X`` is a name bound by an import from cyclonedds (``Entity._entities``);
* ``x._name`` where ``_name`` is a private attribute or method of cyclonedds' own classes
  (``entity._ref``, ``waitset._waitset_wait``), unless ``x`` is ``self``, ``cls`` or a class of
  the module itself (our own ``_lock`` or ``_type``).

The names private to cyclonedds are read from the installed cyclonedds source.
"""

import ast
import pathlib

import cyclonedds

import vehicle_sim

PACKAGE = pathlib.Path(vehicle_sim.__file__).parent
ALLOWED = PACKAGE / 'transport' / 'dds' / 'cyclone_private.py'
PRIVATE_MODULES = ('cyclonedds._', 'cyclonedds.internal')


def _private(name: str) -> bool:
    return name.startswith('_') and not name.startswith('__')


def _cyclonedds_private_names():
    """Return the private attribute and method names defined by cyclonedds' classes."""
    names = set()
    for path in pathlib.Path(cyclonedds.__file__).parent.rglob('*.py'):
        for cls in ast.walk(ast.parse(path.read_text(encoding='utf-8'))):
            if not isinstance(cls, ast.ClassDef):
                continue
            for node in ast.walk(cls):
                if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and \
                        _private(node.name):
                    names.add(node.name)
                elif isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) \
                        and node.value.id == 'self' and _private(node.attr):
                    names.add(node.attr)
    return names


CYCLONEDDS_PRIVATE = _cyclonedds_private_names()


def private_uses(source: str):
    """Return ``(line, text)`` of each use of a cyclonedds internal in ``source``."""
    tree = ast.parse(source)
    bound, own_classes, found = set(), set(), []
    for node in ast.walk(tree):
        if isinstance(node, ast.ClassDef):
            own_classes.add(node.name)
        elif isinstance(node, ast.ImportFrom) and (node.module or '').startswith('cyclonedds'):
            if node.module.startswith(PRIVATE_MODULES) or any(
                    _private(alias.name) for alias in node.names):
                found.append((node.lineno, ast.unparse(node)))
            bound.update(alias.asname or alias.name for alias in node.names)
        elif isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.startswith(PRIVATE_MODULES):
                    found.append((node.lineno, ast.unparse(node)))
                if alias.name.split('.')[0] == 'cyclonedds':
                    bound.add(alias.asname or 'cyclonedds')
    for node in ast.walk(tree):
        if not isinstance(node, ast.Attribute) or not _private(node.attr):
            continue
        receiver = node.value.id if isinstance(node.value, ast.Name) else None
        if receiver in bound or (node.attr in CYCLONEDDS_PRIVATE and receiver not in (
                {'self', 'cls'} | own_classes)):
            found.append((node.lineno, ast.unparse(node)))
    return sorted(found)


def test_the_heuristic_finds_each_kind_of_private_use():
    source = '\n'.join([
        'from cyclonedds._clayer import ddspy_write',
        'import cyclonedds.internal',
        'from cyclonedds.core import Entity, WaitSet',
        'Entity._entities.clear()',
        'participant._delete(participant._ref)',
        'WaitSet(p)._waitset_wait',
    ])
    assert [line for line, _ in private_uses(source)] == [1, 2, 4, 5, 5, 6]


def test_the_heuristic_leaves_our_own_private_attributes_alone():
    source = '\n'.join([
        'import threading',
        'class Context:',
        '    _lock = threading.Lock()',
        '    def f(self, node):',
        '        with Context._lock, self._lock:',
        '            return self._type, node._graph_visible, self._reader.guid.bytes',
    ])
    assert private_uses(source) == []


def test_no_module_but_cyclone_private_uses_cyclonedds_internals():
    assert {'_ref', '_delete', '_entities', '_waitset_wait'} <= CYCLONEDDS_PRIVATE
    found = {}
    for path in sorted(PACKAGE.rglob('*.py')):
        if path != ALLOWED:
            uses = private_uses(path.read_text(encoding='utf-8'))
            if uses:
                found[str(path.relative_to(PACKAGE))] = uses
    assert found == {}
    assert private_uses(ALLOWED.read_text(encoding='utf-8'))   # the check sees them there
