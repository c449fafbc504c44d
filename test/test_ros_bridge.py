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
The Ackermann → differential bridge node and the differential robot node.

In-process tests drive BridgeController / the node with injected time. Cross-process tests run
the bridge and the robot node as subprocesses on the embedded Cyclone DDS transport, with the
Autoware types under their real names, and talk to them from this process: the robot runs in
synchronous mode and the bridge on sim time, so the watchdog assertions are on simulated time.
Waits have generous wall-clock bounds; assertions are on outcomes, never durations.
"""

import contextlib
import math
import os
import subprocess
import sys

from automobile_helpers import wait_node_matched
from conftest import sleeper_process, stop_processes
import numpy as np
import pytest

from vehicle_sim.core.autoware.codes import (
    GEAR_DRIVE,
    GEAR_PARK,
    GEAR_REVERSE,
    MODE_AUTONOMOUS,
    MODE_MANUAL,
)
from vehicle_sim.core.bridge.controller import BridgeController
from vehicle_sim.core.bridge.converter import STOP_COMMAND
from vehicle_sim.core.bridge.params import bridge_params_from_dict
from vehicle_sim.core.specs.errors import InvalidCommandError
from vehicle_sim.ros import autoware_interfaces as awi
from vehicle_sim.ros import bridge_interfaces as bi
from vehicle_sim.ros import robot_interfaces as ri
from vehicle_sim.ros.endpoints import Topic
from vehicle_sim.transport.qos import QOS_ROSOUT

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
WAIT_S = 30.0
# Bridge under test: tread = wheel_base = 0.4 m (the caster robot's tread, Autoware's advice),
# wheel radius 0.1 m, wheel limit 1 m/s, no ramps (closed-form outputs), timeout 0.5 s brake.
L_M, T_M, R_M, VMAX = 0.4, 0.4, 0.1, 1.0
TIMEOUT_S, CONTROL_HZ = 0.5, 20.0
BRIDGE_ARGS = [
    '-p', f'wheel_base:={L_M}', '-p', f'wheel_tread:={T_M}', '-p', f'wheel_radius:={R_M}',
    '-p', f'max_wheel_speed_mps:={VMAX}', '-p', 'max_accel_mps2:=0.0',
    '-p', 'max_decel_mps2:=0.0', '-p', f'command_timeout_s:={TIMEOUT_S}',
    '-p', f'control_rate_hz:={CONTROL_HZ}']
# The other input types, each in its own bridge with its own topics.
OTHER_INPUTS = (awi.AUTO_ACKERMANN, awi.ACKERMANN_DRIVE, awi.TWIST_STAMPED)


def f32(value):
    """Round like a float32 message field."""
    return float(np.float32(value))


def closed_form(v, steering):
    """ω = v·tan δ / L; v_l = v − ω t/2, v_r = v + ω t/2 (docs/bridge_kinematics.md)."""
    omega = v * math.tan(steering) / L_M
    return v - omega * T_M / 2, v + omega * T_M / 2


# --------------------------------------------------------------------------------------------
# In-process: BridgeController with injected time (no ROS)


def controller(**overrides):
    values = {'wheel_base': L_M, 'wheel_tread': T_M, 'wheel_radius': R_M,
              'max_wheel_speed_mps': VMAX, 'max_accel_mps2': 0.0, 'max_decel_mps2': 0.0,
              'command_timeout_s': TIMEOUT_S}
    values.update(overrides)
    return BridgeController(bridge_params_from_dict(values))


def test_controller_command_gives_closed_form_wheel_speeds():
    out = controller().command(0.3, 0.2, now_s=1.0)
    assert (out.left_mps, out.right_mps) == pytest.approx(closed_form(0.3, 0.2), rel=1e-12)
    assert out.left_radps == pytest.approx(out.left_mps / R_M, rel=1e-12)


@pytest.mark.parametrize('speed, steering', [(float('nan'), 0.0), (0.3, float('nan')),
                                             (math.inf, 0.0), (0.3, math.pi / 2), (0.3, -2.0)])
def test_controller_bad_command_raises_and_does_not_feed_the_watchdog(speed, steering):
    ctl = controller()
    ctl.command(0.3, 0.1, now_s=1.0)
    with pytest.raises(InvalidCommandError):
        ctl.command(speed, steering, now_s=1.4)
    assert ctl.watchdog.last_feed_s == 1.0
    assert ctl.tick(1.6) == STOP_COMMAND       # stale at 1.6 > 1.0 + 0.5


@pytest.mark.parametrize('action, expected', [('brake', STOP_COMMAND), ('coast', None),
                                              ('hold', 'last')])
def test_controller_watchdog_action_when_commands_stop(action, expected):
    ctl = controller(timeout_action=action)
    last = ctl.command(0.3, 0.1, now_s=1.0)
    assert ctl.tick(1.5) == last                # age = timeout: still fresh
    out = ctl.tick(1.51)
    assert out == (last if expected == 'last' else expected)


def test_controller_reverse_gear_backs_along_the_commanded_curvature():
    ctl = controller()
    ctl.set_gear(GEAR_REVERSE)
    out = ctl.command(0.3, 0.2, now_s=1.0)
    left, right = closed_form(-0.3, 0.2)
    assert (out.left_mps, out.right_mps) == pytest.approx((left, right), rel=1e-12)
    assert out.speed_mps < 0.0 and out.yaw_rate_radps < 0.0   # backing with left steer


def test_controller_park_and_neutral_give_zero_wheels():
    ctl = controller()
    ctl.set_gear(GEAR_PARK)
    assert ctl.command(0.5, 0.1, now_s=1.0) == STOP_COMMAND
    ctl.set_gear(GEAR_DRIVE)
    assert ctl.command(0.5, 0.0, now_s=1.1).left_mps == pytest.approx(0.5)


def test_controller_manual_mode_stops_once_then_publishes_nothing():
    ctl = controller()
    ctl.command(0.5, 0.0, now_s=1.0)
    assert ctl.request_control_mode(MODE_MANUAL)
    assert ctl.tick(1.1) == STOP_COMMAND
    assert ctl.command(0.5, 0.0, now_s=1.2) is None
    assert not ctl.request_control_mode(2)     # AUTONOMOUS_STEER_ONLY unsupported
    assert ctl.request_control_mode(MODE_AUTONOMOUS)
    assert ctl.command(0.5, 0.0, now_s=1.3).left_mps == pytest.approx(0.5)


def test_controller_saturated_wheels_keep_the_curvature():
    out = controller().command(2.0, 0.3, now_s=1.0)
    assert max(abs(out.left_mps), abs(out.right_mps)) == pytest.approx(VMAX)
    assert out.yaw_rate_radps / out.speed_mps == pytest.approx(math.tan(0.3) / L_M, rel=1e-12)


def test_controller_acceleration_ramp_follows_node_time():
    ctl = controller(max_accel_mps2=1.0)
    assert ctl.command(0.5, 0.0, now_s=10.0).speed_mps == pytest.approx(0.0, abs=1e-8)
    assert ctl.tick(10.2).speed_mps == pytest.approx(0.2)   # 1 m/s² × 0.2 s
    assert ctl.tick(10.4).speed_mps == pytest.approx(0.4)


def test_bridge_config_and_docs_list_every_parameter():
    import yaml

    from vehicle_sim.core.bridge.params import BRIDGE_PARAM_SPECS
    from vehicle_sim.ros.bridge_node import NODE_PARAMETERS
    with open(os.path.join(REPO_ROOT, 'config', 'bridge.yaml'), encoding='utf-8') as stream:
        values = yaml.safe_load(stream)['ackermann_to_differential']['ros__parameters']
    with open(os.path.join(REPO_ROOT, 'docs', 'autoware.md'), encoding='utf-8') as stream:
        doc = stream.read()
    names = [spec.key for spec in BRIDGE_PARAM_SPECS + NODE_PARAMETERS]
    assert set(values) == set(names) | {'use_sim_time'}
    assert all(f'`{name}`' in doc for name in names)
    bridge_params_from_dict({k: values[k] for k in values if k in
                             {spec.key for spec in BRIDGE_PARAM_SPECS}}, source='bridge.yaml')


# --------------------------------------------------------------------------------------------
# Cross-process over DDS


def _env():
    env = dict(os.environ)
    env['PYTHONPATH'] = REPO_ROOT + os.pathsep + env.get('PYTHONPATH', '')
    env['PYTHONUNBUFFERED'] = '1'
    return env


def _spawn(module, *ros_args):
    return subprocess.Popen([sys.executable, '-m', module, '--ros-args', *ros_args],
                            env=_env(), stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                            text=True)


class Collector:
    """Keep every message of one topic."""

    def __init__(self, node, spec, name=None):
        self.msgs = []
        self.sub = node.create_subscription(spec.ros_type, name or spec.name, self.msgs.append,
                                            spec.qos)


@contextlib.contextmanager
def running_system():
    """Start the robot and the bridges, then this test's node; stop all of them on exit."""
    from vehicle_sim.transport.dds import DdsNode
    procs = []
    node = None
    try:
        procs.append(_spawn('vehicle_sim.ros.diff_robot_node', '-p', 'synchronous:=true'))
        procs.append(_spawn(
            'vehicle_sim.ros.bridge_node', *BRIDGE_ARGS, '-p', 'use_sim_time:=true',
            '-p', 'publish_twist:=true',
            '-r', f'{bi.DIFFERENTIAL_COMMAND_OUT.name}:=/diff_robot/differential_command',
            '-r', f'{bi.JOINT_STATES_IN.name}:=/diff_robot/joint_states'))
        for i, input_type in enumerate(OTHER_INPUTS):
            procs.append(_spawn(
                'vehicle_sim.ros.bridge_node', *BRIDGE_ARGS, '-r', f'__node:=bridge_in{i}',
                '-p', f'input_type:={input_type}', '-p', 'vehicle_status:=false',
                '-r', f'{awi.BRIDGE_INPUTS[input_type].name}:=/in{i}/command',
                '-r', f'{bi.DIFFERENTIAL_COMMAND_OUT.name}:=/in{i}/differential_command',
                '-r', f'{bi.WHEEL_VELOCITIES_OUT.name}:=/in{i}/wheel_velocities'))
        node = DdsNode('bridge_tester', '/bridge_test')
        env = {'node': node, 'procs': procs}
        env['diff'] = Collector(node, ri.ROBOT_DIFFERENTIAL_COMMAND,
                                '/diff_robot/differential_command')
        env['array'] = Collector(node, bi.WHEEL_VELOCITIES_OUT)
        env['twist'] = Collector(node, bi.TWIST_OUT)
        env['rosout'] = Collector(node, Topic('/rosout', 'rcl_interfaces/msg/Log', QOS_ROSOUT))
        env['clock'] = Collector(node, bi.CLOCK)
        for spec in awi.STATUS_TOPICS:
            env[spec.name] = Collector(node, spec)
        env['control'] = node.create_publisher(awi.CONTROL, awi.BRIDGE_INPUTS[awi.CONTROL].name)
        env['time_step'] = node.create_client(ri.ROBOT_TIME_STEP.ros_type,
                                              '/diff_robot/robot/time_step')
        env['mode'] = node.create_client(awi.CONTROL_MODE_REQUEST.ros_type,
                                         awi.CONTROL_MODE_REQUEST.name)
        for i, input_type in enumerate(OTHER_INPUTS):
            env[f'in{i}'] = node.create_publisher(input_type, f'/in{i}/command')
            env[f'out{i}'] = Collector(node, ri.ROBOT_DIFFERENTIAL_COMMAND,
                                       f'/in{i}/differential_command')
        ready = node.spin_until(
            lambda: env['time_step'].service_is_ready() and env['mode'].service_is_ready()
            and env['control'].get_subscription_count() > 0
            and all(env[f'in{i}'].get_subscription_count() > 0
                    for i in range(len(OTHER_INPUTS)))
            and env['diff'].sub.get_publisher_count() > 0, WAIT_S)
        if not ready:
            raise RuntimeError('nodes did not come up:\n' + '\n'.join(
                p.stderr.read() if p.poll() is not None else f'pid {p.pid} running'
                for p in procs))
        for name in ['diff_robot', bi.BRIDGE_NODE_NAME] + [
                f'bridge_in{i}' for i in range(len(OTHER_INPUTS))]:
            wait_node_matched(node, f'/{name}/list_parameters',
                              'rcl_interfaces/srv/ListParameters')
        yield env
    finally:
        if node is not None:
            node.shutdown()
        stop_processes(procs, WAIT_S)


