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
The packages have no import cycle, counting the imports inside functions.

A cycle hidden behind a function-level import still ties two modules into one: neither can be
understood, tested or moved without the other. The graph below has one node per module of
vehicle_sim and vehicle_msgs_py and an edge for every import statement anywhere in the file.
"""

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
PACKAGES = ('vehicle_sim', 'vehicle_msgs_py')

# Cycles that exist today and are being removed on another branch. Each entry must disappear
# (the strict xfail below turns green into red once the cycle is gone: then delete the entry).
KNOWN_CYCLES_BEING_REMOVED = {
    # The generic spec language knows the sensor kinds; the sensor-registration rework lets the
    # sensor package register its own kind and removes this cycle.
    frozenset({'vehicle_sim.core.param_spec', 'vehicle_sim.core.sensor_sets',
               'vehicle_sim.core.sensor_params'}): 'sensor registration rework',
}


def module_files(root=ROOT):
    """Return {dotted module name: path} for every module of the packages."""
    modules = {}
    for package in PACKAGES:
        for path in sorted((root / package).rglob('*.py')):
            parts = list(path.relative_to(root).with_suffix('').parts)
            if parts[-1] == '__init__':
                parts.pop()
            modules['.'.join(parts)] = path
    return modules


def _resolve(module, is_package, node):
    """Return the absolute module an ImportFrom names (relative imports resolved)."""
    if not node.level:
        return node.module
    base = module.split('.')
    base = base[:len(base) - node.level + (1 if is_package else 0)]
    return '.'.join(base + ([node.module] if node.module else []))


def imports_of(module, source, known, is_package=False):
    """Return the known modules a module's source imports anywhere (functions included)."""
    found = set()
    for node in ast.walk(ast.parse(source)):
        names = []
        if isinstance(node, ast.Import):
            names = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            target = _resolve(module, is_package, node)
            # ``from pkg import mod`` imports the module pkg.mod; ``from mod import name`` mod.
            names = [f'{target}.{alias.name}' if f'{target}.{alias.name}' in known else target
                     for alias in node.names]
        for name in names:
            while name and name not in known:      # a name inside a module: its module
                name = name.rpartition('.')[0]
            if name and name != module:
                found.add(name)
    return found


def import_graph(root=ROOT):
    """Return {module: set of imported package modules}."""
    files = module_files(root)
    return {module: imports_of(module, path.read_text(encoding='utf-8'), files,
                               path.name == '__init__.py')
            for module, path in files.items()}


def cycles(graph):
    """Return the strongly connected components of more than one module (Tarjan), as frozensets."""
    index, low, stack, on_stack, found = {}, {}, [], set(), []

    def visit(start):
        work = [(start, iter(sorted(graph[start])))]
        index[start] = low[start] = len(index)
        stack.append(start)
        on_stack.add(start)
        while work:
            node, children = work[-1]
            child = next(children, None)
            if child is not None:
                if child not in index:
                    index[child] = low[child] = len(index)
                    stack.append(child)
                    on_stack.add(child)
                    work.append((child, iter(sorted(graph[child]))))
                elif child in on_stack:
                    low[node] = min(low[node], index[child])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                component = set()
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    component.add(member)
                    if member == node:
                        break
                if len(component) > 1:
                    found.append(frozenset(component))

    for node in sorted(graph):
        if node not in index:
            visit(node)
    return found


def test_the_graph_sees_the_packages():
    graph = import_graph()
    assert 'vehicle_sim.core.param_spec' in graph
    assert 'vehicle_sim.core.errors' in graph['vehicle_sim.scenarios.criteria']


def test_package_has_no_import_cycle():
    unexpected = [sorted(c) for c in cycles(import_graph()) if c not in KNOWN_CYCLES_BEING_REMOVED]
    assert not unexpected, f'import cycles: {unexpected}'


@pytest.mark.parametrize('cycle', [
    pytest.param(cycle, marks=pytest.mark.xfail(strict=True, reason=f'known cycle: {why}'))
    for cycle, why in KNOWN_CYCLES_BEING_REMOVED.items()], ids=lambda c: '-'.join(
        sorted(m.rpartition('.')[2] for m in c)))
def test_known_cycle_is_gone(cycle):
    assert cycle not in cycles(import_graph())


@pytest.mark.parametrize('source, expected', [
    ('import vehicle_sim.core.units\n', {'vehicle_sim.core.units'}),
    ('from vehicle_sim.core import units\n', {'vehicle_sim.core.units'}),
    ('from vehicle_sim.core.units import X\n', {'vehicle_sim.core.units'}),
    ('def f():\n    from .units import X\n', {'vehicle_sim.core.units'}),
    ('def f():\n    import vehicle_sim.core.units as u\n', {'vehicle_sim.core.units'}),
])
def test_the_scan_sees_every_import_form(source, expected):
    known = {'vehicle_sim', 'vehicle_sim.core', 'vehicle_sim.core.units', 'vehicle_sim.core.a'}
    assert imports_of('vehicle_sim.core.a', source, known) == expected


@pytest.mark.parametrize('graph, expected', [
    ({'a': {'b'}, 'b': {'c'}, 'c': {'a'}, 'd': {'a'}}, [frozenset('abc')]),
    ({'a': {'b'}, 'b': set()}, []),
    ({'a': {'b'}, 'b': {'a'}, 'c': {'d'}, 'd': {'c'}}, [frozenset('ab'), frozenset('cd')]),
])
def test_cycle_finder(graph, expected):
    assert sorted(cycles(graph), key=sorted) == expected
