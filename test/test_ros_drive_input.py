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
cmd_vel and drive over the wire: the node in a subprocess, this test's node on DDS.

The nodes run synchronously, so time moves only on robot/time_step and every assertion is on
simulated time. A command is known to be applied before the next step when the car's
``get_cruising_speed`` answers its cruising speed (the barrier of :func:`send`).

Tolerances: in a steady turn the measured (ground truth) base_link speed is within 2 % of the
commanded v and the yaw rate within 3 % of ω = v·tan(δ)/L (tyre slip and the Ackermann wheels'
mean angle differ slightly from the bicycle model; measured 0.1 % and 0.5 % for the default Car).
"""

import math

from automobile_helpers import NodeProcess, wait_for, wait_node_matched, WAIT_S
import pytest

from vehicle_sim.config import load_car
from vehicle_sim.core.car.ackermann import ackermann_angles
from vehicle_sim.core.specs.units import kmh_to_mps
from vehicle_sim.ros import automobile_interfaces as itf
from vehicle_sim.ros import robot_interfaces as ri
from vehicle_sim.testing import AutomobileSim, stamp_s

pytestmark = pytest.mark.transport

DT_S = 0.01               # the nodes' basic step
CAR_WHEELBASE_M = 4.0     # config/cars/Car.yaml
CAR_MAX_STEERING_RAD = 1.0


def _twist(node, v, w, stamped=False):
    if stamped:
        msg = node.msg(itf.CMD_VEL_STAMPED.ros_type)()
        msg.twist.linear.x, msg.twist.angular.z = float(v), float(w)
        return msg
    msg = node.msg(itf.CMD_VEL.ros_type)()
    msg.linear.x, msg.angular.z = float(v), float(w)
    return msg


def _drive(node, speed, steering):
    msg = node.msg(itf.DRIVE.ros_type)()
    msg.drive.speed, msg.drive.steering_angle = float(speed), float(steering)
    return msg


class Car:
    """A synchronous automobile node and publishers on its cmd_vel and drive."""

    def __init__(self, namespace='', **params):
        self.sim = AutomobileSim(namespace=namespace, params=params)
        try:
            self._wire(params)
        except BaseException:
            self.sim.close()      # never leave the node process running
            raise

    def _wire(self, params):
        self.client = client = self.sim.client
        node = client.node
        stamped = params.get('cmd_vel_stamped', False)
        self.cmd_vel = node.create_publisher(itf.CMD_VEL_INPUTS[stamped].ros_type,
                                             f'{client.namespace}/cmd_vel')
        self.drive = node.create_publisher(itf.DRIVE.ros_type, f'{client.namespace}/drive')
        assert node.spin_until(lambda: self.cmd_vel.get_subscription_count() > 0 and
                               self.drive.get_subscription_count() > 0, WAIT_S)
        self.stamped = stamped
        self.odom = client.topic('odom')

    def cruising_kmh(self):
        return self.client.call('get_cruising_speed').value

    def send(self, publisher, msg, cruising_kmh):
        """Publish once; wait until the node answers the cruising speed it sets (the barrier)."""
        publisher.publish(msg)
        assert wait_for(lambda: math.isclose(self.cruising_kmh(), cruising_kmh, rel_tol=1e-9,
                                             abs_tol=1e-9), WAIT_S), \
            f'command not applied: {self.cruising_kmh()} km/h'

    def twist(self, v, w):
        delta = math.atan(w * CAR_WHEELBASE_M / v)
        # The front-driven Car's cruising speed runs the rear axle at v (docs/drive.md).
        self.send(self.cmd_vel, _twist(self.client.node, v, w, self.stamped),
                  v / math.cos(delta) * 3.6)

    def ackermann(self, speed, steering):
        self.send(self.drive, _drive(self.client.node, speed, steering),
                  speed / math.cos(steering) * 3.6)

    def latest_odom(self):
        return self.client.latest('odom')

    def close(self):
        return self.sim.close()


@pytest.fixture(scope='module')
def car():
    car = Car('/free', cmd_vel_timeout_s=0.0)   # each node of this module in its own namespace
    yield car
    car.close()


def _steady_turn(car, seconds=6.0):
    car.client.step(int(round(seconds / DT_S)))
    odom = car.latest_odom()
    return odom.twist.twist.linear.x, odom.twist.twist.angular.z


def test_car_cmd_vel_drives_at_the_commanded_speed_and_yaw_rate(car):
    v, w = 3.0, 0.3
    car.twist(v, w)
    speed, yaw_rate = _steady_turn(car)
    assert speed == pytest.approx(v, rel=0.02)
    assert yaw_rate == pytest.approx(w, rel=0.03)
    # The measured steering angle (Webots sign, + right) is a left turn of atan(ωL/v).
    steering = car.client.latest('steering_angle').data
    assert -steering == pytest.approx(math.atan(w * CAR_WHEELBASE_M / v), rel=0.03)


def test_car_drive_steering_is_rep103_positive_left_with_the_bicycle_yaw_rate(car):
    speed, steering = 2.0, 0.2
    car.ackermann(speed, steering)
    measured_v, yaw_rate = _steady_turn(car)
    assert measured_v == pytest.approx(speed, rel=0.02)
    assert yaw_rate == pytest.approx(speed * math.tan(steering) / CAR_WHEELBASE_M, rel=0.03)
    assert yaw_rate > 0.0    # left


def test_car_non_finite_command_is_dropped_with_a_warning_and_nothing_changes(car):
    car.ackermann(2.0, 0.1)
    before = car.cruising_kmh()
    car.cmd_vel.publish(_twist(car.client.node, math.nan, 0.0))
    car.drive.publish(_drive(car.client.node, 1.0, math.inf))
    assert wait_for(lambda: 'must be a finite number' in car.sim.output(), WAIT_S), \
        car.sim.output()
    assert car.cruising_kmh() == before


def test_car_steering_beyond_the_limit_saturates_with_a_warning(car):
    msg = _drive(car.client.node, 1.0, CAR_MAX_STEERING_RAD + 0.5)
    car.send(car.drive, msg, 1.0 / math.cos(CAR_MAX_STEERING_RAD) * 3.6)
    assert wait_for(lambda: 'saturated at 1 rad' in car.sim.output(), WAIT_S)
    car.client.step(100)
    # Commanded angle = the limit, to the left (Webots sign: −1 rad): the outer (right) wheel
    # at its Ackermann angle for −1 rad (the inner one stops at the joint limit).
    params = load_car('Car')
    right, _ = ackermann_angles(-CAR_MAX_STEERING_RAD, params.track_front_m, params.wheelbase_m)
    assert car.client.latest('right_steering_angle').data == pytest.approx(right, abs=0.005)


def test_car_takes_twist_stamped_when_cmd_vel_stamped():
    car = Car('/stamped', cmd_vel_timeout_s=0.0, cmd_vel_stamped=True)
    try:
        v, w = 2.0, -0.2       # a right turn
        car.twist(v, w)
        speed, yaw_rate = _steady_turn(car)
        assert speed == pytest.approx(v, rel=0.02)
        assert yaw_rate == pytest.approx(w, rel=0.03)
    finally:
        car.close()


@pytest.fixture(scope='module')
def watched_car():
    car = Car('/watched')      # default watchdog: 0.5 s
    yield car
    car.close()


def test_car_watchdog_brakes_within_timeout_plus_one_step_and_the_car_stops(watched_car):
    car, client = watched_car, watched_car.client
    # Drive up to speed with a command every 0.1 s (alternating 3.0 / 3.001 m/s, so that the
    # barrier sees each one), then stop sending.
    for i in range(20):
        car.twist(3.0 + 0.001 * (i % 2), 0.0)
        client.step(10)
    car.twist(3.0, 0.0)
    received_s = client.sim_time()
    assert kmh_to_mps(client.latest('current_speed').data) > 1.0
    timeout_s = 0.5
    braked_s = None
    while braked_s is None and client.sim_time() < received_s + 2.0:
        client.step(1)
        brake = client.latest('brake_intensity')
        if brake.data == 1.0:
            braked_s = stamp_s(brake)
    assert braked_s is not None, 'the watchdog never braked' + car.sim.output()
    # It acts on the first step whose time exceeds receipt + timeout; that step's state shows it.
    assert received_s + timeout_s < braked_s <= received_s + timeout_s + DT_S + 1e-6
    assert car.cruising_kmh() == 0.0
    client.step(500)
    assert abs(car.latest_odom().twist.twist.linear.x) < 0.01
    assert 'no cmd_vel or drive command for 0.5 s' in car.sim.output()


def test_car_service_call_after_a_command_wins_until_the_next_command(watched_car):
    car, client = watched_car, watched_car.client
    car.twist(2.0, 0.0)
    assert client.call('set_cruising_speed', 9.0).success
    client.step(300)                          # 3 s: six timeouts long
    assert car.cruising_kmh() == 9.0
    assert client.latest('brake_intensity').data == 0.0
    assert kmh_to_mps(client.latest('current_speed').data) == pytest.approx(2.5, rel=0.05)
    car.twist(1.0, 0.0)                       # the next command wins again
    assert car.cruising_kmh() == pytest.approx(3.6)


def test_car_reset_after_a_command_stands_the_watchdog_down(watched_car):
    # A reset puts the logic in its start state; the watchdog of the command before it must not
    # brake the reset car half a second later.
    car, client = watched_car, watched_car.client
    car.twist(2.0, 0.0)
    assert client.call('reset').success
    client.step(100)                          # 1 s: twice the timeout
    assert car.cruising_kmh() == 0.0
    assert client.latest('brake_intensity').data == 0.0


PRIUS_FULL_BRAKE_MPS2 = 4.81    # speed_braking.full_brake_deceleration_mps2 (ToyotaPrius)
PRIUS_RAMP_MPS2 = 100.0 / 3.6 / 10.7


def test_car_watchdog_stop_brakes_at_the_full_brake_deceleration_not_the_cruise_ramp():
    # The Prius at 10 m/s, then no command: the watchdog's safety stop releases the throttle
    # and brakes fully, so the car slows at its full-brake deceleration, 4.81 m/s^2 (+ up to
    # 0.4 from the wheels' damping and rolling), and stops within v^2 / (2 * 4.81) = 10.4 m
    # (-1.5 m, + 0.3 m) of where the watchdog acted, not at the cruise control's 2.6 m/s^2
    # (19 m) as a cruising speed of 0 did.
    car = Car('/prius_stop', car_model='ToyotaPrius')
    try:
        client = car.client
        for i in range(45):
            car.twist(10.0 + 0.001 * (i % 2), 0.0)
            client.step(10)
        samples = []
        while client.sim_time() < 8.0 and (not samples or abs(samples[-1][2]) > 1e-3):
            client.step(1)
            odom = car.latest_odom()
            samples.append((stamp_s(odom), odom.pose.pose.position.x, odom.twist.twist.linear.x,
                            client.latest('brake_intensity').data))
        braked = [sample for sample in samples if sample[3] == 1.0]
        assert braked, 'the watchdog never braked' + car.sim.output()
        t0, x0, v0, _ = braked[0]
        assert v0 == pytest.approx(10.0, abs=0.1)
        # the deceleration from 9 to 2 m/s (a straight line through the speeds)
        fit = [(t, v) for t, _, v, _ in braked if 2.0 < v < 9.0]
        assert len(fit) > 50
        ts, vs = zip(*fit)
        mt, mv = sum(ts) / len(ts), sum(vs) / len(vs)
        slope = sum((t - mt) * (v - mv) for t, v in fit) / sum((t - mt) ** 2 for t in ts)
        assert PRIUS_FULL_BRAKE_MPS2 - 0.1 < -slope < PRIUS_FULL_BRAKE_MPS2 + 0.4
        distance = samples[-1][1] - x0
        ideal = v0 * v0 / (2.0 * PRIUS_FULL_BRAKE_MPS2)
        assert ideal - 1.5 < distance < ideal + 0.3
        assert abs(samples[-1][2]) <= 1e-3
    finally:
        car.close()


# ------------------------------------------------------------------------------ the robot

class Robot:
    """A synchronous diff_robot node, a cmd_vel publisher and its ground truth."""

    def __init__(self, namespace, *params):
        from vehicle_sim.transport.selection import create_node
        # Each robot of this module in its own namespace (one topic type per name and process).
        args = ['--ros-args', '-r', f'__ns:={namespace}', '-p', 'synchronous:=true']
        for param in params:
            args += ['-p', param]
        self.process = NodeProcess(*args, module='vehicle_sim.ros.diff_robot_node')
        self.node = None
        try:
            self._wire(namespace, params, create_node)
        except BaseException:
            self.close()          # never leave the node process running
            raise

    def _wire(self, namespace, params, create_node):
        self.node = node = create_node('drive_input_test', args=['--ros-args',
                                                                  '--disable-rosout-logs'])
        stamped = 'cmd_vel_stamped:=true' in params
        self.stamped = stamped
        self.cmd_vel = node.create_publisher(itf.CMD_VEL_INPUTS[stamped].ros_type,
                                             f'{namespace}/diff_robot/cmd_vel')
        self.odom = []
        self.sub = node.create_subscription(ri.ROBOT_GROUND_TRUTH_ODOM.ros_type,
                                            f'{namespace}/diff_robot/ground_truth/odom',
                                            self.odom.append)
        self.time_s = 0.0
        self.time_step = node.create_client(ri.ROBOT_TIME_STEP.ros_type,
                                            f'{namespace}/diff_robot/robot/time_step')
        assert node.spin_until(lambda: self.time_step.service_is_ready() and
                               self.cmd_vel.get_subscription_count() > 0 and
                               self.sub.get_publisher_count() > 0, WAIT_S), \
            self.process.text()
        wait_node_matched(node, f'{namespace}/diff_robot/list_parameters',
                          'rcl_interfaces/srv/ListParameters')

    def step(self, ms):
        request = self.node.srv(ri.ROBOT_TIME_STEP.ros_type).Request()
        request.value = int(ms)
        assert self.time_step.call(request, WAIT_S).success
        self.time_s += ms / 1000.0
        # The state published at the end of the step.
        assert self.node.spin_until(
            lambda: self.odom and stamp_s(self.odom[-1]) >= self.time_s - 1e-6, WAIT_S)

    def send_until_moving(self, v, w):
        """Publish one command and step 10 ms at a time until the robot moves."""
        self.cmd_vel.publish(_twist(self.node, v, w, self.stamped))
        for _ in range(500):
            self.step(10)
            if self.odom and abs(self.odom[-1].twist.twist.angular.z) + \
                    abs(self.odom[-1].twist.twist.linear.x) > 1e-3:
                return stamp_s(self.odom[-1])
        raise AssertionError('the robot never moved:\n' + self.process.text())

    def close(self):
        if self.node is not None:
            self.node.shutdown()
        self.process.stop()


@pytest.mark.parametrize('stamped', [False, True], ids=['Twist', 'TwistStamped'])
def test_robot_cmd_vel_drives_at_the_commanded_speed_and_yaw_rate(stamped):
    robot = Robot(f'/robot_stamped_{stamped}'.lower(), 'cmd_vel_timeout_s:=0.0',
                  f'cmd_vel_stamped:={str(stamped).lower()}')
    try:
        v, w = 0.3, 0.5
        robot.send_until_moving(v, w)
        robot.step(3000)
        twist = robot.odom[-1].twist.twist
        assert twist.linear.x == pytest.approx(v, rel=0.02)
        assert twist.angular.z == pytest.approx(w, rel=0.03)
    finally:
        robot.close()


def test_robot_watchdog_stops_the_wheels_after_the_timeout():
    robot = Robot('/watched_robot')      # default watchdog: 0.5 s
    try:
        robot.send_until_moving(0.3, 0.0)
        robot.step(3000)
        assert abs(robot.odom[-1].twist.twist.linear.x) < 0.01
        assert wait_for(lambda: 'cmd_vel: no command for 0.5 s' in robot.process.text(), WAIT_S)
    finally:
        robot.close()
