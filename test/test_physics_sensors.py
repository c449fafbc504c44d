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
Simulated sensors against geometry: the golden values of issue 8 and the sensors' semantics.

The world is config/worlds/obstacle_course.yaml: a car at the origin, a wall whose near face is
at x = 19.5 m (6 m wide, 2 m high) and a pole (radius 0.2 m) centred at (10, 5).
"""

import math

import numpy as np
import pybullet
import pytest

from vehicle_sim.config import load_car, load_world, world_from_data
from vehicle_sim.core.geometry.geodesy import LocalTangentPlane
from vehicle_sim.core.sensors.params import sensor_as_dict, sensor_from_dict
from vehicle_sim.core.sensors.readings import (
    COVARIANCE_TYPE_DIAGONAL_KNOWN,
    COVARIANCE_TYPE_UNKNOWN,
)
from vehicle_sim.core.sensors.sampling import due_steps
from vehicle_sim.core.sensors.sets import merge_sensors
from vehicle_sim.physics import World
from vehicle_sim.physics.diff_robot import DiffRobotBody
from vehicle_sim.physics.sensor_urdf import with_sensor_links
from vehicle_sim.physics.sensors import CollisionMonitor, SensorSuite
from vehicle_sim.physics.simulated_car import SimulatedCar
from vehicle_sim.physics.urdf import car_urdf

COURSE = load_world('obstacle_course')
WALL_FACE_X_M = 19.5
SETTLE_STEPS = 300        # 3 s: the suspension is at rest to 1e-6 m/s^2


class Scene:
    """The obstacle course's world with its car (or a replacement) and the sensor suite."""

    def __init__(self, sensors=None, position=(0.0, 0.0, 0.0), model='Car', obstacles=True):
        self.world = World()
        if obstacles:
            for obstacle in COURSE.obstacles:
                self.world.add_obstacle(obstacle)
        vehicle = COURSE.vehicles[0]
        self.params = load_car(model)
        self.car = SimulatedCar(self.world, self.params, position, name=vehicle.name)
        specs = vehicle.sensors if sensors is None else merge_sensors(
            self.params.sensor_set, sensors, 'test')
        self.specs = {s.name: s for s in specs if s.enabled}
        self.suite = SensorSuite(self.world, self.car.body, specs, COURSE.origin)

    def settle(self, steps=SETTLE_STEPS):
        for _ in range(steps):
            self.world.step()

    def close(self):
        self.world.close()


@pytest.fixture
def scene():
    scenes = []

    def make(*args, **kwargs):
        scenes.append(Scene(*args, **kwargs))
        return scenes[-1]
    yield make
    for made in scenes:
        made.close()


def _angles(scan):
    return scan.angle_min_rad + scan.angle_increment_rad * np.arange(scan.scan.size)


# ------------------------------------------------------------------------------- lidar

def test_lidar_ray_at_zero_reads_the_wall_face_minus_the_mount_offset(scene):
    course = scene()
    course.settle()
    scan = course.suite.sample('lidar')
    angles = _angles(scan)
    assert angles[90] == pytest.approx(0.0, abs=1e-12)
    # wall face x = 19.5 m, lidar mounted at x = 1.0 m: 18.5 m
    assert scan.scan[90] == pytest.approx(18.5, abs=1e-3)


def test_lidar_rays_that_miss_read_plus_inf(scene):
    course = scene()
    course.settle()
    scan = course.suite.sample('lidar')
    angles = _angles(scan)
    # right of the wall's edge (atan(3 / 18.5) = 0.161 rad) nothing is within 50 m
    assert np.all(np.isposinf(scan.scan[angles < -0.17]))
    assert scan.range_max_m == 50.0 and scan.scan.dtype == np.float32


def test_lidar_hits_the_pole_within_one_angular_increment(scene):
    course = scene()
    course.settle()
    scan = course.suite.sample('lidar')
    angles = _angles(scan)
    # pole centre seen from the lidar (1, 0): (9, 5) -> atan2(5, 9) = 0.5071 rad; surface at
    # sqrt(9^2 + 5^2) - 0.2 = 10.096 m
    bearing = math.atan2(5.0, 9.0)
    near = np.abs(angles - bearing) <= scan.angle_increment_rad
    nearest = int(np.argmin(np.where(near, scan.scan, np.inf)))
    assert abs(angles[nearest] - bearing) <= scan.angle_increment_rad
    assert scan.scan[nearest] == pytest.approx(math.hypot(9.0, 5.0) - 0.2, abs=0.01)