@pytest.fixture(scope='module')
def system():
    with running_system() as env:
        yield env


def test_system_fixture_stops_its_processes_when_its_own_node_fails(monkeypatch):
    from vehicle_sim.transport import dds
    started = []

    def spawn(*_args):
        started.append(sleeper_process())
        return started[-1]

    def failing_node(*_args, **_kwargs):
        raise dds.TransportError('the test node could not start')

    monkeypatch.setitem(globals(), '_spawn', spawn)
    monkeypatch.setattr(dds, 'DdsNode', failing_node)
    with pytest.raises(dds.TransportError, match='could not start'):
        with running_system():
            pass
    assert len(started) == 2 + len(OTHER_INPUTS)
    assert [proc.poll() is not None for proc in started] == [True] * len(started)


def send_control(env, speed, steering):
    msg = env['node'].msg(awi.CONTROL)()
    msg.longitudinal.velocity = speed
    msg.lateral.steering_tire_angle = steering
    env['control'].publish(msg)


def wait_new(env, collector, count, predicate=lambda m: True, timeout_s=WAIT_S):
    """Spin until a message after index ``count`` satisfies predicate; return it or None."""
    found = []

    def check():
        found[:] = [m for m in collector.msgs[count:] if predicate(m)]
        return bool(found)
    env['node'].spin_until(check, timeout_s)
    return found[0] if found else None


