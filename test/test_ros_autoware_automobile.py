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
The autoware_automobile node: Autoware commands drive a simulated car, reports come from it.

In-process tests build the node on the embedded transport in synchronous mode and step the
world themselves (sim time, deterministic); one cross-process test runs the node as a
subprocess and talks to it over DDS like Autoware would. Signs: Autoware + left, Webots + right.
"""

import contextlib
import math
import subprocess
import sys

from automobile_helpers import wait_node_matched
from conftest import peer_env, sleeper_process, stop_processes
import pytest

from vehicle_sim.core.autoware.car import (
    car_command,
    CarLimits,
    DRIVE,
    NEUTRAL,
    PARK,
    REVERSE,
)
from vehicle_sim.core.autoware.codes import (
    DISABLE,
    ENABLE_LEFT,
    GEAR_DRIVE,
    GEAR_NEUTRAL,
    GEAR_PARK,
    GEAR_REVERSE,
    HAZARD_ENABLE,
    MODE_AUTONOMOUS,
    MODE_MANUAL,
)
from vehicle_sim.core.specs.errors import InvalidCommandError
from vehicle_sim.core.specs.units import mps_to_kmh
from vehicle_sim.ros import autoware_interfaces as awi

WAIT_S = 30.0
CAR = 'ToyotaPrius'          # wheelbase 2.8 m, steering limits ±1 rad (docs/end_to_end.md)
LIMITS = CarLimits(-0.5, 0.6, 180.0, 2.8)


# --------------------------------------------------------------------------------------------
# core mapping


def test_car_command_left_tyre_angle_becomes_negative_webots_steering():
    command = car_command(5.0, 0.2, DRIVE, LIMITS)
    assert command.steering_angle_rad == -0.2              # + left -> + right
    assert command.cruising_speed_kmh == pytest.approx(18.0)   # 5 m/s = 18 km/h
    assert (command.brake_intensity, command.webots_gear, command.coast) == (0.0, 1, False)


@pytest.mark.parametrize('action, speed_kmh, brake, gear, coast', [
    (DRIVE, 18.0, 0.0, 1, False), (REVERSE, -18.0, 0.0, -1, False),
    (PARK, 0.0, 1.0, 0, False), (NEUTRAL, 0.0, 0.0, 0, True)])
def test_car_command_gear_gives_direction_whatever_the_velocity_sign(action, speed_kmh, brake,
                                                                      gear, coast):
    for velocity in (5.0, -5.0):
        command = car_command(velocity, 0.0, action, LIMITS)
        assert command.cruising_speed_kmh == pytest.approx(speed_kmh)
        assert (command.brake_intensity, command.webots_gear, command.coast) == (brake, gear,
                                                                                 coast)


@pytest.mark.parametrize('speed, steering', [
    (float('nan'), 0.0), (1.0, math.inf), (1.0, 0.51), (1.0, -0.61), (50.01, 0.0)])
def test_car_command_beyond_the_limits_is_rejected_not_clamped(speed, steering):
    # limits in Autoware sign: [-max_webots, -min_webots] = [-0.6, 0.5] rad; top speed 50 m/s
    with pytest.raises(InvalidCommandError):
        car_command(speed, steering, DRIVE, LIMITS)


# --------------------------------------------------------------------------------------------
# in-process node


@pytest.fixture
def aw():
    from vehicle_sim.ros.autoware_automobile_node import AutowareAutomobileNode
    node = AutowareAutomobileNode([], transport='dds', parameter_overrides={
        'car_model': CAR, 'synchronous': True, 'publish_period_ms': 100})
    try:
        yield node
    finally:
        node.close()


def control(node, speed, steering):
    msg = node.node.msg(awi.CONTROL)()
    msg.longitudinal.velocity = speed
    msg.lateral.steering_tire_angle = steering
    return msg


def drive(node, speed, steering, seconds):
    """Send the command at 50 Hz of sim time for ``seconds`` and step the world."""
    for step in range(int(round(seconds / 0.01))):
        if step % 2 == 0:
            node.handle_command(control(node, speed, steering))
        node.automobile.step_once()


def gear(node, value):
    node.handle_gear(node.node.msg(awi.GEAR_COMMAND.ros_type)(command=value))


def test_node_left_command_turns_the_car_left_at_18_kmh(aw):
    drive(aw, 5.0, 0.1, 6.0)
    logic, body = aw.car.logic, aw.car.body
    assert logic.commanded_steering_angle_rad == pytest.approx(-0.1)   # Webots + right
    assert logic.current_speed_kmh == pytest.approx(18.0, rel=0.01)
    assert body.yaw_rate_radps() > 0.0                                # REP 103: left
    # steady turn: yaw rate ≈ v tan δ / L (low speed, high grip)
    assert body.yaw_rate_radps() == pytest.approx(5.0 * math.tan(0.1) / 2.8, rel=0.05)
    reports = aw.status_messages()
    assert reports[awi.VELOCITY_STATUS].longitudinal_velocity == pytest.approx(5.0, rel=0.01)
    assert reports[awi.VELOCITY_STATUS].heading_rate > 0.0
    assert reports[awi.STEERING_STATUS].steering_tire_angle == pytest.approx(0.1, abs=0.005)
    assert reports[awi.GEAR_STATUS].report == GEAR_DRIVE
    assert reports[awi.CONTROL_MODE_STATUS].mode == MODE_AUTONOMOUS


def test_node_reverse_gear_moves_backwards_and_reports_reverse(aw):
    gear(aw, GEAR_REVERSE)
    drive(aw, 2.0, 0.0, 3.0)
    assert aw.car.body.forward_speed_mps() == pytest.approx(-2.0, rel=0.05)
    assert aw.car.logic.backwards_lights
    reports = aw.status_messages()
    assert reports[awi.GEAR_STATUS].report == GEAR_REVERSE
    assert reports[awi.VELOCITY_STATUS].longitudinal_velocity < -1.9


def test_node_park_stops_the_car_and_holds_it(aw):
    drive(aw, 3.0, 0.0, 3.0)
    gear(aw, GEAR_PARK)
    drive(aw, 3.0, 0.0, 3.0)      # commands keep coming; PARK wins
    assert abs(aw.car.body.forward_speed_mps()) < 0.01
    assert aw.car.logic.brake_intensity == 1.0
    assert aw.status_messages()[awi.GEAR_STATUS].report == GEAR_PARK


def test_node_neutral_coasts(aw):
    drive(aw, 3.0, 0.0, 3.0)
    gear(aw, GEAR_NEUTRAL)
    drive(aw, 3.0, 0.0, 1.0)
    speed = aw.car.body.forward_speed_mps()
    assert 2.0 < speed < 3.0     # rolling on, slowly losing speed (no drive, no brake)
    assert aw.status_messages()[awi.GEAR_STATUS].report == GEAR_NEUTRAL


@pytest.mark.parametrize('speed, steering', [(float('nan'), 0.0), (3.0, float('nan')),
                                             (3.0, 1.2), (3.0, -1.2), (60.0, 0.0)])
def test_node_bad_command_is_rejected_and_the_car_is_unchanged(aw, speed, steering):
    drive(aw, 3.0, 0.2, 1.0)
    logic = aw.car.logic
    before = (logic.commanded_steering_angle_rad, logic.target_cruising_speed_kmh,
              aw.state.watchdog.last_feed_s)
    assert aw.handle_command(control(aw, speed, steering)) is None
    assert aw.rejected == 1
    assert (logic.commanded_steering_angle_rad, logic.target_cruising_speed_kmh,
            aw.state.watchdog.last_feed_s) == before


def test_node_watchdog_stops_the_car_after_the_timeout_of_sim_time(aw):
    drive(aw, 3.0, 0.0, 2.0)
    last_s = aw.state.watchdog.last_feed_s
    acted_s = None
    while not aw.state.timed_out:
        acted_s = aw.now_s()            # the hook runs at the time before the step
        aw.automobile.step_once()
    # stale once age > 0.5 s, checked every 10 ms step
    assert 0.5 < acted_s - last_s <= 0.5 + 0.01 + 1e-9
    assert aw.car.logic.target_cruising_speed_kmh == 0.0


@pytest.mark.parametrize('how', ['sim_reset', 'vehicle_reset'])
def test_node_reset_puts_the_autoware_interface_back_in_its_start_state(aw, how):
    def reported(messages):
        return (messages[awi.GEAR_STATUS].report, messages[awi.TURN_INDICATORS_STATUS].report,
                messages[awi.HAZARD_LIGHTS_STATUS].report, messages[awi.CONTROL_MODE_STATUS].mode)

    start = reported(aw.status_messages())
    assert start[0] == GEAR_DRIVE
    gear(aw, GEAR_REVERSE)
    drive(aw, 2.0, 0.2, 2.0)
    assert aw.status_messages()[awi.GEAR_STATUS].report == GEAR_REVERSE
    if how == 'sim_reset':
        aw.automobile.reset()                                  # as /sim/reset
    else:
        aw.automobile.reset_vehicle('')                        # as the car's /reset
    assert reported(aw.status_messages()) == start             # gear DRIVE, as at start
    assert aw.state.target is None and not aw.state.timed_out
    for _ in range(100):                                       # no command: it stays at rest
        aw.automobile.step_once()
    assert abs(aw.car.body.forward_speed_mps()) < 0.01
    assert not aw.state.timed_out                              # nothing to time out
    drive(aw, 2.0, 0.0, 3.0)                                   # forward, not in reverse
    assert aw.car.body.forward_speed_mps() == pytest.approx(2.0, rel=0.05)


def test_node_reset_keeps_manual_mode_and_forgets_the_gear(aw):
    gear(aw, GEAR_PARK)
    assert aw.request_control_mode(MODE_MANUAL)
    aw.automobile.reset()
    assert aw.state.action == DRIVE and not aw.state.autonomous
    reports = aw.status_messages()
    assert reports[awi.CONTROL_MODE_STATUS].mode == MODE_MANUAL   # the operator's choice stays
    assert reports[awi.GEAR_STATUS].report == GEAR_DRIVE


def test_node_lights_and_control_mode_are_reported_from_the_car(aw):
    turn = aw.node.msg(awi.TURN_INDICATORS_COMMAND.ros_type)
    hazard = aw.node.msg(awi.HAZARD_LIGHTS_COMMAND.ros_type)
    aw.handle_turn_indicators(turn(command=ENABLE_LEFT))
    aw.handle_hazard_lights(hazard(command=HAZARD_ENABLE))
    assert aw.car.logic.indicator == 2 and aw.car.logic.hazard_flashers   # Webots LEFT = 2
    reports = aw.status_messages()
    assert reports[awi.TURN_INDICATORS_STATUS].report == ENABLE_LEFT
    assert reports[awi.HAZARD_LIGHTS_STATUS].report == HAZARD_ENABLE
    aw.handle_turn_indicators(turn(command=DISABLE))
    assert aw.status_messages()[awi.TURN_INDICATORS_STATUS].report == DISABLE
    drive(aw, 3.0, 0.0, 2.0)
    assert aw.request_control_mode(MODE_MANUAL)
    assert aw.car.logic.target_cruising_speed_kmh == 0.0           # one stop on MANUAL
    aw.handle_command(control(aw, 3.0, 0.0))
    assert aw.car.logic.target_cruising_speed_kmh == 0.0           # MANUAL: ignored
    assert aw.status_messages()[awi.CONTROL_MODE_STATUS].mode == MODE_MANUAL
    assert not aw.request_control_mode(2)
    assert aw.request_control_mode(MODE_AUTONOMOUS)
    aw.handle_command(control(aw, 3.0, 0.0))
    assert aw.car.logic.target_cruising_speed_kmh == pytest.approx(mps_to_kmh(3.0))


def _bridge_refuses(setter_name, value):
    from vehicle_sim.core.bridge.controller import BridgeController
    from vehicle_sim.core.bridge.params import DEFAULT_BRIDGE_PARAMS
    try:
        getattr(BridgeController(DEFAULT_BRIDGE_PARAMS), setter_name)(value)
    except InvalidCommandError:
        return True
    return False


@pytest.mark.parametrize('endpoint, handler, bridge_setter', [
    (awi.GEAR_COMMAND, 'handle_gear', 'set_gear'),
    (awi.TURN_INDICATORS_COMMAND, 'handle_turn_indicators', 'set_turn_indicators'),
    (awi.HAZARD_LIGHTS_COMMAND, 'handle_hazard_lights', 'set_hazard_lights'),
])
def test_node_refuses_exactly_the_commands_the_bridge_refuses(aw, endpoint, handler,
                                                               bridge_setter):
    # One validation (core/autoware/codes.py) for both vehicle interfaces; a refusal changes
    # nothing.
    msg = aw.node.msg(endpoint.ros_type)
    refused = []
    for value in list(range(0, 30)) + [255]:
        before = (aw.rejected, aw.status_messages()[awi.GEAR_STATUS].report,
                  aw.car.logic.indicator, aw.car.logic.hazard_flashers)
        getattr(aw, handler)(msg(command=value))
        if aw.rejected != before[0]:
            refused.append(value)
            assert (aw.status_messages()[awi.GEAR_STATUS].report, aw.car.logic.indicator,
                    aw.car.logic.hazard_flashers) == before[1:]
        assert (value in refused) == _bridge_refuses(bridge_setter, value), value
    assert refused and refused[-1] == 255


# --------------------------------------------------------------------------------------------
# cross-process over DDS


def _start_node():
    return subprocess.Popen(
        [sys.executable, '-m', 'vehicle_sim.ros.autoware_automobile_node', '--ros-args',
         '-p', f'car_model:={CAR}', '-p', 'synchronous:=true', '-p', 'publish_period_ms:=100'],
        env=peer_env(), stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)


@contextlib.contextmanager
def node_and_tester():
    """Start the node in a subprocess, then this test's node; stop both on exit."""
    from vehicle_sim.transport.dds import DdsNode
    proc = _start_node()
    node = None
    try:
        node = DdsNode('autoware_tester', '/aw_test')
        yield proc, node
    except Exception as error:      # what the node said goes with the failure (its log)
        stop_processes([proc], WAIT_S)
        if hasattr(error, 'add_note'):      # (Python 3.11 and later)
            error.add_note("the node's stderr:\n" + (proc.stderr.read() if proc.stderr else ''))
        raise
    finally:
        if node is not None:
            node.shutdown()
        stop_processes([proc], WAIT_S)