def test_lidar_return_closer_than_min_range_reads_minus_inf(scene):
    course = scene([{'name': 'lidar', 'type': 'lidar', 'pose': {'x': 1.0, 'z': 1.5},
                     'fov': 1.0, 'horizontal_resolution': 11, 'min_range': 19.0,
                     'max_range': 50.0}])
    scan = course.suite.sample('lidar')
    assert np.isneginf(scan.scan[5])            # the wall at 18.5 m < 19 m


def test_lidar_rays_ignore_the_vehicle_s_own_body(scene):
    # mounted behind the car, at the height of its body box (x -0.5 .. 4.5, z 0.4 .. 1.4):
    # the forward ray passes through the own body and reads the wall at 19.5 + 1.0 m
    course = scene([{'name': 'lidar', 'type': 'lidar', 'pose': {'x': -1.0, 'z': 0.9},
                     'fov': 0.2, 'horizontal_resolution': 3, 'max_range': 50.0}])
    course.settle(1)
    assert course.suite.sample('lidar').scan[1] == pytest.approx(20.5, abs=1e-3)


def test_lidar_rays_are_cast_with_the_own_vehicle_aside_and_see_the_others(scene):
    # the own car stands 10 km below while its rays are cast (Bullet would test each ray
    # against its shapes before the mask drops the hit), then back with its velocities; a
    # second car ahead on the forward ray is seen
    course = scene([{'name': 'lidar', 'type': 'lidar', 'pose': {'x': -1.0, 'z': 0.9},
                     'fov': 0.2, 'horizontal_resolution': 3, 'max_range': 50.0}],
                   obstacles=False)
    other = SimulatedCar(course.world, course.params, (10.0, 0.0, 0.0), name='other')
    course.car.logic.set_cruising_speed_kmh(20.0)
    course.settle(100)
    cid, body_id = course.world.client_id, course.car.body.body_id
    seen = []
    cast = pybullet.rayTestBatch

    def spy(*args, **kwargs):
        seen.append(pybullet.getBasePositionAndOrientation(body_id, physicsClientId=cid)[0])
        return cast(*args, **kwargs)

    def state(body):                  # pose and velocities, flat
        return [v for part in (*pybullet.getBasePositionAndOrientation(body, physicsClientId=cid),
                               *pybullet.getBaseVelocity(body, physicsClientId=cid))
                for v in part]
    before = [state(body_id), state(other.body.body_id)]
    pybullet.rayTestBatch = spy
    try:
        scan = course.suite.sample('lidar')
    finally:
        pybullet.rayTestBatch = cast
    assert [z for _, _, z in seen] == [-1.0e4]
    # back where it was (the orientation read back to its last bit: Bullet keeps a matrix),
    # its velocities too
    assert state(body_id) == pytest.approx(before[0], rel=0.0, abs=1e-15)
    assert state(other.body.body_id) == before[1]
    assert before[0][7] > 2.0                       # it was moving: its velocity came back
    # the forward ray, from 1 m behind the car's origin (its base 2 m ahead of it), reads the
    # other car's rear (its base at 12 m, its body box 2.5 m back)
    lidar_x = before[0][0] - 2.0 - 1.0
    assert scan.scan[1] == pytest.approx(12.0 - 2.5 - lidar_x, abs=1e-3)


def test_lidar_layers_give_an_organized_cloud_with_nan_for_misses(scene):
    course = scene([{'name': 'lidar', 'type': 'lidar', 'pose': {'x': 1.0, 'z': 1.5},
                     'fov': 1.0, 'horizontal_resolution': 101, 'layers': 3,
                     'vertical_fov': 0.04, 'max_range': 50.0}])
    course.settle(1)
    scan = course.suite.sample('lidar')
    points = scan.points()
    assert points.shape == (3, 101, 3) and points.dtype == np.float32
    assert scan.layer_elevations_rad == pytest.approx((0.02, 0.0, -0.02))
    base_z = course.car.body.pose()[2]
    # every layer's middle ray hits the wall face 18.5 m ahead; its height follows the layer
    for layer, elevation in enumerate(scan.layer_elevations_rad):
        x, y, z = points[layer, 50]
        assert x == pytest.approx(18.5, abs=2e-3) and y == pytest.approx(0.0, abs=1e-6)
        assert z == pytest.approx(18.5 * math.tan(elevation), abs=2e-3)
        assert 1.0 + base_z + z < 2.0           # below the wall's top: a hit
    assert np.all(np.isnan(points[:, 0]))         # the right-most rays (-0.5 rad) miss


