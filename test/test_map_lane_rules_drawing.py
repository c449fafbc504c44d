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
A lane map's rules drawn: stop lines, crosswalks and areas on the road, in RViz and Foxglove.

The map is lane_helpers.signal_crossing: lane 1 east to x = 0, its stop line 101 across it at
x = -2; lane 3's stop line 102 at y = -12; a crosswalk (501) over lane 2 at x 4 .. 7 (the road
3.5 m wide, y -1.75 .. 1.75); a parking area (502) at x -15 .. -5, y -9 .. -4.
"""

import math
from pathlib import Path

from lane_helpers import BULB_Z, CROSSWALK, PARKING, signal_crossing
import numpy as np
import pybullet
import pytest

from vehicle_msgs_py import message_type
from vehicle_sim.config import load_world
from vehicle_sim.core.map.lane_geometry import (
    area_color,
    AREA_COLORS,
    area_meshes,
    crosswalk_mesh,
    MARKING_Z_M,
    OTHER_AREA_COLOR,
    PAINT_COLOR,
    polygon_triangles,
    stop_line_mesh,
    STOP_LINE_WIDTH_M,
    zebra_stripes,
)
from vehicle_sim.core.map.signal_lamps import DARK_LAMP_COLOR, LAMP_COLORS, LAMP_RADIUS_M
from vehicle_sim.foxglove import map_scene
from vehicle_sim.physics import World
from vehicle_sim.physics.lane_layer import build_lane_bodies, SURFACE_COLOR
from vehicle_sim.physics.scene import build_scene
from vehicle_sim.ros.lane_messages import (
    lane_markers_builder,
    LINE_STRIP,
    SPHERE_LIST,
    traffic_light_markers_builder,
    TRIANGLE_LIST,
)


def _area(points, triangles):
    a, b, c = (points[triangles[:, k], :2] for k in range(3))
    (ux, uy), (vx, vy) = (b - a).T, (c - a).T
    return 0.5 * (ux * vy - uy * vx)


# ------------------------------------------------------------------------------ geometry

def test_a_stop_line_is_a_white_bar_of_its_width_along_its_points():
    mesh = stop_line_mesh(signal_crossing())
    first = mesh.vertices[:4]                      # line 101: (-2, -1.75) .. (-2, 1.75)
    assert sorted(set(np.round(first[:, 0], 9))) == [-2.0 - STOP_LINE_WIDTH_M / 2,
                                                     -2.0 + STOP_LINE_WIDTH_M / 2]
    assert sorted(set(np.round(first[:, 1], 9))) == [-1.75, 1.75]
    assert np.all(mesh.vertices[:, 2] == MARKING_Z_M)
    assert _area(mesh.vertices, mesh.triangles).sum() == pytest.approx(
        2 * 3.5 * STOP_LINE_WIDTH_M)


def test_zebra_stripes_run_along_the_road_spaced_across_it_and_stay_inside():
    stripes = zebra_stripes(CROSSWALK)
    spans = [(round(s[:, 1].min(), 9), round(s[:, 1].max(), 9)) for s in stripes]
    assert spans == [(-1.75, -1.25), (-0.75, -0.25), (0.25, 0.75), (1.25, 1.75)]
    assert all((s[:, 0].min(), s[:, 0].max()) == (4.0, 7.0) for s in stripes)
    # a slanted crosswalk (a parallelogram): every stripe corner inside it
    slanted = np.array([(0.0, 0.0), (3.0, 0.0), (5.0, 8.0), (2.0, 8.0)])
    for stripe in zebra_stripes(slanted):
        for x, y in stripe:
            assert 0.0 - 1e-9 <= y <= 8.0 + 1e-9
            assert y / 4.0 - 1e-9 <= x <= 3.0 + y / 4.0 + 1e-9


def test_areas_are_their_polygons_flat_in_their_kinds_colour_and_concave_ones_too():
    meshes = area_meshes(signal_crossing())
    assert list(meshes) == ['parking'] and AREA_COLORS['parking'] != PAINT_COLOR
    assert _area(meshes['parking'].vertices, meshes['parking'].triangles).sum() == \
        pytest.approx(50.0)
    # an L (concave), either winding: every triangle upwards, the L's area
    ell = [(0, 0), (4, 0), (4, 1), (1, 1), (1, 3), (0, 3)]
    for points in (np.array(ell, float), np.array(ell[::-1], float)):
        triangles = polygon_triangles(points)
        areas = _area(points, triangles)
        assert len(triangles) == 4 and np.all(areas > 0) and areas.sum() == pytest.approx(6.0)
    angles = np.linspace(0.0, 2.0 * np.pi, 100, endpoint=False)       # a star: 50 reflex corners
    radius = np.where(np.arange(100) % 2, 10.0, 6.0)
    star = np.column_stack((radius * np.cos(angles), radius * np.sin(angles)))
    areas = _area(star, polygon_triangles(star))
    x, y = star.T
    assert len(areas) == 98 and np.all(areas > 0)
    assert areas.sum() == pytest.approx(0.5 * (x @ np.roll(y, -1) - y @ np.roll(x, -1)))
    assert len(polygon_triangles([(0, 0), (1, 1), (2, 2)])) == 0       # no area, no triangle


def test_the_first_try_ears_are_the_general_loops_triangles_or_none():
    # polygon_triangles takes the ears of a small polygon in plain floats where each is found at
    # its first try: the same triangles, index for index, as the general loop's, or it defers.
    from vehicle_sim.core.map import lane_geometry
    rng = np.random.default_rng(3)
    taken = deferred = 0
    for trial in range(3000):
        n = int(rng.integers(3, 13))
        angles = np.sort(rng.uniform(0.0, 2.0 * np.pi, n))
        radius = rng.uniform(0.5, 2.0, n) if trial % 3 == 1 else np.ones(n)     # star-shaped
        points = np.column_stack((radius * np.cos(angles), radius * np.sin(angles)))
        points *= rng.uniform(0.01, 100.0)
        if trial % 3 == 2:      # a rectangle with a collinear corner, clockwise or not, rounded
            w, h = rng.uniform(0.1, 5.0, 2)
            points = np.round([(0, 0), (w / 2, 0), (w, 0), (w, h), (0, h)],
                              int(rng.integers(0, 4)))[::int(rng.choice((1, -1)))]
        x, y = points.T
        area = 0.5 * (x @ np.roll(y, -1) - y @ np.roll(x, -1))
        if abs(area) < 1e-9:
            continue
        order = list(range(n if trial % 3 != 2 else 5))
        order = order if area > 0 else order[::-1]
        first = lane_geometry._first_try_ears(points.tolist(), order)
        general = lane_geometry._clip_ears(points, order)
        assert np.array_equal(polygon_triangles(points), np.array(general).reshape(-1, 3))
        if first is None:
            deferred += 1
        else:
            taken += 1
            assert first == general, points
    assert taken > 1000 and deferred > 500        # both ways were tried


# ------------------------------------------------------------------------------ physics

TOP_PX, TOP_FOV_DEG, TOP_HEIGHT_M = 400, 60.0, 30.0
TOP_CENTRE = (-2.0, -3.0)


def _top_view(world, centre=TOP_CENTRE, height_m=TOP_HEIGHT_M):
    """Render the ground from ``height_m`` above ``centre``; return ``pixel(x, y)`` -> RGB."""
    world.prepare_render()          # the lamps are made when the world is first drawn
    cid = world.client_id
    cx, cy = centre
    view = pybullet.computeViewMatrix((cx, cy, height_m), (cx, cy, 0.0), (0.0, 1.0, 0.0),
                                     physicsClientId=cid)
    projection = pybullet.computeProjectionMatrixFOV(TOP_FOV_DEG, 1.0, 1.0, 100.0,
                                                     physicsClientId=cid)
    _, _, rgba, _, _ = pybullet.getCameraImage(
        TOP_PX, TOP_PX, view, projection, renderer=pybullet.ER_TINY_RENDERER,
        lightDirection=(0.0, 0.0, 1.0), flags=pybullet.ER_NO_SEGMENTATION_MASK,
        physicsClientId=cid)
    image = np.asarray(rgba, dtype=float).reshape(TOP_PX, TOP_PX, 4)[:, :, :3] / 255.0
    f = 0.5 * TOP_PX / math.tan(math.radians(TOP_FOV_DEG) / 2)

    def pixel(x, y):
        u = 0.5 * TOP_PX + f * (x - cx) / height_m
        v = 0.5 * TOP_PX - f * (y - cy) / height_m
        return image[int(v), int(u)]
    return pixel


def _hue(rgb):
    """Return the colour's chromaticity: RGB over its sum (shading only scales it)."""
    return np.asarray(rgb[:3]) / max(sum(rgb[:3]), 1e-9)


