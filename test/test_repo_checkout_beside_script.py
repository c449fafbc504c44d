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
A script beside a checkout named vehicle_sim (``~/train.py`` next to ``~/vehicle_sim/``).

Python looks in the script's folder first and finds the checkout there. Taken as a namespace
package, its ``config/`` folder hid the module ``vehicle_sim.config`` (``ImportError: cannot
import name 'read_yaml' from 'vehicle_sim.config' (unknown location)``). The checkout's
``__init__.py`` hands the import on to the installed package, or says what happened when none is
installed. Each case runs a real script in a subprocess.
"""

import os
import subprocess
import sys

from conftest import REPO_ROOT

RUN_TIMEOUT_S = 120.0
SCRIPT = ('import vehicle_sim\n'
          'from vehicle_sim.config import read_yaml\n'
          'print(vehicle_sim.__file__)\n'
          'print(read_yaml.__module__)\n')


def _beside_a_checkout(tmp_path, *python_flags):
    os.symlink(REPO_ROOT, tmp_path / 'vehicle_sim', target_is_directory=True)
    (tmp_path / 'train.py').write_text(SCRIPT, encoding='utf-8')
    return subprocess.run([sys.executable, *python_flags, 'train.py'], cwd=tmp_path,
                          capture_output=True, text=True, timeout=RUN_TIMEOUT_S)


def _installed_package_file(tmp_path):
    # what this environment imports from a folder with no checkout in it: the editable install
    # of this checkout here, a colcon-installed copy first on PYTHONPATH in a sourced workspace
    elsewhere = tmp_path / 'elsewhere'
    elsewhere.mkdir()
    result = subprocess.run(
        [sys.executable, '-c', 'import vehicle_sim; print(vehicle_sim.__file__)'],
        cwd=elsewhere, capture_output=True, text=True, timeout=RUN_TIMEOUT_S)
    assert result.returncode == 0, result.stderr
    return result.stdout.strip()


def test_a_script_beside_the_checkout_imports_the_installed_package(tmp_path):
    installed = _installed_package_file(tmp_path)
    result = _beside_a_checkout(tmp_path)
    assert result.returncode == 0, result.stderr
    package_file, module = result.stdout.splitlines()
    assert os.path.realpath(package_file) == os.path.realpath(installed)
    assert installed.endswith(os.path.join('vehicle_sim', '__init__.py'))
    assert module == 'vehicle_sim.config'


def test_without_an_installed_package_the_error_says_what_happened_and_what_to_do(tmp_path):
    # -S: no site-packages, -E: no PYTHONPATH (a sourced ROS workspace's), so no vehicle_sim
    # installed (nor anything else); the script's folder still comes first.
    result = _beside_a_checkout(tmp_path, '-S', '-E')
    assert result.returncode == 1
    checkout = tmp_path / 'vehicle_sim'
    assert result.stderr.strip().splitlines()[-1] == (
        f'ImportError: vehicle_sim is not installed, and Python took the folder {checkout} '
        f'for it: a vehicle_sim checkout beside the script being run (Python looks in '
        f"the script's folder, {tmp_path}, first). Install it (pip install -e {checkout}), "
        'or run the script from another folder')