def test_node_and_tester_stop_the_subprocess_when_the_test_node_fails(monkeypatch):
    from vehicle_sim.transport import dds
    started = []

    def start():
        started.append(sleeper_process())
        return started[-1]

    def failing_node(*_args, **_kwargs):
        raise dds.TransportError('the test node could not start')

    monkeypatch.setitem(globals(), '_start_node', start)
    monkeypatch.setattr(dds, 'DdsNode', failing_node)
    with pytest.raises(dds.TransportError, match='could not start'):
        with node_and_tester():
            pass
    (proc,) = started
    assert proc.poll() is not None


def test_node_subprocess_control_over_dds_drives_the_car_and_reports_velocity():
    with node_and_tester() as (proc, node):
        reports = []
        node.create_subscription(awi.VELOCITY_STATUS.ros_type, awi.VELOCITY_STATUS.name,
                                 reports.append, awi.VELOCITY_STATUS.qos)
        publisher = node.create_publisher(awi.CONTROL, awi.BRIDGE_INPUTS[awi.CONTROL].name)
        step = node.create_client('vehicle_msgs/srv/SetInt', '/robot/time_step')
        assert node.spin_until(lambda: step.service_is_ready()
                               and publisher.get_subscription_count() > 0, WAIT_S), \
            proc.stderr.read() if proc.poll() is not None else 'node did not come up'
        # ready on this side is not yet matched on the node's: a request written before the
        # node matched the client's request writer is lost (docs/transport.md)
        wait_node_matched(node, '/robot/get_time', 'vehicle_msgs/srv/GetFloat')
        msg = node.msg(awi.CONTROL)()
        msg.longitudinal.velocity, msg.lateral.steering_tire_angle = 5.0, 0.1
        request = node.srv('vehicle_msgs/srv/SetInt').Request(value=100)
        for _ in range(60):                 # 6 s of sim time, a command every 0.1 s
            publisher.publish(msg)
            node.spin_once(0.005)
            assert step.call(request, timeout_s=WAIT_S).success
        # /robot/time_step is the composed automobile node's: /automobile/* stays available
        assert node.spin_until(lambda: any(m.longitudinal_velocity > 4.9 for m in reports),
                               WAIT_S)
        last = [m for m in reports if m.longitudinal_velocity > 4.9][-1]
        print(f'velocity_status over DDS: {last.longitudinal_velocity:.3f} m/s, heading rate '
              f'{last.heading_rate:.4f} rad/s')
        assert last.longitudinal_velocity == pytest.approx(5.0, rel=0.01)
        assert last.heading_rate > 0.0


