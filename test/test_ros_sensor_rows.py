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
The sensor rows in process: converters, message layout and CDR, name clashes, no cost when off.

Readings come from the obstacle course's physics (config/worlds/obstacle_course.yaml, the car at
rest at the origin); the rows' converters turn them into messages of the embedded transport's
classes, whose CDR must equal rosbags' for the same message (the rclpy wire format).
"""

import math
import re
from types import SimpleNamespace

import numpy as np
import pytest

from vehicle_msgs_py import message_type, to_rosbags, typestore
from vehicle_sim.config import load_car, load_world
from vehicle_sim.core.sensors.sets import merge_sensors
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.physics import SimulatedCar, World
from vehicle_sim.physics.sensors import CollisionMonitor, SensorFeed, SensorSuite
from vehicle_sim.ros import sensor_interfaces as si
from vehicle_sim.ros.endpoints import EACH_SAMPLE, MessageKit, ON_EVENT
from vehicle_sim.ros.messages import stamp_builder
from vehicle_sim.transport import TransportError

pytestmark = pytest.mark.transport

COURSE = load_world('obstacle_course')
# The course's car with two more sensors: a 4-layer lidar and a distance sensor (no topic
# clash: 'points' and 'front').
EXTRA = [{'type': 'lidar', 'name': 'lidar3d', 'pose': {'x': 1.0, 'z': 1.5}, 'layers': 4,
          'vertical_fov': 0.2, 'horizontal_resolution': 9, 'fov': 0.4, 'max_range': 50.0},
         {'type': 'distance', 'name': 'front', 'pose': {'x': 1.0, 'z': 1.0},
          'max_range': 30.0}]


def rosbags_bytes(message):
    return bytes(typestore().serialize_cdr(to_rosbags(message), type(message).__ros_type__))


@pytest.fixture(scope='module')
def readings():
    """{sensor name: reading} of every sensor of the course's car (and EXTRA), at 0.5 s."""
    world = World()
    try:
        for obstacle in COURSE.obstacles:
            world.add_obstacle(obstacle)
        vehicle = COURSE.vehicles[0]
        car = SimulatedCar(world, load_car(vehicle.model), (0.0, 0.0, 0.0), name=vehicle.name)
        specs = merge_sensors(vehicle.sensors, EXTRA, 'test')
        suite = SensorSuite(world, car.body, specs, COURSE.origin)
        for _ in range(50):
            world.step()
        yield specs, {name: suite.sample(name) for name in suite.specs}
    finally:
        world.close()


def _messages(specs, found, prefix='car1/'):
    """Return {topic: message} of the sensor rows for the readings ``found``."""
    kit = MessageKit(message_type)
    wiring = SimpleNamespace(frame_prefix=prefix)
    ctx = SimpleNamespace(readings=found, sample_stamp=stamp_builder(message_type)(0.5))
    rows = si.sensor_rows(specs)
    assert {row.cadence for row in rows} == {EACH_SAMPLE}
    assert {(row.qos.reliability, row.qos.depth) for row in rows} == {('reliable', 5)}
    return {row.name: row.converter(kit, wiring)(ctx) for row in rows}


def test_each_mounted_sensor_has_its_rows_and_messages_from_its_reading(readings):
    specs, found = readings
    messages = _messages(specs, found)
    assert {topic: type(msg).__ros_type__ for topic, msg in messages.items()} == {
        'scan': 'sensor_msgs/msg/LaserScan', 'points': 'sensor_msgs/msg/PointCloud2',
        'imu': 'sensor_msgs/msg/Imu', 'gnss/fix': 'sensor_msgs/msg/NavSatFix',
        'front': 'sensor_msgs/msg/Range', 'camera/image_raw': 'sensor_msgs/msg/Image',
        'camera/camera_info': 'sensor_msgs/msg/CameraInfo'}
    frames = {topic: msg.header.frame_id for topic, msg in messages.items()}
    assert frames == {'scan': 'car1/lidar', 'points': 'car1/lidar3d', 'imu': 'car1/imu',
                      'gnss/fix': 'car1/gnss', 'front': 'car1/front',
                      'camera/image_raw': 'car1/camera_optical',
                      'camera/camera_info': 'car1/camera_optical'}
    assert {(m.header.stamp.sec, m.header.stamp.nanosec) for m in messages.values()} == {
        (0, 500_000_000)}