def test_the_camera_sees_the_stop_line_the_zebra_and_the_parking_area_on_the_road():
    with World() as world:
        world.show_ground()
        built = build_lane_bodies(world, signal_crossing())
        # the rules add two bodies: the parking area and the crosswalk's stripes (the lines'
        # white paint is one mesh, the crosswalks' another: their labels differ)
        assert len(built.visual_ids) == 4
        pixel = _top_view(world)
        white, asphalt = pixel(-2.0, 0.0), pixel(-3.0, 0.0)          # on / before the line
        # (the renderer shades both alike: paint 0.95 and asphalt 0.3 keep their ratio)
        assert white.min() > 2.5 * asphalt.max() and np.ptp(white) < 0.02
        assert pixel(-2.0, 0.0) == pytest.approx(pixel(-2.0, 1.0), abs=0.02)
        stripes = [pixel(5.5, y).min() for y in (-1.5, -1.0, -0.5, 0.0, 0.5, 1.0, 1.5)]
        painted = [value > 2.5 * asphalt.max() for value in stripes]
        assert painted == [True, False, True, False, True, False, True]
        parking = pixel(-10.0, -6.5)
        assert _hue(parking) == pytest.approx(_hue(AREA_COLORS['parking']), abs=0.02)
        assert _hue(asphalt) == pytest.approx(_hue(SURFACE_COLOR), abs=0.02)


