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
No import cycle in the package, counting the imports written inside functions.

A cycle hidden in a function works until the day someone moves the import to the top of the
module; it also means two modules each know the other's business. The graph is built from the
source (ast), so nothing is imported to check it.
"""

import ast
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
PACKAGES = ('vehicle_sim', 'vehicle_msgs_py')


def _modules():
    modules = {}
    for package in PACKAGES:
        for path in (REPO / package).rglob('*.py'):
            parts = list(path.relative_to(REPO).with_suffix('').parts)
            if parts[-1] == '__init__':
                parts = parts[:-1]
            modules['.'.join(parts)] = path
    return modules


def import_graph(modules):
    """Return {module: set of the package's modules it imports}, function-level imports too."""
    def resolve(name):
        while name and name not in modules:
            name = name.rpartition('.')[0]
        return name or None

    graph = {}
    for module, path in modules.items():
        package = module.split('.') if path.name == '__init__.py' else module.split('.')[:-1]
        found = set()
        for node in ast.walk(ast.parse(path.read_text(encoding='utf-8'))):
            if isinstance(node, ast.Import):
                found.update(resolve(alias.name) for alias in node.names)
            elif isinstance(node, ast.ImportFrom):
                base = node.module or ''
                if node.level:
                    base = '.'.join(package[:len(package) - node.level + 1] +
                                    ([base] if base else []))
                found.update(resolve(f'{base}.{alias.name}') for alias in node.names)
        graph[module] = found - {None, module}
    return graph


def cycles(graph):
    """Return the strongly connected components of more than one module (Tarjan), sorted."""
    index, low, stack, on_stack, found = {}, {}, [], set(), []

    def visit(node):
        index[node] = low[node] = len(index)
        stack.append(node)
        on_stack.add(node)
        for other in graph[node]:
            if other not in index:
                visit(other)
                low[node] = min(low[node], low[other])
            elif other in on_stack:
                low[node] = min(low[node], index[other])
        if low[node] == index[node]:
            component = []
            while True:
                other = stack.pop()
                on_stack.discard(other)
                component.append(other)
                if other == node:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for node in graph:
        if node not in index:
            visit(node)
    return sorted(found)


def test_the_cycle_finder_finds_a_cycle_through_a_function_level_import():
    graph = {'a': {'b'}, 'b': {'c'}, 'c': {'a'}, 'd': {'a'}}
    assert cycles(graph) == [['a', 'b', 'c']]
    assert cycles({'a': {'b'}, 'b': set()}) == []


def test_the_graph_counts_imports_inside_functions():
    graph = import_graph(_modules())
    # automobile_client.py imports the interface table inside AutomobileClient.__init__ only
    assert 'vehicle_sim.ros.automobile_interfaces' in graph['vehicle_sim.automobile_client']


def test_the_package_has_no_import_cycle():
    assert cycles(import_graph(_modules())) == []