def test_lidar_noise_is_seeded_and_off_by_default(scene):
    noisy = [{'name': 'lidar', 'type': 'lidar', 'pose': {'x': 1.0, 'z': 1.5}, 'fov': 0.2,
              'horizontal_resolution': 201, 'max_range': 50.0, 'noise': 0.05, 'seed': 4}]
    first, second = scene(noisy), scene(noisy)
    a, b = first.suite.sample('lidar').scan, second.suite.sample('lidar').scan
    assert np.array_equal(a, b)
    # the wall is hit by every ray: ranges 18.5 / cos(angle) plus noise of sigma 0.05 m
    exact = 18.5 / np.cos(_angles(first.suite.latest('lidar')))
    assert np.std(a - exact) == pytest.approx(0.05, rel=0.25)


# ------------------------------------------------------------------------------- IMU

def test_imu_at_rest_reads_plus_g_on_z_and_no_rotation(scene):
    course = scene()
    course.suite.start(['imu'])
    course.settle()
    imu = course.suite.latest('imu')
    assert imu.time_s == pytest.approx(3.0)
    assert imu.linear_acceleration_mps2 == pytest.approx((0.0, 0.0, 9.81), abs=1e-3)
    assert imu.angular_velocity_radps == pytest.approx((0.0, 0.0, 0.0), abs=1e-6)
    assert imu.roll_pitch_yaw_rad == pytest.approx((0.0, 0.0, 0.0), abs=1e-4)
    assert imu.linear_acceleration_covariance == (0.0,) * 9


def test_imu_rolled_a_quarter_turn_feels_gravity_on_its_y_axis(scene):
    # roll +pi/2: the sensor's y axis points up, its z axis to the right (-y of the world)
    course = scene([{'name': 'imu', 'pose': {'z': 0.5, 'roll': math.pi / 2}}])
    course.suite.start(['imu'])
    course.settle()
    imu = course.suite.latest('imu')
    assert imu.linear_acceleration_mps2 == pytest.approx((0.0, 9.81, 0.0), abs=1e-3)
    assert imu.roll_pitch_yaw_rad[0] == pytest.approx(math.pi / 2, abs=1e-4)


def test_imu_orientation_and_gyro_follow_the_car_in_a_turn(scene):
    course = scene(position=(0.0, 0.0, 0.7))
    course.suite.start(['imu'])
    logic = course.car.logic
    logic.set_cruising_speed_kmh(15.0)
    logic.set_steering_angle(-0.3)           # Webots sign: negative = left
    course.settle(500)
    imu = course.suite.latest('imu')
    body = course.car.body
    assert imu.angular_velocity_radps[2] == pytest.approx(body.yaw_rate_radps(), abs=1e-3)
    assert imu.angular_velocity_radps[2] > 0.1                      # turning left
    yaw = math.atan2(2.0 * body.pose()[6] * body.pose()[5], 1.0 - 2.0 * body.pose()[5] ** 2)
    assert imu.roll_pitch_yaw_rad[2] == pytest.approx(yaw, abs=0.02)
    # centripetal acceleration towards the turn centre (+y of the car): v * omega
    speed = body.forward_speed_mps()
    assert imu.linear_acceleration_mps2[1] == pytest.approx(speed * body.yaw_rate_radps(),
                                                            rel=0.1)


# ------------------------------------------------------------------------------- GNSS

def test_gnss_at_the_origin_reads_the_origin(scene):
    course = scene()
    course.settle(1)
    fix = course.suite.sample('gnss')
    assert (fix.latitude_deg, fix.longitude_deg) == pytest.approx((48.0, 11.0), abs=1e-9)
    # antenna 1.5 m above base_link, which rests on the ground (within the tyre contact)
    assert fix.altitude_m == pytest.approx(501.5, abs=0.01)
    assert fix.covariance_type == COVARIANCE_TYPE_UNKNOWN and fix.status == 0


def test_gnss_100_m_east_changes_longitude_by_the_exact_value(scene):
    at_origin, east = scene(), scene(position=(100.0, 0.0, 0.0), obstacles=False)
    at_origin.settle(1)
    east.settle(1)
    delta = (east.suite.sample('gnss').longitude_deg
             - at_origin.suite.sample('gnss').longitude_deg)
    assert delta == pytest.approx(0.00133992, abs=1e-8)


