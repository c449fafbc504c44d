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

"""The raster of what is drawn on the ground (core/map/surface_raster.py)."""

import numpy as np

from vehicle_sim.core.map import surface_raster
from vehicle_sim.core.map.surface_raster import SurfaceRaster

QUAD = np.array([[0, 1, 2], [0, 2, 3]])


def quad(x0, y0, x1, y1):
    return np.array([[x0, y0, 0.0], [x1, y0, 0.0], [x1, y1, 0.0], [x0, y1, 0.0]])


def test_the_last_layer_drawn_wins_and_a_thin_line_marks_the_cells_it_crosses():
    raster = SurfaceRaster([(1, quad(0, 0, 10, 4), QUAD),
                            (2, quad(0, 1.925, 10, 2.075), QUAD[:, ::-1])])   # clockwise too
    assert raster.labels_at([5.0, 5.0, 5.0, 5.0, 9.9, 10.3, -0.3],
                            [1.0, 2.0, 1.92, 3.9, 0.05, 2.0, 2.0]).tolist() == \
        [1, 2, 2, 1, 1, 0, 0]
    assert raster.cell_m == surface_raster.CELL_M


def test_a_long_diagonal_strip_is_drawn_along_its_whole_length_and_no_wider():
    strip = np.array([[0.0, 0.0, 0.0], [200.0, 200.0, 0.0], [200.0, 200.3, 0.0],
                      [0.0, 0.3, 0.0]])
    raster = SurfaceRaster([(3, strip, QUAD)])
    along = np.linspace(1.0, 199.0, 500)
    assert set(raster.labels_at(along, along + 0.15).tolist()) == {3}
    assert set(raster.labels_at(along, along + 0.6).tolist()) == {0}
    assert set(raster.labels_at(along, along - 0.3).tolist()) == {0}


def test_a_large_map_gets_coarser_cells_within_the_cap(monkeypatch):
    monkeypatch.setattr(surface_raster, 'MAX_CELLS', 10_000)
    raster = SurfaceRaster([(1, quad(0, 0, 100, 50), QUAD)])
    assert raster.labels_at([50.0, 150.0], [25.0, 25.0]).tolist() == [1, 0]
    assert raster.cell_m > surface_raster.CELL_M
    assert raster._raster().size <= 10_000


def test_nothing_drawn_reads_zero():
    assert SurfaceRaster([]).labels_at([0.0], [0.0]).tolist() == [0]
