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
An occupancy map's walls in the physics world: lidar, collisions, spawn and teleport checks.

The map is the room with a pillar of test/map_helpers.py (20 x 12 m, 0.1 m cells); the car
stands at the world origin, heading +x. The lidar's golden values are a ray march over the same
grid (core/map/occupancy.py), from the lidar's own position.
"""

import math

from map_helpers import ORIGIN, RESOLUTION_M, room_pixels, world_data, write_map
import numpy as np
import pytest

from vehicle_sim.config import load_world, world_from_data
from vehicle_sim.core.map.occupancy import ray_march
from vehicle_sim.core.specs.errors import InvalidParameterError, InvalidPoseError
from vehicle_sim.physics.scene import build_scene, mount_suite
from vehicle_sim.physics.sensors import CollisionMonitor

LIDAR = {'name': 'lidar', 'type': 'lidar', 'pose': {'x': 1.0, 'z': 0.5}, 'fov': 1.5 * math.pi,
         'horizontal_resolution': 1080, 'max_range': 30.0, 'min_range': 0.1}
SETTLE_STEPS = 100


@pytest.fixture
def scenes():
    built = []

    def build(data, source='/tmp/world.yaml', **kwargs):
        scene = build_scene(world_from_data(data, source), **kwargs)
        built.append(scene)
        return scene
    yield build
    for scene in built:
        scene.world.close()


@pytest.mark.parametrize('grid_yaw, world_in_map, studs', [
    (0.0, None, 0),
    (0.3, None, 0),                                     # a rotated grid
    (0.0, {'x': 1.5, 'y': -0.5, 'yaw': -0.2}, 0),       # map -> world not the identity
    (0.0, None, 400),                                   # hundreds of walls in one body
])
def test_lidar_ranges_equal_a_ray_march_over_the_image_within_one_cell(
        tmp_path, scenes, grid_yaw, world_in_map, studs):
    path = write_map(tmp_path, pixels=room_pixels(studs),
                     origin=[ORIGIN[0], ORIGIN[1], grid_yaw])
    extra = {} if world_in_map is None else {'world_in_map': world_in_map}
    scene = scenes(world_data(path, sensors=[LIDAR], **extra), mount=mount_suite)
    for _ in range(SETTLE_STEPS):
        scene.world.step()
    car = scene.vehicles['car']
    scan = car.sensors.sample('lidar')
    x, y, _, qx, qy, qz, qw = car.body.pose()
    yaw = math.atan2(2.0 * (qw * qz + qx * qy), 1.0 - 2.0 * (qy * qy + qz * qz))
    built = scene.parts['map']
    placement = built.spec.world_in_map
    lidar_x, lidar_y = placement.to_map(x + math.cos(yaw), y + math.sin(yaw))
    angles = scan.angle_min_rad + scan.angle_increment_rad * np.arange(scan.scan.size)
    def march(offset_rad):
        return np.array([ray_march(built.grid, built.walls, lidar_x, lidar_y,
                                   yaw + placement.yaw_rad + angle + offset_rad, 30.0)
                         for angle in angles])
    marched = march(0.0)
    assert scan.scan.size == 1080
    assert np.all(np.isfinite(marched))           # a closed room: every ray hits a wall
    # A ray that grazes a wall's corner may pass it or not, as the lidar's own position (read
    # to the millimetre) decides: it agrees with the march of a ray turned by 1 mrad.
    error = np.min([np.abs(scan.scan - marched), np.abs(scan.scan - march(1e-3)),
                    np.abs(scan.scan - march(-1e-3))], axis=0)
    assert np.max(error) <= RESOLUTION_M
    assert np.count_nonzero(np.abs(scan.scan - marched) > RESOLUTION_M) <= 2
    # the pillar is seen: some rays stop well short of the room's walls
    assert np.min(scan.scan) < 6.0
    if studs:
        assert len(built.rectangles) > 400         # each stud one rectangle or more


def test_walls_are_few_merged_bodies_named_map(tmp_path, scenes):
    scene = scenes(world_data(write_map(tmp_path)))
    built = scene.parts['map']
    assert len(built.rectangles) == 5               # four walls and the pillar
    assert {scene.world.body_name(body) for body in built.body_ids} == {'map'}


def test_driving_at_a_wall_of_the_map_gives_exactly_one_collision(tmp_path, scenes):
    scene = scenes(world_data(write_map(tmp_path)))
    car = scene.vehicles['car']
    monitor = CollisionMonitor(scene.world, car.body)
    car.car.logic.set_cruising_speed_kmh(20.0)
    events = []
    for _ in range(800):     # 8 s: the front (x = 4.5 m) reaches the wall face at 9.7 m
        scene.world.step()
        events.extend(monitor.fresh)
    assert [e.other for e in events] == ['map']
    assert car.body.pose()[0] + 4.5 == pytest.approx(10.0 - 0.3, abs=0.1)


def test_teleport_into_a_wall_is_refused_and_the_car_stays(tmp_path, scenes):
    scene = scenes(world_data(write_map(tmp_path)))
    car = scene.vehicles['car']
    before = car.body.pose()
    with pytest.raises(InvalidPoseError, match='map'):
        car.car.teleport((5.0, 2.4, 0.0))          # across the pillar
    assert car.body.pose() == pytest.approx(before)
    car.car.teleport((-5.0, -2.0, 0.0))             # free space: taken
    assert car.body.pose()[:2] == pytest.approx((-5.0, -2.0), abs=1e-6)


def test_spawn_on_an_occupied_cell_is_refused_naming_the_world_file_and_field(tmp_path, scenes):
    with pytest.raises(InvalidParameterError) as refused:
        scenes(world_data(write_map(tmp_path), pose=(6.4, 2.4, 0.0)), source='/w/room.yaml')
    text = str(refused.value)
    assert "/w/room.yaml: vehicles[0] (car): field 'pose'" in text
    assert 'occupied cell' in text and 'room.yaml' in text


def test_spawn_whose_outline_overlaps_a_wall_is_refused(tmp_path, scenes):
    # base_link in free space, the car's nose (4.5 m ahead) in the east wall
    with pytest.raises(InvalidPoseError, match="'car' starts inside 'map'"):
        scenes(world_data(write_map(tmp_path), pose=(7.0, -4.0, 0.0)))


def test_unknown_cells_become_walls_when_asked(tmp_path, scenes):
    pixels = np.full((60, 100), 128, dtype=np.uint8)     # unknown: occ 0.498 in 0.25 .. 0.65
    pixels[:, :80] = 254                                 # x -2 .. 6 m free
    path = write_map(tmp_path, pixels=pixels, origin=[-2.0, -3.0, 0.0])
    free = scenes(world_data(path))
    assert free.parts['map'].body_ids == ()
    walls = scenes(world_data(path, unknown='occupied'))
    assert len(walls.parts['map'].rectangles) == 1


def test_the_shipped_race_track_puts_the_car_between_walls_its_lidar_sees():
    scene = build_scene(load_world('race_track'), mount=mount_suite)
    try:
        for _ in range(SETTLE_STEPS):
            scene.world.step()
        scan = scene.vehicles['Car'].sensors.sample('lidar')
        assert scan.scan.size == 1080
        assert scan.angle_max_rad - scan.angle_min_rad == pytest.approx(1.5 * math.pi, abs=0.01)
        # the track is 7 m wide, the car in its middle: the walls 3.5 m to either side
        angles = scan.angle_min_rad + scan.angle_increment_rad * np.arange(scan.scan.size)
        left = scan.scan[np.argmin(np.abs(angles - math.pi / 2))]
        right = scan.scan[np.argmin(np.abs(angles + math.pi / 2))]
        assert (left, right) == pytest.approx((3.5, 3.5), abs=0.15)
        assert scene.parts['map'].map_yaml.resolution_m == 0.1
    finally:
        scene.world.close()


def test_a_camera_sees_the_wall_ahead_in_the_walls_colour(tmp_path, scenes):
    camera = {'name': 'camera', 'type': 'camera', 'pose': {'x': 1.5, 'z': 0.5}, 'width': 64,
              'height': 48, 'fov': 0.5}
    data = world_data(write_map(tmp_path), sensors=[camera])
    centres = []
    for world in (data, {k: v for k, v in data.items() if k != 'map'}):
        scene = scenes(world, mount=mount_suite)
        scene.world.step()
        image = scene.vehicles['car'].sensors.sample('camera')
        pixels = np.frombuffer(bytes(image.data), np.uint8).reshape(image.height, image.width, 3)
        centres.append(pixels[image.height // 2, image.width // 2].astype(int))
    wall, open_plane = centres
    assert not np.array_equal(wall, open_plane)
    assert wall[2] > wall[0] == wall[1]          # the walls' grey is a little blue (0.55, 0.6)


def test_a_scenario_with_a_map_next_to_it_fails_no_collision_at_the_map_s_wall(tmp_path):
    from vehicle_sim.scenarios.runner import run_scenario
    from vehicle_sim.scenarios.schema import load_scenario
    write_map(tmp_path)
    path = tmp_path / 'scenario_room.yaml'
    path.write_text(
        'name: room\nduration: 8.0\ndriver: {commands: [{t: 0.0, cruising_speed: 20.0}]}\n'
        'world:\n  vehicles: [{name: Car}]\n'
        '  map: {type: occupancy_grid, file: room.yaml}\n'
        'criteria:\n  - kind: no_collision\n', encoding='utf-8')
    assert load_scenario(path).world.map.file == str(tmp_path / 'room.yaml')
    result = run_scenario(path)
    assert not result.passed
    assert not result.criterion('no_collision').passed
    assert 'map' in result.criterion('no_collision').detail


def test_lidar_over_the_grid_sees_what_bullet_sees_of_the_wall_meshes(tmp_path, scenes):
    # The same rays with the map's grid (walls over the grid, Bullet up to them) and without it
    # (Bullet alone, walking the map's meshes): the same hits, an obstacle in front of a wall
    # included; rays that graze a corner may differ.
    from vehicle_sim.physics.sensors.rays import cast_rays
    data = world_data(write_map(tmp_path, pixels=room_pixels(200)))
    data['obstacles'] = [{'name': 'pole', 'shape': 'cylinder', 'radius': 0.3, 'height': 2.0,
                          'position': [3.0, -3.0, 1.0]}]
    scene = scenes(data)
    world = scene.world
    origin = np.array([1.0, 0.0, 0.5])
    angles = np.linspace(-math.pi, math.pi, 2000, endpoint=False)
    for z, length in ((0.0, 30.0), (-0.02, 30.0), (0.0, 4.0)):     # level, downwards, short
        ends = origin + length * np.stack([np.cos(angles), np.sin(angles),
                                           np.full(angles.shape, z)], axis=1)
        mask = world.ray_mask_excluding(scene.vehicles['car'].body.body_id)
        over_grid = cast_rays(world, origin, ends, mask)
        grids, world.ray_grids = world.ray_grids, []
        try:
            bullet = cast_rays(world, origin, ends, mask)
        finally:
            world.ray_grids = grids
        assert np.count_nonzero(over_grid < 1.0) > (1900 if length > 10.0 else 100)
        differ = np.abs(over_grid - bullet) * length > 1e-4
        assert np.count_nonzero(differ) <= 4
    pole = np.abs(angles - math.atan2(-3.0, 2.0)) < 0.05
    assert np.all(over_grid[pole] * 4.0 < math.hypot(2.0, 3.0))      # the pole, not the wall


def test_a_lidar_inside_a_wall_reads_closer_than_its_minimum_range(tmp_path, scenes):
    # mounted 6.4 m ahead of the car, 2.4 m to the left: in the middle of the pillar (x 6 ..
    # 6.8 m, y 2 .. 2.8 m); every ray starts in the wall (the ray march: 0 m), so every range
    # reads -inf (REP 117: closer than min_range); Bullet's rays saw the pillar's faces from
    # inside, 0.4 .. 0.57 m away
    lidar = dict(LIDAR, pose={'x': 6.4, 'y': 2.4, 'z': 0.5}, horizontal_resolution=90)
    scene = scenes(world_data(write_map(tmp_path), sensors=[lidar]), mount=mount_suite)
    scene.world.step()
    scan = scene.vehicles['car'].sensors.sample('lidar')
    assert np.all(scan.scan == -np.inf)


def test_a_lidar_sampled_every_step_leaves_the_walls_where_they_collide(tmp_path, scenes):
    # Bullet's rays are cast with the wall meshes moved out of their way and back: the car still
    # meets the wall where it did without a lidar, once
    scene = scenes(world_data(write_map(tmp_path), sensors=[LIDAR]), mount=mount_suite)
    car = scene.vehicles['car']
    monitor = CollisionMonitor(scene.world, car.body)
    car.car.logic.set_cruising_speed_kmh(20.0)
    events = []
    for _ in range(800):
        scene.world.step()
        car.sensors.sample('lidar')
        events.extend(monitor.fresh)
    assert [e.other for e in events] == ['map']
    assert car.body.pose()[0] + 4.5 == pytest.approx(10.0 - 0.3, abs=0.1)


def test_rays_move_only_the_wall_bodies_whose_boxes_they_reach(tmp_path, scenes, monkeypatch):
    # One wall rectangle a body (the room's four walls and the pillar): while Bullet's rays
    # are cast, the bodies whose bounding boxes the rays (cut at the walls) reach stand away,
    # the others stay (no ray can meet them); the fractions are those with every body away.
    import pybullet

    from vehicle_sim.physics import map_layer
    from vehicle_sim.physics.sensors import rays
    monkeypatch.setattr(map_layer, 'BOXES_PER_BODY', 1)
    scene = scenes(world_data(write_map(tmp_path)))
    world, bodies = scene.world, scene.parts['map'].body_ids
    assert len(bodies) == 5
    away = []
    ray_test = pybullet.rayTestBatch

    def spy(*args, **kwargs):
        cid = world.client_id
        away.append({body for body in bodies if pybullet.getBasePositionAndOrientation(
            body, physicsClientId=cid)[0][2] < -1000.0})
        return ray_test(*args, **kwargs)
    monkeypatch.setattr(pybullet, 'rayTestBatch', spy)
    mask = world.ray_mask_excluding(scene.vehicles['car'].body.body_id)
    origin = np.array([1.0, 0.0, 0.5])
    angles = np.linspace(-math.pi, math.pi, 360, endpoint=False)
    ring = np.stack([np.cos(angles), np.sin(angles), np.zeros(angles.shape)], axis=1)
    # 1 m rays in the middle of the room reach no wall's box: nothing moves
    rays.cast_rays(world, origin, origin + ring, mask)
    assert away == [set()]
    # rays east, cut at the east wall (x = 10 m) before the pillar's box: that wall alone
    east = np.abs(angles) < 0.2
    fractions = rays.cast_rays(world, origin, origin + 30.0 * ring[east], mask)
    east_wall = [body for body in bodies
                 if pybullet.getAABB(body, physicsClientId=world.client_id)[0][0] > 9.0]
    assert away[-1] == set(east_wall) and len(east_wall) == 1
    # every direction: every wall and the pillar; the same fractions as with all of them away
    fractions = rays.cast_rays(world, origin, origin + 30.0 * ring, mask)
    assert away[-1] == set(bodies)
    every = world.rays_past_grids
    monkeypatch.setattr(world, 'rays_past_grids', lambda reach=None: every())
    assert rays.cast_rays(world, origin, origin + 30.0 * ring, mask).tobytes() \
        == fractions.tobytes()