def test_gnss_local_position_is_the_antenna_in_the_world(scene):
    course = scene(position=(3.0, -2.0, math.pi / 2))
    course.settle(1)
    fix = course.suite.sample('gnss')
    # antenna at (0, 0, 1.5) in base_link; yaw pi/2 keeps x, y
    assert fix.position_m == pytest.approx((3.0, -2.0, 1.5), abs=0.01)
    assert LocalTangentPlane(COURSE.origin).to_geodetic(*fix.position_m) == pytest.approx(
        (fix.latitude_deg, fix.longitude_deg, fix.altitude_m), abs=1e-9)


def test_gnss_noise_has_its_sigma_and_a_known_diagonal_covariance(scene):
    course = scene([{'name': 'gnss', 'pose': {'z': 1.5}, 'noise': 0.5, 'seed': 2}])
    plane = LocalTangentPlane(COURSE.origin)
    east = [plane.from_geodetic(f.latitude_deg, f.longitude_deg, f.altitude_m)[0]
            for f in (course.suite.sample('gnss') for _ in range(2000))]
    fix = course.suite.latest('gnss')
    assert fix.covariance_type == COVARIANCE_TYPE_DIAGONAL_KNOWN
    assert fix.position_covariance == pytest.approx((0.25, 0, 0, 0, 0.25, 0, 0, 0, 0.25))
    assert np.std(east) == pytest.approx(0.5, rel=0.1)


# ------------------------------------------------------------------------------- distance

def test_distance_sensor_reads_the_wall_and_its_lookup_table_value(scene):
    course = scene([{'type': 'distance', 'name': 'front', 'pose': {'x': 4.6, 'z': 0.9},
                     'lookup_table': [[0.0, 0.0, 0.0], [20.0, 1000.0, 0.0]]}])
    course.settle(1)
    reading = course.suite.sample('front')
    # 19.5 - 4.6 = 14.9 m; value 14.9 / 20 * 1000 = 745
    assert reading.range_m == pytest.approx(14.9, abs=1e-3)
    assert reading.value == pytest.approx(745.0, abs=0.1)
    assert reading.max_range_m == 20.0


def test_distance_sensor_without_a_hit_reads_plus_inf_and_the_table_end(scene):
    course = scene([{'type': 'distance', 'name': 'left', 'pose': {'x': 2.0, 'y': 1.0, 'z': 0.9,
                                                                  'yaw': -math.pi / 2},
                     'max_range': 8.0}])
    reading = course.suite.sample('left')
    assert math.isinf(reading.range_m) and reading.range_m > 0
    assert (reading.distance_m, reading.value) == (8.0, 8.0)


def test_distance_cone_reports_the_nearest_ray(scene):
    # aimed just left of the wall's edge: the axis misses, a ray of the 0.4 rad cone hits
    bearing = math.atan2(3.2, 18.5)
    course = scene([{'type': 'distance', 'name': 'cone', 'pose': {'x': 1.0, 'z': 1.0,
                                                                  'yaw': bearing},
                     'rays': 9, 'aperture': 0.4, 'max_range': 40.0}])
    course.settle(1)
    assert math.isfinite(course.suite.sample('cone').range_m)
    single = scene([{'type': 'distance', 'name': 'cone', 'pose': {'x': 1.0, 'z': 1.0,
                                                                  'yaw': bearing},
                     'max_range': 40.0}])
    single.settle(1)
    assert math.isinf(single.suite.sample('cone').range_m)


# ------------------------------------------------------------------------------- camera

WALL_RGB = np.array(COURSE.obstacles[0].color_rgba[:3])


def _is_wall(rgb):
    """Pixels whose colour is the wall's, shaded (same chromaticity, 40..100 % brightness)."""
    pixels = rgb.astype(float) / 255.0
    scale = pixels.sum(axis=-1, keepdims=True) / WALL_RGB.sum()
    return (np.abs(pixels - scale * WALL_RGB).max(axis=-1) < 0.03) & (scale[..., 0] > 0.4)


def test_camera_sees_the_wall_colour_in_its_centre_pixels(scene):
    course = scene()
    course.settle(1)
    frame = course.suite.sample('camera')
    assert (frame.width, frame.height, frame.rgb.shape) == (160, 120, (120, 160, 3))
    centre = frame.rgb[58:62, 78:82]
    assert _is_wall(centre).all()
    assert len(frame.data) == frame.step * frame.height == 160 * 120 * 3


