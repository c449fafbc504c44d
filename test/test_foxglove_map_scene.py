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
The live view's static layers: an occupancy map's walls, a lane map, and the update stream.

Walls: the room with a pillar of test/map_helpers.py built by the scene builder; the cubes are
the merged wall rectangles, at the corners the physics' wall meshes have. Lanes: the shipped
highway world (``roads:``), its lanes loaded without physics.
"""

import math
from types import SimpleNamespace

from map_helpers import room_pixels, world_data, write_map
import numpy as np
import pytest

from vehicle_sim.config import load_world, world_from_data
from vehicle_sim.core.map.lane_geometry import LINE_WIDTH_M, MARKING_Z_M
from vehicle_sim.core.map.lane_graph import distances_to_polyline
from vehicle_sim.foxglove import map_scene
from vehicle_sim.foxglove import scene as fs
from vehicle_sim.foxglove.scene_stream import SceneStream
from vehicle_sim.maps.lane_maps import with_lanes
from vehicle_sim.physics.map_layer import _wall_corners
from vehicle_sim.physics.scene import build_scene

CM = 0.01


def _cube_corners(cube):
    # float (8, 3): bottom four then top four corners, counter-clockwise from (-x, -y).
    (x, y, z), (sx, sy, sz) = cube.position_m, cube.size_m
    qx, qy, qz, qw = cube.orientation
    assert (qx, qy) == (0.0, 0.0)
    yaw = 2.0 * math.atan2(qz, qw)
    c, s = math.cos(yaw), math.sin(yaw)
    local = [(-sx / 2, -sy / 2), (sx / 2, -sy / 2), (sx / 2, sy / 2), (-sx / 2, sy / 2)]
    ring = [(x + c * u - s * v, y + s * u + c * v) for u, v in local]
    return np.array([(px, py, z - sz / 2) for px, py in ring]
                    + [(px, py, z + sz / 2) for px, py in ring])


@pytest.mark.parametrize('grid_yaw, world_in_map, studs', [
    (0.0, None, 5),
    (0.3, None, 0),                                    # a turned grid
    (0.0, {'x': 1.5, 'y': -0.5, 'yaw': -0.2}, 0),      # map -> world not the identity
])
def test_wall_cubes_are_the_merged_rectangles_where_the_physics_has_them(
        tmp_path, grid_yaw, world_in_map, studs):
    origin = [-10.0, -6.0, grid_yaw]
    extra = {'world_in_map': world_in_map} if world_in_map else {}
    path = write_map(tmp_path, pixels=room_pixels(studs), origin=origin)
    scene = build_scene(world_from_data(world_data(path, wall_height=2.5, **extra),
                                        '/tmp/world.yaml'))
    try:
        built = scene.parts['map']
        (walls,) = fs.scene_entities(scene, ['map'])
        assert walls.id == 'map/walls' and walls.frame_id == fs.WORLD_FRAME
        # the room's 4 walls and the pillar (and the studs): one cube per merged rectangle
        assert len(built.rectangles) >= 5 + studs
        assert len(walls.primitives) == len(built.rectangles)
        expected = _wall_corners(built.grid, built.rectangles, built.spec)
        for cube, corners in zip(walls.primitives, expected):
            assert cube.kind == 'cube' and cube.color_rgba == map_scene.WALL_COLOR
            assert cube.size_m[2] == 2.5 and cube.position_m[2] == 1.25
            assert _cube_corners(cube) == pytest.approx(corners, abs=1e-9)
    finally:
        scene.world.close()


def test_a_world_without_a_map_or_lanes_has_no_static_entities():
    scene = SimpleNamespace(spec=SimpleNamespace(map=None, obstacles=()), lanes=None, parts={},
                            vehicles={}, obstacles={})
    assert fs.scene_entities(scene, ['map', 'lanes']) == []


@pytest.fixture(scope='module')
def highway():
    spec = with_lanes(load_world('highway', 'ToyotaPrius'))
    return SimpleNamespace(spec=spec, lanes=spec.lanes, parts={}, vehicles={}, obstacles={})


def test_highway_lane_entities_are_surface_markings_and_centrelines(highway):
    entities = {entity.id: entity for entity in fs.scene_entities(highway, ['lanes'])}
    # the motorway has no curbstones or walls: no barrier entity
    assert list(entities) == ['lanes/surface', 'lanes/markings', 'lanes/centerlines']
    (surface,) = entities['lanes/surface'].triangles
    assert len(surface.indices) > 0 and surface.indices.max() < len(surface.points_m)
    assert surface.color_rgba == map_scene.SURFACE_COLOR
    centerlines = entities['lanes/centerlines'].lines
    # 3 lanes each way, on each of the 5 segments
    assert len(centerlines) == len(highway.lanes.lanes) == 30
    for lines, lane in zip(centerlines, highway.lanes.lanes.values()):
        assert lines.kind == 'line_strip'
        assert lines.points_m[:, :2] == pytest.approx(np.asarray(lane.centerline), abs=1e-9)


def test_highway_marking_lines_lie_on_the_lane_boundaries_coloured_by_type(highway):
    (markings,) = fs.scene_entities(highway, ['lanes'])[1:2]
    boundaries = highway.lanes.boundaries()
    solid = [b for b in boundaries if b.line_type == 'solid']
    dashed = [b for b in boundaries if b.line_type == 'dashed']
    double = [b for b in boundaries if b.line_type == 'solid_solid']
    # per segment (5): 2 edge lines, 4 lane lines, a centre line of two stripes
    assert (len(solid), len(dashed), len(double)) == (10, 20, 5)
    strips = [line for line in markings.lines if line.kind == 'line_strip']
    lists = [line for line in markings.lines if line.kind == 'line_list']
    assert len(strips) == len(solid) + 2 * len(double) and len(lists) == len(dashed)
    for line in strips:
        assert line.color_rgba == map_scene.MARKING_COLOR['solid']
    for line in lists:
        assert line.color_rgba == map_scene.MARKING_COLOR['dashed']
        assert len(line.points_m) % 2 == 0
    for line in markings.lines:
        assert line.thickness_m == LINE_WIDTH_M
        assert np.all(line.points_m[:, 2] == MARKING_Z_M)
    # Each edge line and each dash lies on its boundary within 1 cm; a solid edge line's
    # points are its boundary's points.
    edge_points = [line.points_m[:, :2] for line in strips]
    for boundary in solid:
        assert any(points.shape == boundary.points.shape and np.allclose(
            points, boundary.points, atol=CM) for points in edge_points)
    for line, boundary in zip(lists, dashed):
        assert distances_to_polyline(line.points_m[:, :2], boundary.points).max() < CM
        # dashes of 3 m: each segment pair lies on one dash
        lengths = np.hypot(*(line.points_m[1::2, :2] - line.points_m[0::2, :2]).T)
        assert lengths.max() <= 3.0 + 1e-9 and lengths.sum() > 0.25 * _length(boundary.points)
    # the centre line's two stripes run either side of it, (line width + gap) / 2 away
    assert len(strips) == len(solid) + 2 * len(double)
    centre_stripes = [line for line in strips if not any(
        distances_to_polyline(line.points_m[:, :2], b.points).max() < CM for b in solid)]
    assert len(centre_stripes) == 2 * len(double)
    for line in centre_stripes:
        distances = min((distances_to_polyline(line.points_m[:, :2], b.points) for b in double),
                        key=lambda d: d.max())
        assert distances == pytest.approx(0.135, abs=CM)


def _length(points):
    return float(np.hypot(*np.diff(points, axis=0).T).sum())


def test_barrier_pieces_are_cubes_along_the_line_with_its_height():
    from vehicle_sim.core.map.lane_graph import Boundary, Lane, LaneGraph
    left = Boundary(1, np.array([[0.0, 2.0], [10.0, 2.0], [10.0, 12.0]]), 'wall')
    right = Boundary(2, np.array([[0.0, -2.0], [14.0, -2.0], [14.0, 12.0]]), 'curbstone')
    lane = Lane(7, np.array([[0.0, 0.0], [12.0, 0.0], [12.0, 12.0]]), left, right, 10.0)
    entity = map_scene.barriers_entity(LaneGraph([lane], 'test'))
    first, second, third, _ = entity.primitives
    assert first.position_m == pytest.approx((5.0, 2.0, 0.5))
    assert first.size_m == pytest.approx((10.0, 0.2, 1.0))
    assert second.position_m == pytest.approx((10.0, 7.0, 0.5))
    assert second.orientation == pytest.approx((0.0, 0.0, math.sin(math.pi / 4),
                                                math.cos(math.pi / 4)))
    assert third.size_m == pytest.approx((14.0, 0.2, 0.15))


# ------------------------------------------------------------------------------ the stream

def _scene():
    return SimpleNamespace(vehicles={}, spec=SimpleNamespace(obstacles=(), map=None),
                           obstacles={}, lanes=None, parts={})


def test_static_entities_go_in_full_updates_moving_ones_in_every_one(monkeypatch):
    monkeypatch.setattr(fs, 'ENTITY_SOURCES', dict(fs.ENTITY_SOURCES))
    monkeypatch.setattr(fs, 'STATIC_SOURCES', set(fs.STATIC_SOURCES))
    built = []

    def ground(scene):
        built.append(1)
        return [fs.Entity('ground', fs.WORLD_FRAME, ())]

    cars = {'a': 0.0, 'b': 5.0}

    def carts(scene):
        return [fs.boxes_entity(f'cart/{name}', (x, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0),
                                [((0.0, 0.0, 0.75), fs.IDENTITY, (4.0, 1.8, 1.5))],
                                (1.0, 0.0, 0.0, 1.0))
                for name, x in cars.items()]

    fs.register_entity_source('ground', ground, static=True)
    fs.register_entity_source('carts', carts)
    stream, scene = SceneStream(), _scene()
    first = stream.frame(scene, full=False)      # the first update is full
    assert [e.id for e in first.entities] == ['ground', 'cart/a', 'cart/b']
    cars['a'] = 2.0
    second = stream.frame(scene, full=False)
    assert [e.id for e in second.entities] == ['cart/a', 'cart/b']
    assert second.entities[0].primitives[0].position_m == (2.0, 0.0, 0.75)
    del cars['b']                                 # a cart gone: deleted
    third = stream.frame(scene, full=True)       # a client subscribed: the ground again
    assert [e.id for e in third.entities] == ['ground', 'cart/a']
    assert third.deleted_ids == ('cart/b',)
    assert stream.frame(scene, full=False).deleted_ids == ()
    assert len(built) == 1                        # static sources built once per scene


def test_an_id_of_a_static_and_a_moving_source_is_refused(monkeypatch):
    monkeypatch.setattr(fs, 'ENTITY_SOURCES', dict(fs.ENTITY_SOURCES))
    monkeypatch.setattr(fs, 'STATIC_SOURCES', set(fs.STATIC_SOURCES))
    fs.register_entity_source('one', lambda scene: [fs.Entity('x', fs.WORLD_FRAME, ())],
                              static=True)
    fs.register_entity_source('two', lambda scene: [fs.Entity('x', fs.WORLD_FRAME, ())])
    with pytest.raises(ValueError, match="entity id 'x' given by a static and a moving"):
        SceneStream().frame(_scene(), full=True)


def _decoded(messages, update):
    # The update decoded with protobuf from the schema the channel advertises.
    descriptor_pb2 = pytest.importorskip(
        'google.protobuf.descriptor_pb2', reason='protobuf (Python) decodes the update here')
    from google.protobuf import descriptor_pool, message_factory
    schema = messages.SceneUpdate.get_schema()
    files = descriptor_pb2.FileDescriptorSet.FromString(schema.data)
    pool = descriptor_pool.DescriptorPool()
    for file in files.file:
        pool.Add(file)
    kind = message_factory.GetMessageClass(pool.FindMessageTypeByName(schema.name))
    return kind.FromString(update.encode())


def test_lines_and_triangles_become_foxglove_primitives(highway):
    foxglove = pytest.importorskip('foxglove', reason='foxglove-sdk (the foxglove extra)')
    from vehicle_sim.foxglove import scene_messages
    messages = foxglove.messages
    entities = fs.scene_entities(highway, ['lanes'])
    update = _decoded(messages, scene_messages.scene_update(
        messages, entities, 1.5, deleted_ids=['traffic/b']))
    (deletion,) = update.deletions
    assert (deletion.id, deletion.type, deletion.timestamp.seconds, deletion.timestamp.nanos) == (
        'traffic/b', 0, 1, 500_000_000)                # MATCHING_ID at the update's time
    surface, markings = update.entities[:2]
    (mesh,) = entities[0].triangles
    (triangles,) = surface.triangles
    assert list(triangles.indices) == mesh.indices.reshape(-1).tolist()
    assert np.array([(p.x, p.y, p.z) for p in triangles.points]) == pytest.approx(
        mesh.points_m)
    assert (triangles.color.r, triangles.color.a) == pytest.approx((0.3, 1.0))
    for got, lines in zip(markings.lines, entities[1].lines):
        assert got.type == {'line_strip': 0, 'line_list': 2}[lines.kind]
        assert got.thickness == pytest.approx(lines.thickness_m) and not got.scale_invariant
        assert np.array([(p.x, p.y, p.z) for p in got.points]) == pytest.approx(lines.points_m)
    assert markings.frame_id == 'world' and markings.id == 'lanes/markings'


@pytest.mark.parametrize('make, message', [
    (lambda: fs.Lines('line_loop', [[0, 0, 0], [1, 0, 0]], 0.1, (1, 1, 1, 1)),
     "lines kind 'line_loop'; known: line_strip, line_list"),
    (lambda: fs.Lines('line_list', [[0, 0, 0], [1, 0, 0], [2, 0, 0]], 0.1, (1, 1, 1, 1)),
     'a line list takes points in pairs; got 3 points'),
    (lambda: fs.Lines('line_strip', [[0, 0], [1, 0]], 0.1, (1, 1, 1, 1)),
     r'lines points_m: expected \(N, 3\) points \[m\], got shape \(2, 2\)'),
    (lambda: fs.Triangles([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [0, 1, 3], (1, 1, 1, 1)),
     'triangles indices must be triples into the 3 points'),
    (lambda: fs.Triangles([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [0, 1], (1, 1, 1, 1)),
     'triangles indices must be triples into the 3 points'),
])
def test_bad_lines_and_triangles_are_refused_naming_the_field(make, message):
    with pytest.raises(ValueError, match=message):
        make()


def test_lines_and_triangles_take_plain_lists():
    lines = fs.Lines('line_list', [[0, 0, 0], [1, 0, 0]], 0.1, (1, 1, 1, 1))
    triangles = fs.Triangles([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [0, 1, 2], (1, 1, 1, 1))
    assert lines.points_m.shape == (2, 3) and triangles.indices.tolist() == [[0, 1, 2]]