PRIUS_FULL_BRAKE_MPS2 = 4.81    # speed_braking.full_brake_deceleration_mps2 (ToyotaPrius)


def test_node_subprocess_watchdog_brake_stops_at_the_full_brake_deceleration_over_dds():
    # Control at 10 m/s, then silence: the watchdog's brake is a safety stop (throttle released,
    # full brake), so velocity_status falls at the Prius's full-brake deceleration, 4.81 m/s^2
    # (-0.1, +0.4: the wheels' damping and rolling), and the car stops within
    # v^2 / (2 * 4.81) = 10.4 m (-1.5 m, +0.3 m) of where it acted; at the cruise control's
    # 2.6 m/s^2 (a cruising speed of 0, as before) it took 19 m.
    with node_and_tester() as (proc, node):
        reports = []
        node.create_subscription(awi.VELOCITY_STATUS.ros_type, awi.VELOCITY_STATUS.name,
                                 reports.append, awi.VELOCITY_STATUS.qos)
        publisher = node.create_publisher(awi.CONTROL, awi.BRIDGE_INPUTS[awi.CONTROL].name)
        step = node.create_client('vehicle_msgs/srv/SetInt', '/robot/time_step')
        assert node.spin_until(lambda: step.service_is_ready()
                               and publisher.get_subscription_count() > 0, WAIT_S), \
            proc.stderr.read() if proc.poll() is not None else 'node did not come up'
        # ready on this side is not yet matched on the node's: a request written before the
        # node matched the client's request writer is lost (docs/transport.md)
        wait_node_matched(node, '/robot/get_time', 'vehicle_msgs/srv/GetFloat')
        msg = node.msg(awi.CONTROL)()
        msg.longitudinal.velocity = 10.0
        for _ in range(60):                 # 6 s of sim time, a command every 0.1 s
            publisher.publish(msg)
            node.spin_once(0.005)
            assert step.call(node.srv('vehicle_msgs/srv/SetInt').Request(value=100),
                             timeout_s=WAIT_S).success
        assert node.spin_until(lambda: reports and reports[-1].longitudinal_velocity > 9.9,
                               WAIT_S)
        start = len(reports)
        for _ in range(60):                 # 3 s without a command, 50 ms at a time
            assert step.call(node.srv('vehicle_msgs/srv/SetInt').Request(value=50),
                             timeout_s=WAIT_S).success
        assert node.spin_until(lambda: len(reports) >= start + 85, WAIT_S)   # 30 Hz
        samples = [(m.header.stamp.sec + 1e-9 * m.header.stamp.nanosec,
                    m.longitudinal_velocity) for m in reports[start - 1:]]
        slowing = [i for i, (_, v) in enumerate(samples) if v < 9.95]
        assert slowing, samples
        first = slowing[0] - 1            # the last report at speed, before the stop acted
        t0, v0 = samples[first]
        assert v0 == pytest.approx(10.0, abs=0.1)
        fit = [(t, v) for t, v in samples if 2.0 < v < 9.0]
        assert len(fit) > 30
        ts, vs = zip(*fit)
        mt, mv = sum(ts) / len(ts), sum(vs) / len(vs)
        slope = sum((t - mt) * (v - mv) for t, v in fit) / sum((t - mt) ** 2 for t in ts)
        assert PRIUS_FULL_BRAKE_MPS2 - 0.1 < -slope < PRIUS_FULL_BRAKE_MPS2 + 0.4
        # the distance from the last report at speed: the reported speeds, integrated
        after = samples[first:]
        distance = sum(0.5 * (v1 + v2) * (t2 - t1)
                       for (t1, v1), (t2, v2) in zip(after, after[1:]))
        ideal = v0 * v0 / (2.0 * PRIUS_FULL_BRAKE_MPS2)
        assert ideal - 1.5 < distance < ideal + 0.3
        assert abs(samples[-1][1]) < 0.01
