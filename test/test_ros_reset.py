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


Reset, teleport and pause over the wire (issue 9): the nodes in subprocesses, a client here.

The automobile node runs a world with a static wall and a movable crate in front of the car,


whose lidar ray straight ahead measures the crate; the robot node runs alone. Synchronous


stepping makes every assertion on simulated time exact; the real-time node shows /sim/pause.


Tolerances: the issue's 1 cm / 1 mrad between a teleport request and the odometry one step


later (the car settles on its suspension by a fraction of a millimetre in that step).
"""


import math
import time

from automobile_helpers import (
    automobile_fixtures,
    car_fixture,
    node_fixture,
    NodeProcess,
    stamp_of,
    VehicleClient,
    wait_for,
    wait_node_matched,
    WAIT_S,
)
import pytest

from vehicle_sim.config import load_car, load_world
from vehicle_sim.core.car.logic import CarLogic
from vehicle_sim.core.geometry.frames import (
    pose_in_frame,
    quaternion_from_rpy,
    rpy_from_quaternion,
)
from vehicle_sim.ros import automobile_interfaces as itf
from vehicle_sim.ros import robot_interfaces as ri
from vehicle_sim.ros.sensor_interfaces import sensor_rows
from vehicle_sim.ros.sim_control import INITIALPOSE
from vehicle_sim.transport.logger import WARN_THROTTLE_S
from vehicle_sim.transport.qos import QOS_DEFAULT

pytestmark = pytest.mark.transport


MODEL = 'Car'
POSITION_TOL_M = 0.01
YAW_TOL_RAD = 1e-3
CRATE_X_M = 8.0
# Lidar at x = 1 m on the car: the crate's near face (x = 7.5 m) is 6.5 m away at spawn.
CRATE_RANGE_M = CRATE_X_M - 0.5 - 1.0
WORLD = f"""
vehicles:
  - name: Car
    namespace: ''
    model: {MODEL}
    pose: {{x: 0.0, y: 0.0, yaw: 0.0}}
    sensors:
      - {{type: lidar, name: lidar, pose: {{x: 1.0, y: 0.0, z: 0.5}}, fov: 0.2,
         horizontal_resolution: 3, min_range: 0.1, max_range: 60.0, rate_hz: 100.0}}
obstacles:
  - {{name: wall, shape: box, size: [1.0, 6.0, 2.0], position: [30.0, 0.0, 1.0]}}
  - {{name: crate, shape: box, size: [1.0, 1.0, 1.0], position: [{CRATE_X_M}, 0.0, 0.5],
     mass: 20.0}}