def test_the_shipped_urban_map_shows_its_zebras_stop_lines_and_lamps():
    # config/worlds/urban.yaml (a Lanelet2 map in Autoware's format): crosswalk 301 spans the
    # southern arm (x -4.5 .. 4.5, y -14 .. -10); its stripes run along the road (y), 0.5 m
    # wide and apart across it (x). Four groups of three bulbs, each light on a pole off the
    # road.
    pytest.importorskip('lanelet2', reason="lanelet2 is not installed (pip install "
                                           "'vehicle_sim[lanelet2]'; the test extra has it)")
    scene = build_scene(load_world('urban'))
    try:
        rules = scene.lanes.rules
        assert sorted(a.id for a in rules.areas if a.kind == 'crosswalk') == [300, 301, 302, 303]
        lamps = scene.parts['signal_lamps']
        assert (len(lamps.lamps), len(lamps.poles)) == (12, 4)
        assert lamps.controller is scene.parts['signals'].controller
        scene.world.show_ground()
        pixel = _top_view(scene.world, centre=(0.0, -12.0), height_m=15.0)
        asphalt = pixel(0.0, -8.0)                    # inside the intersection, no paint
        # 9 stripes centred on the 9 m: at x = -4, -3, ..., 4; gaps at -3.5, ..., 3.5
        across = [pixel(x, -12.0).min() for x in np.arange(-4.0, 4.01, 0.5)]
        painted = [value > 2.5 * asphalt.max() for value in across]
        assert painted == [k % 2 == 0 for k in range(len(across))], across
        seen = [line.points.mean(axis=0) for line in rules.stop_lines
                if np.abs(line.points.mean(axis=0) - (0.0, -12.0)).max() < 8.0]
        assert seen and all(pixel(*middle).min() > 2.5 * asphalt.max() for middle in seen)
    finally:
        scene.world.close()


# ------------------------------------------------------------------------------ RViz

def test_map_lanes_markers_have_the_stop_lines_crosswalks_and_areas():
    stamp = message_type('builtin_interfaces/msg/Time')(sec=1, nanosec=0)
    array = lane_markers_builder(message_type, 'map')(stamp, signal_crossing())
    by_ns = {}
    for marker in array.markers:
        by_ns.setdefault(marker.ns, {})[marker.id] = marker
    lines = by_ns['stop_lines']
    assert sorted(lines) == [101, 102]
    assert lines[101].type == LINE_STRIP and lines[101].scale.x == STOP_LINE_WIDTH_M
    assert [(p.x, p.y) for p in lines[101].points] == [(-2.0, -1.75), (-2.0, 1.75)]
    (crosswalk,) = by_ns['crosswalks'].values()
    assert crosswalk.id == 501 and crosswalk.type == TRIANGLE_LIST
    points = np.array([(p.x, p.y) for p in crosswalk.points])
    assert len(points) == 4 * 2 * 3                 # four stripes, two triangles each
    assert points[:, 0].min() == 4.0 and points[:, 0].max() == 7.0
    (parking,) = by_ns['areas'].values()
    assert parking.id == 502 and parking.type == TRIANGLE_LIST
    assert (parking.color.r, parking.color.g, parking.color.b) == pytest.approx(
        AREA_COLORS['parking'][:3], abs=1e-6)
    corners = {(p.x, p.y) for p in parking.points}
    assert corners == {tuple(map(float, c)) for c in PARKING}
    heads = by_ns['traffic_lights']         # the static parts of the lights: housings, poles
    assert heads[0].type == heads[1].type == TRIANGLE_LIST
    assert len(heads[0].points) == 6 * 12 * 3          # a closed box per bulb
    assert len(heads[1].points) == 2 * 12 * 3          # a pole per light
    assert max(p.z for p in heads[1].points) == pytest.approx(BULB_Z['red'] + 0.18)
    data = array.serialize()
    assert type(array).deserialize(data).serialize() == data


