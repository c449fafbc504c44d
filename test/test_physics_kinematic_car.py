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

"""A car with a vehicle_model: moved by its model, driven by the Webots API, seen, colliding."""

import math

import pybullet
import pytest

from vehicle_sim.config import load_world
from vehicle_sim.core.car.ackermann import ackermann_angles
from vehicle_sim.core.car.kinematic_drive import model_inputs
from vehicle_sim.core.car.kinematic_models import KinematicModel
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.physics.kinematic_car import KinematicCar
from vehicle_sim.physics.sensors.collisions import CollisionMonitor
from vehicle_sim.webots import Driver

WORLD = """
vehicles:
  - name: Car
    model: ToyotaPrius
    pose: {{x: 0.0, y: 0.0, yaw: 0.0}}
    vehicle_model: {model}
obstacles:
  - {{name: wall, shape: box, size: [1.0, 6.0, 2.0], position: [40.0, 0.0, 1.0], yaw: 0.0}}
"""


def _driver(tmp_path, model='DELAY_STEER_ACC'):
    path = tmp_path / 'world.yaml'
    path.write_text(WORLD.format(model=model))
    return Driver(world_file=str(path))


def test_world_file_car_is_moved_by_its_model_through_the_driver_api(tmp_path):
    driver = _driver(tmp_path)
    try:
        car = driver.simulated_car
        assert isinstance(car, KinematicCar)
        driver.setCruisingSpeed(36.0)
        driver.setSteeringAngle(-0.05)          # Webots: negative = left
        # the same model, fed what the mapping gives, offline
        shadow = KinematicModel(car.vehicle_model, car.params.wheelbase_m,
                                driver.world.time_step_s)
        for _ in range(300):
            shadow.step(*model_inputs(car.logic, shadow, car._a_ramp))
            driver.step()
        model = car.model
        assert (model.x_m, model.y_m, model.yaw_rad) == pytest.approx(
            (shadow.x_m, shadow.y_m, shadow.yaw_rad), abs=1e-9)
        x, y, _, qx, qy, qz, qw = car.body.pose()
        assert (x, y) == pytest.approx((model.x_m, model.y_m), abs=1e-6)
        assert model.yaw_rad > 0.1 and model.y_m > 0.5        # turned left
        assert 2.0 * math.atan2(qz, qw) == pytest.approx(model.yaw_rad, abs=1e-6)
        # the twist every reader sees: base_link at vx along the heading, yaw rate about z
        (vx, vy, _), (_, _, wz) = car.body.velocity()
        assert math.hypot(vx, vy) == pytest.approx(model.vx_mps, abs=1e-6)
        assert wz == pytest.approx(model.yaw_rate_radps, abs=1e-6)
        assert car.body.forward_speed_mps() == pytest.approx(model.vx_mps, abs=1e-6)
        # the driver's speed estimate (wheel encoders, read before the step: it lags 1-2 steps
        # while accelerating at a_ramp, 2.6 m/s^2) and the steering joints follow the model
        assert driver.getCurrentSpeed() == pytest.approx(model.vx_mps * 3.6, abs=0.3)
        right, left = ackermann_angles(-model.steer_rad, car.params.track_front_m,
                                       car.params.wheelbase_m)
        assert car.body.steer_angles == pytest.approx((right, left), abs=1e-12)
        # the driver reads them before the step (the model's steering then a step earlier)
        assert (car.logic.right_steering_angle_rad, car.logic.left_steering_angle_rad) == \
            pytest.approx((right, left), abs=1e-6)
        assert model.steer_rad == pytest.approx(0.05, abs=1e-4)
    finally:
        driver.close()


def test_throttle_brake_and_reverse_gear_drive_the_model(tmp_path):
    driver = _driver(tmp_path, 'DELAY_STEER_ACC_GEARED')
    try:
        car = driver.simulated_car
        driver.setGear(1)
        driver.setThrottle(1.0)
        for _ in range(200):
            driver.step()
        moving = car.model.vx_mps
        assert moving > 3.0
        driver.setThrottle(0.0)
        driver.setBrakeIntensity(1.0)
        for _ in range(300):
            driver.step()
        assert car.model.vx_mps == 0.0                  # stopped, not rolling back
        driver.setBrakeIntensity(0.0)
        driver.setGear(-1)
        driver.setThrottle(0.5)
        for _ in range(200):
            driver.step()
        assert car.model.vx_mps < -1.0
    finally:
        driver.close()


