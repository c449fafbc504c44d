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
Top speed and fast joints: nothing saturates at Bullet's default 100 rad/s velocity clamp.

Every claim is checked on simulated time against ground truth (chassis speed) or the commanded
joint speed, with the tolerance stated beside it.
"""

import dataclasses

import numpy as np
import pytest

from vehicle_sim.config import car_names, load_car
from vehicle_sim.core.car.vehicle_io import Actuation, Wheel, WheelMode
from vehicle_sim.core.specs.simulation import CHECKED_TIME_STEPS_MS
from vehicle_sim.core.specs.units import mps_to_kmh, RPM_PER_RADPS
from vehicle_sim.physics import CarBody, World
from vehicle_sim.physics.diff_robot import DiffRobotBody, load_robot
from vehicle_sim.physics.world import MAX_COORDINATE_VELOCITY
from vehicle_sim.webots import Car

# Well above the ground, upright: a body falls freely for the few steps of a joint test.
IN_THE_AIR = (0.0, 0.0, 5.0, 0.0, 0.0, 0.0, 1.0)
# Above Bullet's default clamp (100) and the highest preset top-speed wheel speed (176 rad/s).
FAST_JOINT_RADPS = 300.0
# After the SPEED-mode ramp, time for the last transients (steering-free, straight ahead).
SETTLE_S = 3.0
# Steady state at top speed: wheel estimates, ground truth and the target agree within 1 %
# (slip of the driven tyres, rolling of the free ones, suspension motion).
STEADY_REL = 0.01


def _radius(params, index):
    return params.front_tire_radius_m if index < 2 else params.rear_tire_radius_m


@pytest.mark.parametrize('step_ms', CHECKED_TIME_STEPS_MS)
@pytest.mark.parametrize('model', car_names())
def test_every_preset_reaches_its_top_speed_with_consistent_wheel_speeds(model, step_ms):
    # SPEED mode at maxVelocity: the wheel motors ramp at (100/3.6)/time0To100 m/s^2 at the tyre
    # and saturate at maxVelocity / r, so after time0To100 * top / (100 km/h) the car holds its
    # top speed, every wheel turning at maxVelocity / r (TeslaModel3: 138.9 rad/s).
    params = load_car(model)
    top_mps = params.max_velocity_mps
    top_kmh = mps_to_kmh(top_mps)
    ramp_s = params.time_0_to_100_s * top_kmh / 100.0
    with Car(model, time_step_ms=step_ms) as car:
        car.setCruisingSpeed(top_kmh)
        for _ in range(round((ramp_s + SETTLE_S) * 1000.0 / step_ms)):
            car.step()
        assert car.getTargetCruisingSpeed() == top_kmh
        assert car.simulated_car.body.forward_speed_mps() == pytest.approx(top_mps, rel=STEADY_REL)
        assert car.getCurrentSpeed() == pytest.approx(top_kmh, rel=STEADY_REL)
        for wheel in range(4):
            assert car.getWheelSpeed(wheel) == pytest.approx(
                top_mps / _radius(params, wheel), rel=STEADY_REL), wheel


def test_torque_mode_rpm_follows_the_true_wheel_speed_above_100_radps():
    # driver.c compute_rpm: rpm = |mean wheel speed| * gear ratio * 60 / 2pi. At full throttle
    # in its single forward gear (ratio 9) a TeslaModel3 passes 105 rad/s after about 25 s
    # (its steady state is about 110 rad/s); the wheels must follow the chassis there:
    # omega * r = ground-truth speed within 1 %, so the rpm is that of the real wheels.
    params = load_car('TeslaModel3')
    ratio = params.gear_ratio[1]
    with Car('TeslaModel3') as car:
        car.setGear(1)
        car.setThrottle(1.0)
        mean_radps = 0.0
        while mean_radps < 105.0 and car.getTime() < 60.0:
            car.step()
            mean_radps = float(np.mean([car.getWheelSpeed(i) for i in range(4)]))
        assert mean_radps >= 105.0
        for _ in range(50):
            car.step()
            speeds = [car.getWheelSpeed(i) for i in range(4)]
            assert min(speeds) > 100.0
            ground_radps = car.simulated_car.body.forward_speed_mps() / params.front_tire_radius_m
            assert np.mean(speeds) == pytest.approx(ground_radps, rel=STEADY_REL)
            assert car.getRpm() == pytest.approx(abs(np.mean(speeds)) * ratio * RPM_PER_RADPS,
                                                 rel=1e-9)
            assert car.getRpm() == pytest.approx(ground_radps * ratio * RPM_PER_RADPS,
                                                 rel=STEADY_REL)


def test_car_body_wheels_spin_above_100_radps_in_the_air():
    # A velocity motor with 1e8 N*m reaches its target within one step on a free wheel (the
    # wheel damper, applied after the motor, takes off a few 1e-6 of it).
    with World() as world:
        body = CarBody(world, load_car('Car'), position=IN_THE_AIR)
        actuation = Actuation()
        for index in Wheel:
            actuation.wheel_mode[index] = WheelMode.VELOCITY
            actuation.wheel_velocity_radps[index] = FAST_JOINT_RADPS
        for _ in range(5):
            body.apply(actuation)
            world.step()
        _, _, velocities = body.joint_states()
        assert velocities[:4] == pytest.approx([FAST_JOINT_RADPS] * 4, rel=1e-4)


def test_differential_robot_wheels_spin_above_100_radps_in_the_air():
    # The caster robot's wheels (0.5 kg, r = 0.1 m: I = 2.5e-3 kg*m^2) with 20 N*m motors reach
    # 300 rad/s in under 0.05 s; 0.2 s leaves them at their command.
    params = dataclasses.replace(load_robot('caster_robot'), max_wheel_speed_radps=400.0)
    with World() as world:
        robot = DiffRobotBody(world, params, position=IN_THE_AIR)
        robot.set_wheel_velocities(FAST_JOINT_RADPS, FAST_JOINT_RADPS)
        for _ in range(20):
            world.step()
        reading = robot.read()
        assert (reading.left_radps, reading.right_radps) == pytest.approx(
            (FAST_JOINT_RADPS, FAST_JOINT_RADPS), rel=1e-3)


@pytest.mark.parametrize('model', car_names())
def test_bullet_velocity_clamp_is_far_above_every_reachable_wheel_speed(model):
    # The clamp must never bind: not at top speed (maxVelocity / r), nor at the rpm cut in the
    # highest gear of TORQUE mode (engineMaxRPM / (ratio * 60 / 2pi)).
    params = load_car(model)
    top_radps = params.max_velocity_mps / min(params.front_tire_radius_m,
                                              params.rear_tire_radius_m)
    cut_radps = params.engine_max_rpm / RPM_PER_RADPS / min(abs(g) for g in params.gear_ratio)
    assert 10.0 * max(top_radps, cut_radps) <= MAX_COORDINATE_VELOCITY
