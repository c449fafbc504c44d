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
A bad map stops the automobile node at start, naming the file and the field; nothing starts.

Each case writes the room of test/map_helpers.py with one thing wrong and starts the node on a
world using it: the node exits with status 2 before announcing itself ready, and its one-line
error names the file (the world file or the map YAML) and the field.
"""

from automobile_helpers import NodeProcess
from map_helpers import world_data, write_map
import pytest
import yaml

from vehicle_sim.config import world_from_data
from vehicle_sim.core.map.occupancy import MAX_CELLS
from vehicle_sim.core.specs.errors import InvalidParameterError

pytestmark = pytest.mark.transport


def _missing_image(folder):
    path = write_map(folder)
    (folder / 'room.pgm').unlink()
    return path, 'room.yaml', "field 'image' = ", 'does not exist'


def _unreadable_image(folder):
    path = write_map(folder)
    (folder / 'room.pgm').write_bytes(b'this is no image\n' * 10)
    return path, 'room.yaml', "field 'image' = ", 'cannot read it as an image'


def _too_large(folder):
    path = write_map(folder)
    # A PGM header claiming 6000 x 5000 pixels: refused from the header, before any pixel.
    (folder / 'room.pgm').write_bytes(b'P5\n6000 5000\n255\n' + bytes(1000))
    return path, 'room.yaml', "field 'image' = ", f'more than the {MAX_CELLS} cells'


def _no_resolution(folder):
    return write_map(folder, resolution=None), 'room.yaml', "field 'resolution'", 'is required'


def _negative_resolution(folder):
    return (write_map(folder, resolution=-0.05), 'room.yaml', "field 'resolution' = -0.05",
            'must be > 0')


def _thresholds_crossed(folder):
    return (write_map(folder, occupied_thresh=0.2, free_thresh=0.25), 'room.yaml',
            "field 'occupied_thresh' = 0.2", 'must be > free_thresh (0.25)')


def _missing_yaml(folder):
    path = write_map(folder)
    path.unlink()
    return path, 'world.yaml', "map: field 'file' = ", 'does not exist'


CASES = [_missing_image, _unreadable_image, _too_large, _no_resolution, _negative_resolution,
         _thresholds_crossed, _missing_yaml]


def _write_world(folder, map_path, pose=(0.0, 0.0, 0.0)):
    path = folder / 'world.yaml'
    path.write_text(yaml.safe_dump(world_data(map_path.name, pose=pose)), encoding='utf-8')
    return path


def _refused_at_start(world_path):
    process = NodeProcess('--ros-args', '-r', '__ns:=/bad_map', '-p', f'world:={world_path}')
    try:
        status = process.wait()
    finally:
        process.stop()
    output = process.text()
    assert status == 2, output
    assert 'ready' not in output and 'Traceback' not in output, output
    return output


@pytest.mark.parametrize('case', CASES, ids=lambda case: case.__name__.strip('_'))
def test_a_bad_map_stops_the_node_at_start_naming_file_and_field(tmp_path, case):
    map_path, file_name, field, reason = case(tmp_path)
    world = _write_world(tmp_path, map_path)
    output = _refused_at_start(world)
    assert str(tmp_path / file_name) in output, output
    assert field in output and reason in output, output
    assert output.count(field) == 1, output        # one refusal, not one wrapped in another


def test_a_spawn_on_an_occupied_cell_stops_the_node_naming_the_vehicle_pose(tmp_path):
    world = _write_world(tmp_path, write_map(tmp_path), pose=(6.4, 2.4, 0.0))   # the pillar
    output = _refused_at_start(world)
    assert f"{world}: vehicles[0] (car): field 'pose'" in output, output
    assert 'occupied cell' in output, output


@pytest.mark.parametrize('value, fragment', [
    ({'type': 'occupancy_grid'}, "map: field 'file' is required"),
    ({'type': 'lanes', 'file': 'x.yaml'}, "map: field 'type' = 'lanes': unknown; valid: "),
    ({'type': 'occupancy_grid', 'file': 'm.yaml', 'wall_height': 0.0},
     "map: field 'wall_height' = 0.0: must be > 0"),
    ({'type': 'occupancy_grid', 'file': 'm.yaml', 'unknown': 'maybe'},
     "map: field 'unknown' = 'maybe'"),
    ('track.yaml', 'map: must be a mapping with a "type"'),
])
def test_a_bad_map_key_is_refused_when_the_world_is_read(value, fragment):
    with pytest.raises(InvalidParameterError) as refused:
        world_from_data({'vehicles': [{'name': 'car'}], 'map': value}, '/w/world.yaml')
    assert f'/w/world.yaml: {fragment}' in str(refused.value)
