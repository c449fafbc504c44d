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
What ``vehicle-sim run`` says at start: the map it loaded, or why it refused the world.

Each line is checked word for word: counts agree with their nouns ('1 wall rectangle'), a
world's roads are named once, and a refused start names the world file.
"""

import os
import subprocess
import sys

from conftest import peer_env, REPO_ROOT
from map_helpers import world_data, write_map
import numpy as np
import pytest
import yaml

pytestmark = pytest.mark.transport

# Generous bound for one run: interpreter start, discovery, one second of simulation.
RUN_TIMEOUT_S = 60.0
READY = 'automobile ready'


def _run(world):
    return subprocess.run([sys.executable, '-m', 'vehicle_sim', 'run', '--no-status',
                           '--duration', '1', '--world', str(world)],
                          env=peer_env(), capture_output=True, text=True, timeout=RUN_TIMEOUT_S)


def _logged(stderr, start):
    # The log lines' texts (after '[node]: ') that begin with ``start``.
    texts = [line.split(']: ', 1)[-1] for line in stderr.splitlines()]
    return [text for text in texts if text.startswith(start)]


def _write_world(tmp_path, data):
    path = tmp_path / 'world.yaml'
    path.write_text(yaml.safe_dump(data), encoding='utf-8')
    return path


def test_a_map_of_one_wall_rectangle_says_rectangle_in_the_singular(tmp_path):
    pixels = np.full((100, 100), 254, dtype=np.uint8)
    pixels[:4, :4] = 0                        # one 4 x 4 block in the top-left corner
    map_file = write_map(tmp_path, pixels, origin=[-5.0, -5.0, 0.0])
    result = _run(_write_world(tmp_path, world_data(map_file)))
    assert READY in result.stderr, result.stderr
    assert _logged(result.stderr, 'map ') == [
        f'map {map_file}: 100 x 100 cells (10 x 10 m), 1 wall rectangle; publishing /map, '
        '/map_metadata']


def test_a_world_with_roads_names_its_file_and_roads_once():
    world = os.path.join(REPO_ROOT, 'config', 'worlds', 'highway.yaml')
    result = _run(world)
    assert READY in result.stderr, result.stderr
    assert _logged(result.stderr, world) == [
        f'{world}: roads: 30 lanes, 35 boundaries, 0 barrier pieces; publishing /map/lanes']
    assert _logged(result.stderr, 'roads ') == []


def test_a_car_whose_outline_overlaps_a_wall_is_refused_naming_the_world_file(tmp_path):
    # base_link in free space, the car's nose (4.5 m ahead) in the room's east wall
    world = _write_world(tmp_path, world_data(write_map(tmp_path), pose=(7.0, -4.0, 0.0)))
    result = _run(world)
    assert result.returncode == 2, result.stderr
    assert result.stderr.strip().splitlines()[-1] == (
        f"vehicle-sim run: {world}: vehicle 'car' starts inside 'map': its start pose must be "
        'clear of every wall (as set_pose requires)')
    assert READY not in result.stderr
