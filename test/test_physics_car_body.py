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

"""CarBody and its URDF: resting, wheel motors, steering motor, brakes, torque mode, turning."""

import math
import xml.etree.ElementTree as ElementTree

import pytest

from vehicle_sim.config import car_names, load_car
from vehicle_sim.core.car.vehicle_io import Actuation, Measurement, Wheel, WheelMode
from vehicle_sim.core.geometry.angles import yaw_from_quaternion
from vehicle_sim.core.specs.simulation import CHECKED_TIME_STEPS_MS
from vehicle_sim.physics import CarBody, joint_names, World
from vehicle_sim.physics.urdf import car_urdf

G = 9.81


def _tilt_rad(pose):
    qx, qy, _, _ = pose[3:]
    return 2.0 * math.asin(min(1.0, math.hypot(qx, qy)))


def _radius(params, index):
    return params.front_tire_radius_m if index < 2 else params.rear_tire_radius_m


def _run(world, car, actuation, seconds):
    for _ in range(round(seconds / world.time_step_s)):
        car.apply(actuation)
        world.step()


def _all_wheels(mode, value=0.0):
    actuation = Actuation()
    for index in Wheel:
        actuation.wheel_mode[index] = mode
        actuation.wheel_velocity_radps[index] = value
    return actuation


@pytest.mark.parametrize('model', car_names())
def test_car_urdf_parses_and_names_every_joint(model):
    params = load_car(model)
    root = ElementTree.fromstring(car_urdf(params))
    joints = {j.get('name'): j for j in root.findall('joint')}
    names = joint_names()
    expected = set(names['wheel'] + names['steer'] + names['suspension'])
    assert set(joints) == expected
    links = {link.get('name') for link in root.findall('link')}
    assert 'base_link' in links
    for joint in joints.values():
        assert joint.find('parent').get('link') in links
        assert joint.find('child').get('link') in links
    # Webots signs: steering about -z (positive = right), spin about +y (positive = forward).
    assert joints['front_right_steer'].find('axis').get('xyz') == '0 0 -1'
    assert joints['rear_left_wheel'].find('axis').get('xyz') == '0 1 0'
    # Right wheels at -y, front wheels at the wheelbase, anchors at the rear-axle height.
    x, y, z = (float(v) for v in
               joints['front_right_suspension'].find('origin').get('xyz').split())
    assert (x, y, z) == pytest.approx((params.wheelbase_m, -params.track_front_m / 2,
                                       params.rear_tire_radius_m))
    assert float(root.find('link/inertial/mass').get('value')) == pytest.approx(params.mass_kg)


def test_car_urdf_prefix_applies_to_every_link_and_joint():
    root = ElementTree.fromstring(car_urdf(load_car('Car'), prefix='car1/'))
    names = [e.get('name') for e in root.findall('joint') + root.findall('link')]
    assert names and all(name.startswith('car1/') for name in names)


@pytest.mark.parametrize('step_ms', CHECKED_TIME_STEPS_MS)
@pytest.mark.parametrize('model', car_names())
def test_car_body_rests_on_its_wheels_with_a_small_static_sag(model, step_ms):
    params = load_car(model)
    with World(time_step_s=step_ms / 1000.0) as world:
        car = CarBody(world, params, position=(3.0, -2.0, 0.7))
        _run(world, car, Actuation(), 3.0)   # (the MercedesBenzSprinter's pitch settles last)
        pose = car.pose()
        # base_link starts on the ground; the suspension servos and the contacts give a few
        # millimetres (docs/physics.md): 0.5 mm above to 10 mm below, level within 0.3 deg.
        assert -0.010 < pose[2] < 0.0005
        assert pose[:2] == pytest.approx((3.0, -2.0), abs=1e-3)
        assert yaw_from_quaternion(*pose[3:]) == pytest.approx(0.7, abs=1e-3)
        assert _tilt_rad(pose) < math.radians(0.3)
        names, positions, velocities = car.joint_states()
        assert len(names) == len(positions) == len(velocities) == 10
        for name, position, velocity in zip(names, positions, velocities):
            assert abs(velocity) < 1e-3, name
            if name.endswith('_suspension'):
                assert 0.0 <= position < 0.010, name
        linear, angular = car.velocity()
        assert max(abs(v) for v in linear + angular) < 1e-3


def test_forward_speed_from_a_pose_just_read_is_the_speed_it_reads_itself():
    # the traffic's view of our vehicles (traffic_boxes.our_vehicle) reads the pose once and
    # hands it to forward_speed_mps: the same number as the call that reads it again
    with World() as world:
        car = CarBody(world, load_car('Car'))
        _run(world, car, _all_wheels(WheelMode.VELOCITY, 12.0), 1.0)
        speed = car.forward_speed_mps()
        assert speed > 3.0
        assert car.forward_speed_mps(car.pose()) == speed