def test_camera_wall_corner_lands_on_the_pixel_the_intrinsics_predict(scene):
    course = scene()
    course.settle(1)
    frame = course.suite.sample('camera')
    fx, _, cx, _, fy, cy = frame.k[0], frame.k[1], frame.k[2], frame.k[3], frame.k[4], frame.k[5]
    base = course.car.body.pose()
    camera_x, camera_y, camera_z = 1.5 + base[0], base[1], 1.3 + base[2]
    # the top-left corner of the wall's face (19.5, 3, 2) in the optical frame: x right, y
    # down, z forward; u = cx + fx x / z, v = cy + fy y / z
    depth = WALL_FACE_X_M - camera_x
    u = cx + fx * -(3.0 - camera_y) / depth
    v = cy + fy * -(2.0 - camera_z) / depth
    rows, cols = np.nonzero(_is_wall(frame.rgb))
    assert cols.min() == pytest.approx(u, abs=1.0)
    assert rows.min() == pytest.approx(v, abs=1.0)


def test_camera_intrinsics_are_those_of_its_horizontal_fov(scene):
    course = scene()
    frame = course.suite.sample('camera')
    focal = 80.0 / math.tan(0.5)
    assert frame.k == pytest.approx((focal, 0, 79.5, 0, focal, 59.5, 0, 0, 1))
    assert frame.p == pytest.approx((focal, 0, 79.5, 0, 0, focal, 59.5, 0, 0, 0, 1, 0))
    assert course.specs['camera'].vertical_fov_rad == pytest.approx(2 * math.atan(
        math.tan(0.5) * 0.75))


def test_camera_sees_a_grey_ground_below_the_horizon(scene):
    course = scene([{'name': 'camera', 'pose': {'x': 1.5, 'z': 3.0, 'pitch': 0.3}}])
    frame = course.suite.sample('camera')
    bottom = frame.rgb[-10:].reshape(-1, 3).astype(int)
    assert np.all(np.abs(bottom - bottom[:, :1]) <= 2)        # grey: r = g = b
    assert 60 < bottom.mean() < 200


# ------------------------------------------------------------------------------- collisions

def test_driving_into_the_wall_produces_exactly_one_collision_event(scene):
    course = scene(sensors=[])
    monitor = CollisionMonitor(course.world, course.car.body)
    course.car.logic.set_cruising_speed_kmh(20.0)
    events = []
    for _ in range(800):            # 8 s: reaches the wall (15 m) after about 4.7 s and pushes
        course.world.step()
        events.extend(monitor.fresh)
    assert [e.other for e in events] == ['wall']
    front = course.car.body.pose()[0] + 4.5
    assert front == pytest.approx(WALL_FACE_X_M, abs=0.1)
    assert events[0].normal_force_n > 0.0


def test_collision_with_another_vehicle_names_it(scene):
    course = scene(sensors=[], obstacles=False)
    SimulatedCar(course.world, course.params, (8.0, 0.0, 0.0), name='parked')
    monitor = CollisionMonitor(course.world, course.car.body)
    course.car.logic.set_cruising_speed_kmh(10.0)
    others = []
    for _ in range(600):
        course.world.step()
        others.extend(e.other for e in monitor.fresh)
    assert others == ['parked']


# ------------------------------------------------------------------------------- scheduling

def test_suite_samples_a_40_hz_lidar_at_the_scheduled_steps(scene):
    course = scene([{'name': 'lidar', 'rate_hz': 40.0, 'horizontal_resolution': 11}])
    course.suite.start()
    steps = []
    for _ in range(20):
        course.world.step()
        if course.suite.fresh:
            steps.append(course.world.step_count)
            assert course.suite.fresh[0].time_s == pytest.approx(course.world.time_s)
    assert tuple(steps) == due_steps(40.0, 0.01, 8) == (3, 5, 8, 10, 13, 15, 18, 20)


def test_suite_without_mounted_sensors_adds_no_step_hook(scene):
    course = scene(sensors=[])
    course.suite.start()
    assert course.world._post_step == []
    assert course.suite.latest('lidar') is None


