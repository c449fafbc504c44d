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
The race track lapped: scenarios/race_track_lap.yaml runs examples/race_track_controller.py.

The controller (a lidar "follow the gap") drives the race_track world's CitroenCZero; the run
is judged by the scenario's criteria and, here, by its track: the distance driven to the lap
goal, and every footprint corner on a free cell of the map.
"""

import math
from pathlib import Path

import pytest

from vehicle_sim.core.map.kinds import map_from_dict
from vehicle_sim.core.map.occupancy import wall_mask
from vehicle_sim.maps.occupancy_files import load_occupancy_grid
from vehicle_sim.scenarios.runner import run_scenario

pytest.importorskip('PIL', reason="the race track's map is a PNG: pip install "
                                  "'vehicle_sim[maps]'")

ROOT = Path(__file__).resolve().parent.parent
LAP = ROOT / 'scenarios' / 'race_track_lap.yaml'
MAP = ROOT / 'config' / 'maps' / 'race_track.yaml'
CENTRELINE_M = 190.25          # config/maps/make_track.py's smoothed centreline, closed


@pytest.fixture(scope='module')
def lap():
    return run_scenario(LAP)


def test_the_controller_laps_the_track_touching_no_wall(lap):
    assert lap.error is None
    assert lap.passed, [c.detail for c in lap.failures]
    assert lap.criterion('no_collision').value == 0
    # Round the track in order: a quarter, half, three quarters, then behind the start line.
    times = [lap.criterion(name).value for name in ('quarter', 'half', 'three_quarters', 'lap')]
    assert times == sorted(times) and times[-1] < 40.0


def test_the_lap_covers_the_track_length_and_ends_near_the_start(lap):
    track = lap.tracks['Car']
    done = next(i for i, t in enumerate(track.time_s) if t >= lap.criterion('lap').value)
    driven_m = sum(math.hypot(track.x_m[i + 1] - track.x_m[i], track.y_m[i + 1] - track.y_m[i])
                   for i in range(done))
    # The centreline less the corners it cuts (inside lines on a 7 m wide track), short of the
    # start line by the lap goal's 8.5 m and its radius.
    assert 0.85 * CENTRELINE_M < driven_m < CENTRELINE_M
    # On the start straight (7 m wide), behind the start line (x = 0), heading along +x.
    assert track.x_m[done] < 0.0 and abs(track.y_m[done]) < 3.5
    assert abs(math.remainder(track.yaw_rad[done], 2.0 * math.pi)) < 0.5


def test_every_footprint_corner_stays_on_a_free_cell(lap):
    spec = map_from_dict({'type': 'occupancy_grid', 'file': str(MAP)}, 'race_track')
    _, grid = load_occupancy_grid(spec)
    walls = wall_mask(grid, False)
    track = lap.tracks['Car']
    on_walls = []
    for t, x, y, yaw in zip(track.time_s, track.x_m, track.y_m, track.yaw_rad):
        for corner in track.outline.corners(x, y, yaw):
            cell = grid.cell_at(*corner)
            if cell is None or walls[cell]:
                on_walls.append((t, corner))
    assert on_walls == []