def test_a_row_gives_nothing_for_a_sensor_without_a_reading(readings):
    specs, found = readings
    messages = _messages(specs, {'imu': found['imu']})
    assert [topic for topic, msg in messages.items() if msg is not None] == ['imu']


@pytest.mark.parametrize('topic', ['scan', 'points', 'imu', 'gnss/fix', 'front',
                                   'camera/image_raw', 'camera/camera_info'])
def test_sensor_message_cdr_equals_rosbags_bytes(readings, topic):
    specs, found = readings
    message = _messages(specs, found)[topic]
    assert message.serialize() == rosbags_bytes(message)


def test_laser_scan_carries_the_reading_rep_117_values_as_float32(readings):
    specs, found = readings
    scan, reading = _messages(specs, found)['scan'], found['lidar']
    assert list(scan.ranges) == reading.scan.tolist()
    assert scan.ranges[90] == pytest.approx(18.5, abs=1e-3)      # the wall, 19.5 - 1.0 m
    assert math.isinf(scan.ranges[0]) and scan.ranges[0] > 0
    assert (scan.angle_min, scan.angle_increment, scan.range_max) == pytest.approx(
        (-3.14159 / 2, 3.14159 / 180, 50.0))


def test_point_cloud_is_organized_xyz_float32_with_nan_for_misses(readings):
    specs, found = readings
    cloud, reading = _messages(specs, found)['points'], found['lidar3d']
    assert (cloud.height, cloud.width, cloud.point_step, cloud.row_step) == (4, 9, 12, 108)
    assert [(f.name, f.offset, f.datatype, f.count) for f in cloud.fields] == [
        ('x', 0, 7, 1), ('y', 4, 7, 1), ('z', 8, 7, 1)]
    assert (cloud.is_bigendian, cloud.is_dense) == (False, False)
    points = np.frombuffer(bytes(cloud.data), dtype='<f4').reshape(4, 9, 3)
    np.testing.assert_array_equal(points, reading.points())
    # layers at +0.1, +1/30, -1/30, -0.1 rad from 1.5 m up: the upper two pass over the 2 m
    # wall (1.5 + 18.5 tan(1/30) = 2.12 m) and miss; the third hits the wall face, x = 18.5 m
    # except its two outer rays (y = 18.5 tan 0.2 = 3.75 m > the wall's 3 m half-width); the
    # lowest reaches the ground first (z = -1.5 m, at 1.5 / tan 0.1 = 15 m)
    assert np.isnan(points[:2]).all()
    assert points[2, 1:-1, 0] == pytest.approx([18.5] * 7, abs=1e-3)
    assert points[3, :, 2] == pytest.approx([-1.5] * 9, abs=0.01)


def test_range_image_and_camera_info_carry_their_readings(readings):
    specs, found = readings
    messages = _messages(specs, found)
    distance = messages['front']
    assert distance.range == pytest.approx(18.5, abs=1e-3)
    assert (distance.max_range, distance.radiation_type, distance.variance) == (30.0, 0, 0.0)
    image, info, frame = messages['camera/image_raw'], messages['camera/camera_info'], \
        found['camera']
    assert bytes(image.data) == frame.data and (image.height, image.width) == (120, 160)
    assert (list(info.k), list(info.p), list(info.d)) == (list(frame.k), list(frame.p),
                                                           [0.0] * 5)


def test_collision_row_gives_one_message_per_event():
    kit = MessageKit(message_type)
    convert = si.COLLISION.converter(kit, SimpleNamespace(base_frame='car1/base_link'))
    event = SimpleNamespace(time_s=4.72, other='wall', normal_force_n=1234.5)
    msg = convert(SimpleNamespace(event=event, event_stamp=stamp_builder(message_type)(4.72)))
    assert (msg.other, msg.normal_force, msg.header.frame_id) == ('wall', 1234.5,
                                                                  'car1/base_link')
    assert msg.serialize() == rosbags_bytes(msg)
    assert si.COLLISION.cadence == ON_EVENT and si.COLLISION.qos.depth == 5


# ------------------------------------------------------------------------------- nodes

NAMESPACE = '/sensor_rows'


def _automobile(**overrides):
    from vehicle_sim.ros.automobile_node import AutomobileNode
    return AutomobileNode(['x', '--ros-args', '-r', f'__ns:={NAMESPACE}'], transport='dds',
                          parameter_overrides={'synchronous': True, **overrides})