def step_ms(env, value_ms):
    request = env['node'].srv(ri.ROBOT_TIME_STEP.ros_type).Request(value=value_ms)
    assert env['time_step'].call(request, timeout_s=WAIT_S).success


def stamp_s(stamp):
    return stamp.sec + stamp.nanosec * 1e-9


def test_bridge_control_command_publishes_closed_form_outputs(system):
    counts = [len(system[k].msgs) for k in ('diff', 'array', 'twist')]
    send_control(system, 0.3, 0.2)
    v, steer = f32(0.3), f32(0.2)
    left, right = closed_form(v, steer)
    diff = wait_new(system, system['diff'], counts[0],
                    lambda m: m.left_wheel.velocity != 0.0)
    assert diff is not None
    assert (diff.left_wheel.velocity, diff.right_wheel.velocity) == pytest.approx(
        (left, right), rel=1e-9)
    array = wait_new(system, system['array'], counts[1], lambda m: m.data[0] != 0.0)
    assert list(array.data) == pytest.approx([left / R_M, right / R_M], rel=1e-9)
    twist = wait_new(system, system['twist'], counts[2], lambda m: m.linear.x != 0.0)
    assert twist.linear.x == pytest.approx(v, rel=1e-9)
    assert twist.angular.z == pytest.approx(v * math.tan(steer) / L_M, rel=1e-9)


