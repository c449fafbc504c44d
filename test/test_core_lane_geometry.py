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
The road surface, markings and barriers of a lane map, against areas computed by hand.

The road: 30 m along +x, two lanes forward, one backward, 3.5 m lanes (10.5 m wide).
"""

import numpy as np
import pytest

from vehicle_sim.core.map.lane_geometry import (
    barriers,
    LINE_WIDTH_M,
    marking_mesh,
    MARKING_Z_M,
    surface_mesh,
)
from vehicle_sim.core.map.road_segments import lane_graph_from_roads, roads_from_list


def _graph(**road):
    data = dict({'lanes': 2, 'backward_lanes': 1,
                 'segments': [{'type': 'straight', 'length': 30.0}]}, **road)
    return lane_graph_from_roads(roads_from_list([data], 'roads'), 'roads')


def _signed_areas(mesh):
    a, b, c = (mesh.vertices[mesh.triangles[:, k], :2] for k in range(3))
    ab, ac = b - a, c - a
    return 0.5 * (ab[:, 0] * ac[:, 1] - ab[:, 1] * ac[:, 0])


def test_surface_covers_every_lane_with_upward_triangles():
    mesh = surface_mesh(_graph())
    areas = _signed_areas(mesh)
    assert np.all(areas > 0.0)                       # counter-clockwise: normals up
    assert areas.sum() == pytest.approx(3 * 3.5 * 30.0)
    assert mesh.vertices[:, 1].min() == pytest.approx(-7.0)
    assert mesh.vertices[:, 1].max() == pytest.approx(3.5)


def test_markings_paint_solid_lines_whole_and_dashed_lines_three_in_nine_metres():
    mesh = marking_mesh(_graph())
    # two solid edges and a solid centre line, 30 m each; the dashed line between the forward
    # lanes: dashes at 0, 9, 18, 27 m, each 3 m: 12 m
    painted_m = 3 * 30.0 + 12.0
    assert _signed_areas(mesh).sum() == pytest.approx(painted_m * LINE_WIDTH_M)
    assert np.all(mesh.vertices[:, 2] == MARKING_Z_M)
    double = marking_mesh(_graph(centre_line='solid_solid'))
    assert _signed_areas(double).sum() == pytest.approx((painted_m + 30.0) * LINE_WIDTH_M)


def test_curbstone_edges_are_barriers_not_paint():
    graph = _graph(edge_line='curbstone')
    found = barriers(graph)
    assert sorted((b.y0_m, b.line_type, b.height_m) for b in found) == [
        (-7.0, 'curbstone', 0.15), (3.5, 'curbstone', 0.15)]
    assert _signed_areas(marking_mesh(graph)).sum() == pytest.approx(42.0 * LINE_WIDTH_M)
    assert barriers(_graph()) == ()