@pytest.mark.parametrize('step_ms', CHECKED_TIME_STEPS_MS)
@pytest.mark.parametrize('model', ['Car', 'TeslaModel3', 'LincolnMKZ'])
def test_car_body_velocity_controlled_wheels_move_the_chassis_at_omega_r(model, step_ms):
    params = load_car(model)
    speed = 8.0
    ramp = 2000 // step_ms                      # steps in 2 s
    with World(time_step_s=step_ms / 1000.0) as world:
        car = CarBody(world, params)
        actuation = Actuation()
        for index in Wheel:
            actuation.wheel_mode[index] = WheelMode.VELOCITY
            # Ramp over 2 s (as the SPEED-mode logic does), then hold.
            actuation.wheel_velocity_radps[index] = 0.0
        for step in range(2 * ramp):
            for index in Wheel:
                actuation.wheel_velocity_radps[index] = \
                    min(1.0, step / ramp) * speed / _radius(params, index)
            car.apply(actuation)
            world.step()
        # Rolling without slip: v = omega * r within 0.5 %, straight ahead.
        assert car.forward_speed_mps() == pytest.approx(speed, rel=0.005)
        assert abs(car.pose()[1]) < 0.01
        measurement = car.read(Measurement())
        assert all(measurement.wheel_position_rad > 0.0)


@pytest.mark.parametrize('step_ms', CHECKED_TIME_STEPS_MS)
def test_car_body_steering_follows_the_webots_motor_and_is_capped_at_10_radps(step_ms):
    # Webots RotationalMotor: commanded velocity = 10 * error, capped at 10 rad/s; so one step
    # of dt moves 10 * error * dt while |error| <= 1 rad and 10 * dt beyond, and the error left
    # after a step is (1 - 10 dt) of the error before it.
    params = load_car('BmwX5')
    dt = step_ms / 1000.0
    with World(time_step_s=dt) as world:
        car = CarBody(world, params)
        actuation = Actuation()
        measurement = Measurement()

        def step_to(right_rad, left_rad):
            before = car.read(Measurement())
            actuation.steer_right_rad, actuation.steer_left_rad = right_rad, left_rad
            car.apply(actuation)
            world.step()
            car.read(measurement)
            return (measurement.steer_right_rad - before.steer_right_rad,
                    measurement.steer_left_rad - before.steer_left_rad)

        gain, cap = 10.0 * dt, 10.0 * dt            # per step: of the error, at most [rad]
        first = (gain * 0.5, -gain * 0.4)
        assert step_to(0.5, -0.4) == pytest.approx(first, abs=2e-4)
        assert step_to(0.5, -0.4) == pytest.approx(
            tuple((1.0 - gain) * move for move in first), abs=2e-4)
        for _ in range(100):
            step_to(1.0, -1.0)
        assert (measurement.steer_right_rad, measurement.steer_left_rad) == \
            pytest.approx((1.0, -1.0), abs=1e-3)
        # Error 2 rad: 20 rad/s asked, 10 rad/s given, until the error drops below 1 rad.
        capped = round(1.0 / cap) - 1               # the steps with more than 1 rad to go
        moves = [step_to(-1.0, 1.0) for _ in range(capped + 3)]
        for right, left in moves[:capped]:
            assert (right, left) == pytest.approx((-cap, cap), abs=2e-4)
        assert max(max(abs(r), abs(left)) for r, left in moves) <= cap + 1e-4
        assert abs(moves[-1][0]) < cap


@pytest.mark.parametrize('step_ms', CHECKED_TIME_STEPS_MS)
def test_car_body_brake_stops_a_rolling_car_and_holds_it(step_ms):
    params = load_car('Car')
    with World(time_step_s=step_ms / 1000.0) as world:
        car = CarBody(world, params)
        _run(world, car, _all_wheels(WheelMode.VELOCITY, 5.0 / params.rear_tire_radius_m), 2.0)
        assert car.forward_speed_mps() == pytest.approx(5.0, rel=0.01)
        braking = _all_wheels(WheelMode.FREE)
        braking.brake_torque_nm[:] = 700.0
        # Rolling mass: body + 6 knuckles of 0.5 kg + 4 solid wheels (m + I/r^2 = 1.5 m);
        # braking force 4 * 700 N*m / r.
        mass = params.mass_kg + 6 * 0.5 + 4 * 1.5 * params.wheel_mass_kg(True)
        decel = 4 * 700.0 / params.rear_tire_radius_m / mass
        _run(world, car, braking, 0.5)
        assert car.forward_speed_mps() == pytest.approx(5.0 - decel * 0.5, rel=0.1)
        _run(world, car, braking, 2.0)
        stopped_at = car.pose()[0]
        _run(world, car, braking, 1.0)
        assert abs(car.forward_speed_mps()) < 1e-3
        assert car.pose()[0] == pytest.approx(stopped_at, abs=1e-3)
        _, _, velocities = car.joint_states()
        assert max(abs(v) for v in velocities[:4]) < 1e-2