def test_bridge_nan_and_right_angle_steering_are_rejected_with_a_warning(system):
    system['node'].spin_until(lambda: False, 0.5)   # let earlier outputs arrive first
    count, logs = len(system['diff'].msgs), len(system['rosout'].msgs)
    for speed, steering in ((float('nan'), 0.1), (0.3, float('nan')), (0.3, math.pi / 2),
                            (0.3, -2.0)):
        send_control(system, speed, steering)
    warning = wait_new(system, system['rosout'], logs,
                       lambda m: m.level == 30 and 'rejected' in m.msg
                       and m.name == bi.BRIDGE_NODE_NAME)
    assert warning is not None
    system['node'].spin_until(lambda: False, 1.0)   # let any (wrong) output arrive
    assert system['diff'].msgs[count:] == []       # sim time is paused: no ticks either


def test_bridge_saturated_wheels_keep_the_curvature(system):
    count = len(system['diff'].msgs)
    send_control(system, 2.0, 0.3)
    diff = wait_new(system, system['diff'], count,
                    lambda m: abs(m.right_wheel.velocity - 1.0) < 1e-6)
    assert diff is not None
    v = (diff.left_wheel.velocity + diff.right_wheel.velocity) / 2
    omega = (diff.right_wheel.velocity - diff.left_wheel.velocity) / T_M
    assert omega / v == pytest.approx(math.tan(f32(0.3)) / L_M, rel=1e-6)