def test_without_sensors_or_obstacles_the_node_adds_no_step_hook():
    app = _automobile()
    try:
        # only the car itself: no sensor suite, no collision monitor, no feed
        assert [type(body).__name__ for body in app.world.bodies] == ['SimulatedCar']
        assert app._sensing == []
    finally:
        app.close()


def test_obstacles_of_the_world_are_in_the_node_s_world_and_watched_for_collisions():
    app = _automobile(world='obstacle_course')
    try:
        assert sorted(app.world.obstacles) == ['pole', 'wall']
        kinds = [type(body).__name__ for body in app.world.bodies]
        assert kinds == ['SimulatedCar', 'CollisionMonitor', 'SensorSuite', 'SensorFeed']
    finally:
        app.close()


def test_sensors_parameter_mounts_on_every_vehicle_and_all_means_every_preset_sensor():
    app = _automobile(world='two_cars', sensors=['all'])
    try:
        for vehicle in app._vehicles:
            assert sorted(vehicle.feed.specs) == ['camera', 'gnss', 'imu', 'lidar']
        names = {row.name for row in app._vehicles[0].outputs.rows}
        assert {'scan', 'imu', 'gnss/fix', 'camera/image_raw', 'collision'} <= names
    finally:
        app.close()


@pytest.mark.parametrize('value, fragment', [
    (['all', 'lidar'], "'all' must be the only entry"),
    (['radar'], "unknown sensor(s) ['radar']"),
])
def test_a_bad_sensors_parameter_is_refused(value, fragment):
    with pytest.raises((InvalidParameterError, TransportError), match=re.escape(fragment)):
        _automobile(sensors=value)


def test_a_sensor_topic_taken_by_another_vehicle_is_refused_naming_both(tmp_path):
    path = tmp_path / 'clash.yaml'
    # the default car's topics are relative to the node namespace, as vehicle b's namespace
    path.write_text('vehicles:\n'
                    '  - {name: a, namespace: "", sensors: [{type: gnss, name: fix, '
                    'topic: b/odom}]}\n'
                    '  - {name: b, namespace: b}\n')
    with pytest.raises(InvalidParameterError) as info:
        _automobile(world=str(path))
    text = str(info.value)
    assert str(path) in text and "vehicle 'a'" in text and "'odom' of vehicle 'b'" in text
    # written as a global name, the same topic clashes too
    path.write_text(path.read_text().replace('topic: b/odom', f'topic: {NAMESPACE}/b/odom'))
    with pytest.raises(InvalidParameterError, match="'odom' of vehicle 'b'"):
        _automobile(world=str(path))


def test_a_robot_sensor_on_one_of_the_robot_s_topics_is_refused(tmp_path):
    from vehicle_sim.ros.diff_robot_node import DiffRobotNode
    path = tmp_path / 'robot.yaml'
    path.write_text('sensors:\n  - {type: distance, name: wheel_velocities, enabled: true}\n')
    with pytest.raises(InvalidParameterError, match="sensor topic 'wheel_velocities'.*"
                                                    "the robot's 'wheel_velocities'"):
        DiffRobotNode(transport='dds', namespace=NAMESPACE,
                      parameter_overrides={'synchronous': True, 'robot': str(path)})


# ------------------------------------------------------------------------------- the feed


def test_feed_keeps_every_step_s_readings_and_events_until_taken():
    world = World()
    try:
        for obstacle in COURSE.obstacles:
            world.add_obstacle(obstacle)
        car = SimulatedCar(world, load_car('Car'), (0.0, 0.0, 0.0), name='Car')
        specs = merge_sensors(car.params.sensor_set, [{'name': 'imu'}, {'name': 'gnss'}], 't')
        feed = SensorFeed(world, car.body, specs, COURSE.origin)
        assert isinstance(feed.monitor, CollisionMonitor)
        for _ in range(12):
            world.step()
        samples, events = feed.take()
        # the IMU at 100 Hz each step, the GNSS at 10 Hz at step 10
        assert [round(time_s, 9) for time_s, _ in samples] == [
            round(0.01 * k, 9) for k in range(1, 13)]
        assert [sorted(found) for _, found in samples][9] == ['gnss', 'imu']
        assert all(r.time_s == t for t, found in samples for r in found.values())
        assert events == [] and feed.take() == ([], [])
        car.logic.set_cruising_speed_kmh(20.0)
        for _ in range(800):
            world.step()
        others = [event.other for event in feed.take()[1]]
        assert others == ['wall']
        feed.close()
        assert world.bodies == (car,)
    finally:
        world.close()