def test_rays_see_the_car_where_the_model_put_it(tmp_path):
    driver = _driver(tmp_path)
    try:
        car = driver.simulated_car
        driver.setCruisingSpeed(36.0)
        for _ in range(200):
            driver.step()
        cid = driver.world.client_id
        x, y = car.model.x_m, car.model.y_m
        heading = (math.cos(car.model.yaw_rad), math.sin(car.model.yaw_rad))
        centre = (x + 1.4 * heading[0], y + 1.4 * heading[1])   # mid body of the Prius
        hit = pybullet.rayTest((*centre, 5.0), (*centre, -1.0), physicsClientId=cid)[0]
        assert hit[0] == car.body.body_id
        # and no longer at its spawn
        spawn = pybullet.rayTest((1.4, 0.0, 5.0), (1.4, 0.0, -1.0), physicsClientId=cid)[0]
        assert spawn[0] != car.body.body_id
    finally:
        driver.close()


def test_a_collision_is_reported_and_the_model_drives_on(tmp_path):
    driver = _driver(tmp_path)
    try:
        car = driver.simulated_car
        monitor = CollisionMonitor(driver.world, car.body)
        events = []
        driver.setCruisingSpeed(36.0)
        for _ in range(1500):
            driver.step()
            events.extend(monitor.fresh)
            if events:
                break
        assert [event.other for event in events] == ['wall']
        front = car.model.x_m + 2.8 + 0.9        # wheelbase + front overhang (about)
        assert 35.0 < front < 42.0
        speed = car.model.vx_mps
        driver.step()
        assert car.model.vx_mps == pytest.approx(speed, abs=0.1)   # no collision response
    finally:
        driver.close()


def test_reset_and_teleport_put_the_model_back(tmp_path):
    driver = _driver(tmp_path)
    try:
        car = driver.simulated_car
        driver.setCruisingSpeed(20.0)
        for _ in range(100):
            driver.step()
        car.teleport((5.0, 3.0, 0.5))
        assert (car.model.x_m, car.model.y_m, car.model.yaw_rad, car.model.vx_mps) == \
            pytest.approx((5.0, 3.0, 0.5, 0.0), abs=1e-6)
        car.reset()
        assert (car.model.x_m, car.model.y_m, car.model.vx_mps) == (0.0, 0.0, 0.0)
        assert car.body.pose()[:2] == pytest.approx((0.0, 0.0), abs=1e-6)
    finally:
        driver.close()


def test_a_rebuild_at_another_pose_moves_the_model_with_the_body(tmp_path):
    # A Gym reset with start_noise rebuilds the ego's body at an offset pose
    # (gym/drive_sim.py reset_world): the model must go on from there, not from the spawn.
    driver = _driver(tmp_path)
    try:
        car = driver.simulated_car
        car.reset()
        car.body.rebuild((3.0, 1.0, 0.2))
        for _ in range(10):
            driver.step()               # no command: at rest where it was put
        assert (car.model.x_m, car.model.y_m, car.model.yaw_rad, car.model.vx_mps) == \
            pytest.approx((3.0, 1.0, 0.2, 0.0), abs=1e-6)
        assert car.body.pose()[:2] == pytest.approx((3.0, 1.0), abs=1e-6)
        assert car.body.yaw_rad() == pytest.approx(0.2, abs=1e-6)
    finally:
        driver.close()


@pytest.mark.parametrize('model, field', [
    ('{type: DELAY_STEER_ACC, steer_time_constant: 0.0}', 'steer_time_constant'),
    ('FAST_CAR', 'type'),
])
def test_bad_vehicle_model_in_a_world_file_is_refused_naming_the_field(tmp_path, model, field):
    path = tmp_path / 'world.yaml'
    path.write_text(WORLD.format(model=model))
    with pytest.raises(InvalidParameterError, match=rf"vehicle_model.*'{field}'"):
        load_world(str(path))