def test_bridge_feedback_reports_follow_the_measured_robot(system):
    speed, steering = 0.3, 0.2
    for _ in range(25):                     # 2.5 s of sim time, commands every 0.1 s
        send_control(system, speed, steering)
        system['node'].spin_once(0.01)
        step_ms(system, 100)
    count = len(system[awi.VELOCITY_STATUS.name].msgs)
    velocity = wait_new(system, system[awi.VELOCITY_STATUS.name], count)
    steer = wait_new(system, system[awi.STEERING_STATUS.name],
                     len(system[awi.STEERING_STATUS.name].msgs))
    print(f'feedback: v {velocity.longitudinal_velocity:.4f} m/s, yaw rate '
          f'{velocity.heading_rate:.4f} rad/s, steering {steer.steering_tire_angle:.4f} rad')
    assert velocity.longitudinal_velocity == pytest.approx(speed, rel=0.03)
    assert velocity.heading_rate == pytest.approx(speed * math.tan(steering) / L_M, rel=0.05)
    assert steer.steering_tire_angle == pytest.approx(steering, abs=0.02)   # + = left


def test_bridge_watchdog_publishes_zero_within_timeout_plus_one_period_of_sim_time(system):
    count = len(system['diff'].msgs)
    send_control(system, 0.2, 0.0)
    echo = wait_new(system, system['diff'], count,
                    lambda m: m.left_wheel.velocity == pytest.approx(f32(0.2)))
    assert echo is not None
    receipt_s = stamp_s(echo.header.stamp)
    count = len(system['diff'].msgs)
    zero = None
    for _ in range(200):                    # up to 2 s of sim time, one 10 ms step at a time
        step_ms(system, 0)
        zero = wait_new(system, system['diff'], count,
                        lambda m: m.left_wheel.velocity == 0.0 and m.right_wheel.velocity == 0.0,
                        timeout_s=0.02)
        if zero is not None:
            break
    assert zero is not None
    age_s = stamp_s(zero.header.stamp) - receipt_s
    print(f'watchdog: receipt {receipt_s:.3f} s, zero after {age_s:.3f} s of sim time')
    # stale only once age > timeout; detected on the next tick; /clock advances in 10 ms steps
    assert TIMEOUT_S < age_s <= TIMEOUT_S + 1.0 / CONTROL_HZ + 0.01 + 1e-6


def _report(env, spec, predicate):
    return wait_new(env, env[spec.name], 0, predicate) is not None


