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

"""Differential-drive robot body: presets, validation, closed-form motion, determinism."""

import math

import pytest

from vehicle_sim.core.diffdrive.params import DEFAULT_ROBOT, robot_params_from_dict
from vehicle_sim.core.specs.errors import InvalidCommandError, InvalidParameterError
from vehicle_sim.physics.diff_robot import DiffRobotBody, load_robot, robot_urdf
from vehicle_sim.physics.world import World

PRESETS = ('caster_robot', 'skid_steer_robot')
SETTLE_STEPS = 50       # 0.5 s: touch down and reach the wheel speed
MEASURE_STEPS = 200     # 2 s


def drive(preset, left_radps, right_radps):
    """Drive a fresh robot at constant wheel speeds; return (body twist, yaw change, reading)."""
    with World() as world:
        robot = DiffRobotBody(world, preset)
        robot.set_wheel_velocities(left_radps, right_radps)
        for _ in range(SETTLE_STEPS):
            world.step()
        yaw0 = robot.yaw_rad()
        x0, y0 = robot.pose()[:2]
        for _ in range(MEASURE_STEPS):
            world.step()
        dyaw = math.remainder(robot.yaw_rad() - yaw0, 2 * math.pi)
        distance = math.hypot(robot.pose()[0] - x0, robot.pose()[1] - y0)
        return robot.body_twist(), dyaw, distance, robot.read(), robot.params


@pytest.mark.parametrize('preset', PRESETS)
def test_robot_preset_loads_and_validates(preset):
    params = load_robot(preset)
    assert params.model == preset
    assert len(params.wheel_joints) == (2 if params.drive == 'caster' else 4)


@pytest.mark.parametrize('field, value, fragment', [
    ('wheel_radius', -0.1, 'must be > 0'),
    ('wheel_tread', float('nan'), 'must be finite'),
    ('mass', 'heavy', 'must be a number'),
    ('drive', 'tracked', 'must be one of'),
    ('body_size', [0.5, 0.3], 'list of 3'),
    ('caster_radius', 0.2, 'must be < wheel_radius'),
    ('wheel_base', 0.3, 'must be 0 for a caster robot'),
    ('colour', 'red', 'unknown field'),
])
def test_robot_params_bad_field_raises_naming_source_field_and_value(field, value, fragment):
    with pytest.raises(InvalidParameterError) as info:
        robot_params_from_dict({field: value}, source='robots/bad.yaml')
    text = str(info.value)
    assert 'robots/bad.yaml' in text and field in text and repr(value)[:6] in text
    assert fragment in text


def test_robot_preset_file_error_names_the_file(tmp_path):
    path = tmp_path / 'odd.yaml'
    path.write_text('wheel_radius: 0\n')
    with pytest.raises(InvalidParameterError, match=r'odd\.yaml.*wheel_radius.*0'):
        load_robot(str(path))


def test_robot_urdf_names_every_wheel_joint_and_the_caster():
    urdf = robot_urdf(DEFAULT_ROBOT)
    for joint in DEFAULT_ROBOT.wheel_joints + ('caster_joint',):
        assert f'name="{joint}"' in urdf


@pytest.mark.parametrize('preset', PRESETS)
def test_robot_straight_driving_speed_is_omega_times_radius(preset):
    # v = ω·r for both wheels at ω: 6 rad/s × 0.1 m = 0.6 m/s; no yaw.
    (linear, angular), dyaw, distance, reading, params = drive(preset, 6.0, 6.0)
    expected = 6.0 * params.wheel_radius_m
    assert linear[0] == pytest.approx(expected, rel=0.01)
    assert distance == pytest.approx(expected * MEASURE_STEPS * 0.01, rel=0.01)
    assert abs(angular[2]) < 1e-3 and abs(dyaw) < 1e-3
    assert reading.left_radps == pytest.approx(6.0, rel=1e-3)
    assert reading.right_radps == pytest.approx(6.0, rel=1e-3)


def test_caster_robot_spin_in_place_yaw_rate_is_wheel_difference_over_tread():
    # ω = (v_r − v_l)/t = (4·0.1 − (−4·0.1)) / 0.4 = 2 rad/s, v ≈ 0. Tolerance 2 %.
    (linear, angular), dyaw, _, _, params = drive('caster_robot', -4.0, 4.0)
    expected = (4.0 - -4.0) * params.wheel_radius_m / params.wheel_tread_m
    assert angular[2] == pytest.approx(expected, rel=0.02)
    assert dyaw == pytest.approx(math.remainder(expected * MEASURE_STEPS * 0.01, 2 * math.pi),
                                 abs=0.05)
    assert abs(linear[0]) < 0.02


def test_caster_robot_arc_matches_the_differential_law():
    # v = r(ω_l + ω_r)/2 = 0.45 m/s, ω = r(ω_r − ω_l)/t = 0.75 rad/s. Tolerance 2 %.
    (linear, angular), _, _, _, params = drive('caster_robot', 3.0, 6.0)
    r, t = params.wheel_radius_m, params.wheel_tread_m
    assert linear[0] == pytest.approx(r * 4.5, rel=0.02)
    assert angular[2] == pytest.approx(r * 3.0 / t, rel=0.02)


def test_skid_steer_robot_turns_left_when_the_right_side_is_faster():
    # Skid steer slips sideways: the yaw rate is below the ideal (v_r − v_l)/t but has its sign.
    (_, angular), _, _, _, params = drive('skid_steer_robot', -4.0, 4.0)
    ideal = 8.0 * params.wheel_radius_m / params.wheel_tread_m
    assert 0.3 * ideal < angular[2] <= ideal * 1.01


@pytest.mark.parametrize('left, right', [(float('nan'), 0.0), (0.0, math.inf), (15.5, 0.0),
                                         (0.0, -16.0)])
def test_robot_set_wheel_velocities_out_of_range_raises_and_keeps_command(left, right):
    with World() as world:
        robot = DiffRobotBody(world, 'caster_robot')
        robot.set_wheel_velocities(1.0, 2.0)
        with pytest.raises(InvalidCommandError):
            robot.set_wheel_velocities(left, right)
        assert robot.command_radps == (1.0, 2.0)


def test_robot_set_joint_velocities_wrong_length_raises():
    with World() as world:
        robot = DiffRobotBody(world, 'skid_steer_robot')
        with pytest.raises(InvalidCommandError, match='4 expected'):
            robot.set_joint_velocities([1.0, 1.0])


def test_robot_joint_states_list_the_wheels_with_velocities():
    with World() as world:
        robot = DiffRobotBody(world, 'skid_steer_robot')
        robot.set_wheel_velocities(2.0, 3.0)
        for _ in range(30):
            world.step()
        names, positions, velocities = robot.joint_states()
        assert names == robot.params.wheel_joints
        assert velocities == pytest.approx((2.0, 2.0, 3.0, 3.0), rel=1e-3)
        assert all(p > 0.0 for p in positions)


def test_robot_simulation_is_deterministic():
    poses = []
    for _ in range(2):
        with World() as world:
            robot = DiffRobotBody(world, 'caster_robot', (1.0, -2.0, 0.3))
            robot.set_wheel_velocities(2.0, 5.0)
            for step in range(150):
                if step == 75:
                    robot.set_wheel_velocities(-3.0, 1.0)
                world.step()
            poses.append(robot.pose())
    assert poses[0] == poses[1]