@pytest.mark.parametrize('step_ms', CHECKED_TIME_STEPS_MS)
def test_car_body_torque_mode_accelerates_and_a_larger_brake_holds(step_ms):
    params = load_car('TeslaModel3')
    with World(time_step_s=step_ms / 1000.0) as world:
        car = CarBody(world, params)
        actuation = Actuation()
        for index in params.driven_wheels:
            actuation.wheel_mode[index] = WheelMode.TORQUE
            actuation.wheel_torque_nm[index] = 300.0
        actuation.brake_torque_nm[:] = 500.0       # brake > torque: held
        _run(world, car, actuation, 1.0)
        assert abs(car.forward_speed_mps()) < 1e-3
        actuation.brake_torque_nm[:] = 0.0
        _run(world, car, actuation, 1.0)
        wheels = 2 * params.wheel_mass_kg(True) + 2 * params.wheel_mass_kg(False)
        inertia = 4 * 0.5 * params.wheel_mass_kg(True)   # sum I / r^2 of solid wheels
        mass = params.mass_kg + wheels + 6 * 0.5 + inertia
        radius = params.rear_tire_radius_m
        damping = 4 * params.wheels_damping_nms_per_rad / radius ** 2   # N per m/s

        def gain(net_torque_nm, v0):
            # dv/dt = (T / r - damping * v) / m, integrated over 1 s from v0.
            v_end = net_torque_nm / radius / damping
            return (v_end - v0) * (1.0 - math.exp(-damping / mass))

        expected = gain(2 * 300.0, 0.0)
        assert car.forward_speed_mps() == pytest.approx(expected, rel=0.03)
        # Torque + a smaller brake on every wheel: 600 - 4 * 60 N*m net.
        before = car.forward_speed_mps()
        actuation.brake_torque_nm[:] = 60.0
        _run(world, car, actuation, 1.0)
        gained = car.forward_speed_mps() - before
        assert gained == pytest.approx(gain(2 * 300.0 - 4 * 60.0, before), rel=0.05)


def test_car_body_two_cars_do_not_interact_unless_they_touch():
    params = load_car('Car')
    drive = _all_wheels(WheelMode.VELOCITY, 4.0 / params.rear_tire_radius_m)
    with World() as alone_world:
        alone = CarBody(alone_world, params)
        _run(alone_world, alone, drive, 1.5)
        reference = alone.pose()
    with World() as world:
        first = CarBody(world, params, name='first')
        second = CarBody(world, params, position=(0.0, 5.0, 0.0), name='second')
        held = _all_wheels(WheelMode.VELOCITY, 0.0)
        for _ in range(150):
            first.apply(drive)
            second.apply(held)
            world.step()
        assert first.pose() == pytest.approx(reference, abs=1e-6)
        assert second.pose()[:2] == pytest.approx((0.0, 5.0), abs=1e-3)
        # Now they touch: `first` (4 m long box ahead of its rear axle) rams a free `second`.
        world.remove(second)
        target = CarBody(world, params, position=(first.pose()[0] + 7.0, 0.0, 0.0))
        free = _all_wheels(WheelMode.FREE)
        for _ in range(300):
            first.apply(drive)
            target.apply(free)
            world.step()
        assert target.forward_speed_mps() > 1.0