def test_traffic_light_markers_show_each_bulb_in_its_groups_state():
    stamp = message_type('builtin_interfaces/msg/Time')(sec=1, nanosec=0)
    build = traffic_light_markers_builder(message_type, 'world', signal_crossing())
    array = build(stamp, {11: 'red', 12: 'green'})
    (bulbs,) = array.markers
    assert (bulbs.ns, bulbs.id, bulbs.type) == ('traffic_light_bulbs', 0, SPHERE_LIST)
    assert bulbs.scale.x == 2 * LAMP_RADIUS_M
    shown = {(p.x, p.y, p.z): (c.r, c.g, c.b) for p, c in zip(bulbs.points, bulbs.colors)}
    assert len(shown) == 6
    assert shown[(0.0, -2.6, 3.0)] == pytest.approx(LAMP_COLORS['red'][:3], abs=1e-6)
    assert shown[(0.0, -2.6, 2.2)] == pytest.approx(DARK_LAMP_COLOR[:3], abs=1e-6)
    assert shown[(12.6, -12.0, 2.2)] == pytest.approx(LAMP_COLORS['green'][:3], abs=1e-6)
    again = build(stamp, {11: 'green', 12: 'red'}).markers[0]
    assert again.colors[0].r == pytest.approx(DARK_LAMP_COLOR[0], abs=1e-6)
    data = array.serialize()
    assert type(array).deserialize(data).serialize() == data


# ------------------------------------------------------------------------------ Foxglove

def test_foxglove_lane_entities_have_the_stop_lines_crosswalks_areas_and_poles():
    entities = {e.id: e for e in map_scene.lane_map_entities(signal_crossing())}
    assert {'lanes/areas', 'lanes/stop_lines', 'lanes/crosswalks',
            'lanes/signal_poles'} <= set(entities)
    stop = entities['lanes/stop_lines'].lines
    assert [line.thickness_m for line in stop] == [STOP_LINE_WIDTH_M] * 2
    assert stop[0].points_m[:, :2].tolist() == [[-2.0, -1.75], [-2.0, 1.75]]
    (stripes,) = entities['lanes/crosswalks'].triangles
    expected = crosswalk_mesh(signal_crossing())
    assert np.array_equal(stripes.points_m, expected.vertices)
    assert stripes.color_rgba == PAINT_COLOR
    (parking,) = entities['lanes/areas'].triangles
    assert parking.color_rgba == AREA_COLORS['parking']
    assert len(entities['lanes/signal_poles'].primitives) == 2        # one per light
    without = {e.id for e in map_scene.lane_map_entities(signal_crossing(areas=False))}
    assert 'lanes/areas' not in without and 'lanes/crosswalks' not in without


# ------------------------------------------------------------------------------ docs

def test_docs_maps_gives_every_area_colour_the_code_draws():
    text = (Path(__file__).resolve().parents[1] / 'docs' / 'maps.md').read_text(encoding='utf-8')
    rows = {}
    for line in text.splitlines():
        cells = [cell.strip() for cell in line.strip('|').split('|')]
        if len(cells) == 3 and cells[1].startswith('(') and cells[1].endswith(')'):
            rows[cells[0]] = tuple(float(v) for v in cells[1].strip('()').split(','))
    for kind in list(AREA_COLORS) + ['crosswalk']:
        assert rows[f'`{kind}`'] == area_color(kind)[:3]
    (other,) = [colour for name, colour in rows.items() if name.startswith('any other')]
    assert other == OTHER_AREA_COLOR[:3]