def test_mounting_sensors_does_not_change_the_simulated_body(scene):
    # same drive with and without a lidar, IMU and camera: bitwise the same trajectory, and the
    # same PyBullet links and masses (sensor links are in robot_description only)
    def drive(sensors):
        course = scene(sensors, position=(0.0, 0.0, 0.0))
        course.suite.start()
        course.car.logic.set_cruising_speed_kmh(30.0)
        course.car.logic.set_steering_angle(0.2)
        course.settle(300)
        body = course.car.body
        cid = course.world.client_id
        masses = [pybullet.getDynamicsInfo(body.body_id, link, physicsClientId=cid)[0]
                  for link in range(-1, pybullet.getNumJoints(body.body_id,
                                                              physicsClientId=cid))]
        return body.pose(), masses
    without = drive([])
    with_sensors = drive([{'name': 'lidar'}, {'name': 'imu'}, {'name': 'camera', 'rate_hz': 1.0}])
    assert with_sensors == without


def test_robot_description_has_sensor_links_the_body_does_not(scene):
    course = scene()
    urdf = with_sensor_links(course.car.body.urdf, course.specs.values())
    for name in ('lidar', 'imu', 'gnss', 'camera', 'camera_optical'):
        assert f'<link name="{name}"/>' in urdf
        assert f'<link name="{name}"/>' not in course.car.body.urdf
    assert '<origin xyz="1 0 1.5" rpy="0 0 0"/>' in urdf
    assert car_urdf(course.params, name='Car') == course.car.body.urdf


# ------------------------------------------------------------------------------- obstacles

def test_obstacle_with_mass_falls_and_static_ones_stay(scene):
    world_spec = world_from_data(
        {'vehicles': [{'name': 'Car'}], 'obstacles': [
            {'name': 'ball', 'shape': 'sphere', 'radius': 0.3, 'mass': 2.0,
             'position': [5.0, 5.0, 2.0]},
            {'name': 'crate', 'shape': 'box', 'size': [1, 1, 1], 'position': [5.0, -5.0, 0.5]}]},
        'w.yaml')
    course = scene(sensors=[], obstacles=False)
    ids = {o.name: course.world.add_obstacle(o) for o in world_spec.obstacles}
    course.settle(200)
    cid = course.world.client_id
    ball = pybullet.getBasePositionAndOrientation(ids['ball'], physicsClientId=cid)[0]
    crate = pybullet.getBasePositionAndOrientation(ids['crate'], physicsClientId=cid)[0]
    assert ball[2] == pytest.approx(0.3, abs=0.01)          # resting on the ground
    assert crate == pytest.approx((5.0, -5.0, 0.5))
    assert course.world.body_name(ids['crate']) == 'crate'
    assert pybullet.getDynamicsInfo(ids['ball'], -1, physicsClientId=cid)[0] == 2.0


def test_robot_default_lidar_sees_an_obstacle():
    world = World()
    try:
        obstacle = world_from_data({'vehicles': [{'name': 'Car'}], 'obstacles': [
            {'name': 'post', 'shape': 'cylinder', 'radius': 0.1, 'height': 1.0,
             'position': [2.0, 0.0, 0.5]}]}, 'w.yaml').obstacles[0]
        world.add_obstacle(obstacle)
        robot = DiffRobotBody(world, 'caster_robot')
        data = sensor_as_dict(robot.params.sensor_set[0])
        lidar = sensor_from_dict(data | {'enabled': True}, 't')
        suite = SensorSuite(world, robot, [lidar])
        world.step()
        scan = suite.sample('lidar')
        # ray 180 of 360 points straight ahead; the post's face is 2.0 - 0.1 - (-0.1) m away
        ahead = scan.scan[np.argmin(np.abs(_angles(scan)))]
        assert ahead == pytest.approx(2.0 - 0.1 - lidar.pose.x_m, abs=0.01)
    finally:
        world.close()


def test_lidar_with_more_rays_than_one_pybullet_batch_reads_every_ray(scene):
    # 17 layers x 1024 rays = 17408 > PyBullet's 16383 rays per batch
    course = scene([{'name': 'lidar', 'fov': 1.0, 'horizontal_resolution': 1024, 'layers': 17,
                     'vertical_fov': 0.02, 'max_range': 50.0, 'pose': {'x': 1.0, 'z': 1.5}}])
    course.settle(1)
    scan = course.suite.sample('lidar')
    assert scan.ranges_m.shape == (17, 1024)
    # the last layer's middle rays hit the wall too: a ray past the first batch was cast
    assert scan.ranges_m[16, 512] == pytest.approx(18.5 / math.cos(0.01), abs=0.01)
