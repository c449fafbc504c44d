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
Test files are named by one rule: ``test_<area>_<subject>.py``.

The area is the layer the file tests (its package under vehicle_sim/, or ``msgs`` for
vehicle_msgs_py), or ``repo`` for checks of the whole repository, so that a maintainer finds the
tests of a layer by its prefix.
"""

from pathlib import Path
import re

import pytest

TEST_DIR = Path(__file__).resolve().parent
AREAS = ('core', 'physics', 'webots', 'ros', 'transport', 'scenario', 'cli', 'config', 'gui',
         'testing', 'msgs', 'repo')
RULE = re.compile(r'test_(%s)_[a-z0-9_]+\.py' % '|'.join(AREAS))
# Older files named before the rule; rename each (``git mv``) when nobody else is editing it,
# then delete its entry here. New files follow the rule.
NOT_YET_RENAMED = {
    'test_autoware_automobile.py', 'test_cli.py', 'test_copyright.py', 'test_end_to_end.py',
    'test_endpoints.py', 'test_export_interfaces.py', 'test_fidelity.py', 'test_graph.py',
    'test_hostile_files.py', 'test_packaging.py', 'test_param_messages.py',
    'test_parameters.py', 'test_reader_gate.py', 'test_rviz_config.py', 'test_serve_pending.py',
    'test_user_facing_text.py', 'test_vehicle_msgs_py.py',
}


def _test_files():
    return sorted(p.name for p in TEST_DIR.glob('test_*.py'))


def test_test_files_follow_the_naming_rule():
    outliers = [name for name in _test_files()
                if not RULE.fullmatch(name) and name not in NOT_YET_RENAMED]
    assert outliers == []


def test_the_list_of_older_names_holds_only_outliers_that_exist():
    names = set(_test_files())
    assert sorted(NOT_YET_RENAMED - names) == []
    assert sorted(n for n in NOT_YET_RENAMED if RULE.fullmatch(n)) == []


@pytest.mark.parametrize('name, follows', [
    ('test_core_geometry.py', True), ('test_transport_fast_cdr.py', True),
    ('test_repo_import_cycles.py', True), ('test_fast_cdr.py', False),
    ('test_core.py', False), ('test_Core_x.py', False),
])
def test_the_rule(name, follows):
    assert bool(RULE.fullmatch(name)) is follows
