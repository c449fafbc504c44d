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
Lanelet2 maps as lane graphs: a map the test writes (OSM XML), read with the lanelet2 package.

The map, its ids and its two kinds of coordinates are drawn in test/lane_helpers.py.
"""

import math
import sys

from lane_helpers import DEFAULT_MPS, LOCAL_SHIFT, ORIGIN, write_map
import pytest

from vehicle_sim.core.geometry.geodesy import GeodeticOrigin
from vehicle_sim.core.map.lane_invasion import LaneInvasionDetector
from vehicle_sim.core.map.lane_state import LaneTracker
from vehicle_sim.core.map.lanelet2_params import lanelet2_map_from_dict
from vehicle_sim.core.specs.errors import InvalidParameterError

pytest.importorskip('lanelet2', reason="lanelet2 is not installed (pip install "
                                       "'vehicle_sim[lanelet2]'; the test extra has it)")

from vehicle_sim.maps.lanelet2_map import (  # noqa: E402  (after the skip)
    lane_graph_from_map,
    Lanelet2Unavailable,
    line_type_of,
    load_lanelet2,
)


@pytest.fixture(scope='module')
def osm(tmp_path_factory):
    return write_map(tmp_path_factory.mktemp('lanelet2') / 'town.osm')


@pytest.fixture(scope='module')
def loaded(osm):
    return load_lanelet2(str(osm), ORIGIN, 'local_cartesian', DEFAULT_MPS)


def test_a_point_at_s_10_on_a_lanelet_reads_its_id_and_offset_zero(loaded):
    graph = loaded[0]
    found = graph.locate(10.0, 1.75, 0.0)          # lanelet 2001's centreline is y = 1.75
    assert found.lane_id == 2001
    assert found.offset_m == pytest.approx(0.0, abs=0.01)
    assert found.s_m == pytest.approx(10.0, abs=0.01)
    assert found.width_m == pytest.approx(3.5, abs=0.01)
    state = LaneTracker(graph).update(10.0, 1.75, 0.0)
    assert (state.lane_id, round(state.offset_m, 2), round(state.s_m, 2)) == (2001, 0.0, 10.0)
    x, y, _ = graph.pose_at(2001, 10.0, 0.0)
    assert (x, y) == (pytest.approx(10.0, abs=0.01), pytest.approx(1.75, abs=0.01))


def test_successors_and_neighbours_equal_the_routing_graphs(loaded):
    graph, lanelet_map, routing = loaded

    def lane_id(lanelet):
        return -lanelet.id if lanelet.inverted() else lanelet.id

    lanelets = list(lanelet_map.laneletLayer)
    lanelets += [ll.invert() for ll in lanelets if ll.id == 2005]
    assert sorted(graph.lanes) == [-2005, 2001, 2002, 2003, 2004, 2005]
    for lanelet in lanelets:
        lane = graph.lanes[lane_id(lanelet)]
        assert set(lane.successors) == {lane_id(f) for f in routing.following(lanelet)}
        for side in ('left', 'right'):
            change = getattr(routing, side)(lanelet)
            adjacent = getattr(routing, 'adjacent' + side.title())(lanelet)
            expected = change if change is not None else adjacent
            assert getattr(lane, side + '_lane') == (None if expected is None
                                                     else lane_id(expected))
            assert getattr(lane, side + '_change') == (change is not None)
    # the map as drawn: 2001 -> 2003 -> 2005; a change 2001 <-> 2002 across the dashed line;
    # 2003 and 2004 side by side behind a solid line (neighbours, no change)
    lanes = graph.lanes
    assert lanes[2001].successors == (2003,) and lanes[2003].successors == (2005,)
    assert (lanes[2001].left_lane, lanes[2001].left_change) == (2002, True)
    assert (lanes[2003].left_lane, lanes[2003].left_change) == (2004, False)
    assert lanes[-2005].successors == ()


def test_speed_limits_come_from_the_tag_or_the_default(loaded):
    graph = loaded[0]
    assert graph.lanes[2004].speed_limit_mps == pytest.approx(30.0 / 3.6)
    assert graph.lanes[2001].speed_limit_mps == DEFAULT_MPS


def test_line_types_come_from_the_line_strings_tags(loaded):
    graph = loaded[0]
    assert graph.lanes[2001].left.line_type == 'dashed'
    assert graph.lanes[2001].right.line_type == 'solid'
    assert graph.lanes[2005].right.line_type == 'curbstone'
    assert line_type_of({'type': 'line_thick', 'subtype': 'solid_dashed'}) == 'solid_dashed'
    assert line_type_of({'type': 'fence'}) == 'wall'
    assert line_type_of({'type': 'virtual'}) == 'virtual'
    assert line_type_of({}) == 'none'


def test_a_path_across_the_dashed_line_gives_one_invasion_naming_it(loaded):
    detector = LaneInvasionDetector(loaded[0])
    events = []
    for step in range(41):            # from (10, 1.75) on 2001 to (30, 5.75) on 2002
        events += detector.update(10.0 + 0.5 * step, 1.75 + 0.1 * step, 0.05 * step)
    assert [(e.boundary_id, e.line_type) for e in events] == [(1002, 'dashed')]
    assert events[0].y_m == pytest.approx(3.5, abs=0.01)


def test_autoware_local_projector_reads_the_local_tags(osm):
    graph = load_lanelet2(str(osm), ORIGIN, 'autoware_local', DEFAULT_MPS)[0]
    found = graph.locate(10.0 + LOCAL_SHIFT[0], 1.75 + LOCAL_SHIFT[1], 0.0)
    assert found.lane_id == 2001
    assert found.offset_m == pytest.approx(0.0, abs=1e-6)
    assert found.s_m == pytest.approx(10.0, abs=1e-6)
    assert graph.locate(10.0, 1.75, 0.0) is None      # lat/lon are not used


def test_local_cartesian_projector_matches_the_worlds_east_north_up_plane(loaded):
    start = loaded[0].lanes[2002].centerline[0]
    assert start.tolist() == [pytest.approx(0.0, abs=1e-3), pytest.approx(5.25, abs=1e-3)]


def test_utm_projector_turns_the_map_by_the_meridian_convergence(osm):
    # UTM zone 32 (central meridian 9 deg E): at 48.1 N, 11.5 E true east points
    # atan(tan(2.5 deg) sin(48.1 deg)) = 1.861 deg left of grid east; the scale there is
    # 0.9996 (1 + (2.5 deg cos(48.1 deg))^2 / 2) = 1.000025
    graph = load_lanelet2(str(osm), ORIGIN, 'utm', DEFAULT_MPS)[0]
    lane = graph.lanes[2001]
    (x0, y0), (x1, y1) = lane.centerline[0], lane.centerline[-1]
    convergence = math.degrees(math.atan(math.tan(math.radians(2.5))
                                         * math.sin(math.radians(48.1))))
    assert math.degrees(math.atan2(y1 - y0, x1 - x0)) == pytest.approx(convergence, abs=0.01)
    assert lane.length_m == pytest.approx(50.0 * 1.000025, abs=0.002)


def test_a_world_map_entry_loads_relative_to_the_world_file(osm):
    spec = lanelet2_map_from_dict({'type': 'lanelet2', 'file': osm.name,
                                   'projector': 'autoware_local'}, 'w.yaml: map')
    graph = lane_graph_from_map(spec, str(osm.parent / 'w.yaml'), ORIGIN)
    assert 2001 in graph.lanes


@pytest.mark.parametrize('data, match', [
    ({'type': 'lanelet2'}, "w.yaml: map: field 'file' is required"),
    ({'type': 'lanelet2', 'file': 'a.osm', 'projector': 'mgrs'},
     "field 'projector' = 'mgrs': must be one of local_cartesian, utm, autoware_local"),
    ({'type': 'lanelet2', 'file': 'a.osm', 'default_speed_limit': 0.0},
     "field 'default_speed_limit' = 0.0: must be > 0"),
])
def test_bad_map_entries_are_refused_naming_the_field(data, match):
    with pytest.raises(InvalidParameterError, match=match):
        lanelet2_map_from_dict(data, 'w.yaml: map')


def test_bad_files_are_refused_naming_the_file(tmp_path):
    text = tmp_path / 'notes.osm'
    text.write_text('these are not lanes\n', encoding='utf-8')
    gpx = tmp_path / 'track.osm'
    gpx.write_text('<?xml version="1.0"?>\n<gpx version="1.1"></gpx>\n', encoding='utf-8')
    bare = write_map(tmp_path / 'bare.osm', lanelets=False)
    untagged = write_map(tmp_path / 'untagged.osm', local_tags=False)
    cases = [
        (text, 'local_cartesian', r'notes.osm: not an OSM file \(not XML'),
        (gpx, 'local_cartesian', r'track.osm: not an OSM file \(its root element is <gpx>'),
        (bare, 'local_cartesian', 'bare.osm: has no lanelets'),
        (tmp_path / 'missing.osm', 'utm', 'missing.osm: no such file'),
        (untagged, 'autoware_local', r'untagged.osm: node 100 has no local_x/local_y tags'),
    ]
    for path, projector, match in cases:
        with pytest.raises(InvalidParameterError, match='w.yaml: map.file: .*' + match):
            load_lanelet2(str(path), ORIGIN, projector, DEFAULT_MPS, 'w.yaml: map.file')


# What the refusals below tell the user to write.
ORIGIN_HINT = ("set the world file's origin: near the map, e.g. origin: {latitude: 48.1, "
               "longitude: 11.5} (or, its nodes having local_x/local_y tags, the map's "
               'projector: autoware_local)')


def test_a_map_far_from_the_worlds_origin_is_refused_naming_the_origin_key(osm):
    # A world file without origin: (latitude 0, longitude 0) and the map at 48.1 N, 11.5 E:
    # on that origin's east-north-up plane its lanes would lie 4800 km away.
    with pytest.raises(InvalidParameterError) as refused:
        load_lanelet2(str(osm), GeodeticOrigin(), 'local_cartesian', DEFAULT_MPS,
                      'w.yaml: map.file')
    assert str(refused.value) == (
        f"w.yaml: map.file: {osm}: its lanes lie 4,800 km from the world's origin (latitude 0, "
        "longitude 0) with projector 'local_cartesian', which places the map's lat/lon around "
        f'that origin: {ORIGIN_HINT}')


def test_a_map_outside_the_utm_zone_of_the_worlds_origin_is_refused_naming_the_key(osm):
    with pytest.raises(InvalidParameterError) as refused:
        load_lanelet2(str(osm), GeodeticOrigin(), 'utm', DEFAULT_MPS, 'w.yaml: map.file')
    assert str(refused.value) == (
        f"w.yaml: map.file: {osm}: its nodes lie outside the UTM zone of the world's origin "
        "(latitude 0, longitude 0), as lanelet2 says: 'Latitude 48.1, longitude 11.5 out of "
        f"legal range for UTM zone 31': {ORIGIN_HINT}")


def test_a_map_near_the_worlds_origin_is_taken(osm):
    near = GeodeticOrigin(ORIGIN.latitude_deg + 0.5, ORIGIN.longitude_deg, 0.0)   # 56 km north
    graph = load_lanelet2(str(osm), near, 'local_cartesian', DEFAULT_MPS)[0]
    assert graph.lanes[2001].centerline[0][1] == pytest.approx(-55600.0, abs=200.0)


def test_without_lanelet2_the_error_names_the_extra(monkeypatch, osm):
    monkeypatch.setitem(sys.modules, 'lanelet2', None)
    with pytest.raises(Lanelet2Unavailable, match=r"pip install 'vehicle_sim\[lanelet2\]'"):
        load_lanelet2(str(osm), ORIGIN)