@pytest.mark.parametrize('step_ms', CHECKED_TIME_STEPS_MS)
@pytest.mark.parametrize('model', ['BmwX5', 'TeslaModel3'])
def test_car_body_steady_turn_yaw_rate_matches_the_bicycle_model(model, step_ms):
    # Webots driver.c §3.2-3.3: Ackermann wheel angles and the differential's wheel speeds for
    # delta = 0.1 rad (right) at 10 km/h; the yaw rate must be v * tan(delta) / L within 5 %
    # (negative: a right turn, REP 103).
    params = load_car(model)
    delta, speed = 0.1, 10.0 / 3.6
    wheelbase, track_f, track_r = params.wheelbase_m, params.track_front_m, params.track_rear_m
    cot = 1.0 / math.tan(delta)
    theta_r = math.atan(1.0 / (cot - track_f / (2 * wheelbase)))
    theta_l = math.atan(1.0 / (cot + track_f / (2 * wheelbase)))
    radius_r, radius_l = wheelbase / math.sin(theta_r), wheelbase / math.sin(theta_l)
    ratio_f = radius_r / (radius_l + radius_r)
    radius_rr = wheelbase / math.tan(delta) - track_r / 2
    radius_rl = wheelbase / math.tan(delta) + track_r / 2
    ratio_r = radius_rr / (radius_rl + radius_rr)
    targets = {Wheel.FRONT_RIGHT: 2 * speed * ratio_f, Wheel.FRONT_LEFT: 2 * speed * (1 - ratio_f),
               Wheel.REAR_RIGHT: 2 * speed * ratio_r, Wheel.REAR_LEFT: 2 * speed * (1 - ratio_r)}
    ramp = 2000 // step_ms                      # steps in 2 s
    with World(time_step_s=step_ms / 1000.0) as world:
        car = CarBody(world, params)
        actuation = Actuation()
        actuation.steer_right_rad, actuation.steer_left_rad = theta_r, theta_l
        for index in params.driven_wheels:
            actuation.wheel_mode[index] = WheelMode.VELOCITY
        for step in range(3 * ramp):
            for index in params.driven_wheels:
                actuation.wheel_velocity_radps[index] = \
                    min(1.0, step / ramp) * targets[index] / _radius(params, index)
            car.apply(actuation)
            world.step()
        v = car.forward_speed_mps()
        assert v == pytest.approx(speed, rel=0.05)
        expected = -v * math.tan(delta) / wheelbase
        assert car.yaw_rate_radps() == pytest.approx(expected, rel=0.05)


def test_car_body_read_gives_continuous_wheel_angles_and_webots_steer_sign():
    params = load_car('Car')
    with World() as world:
        car = CarBody(world, params)
        actuation = _all_wheels(WheelMode.VELOCITY, 10.0)
        actuation.steer_right_rad = actuation.steer_left_rad = 0.2
        _run(world, car, actuation, 2.0)
        measurement = car.read(Measurement())
        # 10 rad/s for ~2 s: well past 2*pi, not wrapped.
        assert all(measurement.wheel_position_rad > 15.0)
        assert measurement.steer_right_rad == pytest.approx(0.2, abs=1e-3)
        assert car.yaw_rate_radps() < 0.0          # positive steering = right turn


def test_car_body_full_pose_spawn_and_invalid_pose():
    params = load_car('Car')
    with World() as world:
        car = CarBody(world, params, position=(1.0, 2.0, 0.0, 0.0, 0.0, 0.0, 1.0))
        assert car.pose()[:3] == pytest.approx((1.0, 2.0, 0.0), abs=1e-6)
        with pytest.raises(ValueError):
            CarBody(world, params, position=(1.0, 2.0))


@pytest.mark.parametrize('step_ms', CHECKED_TIME_STEPS_MS)
@pytest.mark.parametrize('model', car_names())
def test_car_body_default_grip_lets_every_preset_follow_its_0_to_100_ramp(model, step_ms):
    # Webots SPEED mode ramps the driven wheels at 27.78 / time0To100 m/s^2 at the tyre
    # (Webots' driver.c); with the default friction the chassis (ground truth) keeps up, so
    # 100 km/h is reached within 2 % of time0To100 and the car stays on its line.
    params = load_car(model)
    accel = 100.0 / 3.6 / params.time_0_to_100_s
    with World(time_step_s=step_ms / 1000.0) as world:
        car = CarBody(world, params)
        actuation = Actuation()
        for index in params.driven_wheels:
            actuation.wheel_mode[index] = WheelMode.VELOCITY
        reached_s = None
        while reached_s is None and world.time_s < 1.5 * params.time_0_to_100_s:
            for index in params.driven_wheels:
                actuation.wheel_velocity_radps[index] = \
                    accel * world.time_s / _radius(params, index)
            car.apply(actuation)
            world.step()
            if car.forward_speed_mps() >= 100.0 / 3.6:
                reached_s = world.time_s
        assert reached_s == pytest.approx(params.time_0_to_100_s, rel=0.02)
        assert abs(car.pose()[1]) < 0.05


def test_car_body_pose_and_velocity_equal_pose_and_velocity_read_apart():
    # One read of the base state for both (the ROS node samples them every step): the same
    # numbers as pose() and velocity(), in a turn where the base link moves unlike the COM.
    params = load_car('BmwX5')
    with World() as world:
        car = CarBody(world, params)
        actuation = _all_wheels(WheelMode.VELOCITY, 8.0)
        actuation.steer_right_rad = actuation.steer_left_rad = 0.3
        _run(world, car, actuation, 2.0)
        pose, (linear, angular) = car.pose_and_velocity()
        assert pose == car.pose()
        assert (linear, angular) == car.velocity()
        assert abs(angular[2]) > 0.1 and math.hypot(linear[0], linear[1]) > 1.0