"""
SETTERS = [s for s in itf.SERVICES if s.kind == itf.SETTER]
GETTERS = [s for s in itf.SERVICES if s.kind == itf.GETTER]
FLOAT_TOPICS = ['automobile/throttle', 'automobile/brake_intensity', 'automobile/current_speed',
                'automobile/steering_angle', 'automobile/front_left_wheel_encoder',
                'automobile/rear_right_wheel_speed']


@pytest.fixture(scope='class')
def world_file(tmp_path_factory):
    path = tmp_path_factory.mktemp('reset') / 'crate.yaml'
    path.write_text(WORLD)
    return path


sim, tester, car = automobile_fixtures(
    'reset_tester', lambda request: ['--ros-args', '-p', 'synchronous:=true', '-p',
                                     f'world:={request.getfixturevalue("world_file")}'],
    ['odom', '/tf', 'joint_states', '/clock'] + FLOAT_TOPICS, scope='class')


@pytest.fixture(scope='class')
def lidar(car, tester, world_file):
    row, = sensor_rows(load_world(str(world_file), MODEL).vehicles[0].sensors)
    scans = []
    sub = tester.create_subscription(row.ros_type, '/' + row.name, scans.append, row.qos)
    assert wait_for(lambda: sub.get_publisher_count(), spin=tester)
    car.wait_node_matched()

    def ahead():
        """Step one basic step; return the range of the middle ray of that step's scan."""
        assert car.call('robot/time_step', 0).success
        now = car.time_s()
        scan = wait_for(lambda: scans and abs(stamp_of(scans[-1]) - now) < 1e-9 and scans[-1],
                        spin=tester)
        assert scan, f'no scan stamped {now}'
        return scan.ranges[len(scan.ranges) // 2]
    return ahead


@pytest.fixture(scope='module')
def initialpose(tester):
    return tester.create_publisher(INITIALPOSE.ros_type, INITIALPOSE.name, INITIALPOSE.qos)


def _publish(tester, publisher, msg):
    # The node under test is the only /initialpose reader alive (one process per class).
    assert wait_for(lambda: publisher.get_subscription_count(), spin=tester)
    publisher.publish(msg)


def _pose(node, x, y, z=0.0, rpy=(0.0, 0.0, 0.0), q=None):
    pose_type = node.msg('geometry_msgs/msg/Pose')
    pose = pose_type()
    pose.position.x, pose.position.y, pose.position.z = x, y, z
    qx, qy, qz, qw = q if q is not None else quaternion_from_rpy(*rpy)
    pose.orientation.x, pose.orientation.y, pose.orientation.z, pose.orientation.w = \
        qx, qy, qz, qw
    return pose


def _stamped(node, frame_id, pose):
    msg = node.msg(INITIALPOSE.ros_type)()
    msg.header.frame_id = frame_id
    msg.pose.pose = pose
    return msg


def _xy_yaw(pose):
    p, q = pose.position, pose.orientation
    return p.x, p.y, rpy_from_quaternion((q.x, q.y, q.z, q.w))[2]


def _assert_at(pose, x, y, yaw):
    px, py, pyaw = _xy_yaw(pose)
    assert math.hypot(px - x, py - y) < POSITION_TOL_M, (px, py)
    assert abs(math.remainder(pyaw - yaw, math.tau)) < YAW_TOL_RAD, pyaw


def _odom_after_one_step(car):
    return car.step_and_read('odom')


def _initial_getters():
    logic = CarLogic(load_car(MODEL))
    return {spec.name: getattr(logic, spec.core) for spec in GETTERS}


def _getters(car):
    return {spec.name: car.call(spec.name).value for spec in GETTERS}


# ------------------------------------------------------------------------------ the car

BAD_POSES = [
    pytest.param(dict(x=math.nan, y=0.0), 'x = nan', id='nan'),
    pytest.param(dict(x=0.0, y=math.inf), 'y = inf', id='inf'),
    pytest.param(dict(x=0.0, y=0.0, q=(0.0, 0.0, 0.0, 1.01)), 'norm 1.01', id='norm'),
    pytest.param(dict(x=0.0, y=0.0, q=(0.0, 0.0, 0.0, 0.0)), 'norm 0', id='zero-quaternion'),
    pytest.param(dict(x=30.0, y=1.0), 'inside wall', id='in-the-wall'),
    pytest.param(dict(x=CRATE_X_M + 1.0, y=0.0), 'inside crate', id='on-the-crate'),
    # Beyond the world (|x|, |y| <= 1e6 m): at 1e100 m Bullet lost the car for good.
    pytest.param(dict(x=1e308, y=0.0), 'x = 1e+308 m is outside the world', id='far-x'),
    pytest.param(dict(x=0.0, y=-1.0000001e6), 'y = -1e+06 m is outside the world',
                 id='just-beyond-y'),
]


@pytest.fixture
def resting(car, tester):
    """Teleport the car to (2, 1, 0.3), let it settle; return its odometry and getters."""
    assert car.call('reset').success
    assert car.call('automobile/set_indicator', 2).success
    assert car.call('set_pose', pose=_pose(tester, 2.0, 1.0, rpy=(0, 0, 0.3))).success
    odom = car.step_and_read('odom', 200)
    return odom, _getters(car)


def _assert_unchanged(car, resting):
    odom, getters = resting
    now = _odom_after_one_step(car)
    _assert_at(now.pose.pose, *_xy_yaw(odom.pose.pose))
    assert _getters(car) == getters


BAD_INITIALPOSES = [
    pytest.param('base_link', dict(x=1.0, y=1.0), "unknown frame_id 'base_link'",
                 id='unknown-frame'),
    pytest.param('map', dict(x=math.nan, y=0.0), 'x = nan', id='nan'),
]


class TestCar:
    """The car in the crate world, synchronous."""

    def test_reset_returns_pose_every_getter_and_topic_to_the_initial_values(self, car):
        for spec in SETTERS:
            assert car.call(spec.name, spec.example).success, spec.name
        car.call('automobile/set_brake_intensity', 0.0)     # let it drive (TORQUE mode, gear 1)
        moved = car.step_and_read('odom', 3000).pose.pose.position
        assert math.hypot(moved.x, moved.y) > 1.0
        assert _getters(car) != _initial_getters()
        before_s = car.time_s()
        answer = car.call('reset')
        assert answer.success
        assert 'spawn pose' in answer.message and 'simulated time goes on' in answer.message
        assert car.time_s() == before_s                      # time is not rewound
        assert _getters(car) == _initial_getters()
        odom = _odom_after_one_step(car)
        assert stamp_of(odom) == pytest.approx(before_s + 0.01, abs=1e-9)
        _assert_at(odom.pose.pose, 0.0, 0.0, 0.0)
        twist = odom.twist.twist
        assert math.hypot(twist.linear.x, twist.linear.y) < 0.05
        # Every Float64Stamped topic of that step reports the start state.
        assert car.latest['automobile/throttle'].data == 0.0
        for name, bound in (('automobile/brake_intensity', 0.0), ('automobile/current_speed', 0.2),
                            ('automobile/steering_angle', 1e-3),
                            ('automobile/front_left_wheel_encoder', 0.05),
                            ('automobile/rear_right_wheel_speed', 1.0)):
            assert abs(car.step_and_read(name).data) <= bound, name

    def test_set_pose_teleports_and_odometry_tf_and_joints_agree_in_the_same_step(self, car,
                                                                                   tester):
        assert car.call('reset').success
        car.call('automobile/set_cruising_speed', 20.0)
        car.step_and_read('odom', 1000)
        answer = car.call('set_pose',
                          pose=_pose(tester, 3.0, -4.0, z=2.0, rpy=(0.2, -0.1, 0.7)))
        assert answer.success, answer.message
        assert 'x 3.000 m, y -4.000 m, yaw 0.7000 rad' in answer.message
        odom = _odom_after_one_step(car)
        _assert_at(odom.pose.pose, 3.0, -4.0, 0.7)
        position, q = odom.pose.pose.position, odom.pose.pose.orientation
        assert abs(position.z) < 0.02                        # on the ground, not at z = 2
        roll, pitch, _ = rpy_from_quaternion((q.x, q.y, q.z, q.w))
        assert abs(roll) < 1e-3 and abs(pitch) < 1e-3        # level, as the ground is
        assert math.hypot(odom.twist.twist.linear.x, odom.twist.twist.linear.y) < 0.05
        # /tf of that step carries the same transform; the joints are at rest.
        tf = car.latest['/tf']
        assert stamp_of(tf.transforms[0]) == stamp_of(odom)
        t = tf.transforms[0].transform
        assert (t.translation.x, t.translation.y, t.rotation.z, t.rotation.w) == \
            (position.x, position.y, q.z, q.w)
        joints = car.latest['joint_states']
        assert stamp_of(joints) == stamp_of(odom)
        assert max(abs(v) for v in joints.velocity) < 1.0
        # The cruising speed stays in force: the car drives off again from rest.
        assert car.call('automobile/get_cruising_speed').value == 20.0

    @pytest.mark.parametrize('frame_id', ['map', 'world', '', 'odom'])
    def test_initialpose_teleports_the_first_vehicle(self, car, tester, initialpose, frame_id):
        assert car.call('reset').success
        x, y, yaw = -5.0, 2.0 + len(frame_id), -1.2
        _publish(tester, initialpose,
                 _stamped(tester, frame_id, _pose(tester, x, y, rpy=(0.0, 0.0, yaw))))

        def arrived():
            odom = _odom_after_one_step(car)
            return math.hypot(odom.pose.pose.position.x - x,
                              odom.pose.pose.position.y - y) < POSITION_TOL_M and odom

        odom = wait_for(arrived)
        assert odom, 'the car never reached the /initialpose pose'
        _assert_at(odom.pose.pose, x, y, yaw)

    @pytest.mark.parametrize('request_fields, reason', BAD_POSES)
    def test_set_pose_refuses_a_bad_pose_and_changes_nothing(self, car, tester, resting,
                                                             request_fields, reason):
        answer = car.call('set_pose', pose=_pose(tester, **request_fields))
        assert not answer.success
        assert reason in answer.message and 'nothing moved' in answer.message
        _assert_unchanged(car, resting)

    @pytest.mark.parametrize('frame_id, fields, warning', BAD_INITIALPOSES)
    def test_initialpose_refuses_a_bad_pose_with_a_warning_and_changes_nothing(
            self, car, tester, sim, initialpose, resting, frame_id, fields, warning):
        time.sleep(WARN_THROTTLE_S)    # a warning of the previous case is not throttling this one
        _publish(tester, initialpose, _stamped(tester, frame_id, _pose(tester, **fields)))
        assert wait_for(lambda: warning in sim.text(), spin=tester), sim.text()[-2000:]
        _assert_unchanged(car, resting)

    def test_sim_pause_in_synchronous_mode_answers_that_time_moves_by_time_step(self, car):
        before_s = car.time_s()
        answer = car.call('/sim/pause', data=True)
        assert not answer.success
        assert 'synchronous' in answer.message and 'robot/time_step' in answer.message
        assert car.call('robot/time_step', 0).success       # stepping still works
        assert car.time_s() == pytest.approx(before_s + 0.01, abs=1e-9)

    def test_sim_reset_puts_the_car_and_the_pushed_crate_back(self, car, tester, lidar):
        assert car.call('/sim/reset').success     # earlier tests may have pushed the crate
        assert lidar() == pytest.approx(CRATE_RANGE_M, abs=0.02)
        # Drive into the crate and push it, then bring the car alone back: the crate is farther.
        assert car.call('automobile/set_cruising_speed', 25.0).success
        car.step_and_read('odom', 5000)
        assert car.call('set_pose', pose=_pose(tester, 0.0, 0.0)).success
        assert car.call('automobile/set_cruising_speed', 0.0).success
        assert lidar() > CRATE_RANGE_M + 1.0
        before_s = car.time_s()
        answer = car.call('/sim/reset')
        assert answer.success
        assert "vehicle 'Car'" in answer.message and 'crate' in answer.message
        assert 'wall' not in answer.message           # static: never moves
        assert lidar() == pytest.approx(CRATE_RANGE_M, abs=0.02)
        odom = _odom_after_one_step(car)
        assert stamp_of(odom) > before_s                 # simulated time went on
        _assert_at(odom.pose.pose, 0.0, 0.0, 0.0)
        assert car.call('automobile/get_cruising_speed').value == 0.0


# ------------------------------------------------------------------------------ options

two_cars = node_fixture(['--ros-args', '-p', 'world:=two_cars', '-p', 'synchronous:=true',
                         '-p', 'initialpose_vehicle:=car2'], scope='class', name='two_cars')


realtime_node = node_fixture(['--ros-args', '-p', 'synchronous:=false'], scope='class',
                             name='realtime_node')
realtime = car_fixture(['/clock'], scope='class', node='realtime_node', name='realtime')


class TestTwoCars:
    """Two cars, /initialpose for the second (parameter initialpose_vehicle)."""

    def test_initialpose_vehicle_and_a_pose_in_its_odom_frame(self, two_cars, tester, initialpose):
        car1, car2 = VehicleClient(tester, 'car1'), VehicleClient(tester, 'car2')
        car1.wait_matched(['odom'])
        car2.wait_matched(['odom'])
        assert wait_for(lambda: initialpose.get_subscription_count() >= 1, spin=tester)
        start1 = car1.step_and_read('odom')
        # car2 spawns at (0, 6) in the world: a pose in car2/odom is taken relative to that.
        _publish(tester, initialpose,
                 _stamped(tester, 'car2/odom', _pose(tester, 2.0, 1.0, rpy=(0, 0, 0.5))))

        def arrived():
            odom = car2.step_and_read('odom')
            return abs(odom.pose.pose.position.x - 2.0) < POSITION_TOL_M and odom

        odom = wait_for(arrived)
        assert odom, 'car2 never reached the /initialpose pose'
        _assert_at(odom.pose.pose, 2.0, 1.0, 0.5)          # its odom frame: the request itself
        _assert_at(car1.step_and_read('odom').pose.pose, *_xy_yaw(start1.pose.pose))
        # car2's own set_pose is in the world frame: (0, 6) is its spawn, odom (0, 0).
        assert car2.call('set_pose', pose=_pose(tester, 0.0, 6.0)).success
        _assert_at(car2.step_and_read('odom').pose.pose, 0.0, 0.0, 0.0)

    def test_unknown_initialpose_vehicle_is_refused_naming_the_vehicles(self):
        process = NodeProcess('--ros-args', '-p', 'world:=two_cars', '-p', 'synchronous:=true',
                              '-p', 'initialpose_vehicle:=car3')
        try:
            assert process.wait() != 0
            assert "initialpose_vehicle = 'car3'" in process.text()
            assert 'car1, car2' in process.text()
        finally:
            process.stop()


class TestRealTime:
    """The default car in real time: /sim/pause."""

    def test_sim_pause_stops_clock_and_resume_continues_it(self, realtime, tester):
        car = realtime
        assert wait_for(lambda: '/clock' in car.latest, spin=tester)
        answer = car.call('/sim/pause', data=True)
        assert answer.success and answer.message.startswith('paused at')
        paused_s = car.time_s()
        assert car.call('/sim/pause', data=True).message.startswith('already paused')
        end = time.monotonic() + 0.5
        while time.monotonic() < end:        # let any step in flight arrive
            tester.spin_once(0.05)
        assert car.time_s() == paused_s
        # (within a nanosecond: a stamp's sec + 1e-9 nanosec and the node's float time may
        # differ in the last bit, 0.030000000000000002 against 0.03)
        assert stamp_of(car.latest['/clock']) <= paused_s + 1e-9
        answer = car.call('/sim/pause', data=False)
        assert answer.success and answer.message.startswith('resumed at')
        assert wait_for(lambda: stamp_of(car.latest['/clock']) > paused_s + 0.05, spin=tester)
        assert car.time_s() > paused_s


# ------------------------------------------------------------------------------ the robot

ROBOT_SPAWN = (1.0, 2.0, 0.5)


@pytest.fixture(scope='class')
def robot(tester):
    x, y, yaw = ROBOT_SPAWN
    process = NodeProcess('--ros-args', '-p', 'synchronous:=true', '-p', f'x:={x}', '-p',
                          f'y:={y}', '-p', f'yaw:={yaw}', module='vehicle_sim.ros.diff_robot_node')
    latest = {}
    subs = [tester.create_subscription(
        row.ros_type, f'/{ri.ROBOT_NODE_NAME}/{row.name}',
        lambda msg, key=row.name: latest.__setitem__(key, msg), QOS_DEFAULT)
        for row in (ri.ROBOT_ODOM, ri.ROBOT_GROUND_TRUTH_ODOM)]
    clients = {}

    def call(name, srv_type, **fields):
        if name not in clients:
            full = name if name.startswith('/') else f'/{ri.ROBOT_NODE_NAME}/{name}'
            clients[name] = tester.create_client(srv_type, full)
            assert clients[name].wait_for_service(WAIT_S), full
        request = tester.srv(srv_type).Request()
        for key, value in fields.items():
            setattr(request, key, value)
        return clients[name].call(request, WAIT_S)

    def step():
        """Step once; return (wheel odom, ground truth) stamped with the new time."""
        before = {key: stamp_of(msg) for key, msg in latest.items()}
        assert call('robot/time_step', 'vehicle_msgs/srv/SetInt', value=0).success

        def fresh():
            return len(latest) == 2 and all(stamp_of(latest[k]) > before.get(k, -1.0)
                                           for k in ('odom', 'ground_truth/odom'))
        assert wait_for(fresh, spin=tester)
        return latest['odom'], latest['ground_truth/odom']

    try:
        assert wait_for(lambda: all(s.get_publisher_count() for s in subs), spin=tester)
        wait_node_matched(tester, f'/{ri.ROBOT_NODE_NAME}/list_parameters',
                          'rcl_interfaces/srv/ListParameters')
        yield call, step
    finally:
        process.stop()


class TestRobot:
    """The diff_robot node alone, owning its world, synchronous, spawned off the origin."""

    def test_robot_set_pose_initialpose_and_reset_keep_wheel_odometry_with_ground_truth(
            self, robot, tester, initialpose):
        call, step = robot
        answer = call('set_pose', 'vehicle_msgs/srv/SetPose',
                      pose=_pose(tester, 4.0, -1.0, rpy=(0.0, 0.0, 1.0)))
        assert answer.success, answer.message
        odom, truth = step()
        _assert_at(truth.pose.pose, 4.0, -1.0, 1.0)               # world frame
        x, y, yaw = ROBOT_SPAWN
        xyz, q = pose_in_frame((x, y, 0.0), quaternion_from_rpy(0, 0, yaw), (4.0, -1.0, 0.0),
                               quaternion_from_rpy(0, 0, 1.0))
        _assert_at(odom.pose.pose, xyz[0], xyz[1], rpy_from_quaternion(q)[2])   # odom frame
        # /initialpose in the robot's odom frame (it owns its world, so it reads /initialpose).
        _publish(tester, initialpose, _stamped(tester, 'diff_robot/odom', _pose(tester, 0.5, 0.5,
                                                                      rpy=(0, 0, 0.2))))

        def arrived():
            odom, _ = step()
            return abs(odom.pose.pose.position.x - 0.5) < POSITION_TOL_M

        assert wait_for(arrived)
        odom, truth = step()
        _assert_at(odom.pose.pose, 0.5, 0.5, 0.2)
        answer = call('reset', 'std_srvs/srv/Trigger')
        assert answer.success and 'spawn pose' in answer.message
        odom, truth = step()
        _assert_at(odom.pose.pose, 0.0, 0.0, 0.0)
        _assert_at(truth.pose.pose, *ROBOT_SPAWN)
        refused = call('set_pose', 'vehicle_msgs/srv/SetPose',
                       pose=_pose(tester, 0.0, 0.0, q=(0.0, 0.0, 0.5, 0.5)))
        assert not refused.success and 'norm' in refused.message
        answer = call('/sim/pause', 'std_srvs/srv/SetBool', data=True)
        assert not answer.success and 'synchronous' in answer.message