def test_bridge_reports_reflect_gear_lights_and_control_mode_requests(system):
    node = system['node']
    gear_pub = node.create_publisher(awi.GEAR_COMMAND.ros_type, awi.GEAR_COMMAND.name)
    turn_pub = node.create_publisher(awi.TURN_INDICATORS_COMMAND.ros_type,
                                     awi.TURN_INDICATORS_COMMAND.name)
    hazard_pub = node.create_publisher(awi.HAZARD_LIGHTS_COMMAND.ros_type,
                                       awi.HAZARD_LIGHTS_COMMAND.name)
    assert node.spin_until(lambda: gear_pub.get_subscription_count() > 0
                           and turn_pub.get_subscription_count() > 0
                           and hazard_pub.get_subscription_count() > 0, WAIT_S)
    gear = node.msg(awi.GEAR_COMMAND.ros_type)
    turn = node.msg(awi.TURN_INDICATORS_COMMAND.ros_type)
    hazard = node.msg(awi.HAZARD_LIGHTS_COMMAND.ros_type)
    gear_pub.publish(gear(command=gear.REVERSE))
    turn_pub.publish(turn(command=turn.ENABLE_LEFT))
    hazard_pub.publish(hazard(command=hazard.ENABLE))
    assert _report(system, awi.GEAR_STATUS, lambda m: m.report == gear.REVERSE)
    assert _report(system, awi.TURN_INDICATORS_STATUS, lambda m: m.report == turn.ENABLE_LEFT)
    assert _report(system, awi.HAZARD_LIGHTS_STATUS, lambda m: m.report == hazard.ENABLE)
    # REVERSE: the same forward command now backs the robot.
    count = len(system['diff'].msgs)
    send_control(system, 0.25, 0.0)
    back = wait_new(system, system['diff'], count, lambda m: m.left_wheel.velocity != 0.0)
    assert back.left_wheel.velocity == pytest.approx(-f32(0.25))
    gear_pub.publish(gear(command=gear.DRIVE))
    assert _report(system, awi.GEAR_STATUS, lambda m: m.report == gear.DRIVE)
    srv = node.srv(awi.CONTROL_MODE_REQUEST.ros_type)
    assert system['mode'].call(srv.Request(mode=MODE_MANUAL), timeout_s=WAIT_S).success
    assert _report(system, awi.CONTROL_MODE_STATUS, lambda m: m.mode == MODE_MANUAL)
    assert not system['mode'].call(srv.Request(mode=2), timeout_s=WAIT_S).success
    assert system['mode'].call(srv.Request(mode=MODE_AUTONOMOUS), timeout_s=WAIT_S).success
    count = len(system[awi.CONTROL_MODE_STATUS.name].msgs)
    assert wait_new(system, system[awi.CONTROL_MODE_STATUS.name], count,
                    lambda m: m.mode == MODE_AUTONOMOUS) is not None


@pytest.mark.parametrize('index, input_type', list(enumerate(OTHER_INPUTS)))
def test_bridge_each_input_type_drives_the_wheels(system, index, input_type):
    node = system['node']
    msg = node.msg(input_type)()
    v, second = 0.3, 0.25
    if input_type == awi.AUTO_ACKERMANN:
        msg.longitudinal.speed, msg.lateral.steering_tire_angle = v, second
        expected = closed_form(f32(v), f32(second))
    elif input_type == awi.ACKERMANN_DRIVE:
        msg.drive.speed, msg.drive.steering_angle = v, second
        expected = closed_form(f32(v), f32(second))
    else:                                   # TwistStamped: v and yaw rate straight through
        msg.twist.linear.x, msg.twist.angular.z = v, second
        expected = (v - second * T_M / 2, v + second * T_M / 2)
    collector = system[f'out{index}']
    count = len(collector.msgs)
    out = None
    for _ in range(5):   # the wall-clock watchdog may brake between sends; wait for a match
        system[f'in{index}'].publish(msg)
        out = wait_new(system, collector, count, lambda m: m.left_wheel.velocity != 0.0, 5.0)
        if out is not None:
            break
    assert out is not None
    assert (out.left_wheel.velocity, out.right_wheel.velocity) == pytest.approx(expected,
                                                                                rel=1e-9)


# --------------------------------------------------------------------------------------------
# rclpy: the same node on a real rclpy Node


