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
``vehicle-sim teleop``: the key logic with injected time, then the command in a pseudo-terminal.

The pty test runs the automobile node in real time and teleop in a pseudo-terminal (Python
``pty``), typing as a held key's auto-repeat does; it asserts outcomes (the car's speed rises,
then it comes to rest) with generous bounds, never durations.
"""

import os
import subprocess
import sys
import threading
import time

from automobile_helpers import NodeProcess, stop_process, wait_for, WAIT_S
from conftest import peer_env
import pytest

from vehicle_sim.ros import automobile_interfaces as itf
from vehicle_sim.tools.teleop import topic_names
from vehicle_sim.tools.teleop_keys import (
    BRAKE,
    DOWN,
    HOLD_S,
    KeyDecoder,
    LEFT,
    QUIT,
    RIGHT,
    status_line,
    TeleopLimits,
    TeleopState,
    UP,
)

# ------------------------------------------------------------------------------ keys


def test_key_decoder_reads_arrows_in_both_cursor_modes_and_wasd():
    decoder = KeyDecoder()
    assert decoder.feed(b'\x1b[A\x1b[B\x1b[C\x1b[D') == [UP, DOWN, RIGHT, LEFT]
    assert decoder.feed(b'\x1bOA\x1bOD') == [UP, LEFT]
    assert decoder.feed(b'wasdW q\x03') == [UP, LEFT, DOWN, RIGHT, UP, BRAKE, QUIT, QUIT]


def test_key_decoder_completes_an_escape_sequence_split_over_two_reads():
    decoder = KeyDecoder()
    assert decoder.feed(b'w\x1b[') == [UP]
    assert decoder.feed(b'D') == [LEFT]


def test_key_decoder_ignores_modifiers_other_sequences_and_other_keys():
    decoder = KeyDecoder()
    # Ctrl+Up is ESC [ 1 ; 5 A: an up arrow, not the letter A (= left).
    assert decoder.feed(b'\x1b[1;5A') == [UP]
    assert decoder.feed(b'\x1b[5~xz1') == []       # Page Up, other letters
    assert decoder.feed(b'\x1b') == []              # a lone Escape waits ...
    assert decoder.feed(b'w') == [UP]               # ... and is dropped


def _press_held(state, key, start_s, end_s, repeat_s=0.03):
    # A held key as a terminal reports it: one event every repeat_s.
    t = start_s
    while t <= end_s:
        state.press(key, t)
        state.command(t)
        t += repeat_s


def test_held_up_ramps_the_speed_at_accel_up_to_max_speed():
    state = TeleopState(TeleopLimits(max_speed_mps=2.0, accel_mps2=1.0))
    state.press(UP, 0.0)
    assert state.command(0.0) == (0.0, 0.0)
    state.press(UP, 0.5)
    assert state.command(0.5)[0] == pytest.approx(0.5)     # 1 m/s² for 0.5 s
    _press_held(state, UP, 0.53, 5.0)
    assert state.command(5.0)[0] == pytest.approx(2.0)


def test_no_key_for_the_hold_window_sends_zero():
    state = TeleopState(TeleopLimits(), hold_s=HOLD_S)
    _press_held(state, UP, 0.0, 1.0)
    assert state.command(1.0 + HOLD_S - 0.05)[0] > 0.0     # still held
    assert state.command(1.0 + HOLD_S + 0.05) == (0.0, 0.0)


def test_car_turn_key_gives_a_yaw_rate_of_fixed_curvature_and_none_at_standstill():
    limits = TeleopLimits(max_speed_mps=2.0, accel_mps2=1.0, curvature_per_m=0.2)
    state = TeleopState(limits)
    state.press(LEFT, 0.0)
    assert state.command(0.0) == (0.0, 0.0)                # a car cannot turn in place
    _press_held(state, UP, 0.0, 1.0)
    # Terminals repeat only the last key: ↑ held, then ← pressed; the direction stays.
    _press_held(state, LEFT, 1.03, 1.5)
    speed, yaw_rate = state.command(1.5)
    assert speed == pytest.approx(1.5, abs=0.05)
    assert yaw_rate == pytest.approx(0.2 * speed)          # ω = κ·v
    _press_held(state, UP, 2.2, 2.3)                        # ← released, ↑ again
    assert state.command(2.3)[1] == 0.0


def test_robot_turn_key_turns_in_place():
    state = TeleopState(TeleopLimits(max_yaw_rate_radps=0.8, robot=True))
    state.press(RIGHT, 0.0)
    assert state.command(0.0) == (0.0, -0.8)


def test_space_stops_at_once_and_reversing_keys_stop_first():
    state = TeleopState(TeleopLimits(max_speed_mps=2.0, accel_mps2=1.0))
    _press_held(state, UP, 0.0, 1.0)
    state.press(BRAKE, 1.01)
    assert state.command(1.01) == (0.0, 0.0)
    _press_held(state, UP, 2.0, 3.0)
    state.press(DOWN, 3.01)
    assert -0.05 <= state.command(3.01)[0] <= 0.0           # from 0, not from +v
    _press_held(state, DOWN, 3.04, 4.0)
    assert state.command(4.0)[0] < 0.0


def test_q_quits():
    state = TeleopState()
    state.press(QUIT, 0.0)
    assert state.quit


def test_limits_refuse_non_positive_values():
    with pytest.raises(ValueError, match='max_speed_mps'):
        TeleopLimits(max_speed_mps=0.0)
    with pytest.raises(ValueError, match='accel_mps2'):
        TeleopLimits(accel_mps2=float('nan'))


def test_status_line_shows_commanded_and_measured_speed_and_steering():
    line = status_line((1.0, 0.2), 0.95, 0.3, robot=False)
    assert 'cmd v +1.00 m/s' in line and 'ω +0.20 rad/s' in line
    assert 'measured v +0.95 m/s' in line and 'steering +0.30 rad' in line
    assert 'yaw rate --' in status_line((0.0, 0.0), None, None, robot=True)


def test_topic_names_of_the_car_and_the_robot():
    assert topic_names('', False) == ('/cmd_vel', '/odom', '/automobile/steering_angle')
    assert topic_names('/fleet/', True) == ('/fleet/diff_robot/cmd_vel',
                                            '/fleet/diff_robot/odom', None)


# ------------------------------------------------------------------------------ the command

@pytest.mark.parametrize('stamped', [False, True], ids=['Twist', 'TwistStamped'])
def test_teleop_node_sends_the_cmd_vel_type_the_vehicle_reads(stamped):
    from vehicle_sim.tools.teleop import Teleop
    from vehicle_sim.transport.selection import create_node
    namespace = f'/teleop_send_{stamped}'.lower()
    row = itf.CMD_VEL_INPUTS[stamped]
    teleop = Teleop(namespace, robot=True, stamped=stamped, transport='dds')
    node = create_node('teleop_listener', transport='dds',
                       args=['--ros-args', '--disable-rosout-logs'])
    try:
        received = []
        sub = node.create_subscription(row.ros_type, f'{namespace}/diff_robot/cmd_vel',
                                       received.append)
        assert node.spin_until(lambda: sub.get_publisher_count() > 0, WAIT_S)

        def sent():
            teleop.send(0.25, -0.5)
            return bool(received)
        assert wait_for(sent, WAIT_S, spin=node)
        assert row.converter(received[0]) == (0.25, -0.5)
    finally:
        node.shutdown()
        teleop.close()


TELEOP = [sys.executable, '-m', 'vehicle_sim.tools.cli', 'teleop']


def test_teleop_without_a_terminal_says_so_and_fails():
    result = subprocess.run(TELEOP, stdin=subprocess.DEVNULL, capture_output=True, text=True,
                            env=peer_env(), timeout=WAIT_S)
    assert result.returncode == 1
    assert 'stdin is not a terminal' in result.stderr


def test_the_teleop_executable_drops_ros_arguments_as_ros2_run_passes_them():
    # `ros2 run vehicle_sim teleop --ros-args -r __ns:=/x` runs the `teleop` console script with
    # those arguments: they must not be a usage error (exit 2); the non-tty check answers.
    script = ('import sys; from vehicle_sim.tools.cli import teleop_main; '
              'sys.exit(teleop_main(sys.argv[1:]))')
    result = subprocess.run([sys.executable, '-c', script, '--robot', '--ros-args', '-r',
                             '__ns:=/x'], stdin=subprocess.DEVNULL, capture_output=True,
                            text=True, env=peer_env(), timeout=WAIT_S)
    assert result.returncode == 1, result.stderr
    assert 'stdin is not a terminal' in result.stderr


class PtyProcess:
    """A command whose stdin, stdout and stderr are a pseudo-terminal; its output collected."""

    def __init__(self, args):
        import pty
        self.master, slave = pty.openpty()
        self.proc = subprocess.Popen(args, stdin=slave, stdout=slave, stderr=slave,
                                     env=peer_env(), start_new_session=True)
        os.close(slave)
        self.output = b''
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self):
        while True:
            try:
                data = os.read(self.master, 1024)
            except OSError:
                return
            if not data:
                return
            self.output += data

    def text(self):
        return self.output.decode('utf-8', 'replace')

    def type(self, data):
        os.write(self.master, data)

    def stop(self):
        stop_process(self.proc)
        os.close(self.master)


def test_teleop_in_a_terminal_drives_the_car_and_it_stops_when_the_keys_stop():
    from vehicle_sim.transport.selection import create_node
    namespace = '/teleop_car'
    car = NodeProcess('--ros-args', '-r', f'__ns:={namespace}', '-p', 'synchronous:=false')
    node = teleop = None
    try:
        node = create_node('teleop_test', args=['--ros-args', '--disable-rosout-logs'])
        odom = []
        sub = node.create_subscription(itf.ODOM.ros_type, f'{namespace}/odom', odom.append)
        assert node.spin_until(lambda: sub.get_publisher_count() > 0 and odom, WAIT_S), \
            car.text()
        teleop = PtyProcess(TELEOP + ['--namespace', namespace, '--max-speed', '3'])
        assert wait_for(lambda: 'cmd v' in teleop.text(), WAIT_S), teleop.text()

        def speed():
            return odom[-1].twist.twist.linear.x

        # Hold ↑: an arrow-key event every 30 ms, as auto-repeat sends them.
        deadline = time.monotonic() + WAIT_S
        while speed() < 1.0 and time.monotonic() < deadline:
            teleop.type(b'\x1b[A')
            node.spin_until(lambda: False, 0.03)
        assert speed() >= 1.0, teleop.text() + car.text()
        assert 'cmd v +' in teleop.text()
        # Release: teleop sends zero within its hold window and the car comes to rest.
        assert node.spin_until(lambda: abs(speed()) < 0.02, WAIT_S), teleop.text()
        teleop.type(b'q')
        assert teleop.proc.wait(WAIT_S) == 0
    finally:
        if teleop is not None:
            teleop.stop()
        if node is not None:
            node.shutdown()
        car.stop()
