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

The area is the part of the repository the file tests: a package of vehicle_sim (core, physics,
webots, ros, transport, scenario(s), sweep, foxglove, gym, record, tools, testing), the
``vehicle-sim`` command (cli), the configuration files (config), the interface definitions
(msgs, vehicle_msgs_py), the maps across their layers (map: occupancy and lane maps, map files,
walls, /map; vehicle_sim/maps and core/map), or the repository as a whole (repo: licence
headers, packaging, text, cross-layer registrations).
"""

from pathlib import Path

AREAS = ('core', 'physics', 'webots', 'ros', 'transport', 'scenario', 'sweep', 'foxglove',
         'gym', 'record', 'tools', 'testing', 'cli', 'config', 'msgs', 'map', 'repo')
TEST_DIR = Path(__file__).resolve().parent


def test_every_test_file_is_named_test_area_subject():
    names = sorted(path.stem for path in TEST_DIR.glob('test_*.py'))
    assert len(names) > 50
    stray = [name for name in names
             if not any(name.startswith(f'test_{area}_') for area in AREAS)]
    assert stray == []