def test_bridge_node_on_rclpy_gives_closed_form_outputs():
    pytest.importorskip(
        'rclpy', reason='rclpy not importable: ROS 2 Jazzy is not installed on this machine')
    import rclpy

    from vehicle_sim.ros.bridge_node import AckermannToDifferentialNode
    rclpy.init()
    try:
        bridge = AckermannToDifferentialNode(
            [], transport='rclpy',
            parameter_overrides={'wheel_base': L_M, 'wheel_tread': T_M, 'wheel_radius': R_M,
                                 'max_accel_mps2': 0.0, 'max_decel_mps2': 0.0})
        try:
            msg = bridge.node.msg(awi.CONTROL)()
            msg.longitudinal.velocity, msg.lateral.steering_tire_angle = f32(0.3), f32(0.2)
            out = bridge.handle_command(msg, now_s=1.0)
            assert (out.left_mps, out.right_mps) == pytest.approx(
                closed_form(f32(0.3), f32(0.2)), rel=1e-9)
        finally:
            bridge.destroy()
    finally:
        rclpy.try_shutdown()


def test_bridge_sim_time_tick_behind_the_node_clock_does_not_trip_the_watchdog(monkeypatch):
    # Under use_sim_time the node clock (its own /clock subscription) can be a step ahead of the
    # /clock message that triggers a control tick (two subscriptions of one topic are served in
    # any order). The command's receipt time and the tick must use one time source, else the
    # tick sees a command from "the future" (negative age: stale) and brakes.
    from vehicle_sim.ros.bridge_node import AckermannToDifferentialNode
    from vehicle_sim.transport.ros_time import Time
    bridge = AckermannToDifferentialNode(
        [], transport='dds', parameter_overrides={
            'wheel_base': L_M, 'wheel_tread': T_M, 'wheel_radius': R_M, 'use_sim_time': True,
            'max_accel_mps2': 0.0, 'max_decel_mps2': 0.0})
    try:
        clock_msg = bridge.node.msg('rosgraph_msgs/msg/Clock')

        def clock(t_s):
            msg = clock_msg()
            msg.clock.sec, msg.clock.nanosec = int(t_s), int(round((t_s % 1.0) * 1e9))
            return msg

        bridge._on_clock(clock(2.28))
        # the node clock has seen 2.31 already; the tick's /clock message says 2.30
        monkeypatch.setattr(bridge.node, 'now', lambda: Time(2_310_000_000))
        command = bridge.node.msg(awi.CONTROL)()
        command.longitudinal.velocity, command.lateral.steering_tire_angle = f32(0.3), f32(0.0)
        bridge.handle_command(command)
        bridge._on_clock(clock(2.30))
        out = bridge.controller.last_output
        assert (out.left_mps, out.right_mps) == pytest.approx((f32(0.3), f32(0.3)), rel=1e-9)
    finally:
        bridge.destroy()


def test_bridge_sim_time_ticks_on_the_first_clock_of_every_control_period(monkeypatch):
    # At the period's multiples however late the node started (its first /clock at 10 ms): a
    # lockstep runner then knows which wheel commands answer which /clock. Sim time going back
    # (a reset) ticks at once.
    from vehicle_sim.ros.bridge_node import AckermannToDifferentialNode
    bridge = AckermannToDifferentialNode(
        [], transport='dds', parameter_overrides={
            'wheel_base': L_M, 'wheel_tread': T_M, 'wheel_radius': R_M, 'use_sim_time': True,
            'control_rate_hz': 50.0})
    try:
        ticks = []
        monkeypatch.setattr(bridge, 'tick', lambda now_s=None: ticks.append(round(now_s, 6)))
        clock_msg = bridge.node.msg('rosgraph_msgs/msg/Clock')
        for t_ms in [10, 20, 30, 40, 50, 60, 70, 80, 90, 100, 30, 35, 40]:
            msg = clock_msg()
            msg.clock.sec, msg.clock.nanosec = 0, t_ms * 1_000_000
            bridge._on_clock(msg)
        assert ticks == [0.01, 0.02, 0.04, 0.06, 0.08, 0.1, 0.03, 0.04]
    finally:
        bridge.destroy()
