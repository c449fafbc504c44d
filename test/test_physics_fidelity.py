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
Physics fidelity through the Webots API: documented formulas and basic mechanics.

Every claim is checked on simulated time (deterministic) against ground truth from the physics
(chassis speed, yaw rate), with the tolerance stated beside it.
"""

import math

import numpy as np
import pybullet
import pytest

from vehicle_sim.config import load_car
from vehicle_sim.core.specs.simulation import CHECKED_TIME_STEPS_MS
from vehicle_sim.core.specs.units import kmh_to_mps, RPM_PER_RADPS
from vehicle_sim.webots import Car, Driver

PRESETS = ['Car', 'BmwX5', 'CitroenCZero', 'ToyotaPrius', 'TeslaModel3', 'LincolnMKZ',
           'RangeRoverSportSVR', 'MercedesBenzSprinter']


def _ground_speed_mps(car):
    return car.simulated_car.body.forward_speed_mps()


@pytest.mark.parametrize('step_ms', CHECKED_TIME_STEPS_MS)
@pytest.mark.parametrize('model', PRESETS)
def test_speed_mode_zero_to_hundred_matches_time0to100_within_ten_percent(model, step_ms):
    # SPEED mode ramps the driven wheels at (100/3.6)/time0To100 m/s^2 at the tyre (Car.proto
    # motor acceleration), so ground truth reaches a target v after time0To100 * v / 100 km/h.
    # Cars slower than 100 km/h are measured to 90 % of their top speed (docs/physics.md, grip).
    params = load_car(model)
    top_kmh = params.max_velocity_mps * 3.6
    target_kmh = 100.0 if top_kmh > 100.0 else 0.9 * top_kmh
    expected_s = params.time_0_to_100_s * target_kmh / 100.0
    with Car(model, time_step_ms=step_ms) as car:
        car.setCruisingSpeed(top_kmh)
        while _ground_speed_mps(car) < kmh_to_mps(target_kmh) and car.getTime() < 2 * expected_s:
            car.step()
        assert car.getTime() == pytest.approx(expected_s, rel=0.10)


@pytest.mark.parametrize('step_ms', CHECKED_TIME_STEPS_MS)
@pytest.mark.parametrize('model', ['BmwX5', 'TeslaModel3', 'LincolnMKZ'])
def test_steady_turn_yaw_rate_matches_kinematic_bicycle_within_five_percent(model, step_ms):
    # Low-speed steady cornering without slip: yaw rate = v * tan(delta) / wheelbase, with v the
    # rear-axle centre speed and delta the driver's (centre) steering angle.
    steering_rad = 0.1
    with Car(model, time_step_ms=step_ms) as car:
        car.setCruisingSpeed(10.0)
        car.setSteeringAngle(steering_rad)
        car.step(8000)       # settle 8 s: ramp to 10 km/h, steering motors, transients
        yaw_rates, speeds = [], []
        for _ in range(1000 // step_ms):        # 1 s
            car.step()
            yaw_rates.append(car.simulated_car.body.yaw_rate_radps())
            speeds.append(_ground_speed_mps(car))
        speed = float(np.mean(speeds))
        expected = speed * math.tan(steering_rad) / car.getWheelbase()
        # Positive (Webots) steering turns right: REP 103 yaw rate is negative.
        assert -float(np.mean(yaw_rates)) == pytest.approx(expected, rel=0.05)
        assert speed == pytest.approx(kmh_to_mps(10.0), rel=0.05)


def test_torque_mode_rpm_equals_mean_wheel_speed_times_gear_ratio():
    # driver.c compute_rpm: rpm = |mean of the four wheel speeds * gear ratio| * 60 / 2 pi.
    with Car('BmwX5') as car:
        car.setGear(1)
        car.setThrottle(0.3)
        car.step(10000)      # 10 s
        speeds = [car.getWheelSpeed(i) for i in range(4)]
        expected = abs(np.mean(speeds) * car.logic.params.gear_ratio[1]) * RPM_PER_RADPS
        assert expected > 500.0
        assert car.getRpm() == pytest.approx(expected, rel=0.01)
        car.setGear(0)
        car.step()
        assert car.getRpm() == 0.0


def test_torque_mode_full_throttle_in_first_gear_accelerates_forwards():
    with Car('BmwX5') as car:
        car.setGear(1)
        car.setThrottle(1.0)
        car.step(3000)
        assert _ground_speed_mps(car) > 5.0
        assert car.getCurrentSpeed() > 18.0


def test_torque_mode_reverse_gear_moves_backwards():
    with Car('ToyotaPrius') as car:
        car.setGear(-1)
        car.setThrottle(0.5)
        car.step(2000)
        assert _ground_speed_mps(car) < -1.0
        assert car.getCurrentSpeed() < -3.6
        assert car.getBackwardsLights()


def test_torque_mode_neutral_coasts_without_drive_torque():
    with Car('BmwX5') as car:
        car.setGear(1)
        car.setThrottle(1.0)
        car.step(3000)
        speed_before = _ground_speed_mps(car)
        car.setGear(0)
        car.step(1000)
        speed_after = _ground_speed_mps(car)
        assert all(t == 0.0 for t in car.logic.actuation.wheel_torque_nm)
        # Coasting: slower only through wheel damping and rolling losses, far from braking.
        assert 0.8 * speed_before < speed_after < speed_before


def test_torque_mode_higher_gear_at_same_engine_rpm_gives_less_wheel_torque():
    # Wheel torque = engine torque(rpm) * throttle * gear ratio (driver.c).
    torque_per_gear = {}
    for gear in (1, 2):
        with Car('BmwX5') as car:
            car.setGear(gear)
            car.setThrottle(1.0)
            while car.getRpm() < 2000.0 and car.getTime() < 30.0:
                car.step()
            car.step()
            rpm = car.getRpm()
            wheel_torque = float(np.sum(car.logic.actuation.wheel_torque_nm))
            engine_torque = car.logic.engine.torque_nm(rpm)
            ratio = car.logic.params.gear_ratio[gear]
            assert wheel_torque == pytest.approx(engine_torque * ratio, rel=1e-6)
            torque_per_gear[gear] = (rpm, wheel_torque)
    (rpm1, torque1), (rpm2, torque2) = torque_per_gear[1], torque_per_gear[2]
    assert rpm1 == pytest.approx(rpm2, rel=0.05)
    assert torque2 < torque1 * 0.8


def _stop_from_50(model, brake, step_ms=None):
    with Car(model, time_step_ms=step_ms) as car:
        car.setCruisingSpeed(60.0)   # the chassis only approaches the cruise target
        while _ground_speed_mps(car) < kmh_to_mps(50.0) and car.getTime() < 60.0:
            car.step()
        # Brakes act on driven wheels in TORQUE mode (Webots: barely in SPEED mode).
        car.setThrottle(0.0)
        car.setBrakeIntensity(brake)
        start = car.getTime()
        while _ground_speed_mps(car) > 0.01 and car.getTime() - start < 30.0:
            car.step()
        return car.getTime() - start, car.getBrakeLights()


@pytest.mark.parametrize('step_ms', CHECKED_TIME_STEPS_MS)
def test_full_brake_from_50_kmh_stops_the_car_as_the_braking_torque_predicts(step_ms):
    # Braking torque brake * brakeCoefficient on each of 4 wheels: deceleration
    # a = 4 b C / r / m_eff (below the friction limit), m_eff = body + wheels + wheel inertia.
    params = load_car('BmwX5')
    wheel_mass = params.wheel_mass_kg(True)
    m_eff = params.mass_kg + 4 * wheel_mass * 1.5   # + rotational inertia of ~uniform discs
    decel = 4 * params.brake_coefficient_nm / params.front_tire_radius_m / m_eff
    expected_s = kmh_to_mps(50.0) / decel
    stop_s, brake_light = _stop_from_50('BmwX5', 1.0, step_ms)
    assert stop_s == pytest.approx(expected_s, rel=0.15)
    assert brake_light


def test_weaker_brake_stops_later():
    strong_s, _ = _stop_from_50('BmwX5', 1.0)
    weak_s, _ = _stop_from_50('BmwX5', 0.3)
    assert weak_s > 2.0 * strong_s
    assert weak_s < 30.0


def _split_friction_spread(lsd_enabled):
    """Full throttle with the left wheels on ice; return the mean driven-wheel speed spread."""
    with Car('BmwX5') as car:
        world = car.world
        cid = world.client_id
        ice = pybullet.createCollisionShape(pybullet.GEOM_BOX, halfExtents=[50, 2, 0.005],
                                            physicsClientId=cid)
        ice_body = pybullet.createMultiBody(0, ice, basePosition=[45, 2.814, 0.0],
                                            physicsClientId=cid)
        pybullet.changeDynamics(ice_body, -1, lateralFriction=0.05, physicsClientId=cid)
        car.enableLimitedSlipDifferential(lsd_enabled)
        car.setGear(1)
        car.setThrottle(1.0)
        spread = []
        for _ in range(300):
            car.step()
            spread.append(abs(car.getWheelSpeed(Car.WHEEL_FRONT_LEFT)
                              - car.getWheelSpeed(Car.WHEEL_FRONT_RIGHT)))
        return float(np.mean(spread[100:]))


def test_limited_slip_keeps_driven_wheel_speeds_closer_on_split_friction():
    # The ice strip (y from 0.81 to 4.81 m) lies under the left wheels only (track 1.628 m).
    with_lsd = _split_friction_spread(True)
    without_lsd = _split_friction_spread(False)
    assert without_lsd > 1.0
    assert with_lsd < 0.5 * without_lsd


def test_indicator_blinks_with_the_period_and_cancels_after_the_turn():
    # Phase: on while int(t / period) % 2 == 0 (driver.c); auto-cancel 0.1 rad after the extreme.
    with Car('BmwX5') as car:
        car.setIndicatorPeriod(0.5)
        car.setIndicator(Driver.INDICATOR_RIGHT)
        lamp = []
        for _ in range(200):
            car.step()
            lamp.append(car.logic.right_indicator_light)
        times = np.arange(200) * 0.01          # time before each step
        expected = [int(t / 0.5 + 1e-9) % 2 == 0 for t in times]
        assert lamp == expected
        car.setSteeringAngle(0.3)
        car.setSteeringAngle(0.25)
        assert car.getIndicator() == Driver.INDICATOR_RIGHT
        car.setSteeringAngle(0.19)
        assert car.getIndicator() == Driver.INDICATOR_OFF


def test_hazard_flashers_blink_both_sides_together():
    with Car('BmwX5') as car:
        car.setHazardFlashers(True)
        states = set()
        for _ in range(100):
            car.step()
            states.add((car.logic.right_indicator_light, car.logic.left_indicator_light))
        assert states == {(True, True), (False, False)}
