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
The package builds the way colcon builds an ament_python package, without a warning.

colcon runs ``setup.py egg_info build install``; this test runs the same setuptools commands
(``install_data`` for the ``data_files``) on a copy of the sources in a temporary directory and
checks that nothing prints a warning and that every data file lands where the nodes look for it.
"""

import os
from pathlib import Path
import re
import shutil
import subprocess
import sys

import pytest

from vehicle_msgs_py.catalog import definitions

REPO = Path(__file__).resolve().parent.parent
# What setup.py reads: the package sources and the data_files.
SOURCES = ('setup.py', 'setup.cfg', 'package.xml', 'LICENSE', 'README.md', 'resource', 'launch',
           'config', 'vehicle_sim', 'vehicle_msgs_py')
# Generous bound for a setuptools build of this package.
BUILD_TIMEOUT_S = 300.0


@pytest.fixture(scope='module')
def built(tmp_path_factory):
    """Build a copy of the sources; return (combined output, build/lib dir, data root)."""
    root = tmp_path_factory.mktemp('packaging')
    src = root / 'src'
    src.mkdir()
    ignore = shutil.ignore_patterns('__pycache__', '*.egg-info', '*.pyc')
    for name in SOURCES:
        path = REPO / name
        if path.is_dir():
            shutil.copytree(path, src / name, ignore=ignore)
        else:
            shutil.copy2(path, src / name)
    env = dict(os.environ)
    env.pop('PYTHONDONTWRITEBYTECODE', None)  # else build_py warns that it cannot byte-compile
    # install_data instantiates setuptools' install command, whose own deprecation notice
    # concerns the builder's command, not this package (colcon silences it the same way).
    env['PYTHONWARNINGS'] = 'ignore:setup.py install is deprecated'
    result = subprocess.run(
        [sys.executable, 'setup.py', 'egg_info', '--egg-base', str(root), 'build',
         '--build-base', str(root / 'build'), 'install_data', '--install-dir',
         str(root / 'data')],
        cwd=src, env=env, capture_output=True, text=True, timeout=BUILD_TIMEOUT_S)
    assert result.returncode == 0, result.stdout[-3000:] + result.stderr[-3000:]
    return result.stdout + result.stderr, root / 'build' / 'lib', root / 'data'


def test_build_prints_no_warning(built):
    output, _, _ = built
    warnings = [line for line in output.splitlines() if re.search(r'(?i)\bwarning\b', line)]
    assert warnings == []


def test_build_ships_every_interface_definition(built):
    _, lib, _ = built
    shipped = {p.relative_to(lib / 'vehicle_msgs_py' / 'definitions').as_posix()
               for p in (lib / 'vehicle_msgs_py' / 'definitions').rglob('*') if p.is_file()}
    expected = {f'{d.package}/{d.kind}/{d.path.name}' for d in definitions()}
    assert len(expected) > 30 and shipped == expected


def test_build_ships_every_python_module_and_no_test_code(built):
    _, lib, _ = built
    for package in ('vehicle_sim', 'vehicle_msgs_py'):
        source = {p.relative_to(REPO).as_posix() for p in (REPO / package).rglob('*.py')}
        shipped = {p.relative_to(lib).as_posix() for p in (lib / package).rglob('*.py')}
        assert shipped == source
    assert not (lib / 'test').exists()


def test_install_data_puts_configs_launch_files_and_the_ament_marker_in_share(built):
    _, _, data = built
    share = data / 'share' / 'vehicle_sim'
    for pattern in ('config/*.yaml', 'config/cars/*.yaml', 'config/robots/*.yaml',
                    'config/worlds/*.yaml', 'config/maps/*.yaml', 'config/maps/*.png',
                    'config/maps/*.osm', 'config/maps/*.net.xml', 'config/rviz/*.rviz',
                    'config/foxglove/*.json',
                    'launch/*.launch.py'):
        expected = {p.name for p in REPO.glob(pattern)}
        assert expected and {p.name for p in share.glob(pattern)} == expected, pattern
    assert (share / 'package.xml').is_file()
    assert (data / 'share' / 'ament_index' / 'resource_index' / 'packages' / 'vehicle_sim'
            ).is_file()
