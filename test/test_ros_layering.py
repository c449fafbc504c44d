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
Node modules import core and the shared ROS modules, never each other.

A node module is ``vehicle_sim/ros/*_node.py``. Shared code lives in core (ROS-free logic:
``core/bridge/controller.py``, ``core/autoware/codes.py``) or in a shared module of
``vehicle_sim/ros`` (``node_support.py``: parameter declaration, the main
wrapper; ``automobile.py``: the simulated cars that ``automobile`` runs and
``autoware_automobile`` composes), so no module of ``vehicle_sim/ros`` imports a node module.
"""

import ast
from pathlib import Path

import pytest

ROS_DIR = Path(__file__).resolve().parent.parent / 'vehicle_sim' / 'ros'
ROS_MODULES = sorted(ROS_DIR.glob('*.py'))
NODE_MODULES = {path.stem for path in ROS_MODULES if path.stem.endswith('_node')}


def imported_ros_modules(source):
    """Return the vehicle_sim.ros module names (last component) a module's source imports."""
    found = set()
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            names = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ''
            if node.level:              # relative import inside vehicle_sim.ros
                base = 'vehicle_sim.ros' + ('.' + base if base else '')
            names = [base] + [f'{base}.{alias.name}' for alias in node.names]
        else:
            continue
        for name in names:
            parts = name.split('.')
            if parts[:2] == ['vehicle_sim', 'ros'] and len(parts) >= 3:
                found.add(parts[2])
    return found


def test_the_four_nodes_are_found():
    assert NODE_MODULES == {'automobile_node', 'autoware_automobile_node', 'bridge_node',
                            'diff_robot_node'}


@pytest.mark.parametrize('path', ROS_MODULES, ids=lambda p: p.name)
def test_no_ros_module_imports_a_node_module(path):
    imported = imported_ros_modules(path.read_text(encoding='utf-8'))
    bad = sorted(module for module in imported & NODE_MODULES
                 if module != path.stem)
    assert not bad, f'{path.name} imports node module(s) {bad}: move the shared code to core ' \
        'or a shared module of vehicle_sim/ros'


@pytest.mark.parametrize('source, expected', [
    ('from vehicle_sim.ros.bridge_node import ThrottledWarning', {'bridge_node'}),
    ('from vehicle_sim.ros import bridge_node', {'bridge_node'}),
    ('import vehicle_sim.ros.diff_robot_node as d', {'diff_robot_node'}),
    ('from .bridge_node import X', {'bridge_node'}),
    ('from . import automobile_node', {'automobile_node'}),
    ('def f():\n    from vehicle_sim.ros.bridge_node import X\n', {'bridge_node'}),
    ('from vehicle_sim.core.autoware.codes import GEAR_DRIVE', set()),
])
def test_the_import_scan_sees_every_import_form(source, expected):
    assert imported_ros_modules(source) & NODE_MODULES == expected
