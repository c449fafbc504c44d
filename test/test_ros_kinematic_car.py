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
A car with a vehicle_model: over ROS: the automobile node's topics and services drive its model.

The node (a subprocess, synchronous) runs a world whose car is moved by DELAY_STEER_ACC; the
test node commands it through the driver services, steps it, and reads /odom and /collision.
"""

import math

from automobile_helpers import automobile_fixtures, wait_for
import pytest

from vehicle_sim.config import load_car
from vehicle_sim.core.car.kinematic_drive import model_inputs
from vehicle_sim.core.car.kinematic_models import KinematicModel, vehicle_model_from
from vehicle_sim.core.car.logic import CarLogic
from vehicle_sim.core.car.speed_braking import cruise_ramp_mps2
from vehicle_sim.ros import automobile_interfaces as itf

pytestmark = pytest.mark.transport

NAMESPACE = 'kinematic'
WORLD = """
vehicles:
  - name: Car
    model: ToyotaPrius
    pose: {x: 0.0, y: 0.0, yaw: 0.0}
    vehicle_model: DELAY_STEER_ACC
obstacles:
  - {name: wall, shape: box, size: [1.0, 60.0, 2.0], position: [60.0, 0.0, 1.0], yaw: 0.0}
"""


@pytest.fixture(scope='module')
def world_file(tmp_path_factory):
    path = tmp_path_factory.mktemp('kinematic_world') / 'world.yaml'
    path.write_text(WORLD, encoding='utf-8')
    return path


node, tester, car = automobile_fixtures(
    'kinematic_tester', lambda request: ['--ros-args', '-r', f'__ns:=/{NAMESPACE}', '-p',
                                         f'world:={request.getfixturevalue("world_file")}',
                                         '-p', 'synchronous:=true'],
    ['/clock', 'odom'], NAMESPACE, names=('node', 'tester', 'car'))


def _expected(seconds, speed_kmh, steering_rad, dt=0.01):
    # the same model and mapping, offline
    params = load_car('ToyotaPrius')
    logic = CarLogic(params)
    logic.set_steering_angle(steering_rad)
    logic.set_cruising_speed_within_top_kmh(speed_kmh)
    model = KinematicModel(vehicle_model_from('DELAY_STEER_ACC'), params.wheelbase_m, dt)
    for _ in range(int(round(seconds / dt))):
        model.step(*model_inputs(logic, model, cruise_ramp_mps2(params)))
    return model


def test_driver_services_drive_the_model_and_odom_reports_it(car):
    assert car.call('automobile/set_steering_angle', -0.05).success
    assert car.call('automobile/set_cruising_speed', 36.0).success
    odom = car.step_and_read('odom', 2000)
    expected = _expected(2.0, 36.0, -0.05)
    pose = odom.pose.pose
    assert (pose.position.x, pose.position.y) == pytest.approx(
        (expected.x_m, expected.y_m), abs=1e-4)
    yaw = 2.0 * math.atan2(pose.orientation.z, pose.orientation.w)
    assert yaw == pytest.approx(expected.yaw_rad, abs=1e-5)
    assert expected.yaw_rad > 0.05                  # it turned left
    assert odom.twist.twist.linear.x == pytest.approx(expected.vx_mps, abs=1e-4)
    assert odom.twist.twist.angular.z == pytest.approx(expected.yaw_rate_radps, abs=1e-4)


def test_driving_into_the_wall_gives_a_collision_message(car):
    collisions = []
    sub = car.node.create_subscription(itf.COLLISION.ros_type, car.name('collision'),
                                       collisions.append, itf.COLLISION.qos)
    assert wait_for(lambda: sub.get_publisher_count(), spin=car.node)
    car.wait_node_matched()
    assert car.call('automobile/set_steering_angle', 0.0).success
    for _ in range(20):         # 10 s at 36 km/h: the wall is about 55 m ahead
        assert car.call('robot/time_step', 500).success
    assert wait_for(lambda: collisions, spin=car.node)
    assert collisions[0].other == 'wall'
