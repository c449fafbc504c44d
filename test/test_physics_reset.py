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
Reset and teleport below ROS (issue 9, "Reset, teleport, pause").

CarLogic.reset / come_to_rest, the teleport request check, and SimulatedCar, DiffRobotBody and
World putting bodies back.
"""

import dataclasses
import math

import pybullet
import pytest

from vehicle_sim.config import load_car, load_world
from vehicle_sim.core.car.drivetrain import ControlMode
from vehicle_sim.core.car.logic import CarLogic
from vehicle_sim.core.car.vehicle_io import Measurement
from vehicle_sim.core.geometry.frames import (
    pose_from_frame,
    pose_in_frame,
    quaternion_from_rpy,
    quaternion_from_yaw,
    rpy_from_quaternion,
)
from vehicle_sim.core.specs.errors import InvalidPoseError
from vehicle_sim.core.world.params import obstacle_from_dict
from vehicle_sim.core.world.placement import ground_pose, QUATERNION_NORM_TOLERANCE, WORLD_EXTENT_M
from vehicle_sim.physics import SimulatedCar, World
from vehicle_sim.physics.diff_robot import DiffRobotBody, SPAWN_CLEARANCE_M
from vehicle_sim.physics.sensors import SensorFeed

DT_S = 0.01
SPAWN = (2.0, -1.0, 0.5)


def _without_time(status):
    return dataclasses.replace(status, time_s=0.0)


def _drive_everything(logic):
    # Every command and setting away from its start value.
    logic.set_cruising_speed_kmh(40.0)
    logic.set_steering_angle(0.1)
    logic.set_brake_intensity(0.2)
    logic.set_gear(1)
    logic.set_indicator(2)
    logic.set_hazard_flashers(True)
    logic.set_dipped_beams(True)
    logic.set_antifog_lights(True)
    logic.set_wiper_mode(3)
    logic.set_indicator_period_s(0.5)
    logic.enable_limited_slip_differential(False)
    logic.enable_indicator_auto_disabling(False)


# ------------------------------------------------------------------------------ core

def test_car_logic_reset_equals_a_fresh_logic_except_the_time_of_the_last_step():
    params = load_car('ToyotaPrius')
    logic = CarLogic(params)
    _drive_everything(logic)
    measurement = Measurement()
    for step in range(50):
        measurement.wheel_position_rad[:] = 0.3 * step
        logic.step(measurement, step * DT_S, DT_S)
    logic.set_throttle(0.5)           # TORQUE mode too
    assert _without_time(logic.status()) != _without_time(CarLogic(params).status())
    logic.reset()
    assert _without_time(logic.status()) == _without_time(CarLogic(params).status())
    assert logic.time_s == pytest.approx(49 * DT_S)      # simulated time is not reset
    # The first measurement after the reset starts a new sample: no speed across the jump.
    measurement.wheel_position_rad[:] = 0.0
    logic.step(measurement, 50 * DT_S, DT_S)
    assert logic.status().wheel_speeds_radps == (0.0,) * 4


def test_car_logic_come_to_rest_keeps_commands_and_forgets_the_motion():
    logic = CarLogic(load_car('ToyotaPrius'))
    _drive_everything(logic)
    measurement = Measurement()
    for step in range(50):
        measurement.wheel_position_rad[:] = 0.3 * step
        actuation = logic.step(measurement, step * DT_S, DT_S)
    assert max(actuation.wheel_velocity_radps) > 0.0
    before = logic.status()
    logic.come_to_rest()
    after = logic.status()
    assert after.wheel_speeds_radps == (0.0,) * 4 and after.current_speed_kmh == 0.0
    commands = ('target_cruising_speed_kmh', 'commanded_steering_angle_rad', 'brake_intensity',
                'selected_gear', 'control_mode', 'indicator', 'hazard_flashers', 'dipped_beams',
                'antifog_lights', 'wiper_mode', 'indicator_period_s',
                'limited_slip_differential', 'indicator_auto_disabling')
    assert {k: getattr(after, k) for k in commands} == {k: getattr(before, k) for k in commands}
    assert after.control_mode == ControlMode.SPEED
    # The motors' ramp restarts from rest: one step later the set-point is one ramp increment,
    # and the encoders' jump (a teleport keeps the wheel angles) gives no speed.
    measurement.wheel_position_rad[:] = 100.0
    actuation = logic.step(measurement, 50 * DT_S, DT_S)
    assert logic.status().wheel_speeds_radps == (0.0,) * 4
    increment = max(logic._wheel_acceleration_radps2) * DT_S
    assert 0.0 < max(actuation.wheel_velocity_radps) <= increment + 1e-12


def test_pose_from_frame_inverts_pose_in_frame():
    frame = ((3.0, -2.0, 0.5), quaternion_from_rpy(0.1, -0.2, 1.3))
    pose = ((1.0, 2.0, 3.0), quaternion_from_rpy(0.3, 0.2, -0.7))
    local = pose_in_frame(*frame, *pose)
    xyz, q = pose_from_frame(*frame, *local)
    assert xyz == pytest.approx(pose[0], abs=1e-12)
    assert q == pytest.approx(pose[1], abs=1e-12)


def test_ground_pose_keeps_x_y_and_yaw_and_drops_z_roll_pitch():
    place = ground_pose((4.0, -5.0, 7.0), quaternion_from_rpy(0.4, -0.3, 2.0))
    assert place.position == pytest.approx((4.0, -5.0, 2.0), abs=1e-12)


def test_ground_pose_in_a_frame_is_expressed_in_the_world():
    # Frame at (10, 0) turned +90 deg: its x axis is the world's y axis.
    place = ground_pose((1.0, 0.0, 0.0), quaternion_from_yaw(0.25), (10.0, 0.0, 0.0),
                        quaternion_from_yaw(math.pi / 2))
    assert place.position == pytest.approx((10.0, 1.0, math.pi / 2 + 0.25), abs=1e-12)


def test_ground_pose_accepts_a_norm_within_the_tolerance_and_normalises_it():
    scale = 1.0 + 0.9 * QUATERNION_NORM_TOLERANCE
    q = tuple(scale * v for v in quaternion_from_yaw(0.5))
    assert ground_pose((0.0, 0.0, 0.0), q).yaw_rad == pytest.approx(0.5, abs=1e-12)


@pytest.mark.parametrize('xyz, q, message', [
    ((math.nan, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0), 'x = nan'),
    ((0.0, math.inf, 0.0), (0.0, 0.0, 0.0, 1.0), 'y = inf'),
    ((0.0, 0.0, -math.inf), (0.0, 0.0, 0.0, 1.0), 'z = -inf'),
    ((0.0, 0.0, 0.0), (0.0, 0.0, math.nan, 1.0), 'qz = nan'),
    ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 0.0), 'norm 0'),
    ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0 + 1.5 * QUATERNION_NORM_TOLERANCE), 'norm 1.0015'),
    ((0.0, 0.0, 0.0), (0.0, 0.0, 0.6, 0.6), 'norm 0.848'),
])
def test_ground_pose_refuses_non_finite_values_and_non_unit_quaternions(xyz, q, message):
    with pytest.raises(InvalidPoseError, match=message):
        ground_pose(xyz, q)


def test_ground_pose_refuses_a_place_outside_the_world_and_accepts_its_edge():
    edge = ground_pose((WORLD_EXTENT_M, -WORLD_EXTENT_M, 0.0), (0.0, 0.0, 0.0, 1.0))
    assert (edge.x_m, edge.y_m) == (WORLD_EXTENT_M, -WORLD_EXTENT_M)
    with pytest.raises(InvalidPoseError, match=r'x = 1e\+308 m is outside the world'):
        ground_pose((1e308, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))
    # The check is on the place in the world, after the request's frame.
    with pytest.raises(InvalidPoseError, match='y = 1e\\+06 m is outside the world'):
        ground_pose((0.0, 1.0, 0.0), (0.0, 0.0, 0.0, 1.0), frame_xyz=(0.0, WORLD_EXTENT_M, 0.0))


# ------------------------------------------------------------------------------ physics

@pytest.fixture
def world():
    with World() as world:
        yield world


def _driven(world, car, steps=200):
    car.logic.set_cruising_speed_kmh(30.0)
    car.logic.set_steering_angle(0.2)
    car.logic.set_indicator(1)
    for _ in range(steps):
        world.step()


def test_simulated_car_reset_puts_body_joints_and_logic_back_at_spawn(world):
    car = SimulatedCar(world, load_car('ToyotaPrius'), SPAWN)
    spawn_pose = car.body.pose()
    fresh = CarLogic(car.params).status()
    _driven(world, car)
    assert math.dist(car.body.pose()[:2], spawn_pose[:2]) > 2.0
    time_s = world.time_s
    car.reset()
    assert car.body.pose() == pytest.approx(spawn_pose, abs=1e-6)
    linear, angular = car.body.velocity()
    assert linear == pytest.approx((0.0,) * 3, abs=1e-9)
    assert angular == pytest.approx((0.0,) * 3, abs=1e-9)
    _, positions, velocities = car.body.joint_states()
    assert positions == (0.0,) * len(positions) and velocities == (0.0,) * len(velocities)
    assert _without_time(car.logic.status()) == _without_time(fresh)
    assert world.time_s == time_s
    # The next step measures no speed from the joints' jump back to 0.
    world.step()
    assert max(abs(v) for v in car.logic.status().wheel_speeds_radps) < 0.05


def test_simulated_car_teleport_puts_it_at_rest_level_on_the_ground(world):
    car = SimulatedCar(world, load_car('ToyotaPrius'), SPAWN)
    _driven(world, car)
    _, spin_before, _ = car.body.joint_states()
    car.teleport(ground_pose((-20.0, 30.0, 5.0), quaternion_from_rpy(0.3, 0.2, -2.5)).position)
    pose = car.body.pose()
    assert pose[:3] == pytest.approx((-20.0, 30.0, 0.0), abs=1e-6)     # z from the ground
    roll, pitch, yaw = rpy_from_quaternion(pose[3:])
    assert (roll, pitch, yaw) == pytest.approx((0.0, 0.0, -2.5), abs=1e-6)
    linear, angular = car.body.velocity()
    assert max(map(abs, linear + angular)) < 1e-9
    _, spin_after, velocities = car.body.joint_states()
    assert spin_after[:4] == pytest.approx(spin_before[:4])   # the wheels keep their angles
    assert velocities == (0.0,) * len(velocities)
    assert car.logic.status().current_speed_kmh == 0.0
    assert car.logic.target_cruising_speed_kmh == 30.0   # commands stay
    world.step()
    assert max(abs(v) for v in car.logic.status().wheel_speeds_radps) < 1.0


def _obstacle(name, position, mass=0.0, size=(1.0, 6.0, 2.0)):
    return obstacle_from_dict({'name': name, 'shape': 'box', 'size': list(size),
                               'position': list(position), 'mass': mass}, 'test')


def test_teleport_inside_an_obstacle_or_a_vehicle_is_refused_and_moves_nothing(world):
    world.add_obstacle(_obstacle('wall', (20.0, 0.0, 1.0)))
    car = SimulatedCar(world, load_car('ToyotaPrius'), SPAWN)
    other = SimulatedCar(world, load_car('ToyotaPrius'), (-10.0, 0.0, 0.0), name='other')
    _driven(world, car, 50)
    before = (car.body.pose(), car.body.velocity(), car.body.joint_states(),
              car.logic.status())
    for place, blocker in (((20.0, 0.0, 0.0), 'wall'), ((19.0, 1.0, 1.0), 'wall'),
                           ((-9.0, 0.0, 0.3), 'other')):
        with pytest.raises(InvalidPoseError, match=f'inside {blocker}'):
            car.teleport(place)
        assert (car.body.pose(), car.body.velocity(), car.body.joint_states(),
                car.logic.status()) == before
    # Beside the wall, a body length from it, is free.
    car.teleport((15.0, 0.0, 0.0))
    assert car.body.pose()[:2] == pytest.approx((15.0, 0.0), abs=1e-6)
    assert other.body.pose()[:2] == pytest.approx((-10.0, 0.0), abs=1e-2)


def _lost_by_bullet(world, vehicle):
    # What set_pose did before it refused places beyond the world (the physics-level teleport
    # takes any place): Bullet takes the body out of its simulation, and it falls through the
    # ground after any reset of its pose and velocities.
    vehicle.teleport((1e100, 0.0, 0.0))
    for _ in range(10):
        world.step()


def test_simulated_car_reset_repairs_a_car_bullet_lost_far_beyond_the_world(world):
    car = SimulatedCar(world, load_car('ToyotaPrius'), SPAWN)
    for _ in range(100):
        world.step()
    at_rest = car.body.pose()
    _lost_by_bullet(world, car)
    car.reset()
    for _ in range(300):   # 3 s: the lost car was at z = -44 m by then
        world.step()
    assert car.body.pose() == pytest.approx(at_rest, abs=1e-3)
    car.logic.set_cruising_speed_kmh(20.0)
    for _ in range(300):
        world.step()
    assert car.body.forward_speed_mps() > 3.0
    assert car.body.pose()[2] == pytest.approx(at_rest[2], abs=0.05)


def test_diff_robot_reset_repairs_a_robot_bullet_lost_far_beyond_the_world(world):
    robot = DiffRobotBody(world, 'caster_robot', (1.0, 2.0, 0.3))
    spawn = robot.pose()
    _lost_by_bullet(world, robot)
    robot.reset()
    for _ in range(300):
        world.step()
    assert robot.pose()[:3] == pytest.approx(spawn[:3], abs=1e-2)


def _counting_loads(monkeypatch):
    # every pybullet.loadURDF call from now on, in a list
    loads = []
    load = pybullet.loadURDF

    def counted(*args, **kwargs):
        loads.append(args[0])
        return load(*args, **kwargs)
    monkeypatch.setattr(pybullet, 'loadURDF', counted)
    return loads


def test_resets_put_the_same_bodies_back_loading_no_urdf(world, monkeypatch):
    # PyBullet keeps a loaded body's collision shapes until the whole simulation is reset:
    # a reset that loaded the URDF again grew the process by ~18 KiB each time (issue 33's
    # soak, benchmarks/bench_gym_soak.py), a car put back in place leaves nothing behind.
    car = SimulatedCar(world, load_car('ToyotaPrius'), SPAWN)
    robot = DiffRobotBody(world, 'caster_robot', (1.0, 8.0, 0.3))
    ids = (car.body.body_id, robot.body_id)
    bodies = pybullet.getNumBodies(physicsClientId=world.client_id)
    loads = _counting_loads(monkeypatch)
    for _ in range(5):
        _driven(world, car, 50)
        car.reset()
        robot.reset()
    assert loads == []
    assert (car.body.body_id, robot.body_id) == ids
    assert pybullet.getNumBodies(physicsClientId=world.client_id) == bodies


def test_a_car_reset_after_a_drive_drives_bit_identically_to_a_fresh_car_reset(world):
    # Nothing of the drive stays in Bullet (contacts, motors, joints) after a reset in place.
    # (Against a body loaded at that pose it agrees within 1e-6 m: Bullet's float32 rounds the
    # pose put by resetBasePositionAndOrientation and by loadURDF differently.)
    car = SimulatedCar(world, load_car('ToyotaPrius'), SPAWN)
    _driven(world, car)
    car.reset()
    with World() as other:
        fresh = SimulatedCar(other, load_car('ToyotaPrius'), SPAWN)
        fresh.reset()
        assert car.body.pose() == fresh.body.pose()
        for drive in ((world, car), (other, fresh)):
            drive[1].logic.set_cruising_speed_kmh(30.0)
        for _ in range(300):
            world.step()
            other.step()
            assert car.body.pose() == fresh.body.pose()
            assert car.body.joint_states() == fresh.body.joint_states()


def test_a_car_placed_beyond_the_world_and_back_is_still_repaired_by_a_reset(world,
                                                                            monkeypatch):
    car = SimulatedCar(world, load_car('ToyotaPrius'), SPAWN)
    for _ in range(100):
        world.step()
    at_rest = car.body.pose()
    _lost_by_bullet(world, car)
    car.teleport((5.0, 5.0, 0.0))   # back inside the world: Bullet has it out all the same
    loads = _counting_loads(monkeypatch)
    car.reset()
    assert len(loads) == 1          # this one is loaded afresh
    for _ in range(300):
        world.step()
    assert car.body.pose() == pytest.approx(at_rest, abs=1e-3)
    car.reset()                     # and the next reset is in place again
    assert len(loads) == 1


def test_a_vehicle_starting_inside_an_obstacle_is_refused_naming_both(world):
    # The crate of issue 22 over the car's start: base_link ended 0.96 m under the ground.
    crate = _obstacle('crate', (1.5, 0.0, 1.0), size=(2.0, 2.0, 2.0))
    world.add_obstacle(crate)
    bodies = pybullet.getNumBodies(physicsClientId=world.client_id)
    with pytest.raises(InvalidPoseError, match="vehicle 'Car' starts inside obstacle 'crate'"):
        SimulatedCar(world, load_car('Car'), (0.0, 0.0, 0.0))
    assert pybullet.getNumBodies(physicsClientId=world.client_id) == bodies   # nothing left
    assert world.bodies == ()
    # The other order (an obstacle added over a vehicle already there) is refused as well.
    with World() as other:
        SimulatedCar(other, load_car('Car'), (0.0, 0.0, 0.0))
        with pytest.raises(InvalidPoseError, match="vehicle 'Car' starts inside obstacle"):
            other.add_obstacle(crate)
        assert 'crate' not in other.obstacles
        other.add_obstacle(_obstacle('crate', (10.0, 0.0, 1.0)))


def test_a_hook_watching_a_vehicle_is_no_vehicle_of_its_own(world):
    # A collision monitor keeps the body it watches as 'body'; registering it is no vehicle
    # start (a car pushed into a crate is monitored, not refused) and the car is listed once.
    from vehicle_sim.physics.sensors.collisions import CollisionMonitor
    car = SimulatedCar(world, load_car('Car'), (0.0, 0.0, 0.0))
    world.add_obstacle(_obstacle('crate', (6.0, 0.0, 1.0), size=(2.0, 2.0, 2.0)))
    car.body.place((5.0, 0.0, 0.0))                  # inside the crate now
    monitor = CollisionMonitor(world, car.body)
    assert monitor in world.bodies
    assert world.vehicle_bodies() == [car.body]


def test_reset_obstacles_puts_movable_ones_back_and_leaves_static_ones(world):
    world.add_obstacle(_obstacle('wall', (20.0, 0.0, 1.0)))
    world.add_obstacle(_obstacle('crate', (5.0, 5.0, 0.5), mass=10.0, size=(1.0, 1.0, 1.0)))
    crate = world.obstacles['crate']
    pybullet.resetBaseVelocity(crate, [3.0, 0.0, 0.0], [0.0, 0.0, 1.0],
                               physicsClientId=world.client_id)
    for _ in range(100):
        world.step()
    moved, _ = pybullet.getBasePositionAndOrientation(crate, physicsClientId=world.client_id)
    assert moved[0] > 5.5
    assert world.reset_obstacles() == ('crate',)
    position, orientation = pybullet.getBasePositionAndOrientation(
        crate, physicsClientId=world.client_id)
    assert position == pytest.approx((5.0, 5.0, 0.5), abs=1e-9)
    assert orientation == pytest.approx((0.0, 0.0, 0.0, 1.0), abs=1e-9)
    linear, angular = pybullet.getBaseVelocity(crate, physicsClientId=world.client_id)
    assert max(map(abs, linear + angular)) == 0.0


def test_diff_robot_reset_and_teleport(world):
    robot = DiffRobotBody(world, 'caster_robot', (1.0, 2.0, 0.3))
    spawn = robot.pose()
    robot.set_wheel_velocities(5.0, 4.0)
    for _ in range(100):
        world.step()
    assert math.dist(robot.pose()[:2], spawn[:2]) > 0.3
    robot.reset()
    assert robot.pose() == pytest.approx(spawn, abs=1e-6)
    assert robot.command_radps == (0.0,) * len(robot.command_radps)
    assert robot.read().wheel_position_rad == (0.0,) * len(robot.wheel_joints)
    robot.set_wheel_velocities(5.0, 5.0)
    for _ in range(50):
        world.step()
    robot.teleport((-3.0, 4.0, 1.0))
    pose = robot.pose()
    assert pose[:3] == pytest.approx((-3.0, 4.0, SPAWN_CLEARANCE_M), abs=1e-6)
    assert rpy_from_quaternion(pose[3:]) == pytest.approx((0.0, 0.0, 1.0), abs=1e-6)
    assert robot.read().wheel_velocity_radps == (0.0,) * len(robot.wheel_joints)
    assert robot.command_radps == (5.0,) * len(robot.command_radps)   # the command stays


def test_imu_after_a_teleport_does_not_differentiate_across_the_jump():
    scene = load_world('obstacle_course', 'Car')
    with World() as world:
        spec = scene.vehicles[0]
        car = SimulatedCar(world, load_car('ToyotaPrius'), (0.0, 0.0, 0.0))
        feed = SensorFeed(world, car.body, spec.sensors, scene.origin, collisions=False)
        car.logic.set_cruising_speed_kmh(50.0)
        for _ in range(300):
            world.step()
        car.teleport((-30.0, 0.0, 0.0))
        feed.restart_motion()
        feed.take()
        world.step()
        samples, _ = feed.take()
        imu = samples[-1][1]['imu']
        # At rest a step after the teleport: specific force ~ g, far from (v_before)/dt.
        assert math.dist(imu.linear_acceleration_mps2, (0.0, 0.0, 9.81)) < 3.0
