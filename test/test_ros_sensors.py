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
Sensors, obstacles and collisions over the wire (docs/sensors.md, docs/ros_interface.md).

The automobile node runs the obstacle course (config/worlds/obstacle_course.yaml) in a
subprocess, synchronous; the test steps it through ``robot/time_step`` and reads every sensor
topic with its own DdsNode. Steps go 40 ms at a time while messages are counted, so that no
topic gets more than 4 messages per call (sensor topics keep 5). Expected stamps come from the
sampling rule (the first basic step at or after each k / rate_hz), computed here with exact
fractions; the golden values from the course's geometry (docs/sensors.md).
"""

from fractions import Fraction
import math

from automobile_helpers import (
    automobile_fixtures,
    NodeProcess,
    stamp_of,
    VehicleClient,
    wait_for,
    wait_node_matched,
)
import pytest

from vehicle_sim.ros import automobile_interfaces as itf
from vehicle_sim.ros.sensor_interfaces import QOS_SENSOR
from vehicle_sim.transport.qos import QOS_TF_STATIC_LISTENER

pytestmark = pytest.mark.transport

STEP_S = Fraction(1, 100)           # the course runs on the default 10 ms step
CHUNK_MS = 40
NAMESPACE = 'sensed'
WALL_FACE_X_M = 19.5
# topic -> (type, frame, rate [Hz]) of the course's sensors (config/worlds/obstacle_course.yaml)
COURSE_TOPICS = {
    'scan': ('sensor_msgs/msg/LaserScan', 'lidar', '10.0'),
    'imu': ('sensor_msgs/msg/Imu', 'imu', '100.0'),
    'gnss/fix': ('sensor_msgs/msg/NavSatFix', 'gnss', '10.0'),
    'camera/image_raw': ('sensor_msgs/msg/Image', 'camera_optical', '5.0'),
    'camera/camera_info': ('sensor_msgs/msg/CameraInfo', 'camera_optical', '5.0'),
}


def expected_stamps(rate, until_s):
    """Stamps [s] of a sensor at ``rate`` Hz up to ``until_s``: ceil(k / rate / step) steps."""
    stamps, k = [], 1
    while True:
        steps = math.ceil(Fraction(k) / Fraction(rate) / STEP_S)
        if steps * STEP_S > Fraction(until_s).limit_denominator(1000):
            return stamps
        stamps.append(float(steps * STEP_S))
        k += 1


class Listener:
    """Subscriptions of one test node to sensor topics, keeping every message."""

    def __init__(self, node, prefix, topics):
        self.node = node
        self.prefix = prefix
        self.received = {topic: [] for topic in topics}
        self.subs = [node.create_subscription(
            ros_type, f'{prefix}/{topic}',
            lambda msg, key=topic: self.received[key].append(msg), QOS_SENSOR)
            for topic, (ros_type, *_rest) in topics.items()]

    def wait_matched(self, service='robot/get_time', srv_type='vehicle_msgs/srv/GetFloat'):
        """Return once the node, answering ``service`` under the prefix, has matched them."""
        assert wait_for(lambda: all(s.get_publisher_count() for s in self.subs),
                        spin=self.node)
        wait_node_matched(self.node, f'{self.prefix}/{service}', srv_type)

    def wait_counts(self, counts):
        """Spin until each topic has ``counts[topic]`` messages; return whether it happened."""
        return wait_for(lambda: all(len(self.received[t]) >= n for t, n in counts.items()),
                        spin=self.node)


course, tester, car = automobile_fixtures(
    'sensor_tester', ['--ros-args', '-r', f'__ns:=/{NAMESPACE}', '-p', 'world:=obstacle_course',
                      '-p', 'synchronous:=true'],
    ['/clock', 'collision'], NAMESPACE, names=('course', 'tester', 'car'))


@pytest.fixture(scope='module')
def listener(car, tester):
    found = Listener(tester, f'/{NAMESPACE}', COURSE_TOPICS)
    found.wait_matched()
    return found


def test_every_sensor_topic_is_published_at_its_rate_on_simulated_time(car, listener):
    assert car.time_s() == 0.0
    until_s = 1.0
    for chunk in range(1, round(until_s * 1000 / CHUNK_MS) + 1):
        assert car.call('robot/time_step', CHUNK_MS).success
        now_s = chunk * CHUNK_MS / 1000.0
        assert listener.wait_counts({topic: len(expected_stamps(rate, now_s))
                                     for topic, (_, _, rate) in COURSE_TOPICS.items()})
    assert car.time_s() == pytest.approx(until_s, abs=1e-12)
    for topic, (ros_type, frame, rate) in COURSE_TOPICS.items():
        messages = listener.received[topic]
        # 100 Hz: each 10 ms step; 10 Hz: steps 10, 20, ...; 5 Hz: steps 20, 40, ...
        assert [stamp_of(msg) for msg in messages] == pytest.approx(
            expected_stamps(rate, until_s), abs=1e-9), topic
        assert {msg.header.frame_id for msg in messages} == {frame}, topic
        assert {type(msg).__ros_type__ for msg in messages} == {ros_type}, topic
    assert len(listener.received['imu']) == 100 and len(listener.received['scan']) == 10


def test_scan_imu_and_fix_carry_the_golden_values_of_the_course(car, listener):
    scan = listener.received['scan'][-1]
    # 181 rays over 3.14159 rad: ray 90 at 0 rad reads the wall's near face (x = 19.5 m)
    # minus the lidar's mount offset (x = 1.0 m)
    assert len(scan.ranges) == 181
    assert scan.angle_min + 90 * scan.angle_increment == pytest.approx(0.0, abs=1e-6)
    assert scan.ranges[90] == pytest.approx(WALL_FACE_X_M - 1.0, abs=1e-3)
    assert math.isinf(scan.ranges[0]) and scan.ranges[0] > 0       # REP 117: no return
    assert (scan.range_min, scan.range_max) == pytest.approx((0.1, 50.0))
    assert scan.scan_time == pytest.approx(0.1)
    imu = car_at_rest_imu(car, listener)
    # at rest (3 s: the suspension has settled): +g on z, no rotation
    acceleration = imu.linear_acceleration
    assert (acceleration.x, acceleration.y, acceleration.z) == pytest.approx(
        (0.0, 0.0, 9.81), abs=1e-3)
    assert imu.angular_velocity.z == pytest.approx(0.0, abs=1e-6)
    assert list(imu.orientation_covariance) == [0.0] * 9
    fix = listener.received['gnss/fix'][-1]
    # antenna on the vehicle at the origin: the world's origin, 1.5 m up
    assert (fix.latitude, fix.longitude) == pytest.approx((48.0, 11.0), abs=1e-9)
    assert fix.altitude == pytest.approx(501.5, abs=0.01)
    assert (fix.status.status, fix.status.service, fix.position_covariance_type) == (0, 1, 0)


def car_at_rest_imu(car, listener):
    """Step to 3.0 s in one call and return the IMU message stamped 3.0 s."""
    assert car.call('robot/time_step', round((3.0 - car.time_s()) * 1000)).success
    imu = wait_for(lambda: next((m for m in reversed(listener.received['imu'])
                                 if abs(stamp_of(m) - 3.0) < 1e-9), None), spin=car.node)
    assert imu, 'no IMU message stamped 3.0 s'
    return imu


def test_camera_image_and_info_match_the_configured_camera(car, listener):
    image, info = listener.received['camera/image_raw'][-1], \
        listener.received['camera/camera_info'][-1]
    assert stamp_of(image) == stamp_of(info)
    assert (image.width, image.height, image.encoding, image.step) == (160, 120, 'rgb8', 480)
    assert len(image.data) == 160 * 120 * 3
    # fx = (width / 2) / tan(fov / 2), principal point at the centre of the pixel grid
    focal = 80.0 / math.tan(0.5)
    assert list(info.k) == pytest.approx([focal, 0.0, 79.5, 0.0, focal, 59.5, 0.0, 0.0, 1.0])
    assert (info.width, info.height, info.distortion_model) == (160, 120, 'plumb_bob')


def test_tf_static_holds_the_sensor_frames_and_the_description_their_links(car):
    car.subscribe('/tf_static')
    msg = wait_for(lambda: next((m for m in car.history['/tf_static']
                                 if any(t.child_frame_id == 'lidar' for t in m.transforms)),
                                None), spin=car.node)
    assert msg
    transforms = {(t.header.frame_id, t.child_frame_id):
                  (t.transform.translation.x, t.transform.translation.y,
                   t.transform.translation.z) for t in msg.transforms}
    assert transforms == {('world', 'odom'): (0.0, 0.0, 0.0),
                          ('base_link', 'lidar'): (1.0, 0.0, 1.5),
                          ('base_link', 'imu'): (0.0, 0.0, 0.5),
                          ('base_link', 'gnss'): (0.0, 0.0, 1.5),
                          ('base_link', 'camera'): (1.5, 0.0, 1.3),
                          ('camera', 'camera_optical'): (0.0, 0.0, 0.0)}
    car.subscribe('robot_description')
    urdf = wait_for(lambda: car.latest.get('robot_description'), spin=car.node)
    assert urdf
    for link in ('lidar', 'imu', 'gnss', 'camera', 'camera_optical'):
        assert f'<link name="{link}"/>' in urdf.data


def test_driving_into_the_wall_gives_exactly_one_collision_naming_it(car):
    collisions = []
    car.subscribe('odom')
    sub = car.node.create_subscription(itf.COLLISION.ros_type, car.name('collision'),
                                       collisions.append, itf.COLLISION.qos)
    assert wait_for(lambda: sub.get_publisher_count(), spin=car.node)
    car.wait_node_matched()
    start_s = car.time_s()
    assert car.call('automobile/set_cruising_speed', 20.0).success
    # 20 km/h from rest: the front (4.5 m ahead of base_link) reaches the wall after about
    # 15 m, 5 s; then the car keeps pushing against it
    for _ in range(16):
        assert car.call('robot/time_step', 500).success
    end_s = car.time_s()
    assert wait_for(lambda: collisions, spin=car.node)
    odom = car.step_and_read('odom')
    assert odom.pose.pose.position.x + 4.5 == pytest.approx(WALL_FACE_X_M, abs=0.1)
    # a second report would have been published before the steps' replies; give it time
    assert not wait_for(lambda: len(collisions) > 1, timeout_s=2.0, spin=car.node)
    collision, = collisions
    assert collision.other == 'wall' and collision.normal_force > 0.0
    assert collision.header.frame_id == 'base_link'
    assert start_s < stamp_of(collision) < end_s


# ------------------------------------------------------------------------------- start-up

WORLD_HEAD = 'vehicles:\n  - name: Car\n    sensors:\n'
BAD_WORLDS = [
    pytest.param(WORLD_HEAD + '      - {type: lidar, name: lidar, max_range: -1.0}\n',
                 "sensors[0]: field 'max_range' = -1.0", id='negative-range'),
    pytest.param(WORLD_HEAD + '      - {type: lidar, name: lidar, horizontal_resolution: 0}\n',
                 "field 'horizontal_resolution' = 0", id='zero-resolution'),
    pytest.param(WORLD_HEAD + '      - {type: sonar, name: sonar}\n',
                 "field 'type' = 'sonar': unknown sensor type", id='unknown-type'),
    pytest.param('vehicles: [{name: Car}]\nobstacles:\n  - {name: cone1, shape: cone, '
                 'position: [5.0, 0.0, 0.5]}\n', "obstacles[0]: field 'shape' = 'cone'",
                 id='unknown-shape'),
    pytest.param('vehicles: [{name: Car}]\nobstacles:\n  - {name: box1, shape: box, '
                 'size: [1.0, .nan, 1.0], position: [5.0, 0.0, 0.5]}\n',
                 "obstacles[0]: field 'size'", id='nan-size'),
]


@pytest.mark.parametrize('text, fragment', BAD_WORLDS)
def test_a_bad_sensor_or_obstacle_stops_the_node_at_start_naming_file_and_field(
        tmp_path, text, fragment):
    path = tmp_path / 'bad_world.yaml'
    path.write_text(text)
    process = NodeProcess('--ros-args', '-r', '__ns:=/bad_world', '-p', f'world:={path}')
    try:
        status = process.wait()
    finally:
        process.stop()
    output = process.text()
    assert status == 2, output
    assert str(path) in output and fragment in output, output
    assert 'ready' not in output and 'Traceback' not in output, output


def test_sensors_parameter_mounts_preset_sensors_and_refuses_an_unknown_name(tester):
    process = NodeProcess('--ros-args', '-r', '__ns:=/param_sensors', '-p',
                          'synchronous:=true', '-p', 'sensors:=[lidar]')
    try:
        client = VehicleClient(tester, 'param_sensors')
        found = Listener(tester, '/param_sensors', {'scan': COURSE_TOPICS['scan']})
        found.wait_matched()
        assert client.call('robot/time_step', 100).success
        assert found.wait_counts({'scan': 1})
        scan, = found.received['scan']
        # the car preset's lidar: Webots' Sick LMS 291, 180 rays over 180 deg, 0.1 .. 80 m
        assert (len(scan.ranges), scan.header.frame_id) == (180, 'lidar')
        assert (scan.range_min, scan.range_max) == pytest.approx((0.1, 80.0))
        assert stamp_of(scan) == pytest.approx(0.1, abs=1e-9)
    finally:
        process.stop()
    bad = NodeProcess('--ros-args', '-r', '__ns:=/param_sensors', '-p', 'sensors:=[radar]')
    try:
        status = bad.wait()
    finally:
        bad.stop()
    assert status == 2
    assert "unknown sensor(s) ['radar']" in bad.text() and 'lidar, camera, gnss, imu' in \
        bad.text()


# ------------------------------------------------------------------------------- diff_robot

ROBOT_MODULE = 'vehicle_sim.ros.diff_robot_node'
ROBOT_TOPICS = {'scan': ('sensor_msgs/msg/LaserScan', 'sensed_robot/diff_robot/lidar', '10.0'),
                'imu': ('sensor_msgs/msg/Imu', 'sensed_robot/diff_robot/imu', '100.0')}


def test_diff_robot_publishes_its_lidar_and_imu_the_same_way(tester):
    process = NodeProcess('--ros-args', '-r', '__ns:=/sensed_robot', '-p', 'synchronous:=true',
                          '-p', 'sensors:=[lidar,imu]', module=ROBOT_MODULE)
    try:
        prefix = '/sensed_robot/diff_robot'
        found = Listener(tester, prefix, ROBOT_TOPICS)
        found.wait_matched('list_parameters', 'rcl_interfaces/srv/ListParameters')
        time_step = tester.create_client('vehicle_msgs/srv/SetInt', f'{prefix}/robot/time_step')
        assert time_step.wait_for_service(60.0)
        request = tester.srv('vehicle_msgs/srv/SetInt').Request()
        request.value = CHUNK_MS
        for chunk in range(1, 6):
            assert time_step.call(request, 60.0).success
            now_s = chunk * CHUNK_MS / 1000.0
            assert found.wait_counts({topic: len(expected_stamps(rate, now_s))
                                      for topic, (_, _, rate) in ROBOT_TOPICS.items()})
        for topic, (ros_type, frame, rate) in ROBOT_TOPICS.items():
            messages = found.received[topic]
            assert [stamp_of(m) for m in messages] == pytest.approx(
                expected_stamps(rate, 0.2), abs=1e-9), topic
            assert {m.header.frame_id for m in messages} == {frame}, topic
        # the robot preset's lidar: 360 rays 1 deg apart, 0.12 .. 12 m; nothing to hit
        scan = found.received['scan'][-1]
        assert len(scan.ranges) == 360 and all(math.isinf(r) for r in scan.ranges)
        imu = found.received['imu'][-1]
        assert imu.linear_acceleration.z == pytest.approx(9.81, abs=0.05)
        statics = []
        tester.create_subscription('tf2_msgs/msg/TFMessage', '/tf_static', statics.append,
                                   QOS_TF_STATIC_LISTENER)
        msg = wait_for(lambda: next((m for m in statics if any(
            t.child_frame_id == ROBOT_TOPICS['scan'][1] for t in m.transforms)), None),
            spin=tester)
        assert msg and {t.child_frame_id for t in msg.transforms} == {
            'sensed_robot/diff_robot/odom', 'sensed_robot/diff_robot/lidar',
            'sensed_robot/diff_robot/imu'}
    finally:
        process.stop()
