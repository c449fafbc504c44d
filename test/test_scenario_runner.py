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
Running scenario files: verdicts, determinism, JUnit XML and the CLI.

The shipped examples pass or fail as stated, runs are deterministic, the JUnit XML has pytest's
shape, and ``vehicle-sim scenario`` exits as documented.
"""

import math
from pathlib import Path
import re
import subprocess
import sys
import textwrap
from xml.etree import ElementTree

import pytest

from vehicle_sim.scenarios.junit import write_junit
from vehicle_sim.scenarios.runner import run_scenario
from vehicle_sim.scenarios.yaml_lines import ScenarioError
from vehicle_sim.tools.cli import main

ROOT = Path(__file__).resolve().parent.parent
STOP = ROOT / 'scenarios' / 'stop_before_obstacle.yaml'
BLIND = ROOT / 'scenarios' / 'drive_into_obstacle.yaml'
COMMANDS = ROOT / 'test' / 'scenarios' / 'commands_and_actor.yaml'
# config/worlds/obstacle_course.yaml: the wall's near face.
WALL_FACE_X_M = 19.5


@pytest.fixture(scope='module')
def stop_result():
    return run_scenario(STOP)


@pytest.fixture(scope='module')
def blind_result():
    return run_scenario(BLIND)


def test_runner_lidar_controller_stops_before_the_wall_and_passes(stop_result):
    result = stop_result
    assert result.passed, [c.detail for c in result.criteria]
    assert result.error is None
    assert result.sim_time_s == pytest.approx(10.0, abs=1e-9)
    assert result.criterion('no_collision').value == 0
    # it drove there: the rear axle passed the goal region and stopped short of the wall
    x_end = result.tracks['Car'].x_m[-1]
    assert 9.0 < x_end < WALL_FACE_X_M - 4.5
    assert result.criterion('max_speed').value == pytest.approx(20.0 / 3.6, abs=0.1)


def test_runner_blind_controller_fails_on_exactly_no_collision(blind_result):
    result = blind_result
    assert not result.passed
    assert result.error is None
    assert [c.name for c in result.failures] == ['no_collision']
    collision = result.criterion('no_collision')
    assert collision.value == 1
    assert 'wall' in collision.detail


def test_runner_commands_and_actor_scenario_passes_with_its_values():
    result = run_scenario(COMMANDS)
    assert result.passed, [c.detail for c in result.criteria]
    # ego cruised at 18 km/h = 5 m/s; the actor kept within 1 m of its waypoint path
    assert result.criterion('max_speed').value == pytest.approx(5.0, abs=0.05)
    assert result.criterion('stay_on_path').value < 1.0
    other = result.tracks['other']
    assert other.x_m[-1] > 15.0 and other.y_m[-1] > 10.5     # turned towards (25, 15)
    # the robot actor stopped at its last waypoint (within its tread, 0.4 m, plus braking)
    bot = result.tracks['bot']
    assert result.criterion('reach_goal_2').passed
    assert math.hypot(bot.x_m[-1] - 4.0, bot.y_m[-1] + 4.0) < 0.5


@pytest.mark.parametrize('path', [COMMANDS, STOP], ids=['commands', 'controller'])
def test_runner_same_scenario_and_seed_give_identical_odometry_streams(path):
    first = run_scenario(path, seed=3)
    second = run_scenario(path, seed=3)
    assert first.odometry_sha256 == second.odometry_sha256
    assert first.tracks[first.spec.vehicle].x_m == second.tracks[second.spec.vehicle].x_m
    assert first.deterministic and second.deterministic
    assert first.tracks[first.spec.vehicle].x_m[-1] > 5.0      # not a trivial stream


def test_runner_refused_command_names_its_line(tmp_path):
    path = tmp_path / 'bad_command.yaml'
    path.write_text(textwrap.dedent("""\
        world: {vehicles: [{name: ego}]}
        duration: 1.0
        driver:
          commands:
            - {t: 0.0, cruising_speed: 10.0}
            - {t: 0.5, steering_angle: 3.0}
        criteria: [{kind: no_collision}]
        """), encoding='utf-8')
    with pytest.raises(ScenarioError, match=r'setSteeringAngle\(3.0\) refused') as caught:
        run_scenario(path)
    assert caught.value.line == 6


@pytest.mark.parametrize('brake_command, stops', [
    ('{t: 4.5, brake_intensity: 1.0}', False),                  # cruise control holds 20 km/h
    ('{t: 4.5, throttle: 0.0, brake_intensity: 1.0}', True),    # docs/scenarios.md's example
])
def test_runner_brake_acts_once_the_throttle_ends_cruise_control(tmp_path, brake_command, stops):
    path = tmp_path / 'brake.yaml'
    path.write_text(textwrap.dedent(f"""\
        world: {{vehicles: [{{name: ego}}]}}
        duration: 10.0
        driver:
          commands: [{{t: 0.0, cruising_speed: 20}}, {brake_command}]
        criteria:
          - {{kind: reach_goal, goal: [25.0, 0.0], radius: 15.0, max_speed: 0.05}}
        """), encoding='utf-8')
    result = run_scenario(path)
    assert result.passed is stops
    if stops:
        assert result.notes == []
    else:
        # Said once, with the command's line, where the user reads the result.
        assert result.notes == [
            f'{path}:4: command at t = 4.5 s: setBrakeIntensity(1.0): brake intensity 1 has no '
            'effect while cruise control holds 20 km/h (the driven wheels follow the cruising '
            'speed): set the cruising speed to 0 to slow down, or set the throttle (TORQUE '
            'mode) so that the brake acts']
        assert 'never below the limit there' in result.criteria[0].detail


def _controller_scenario(tmp_path, body):
    script = tmp_path / 'controller.py'
    script.write_text('from vehicle_sim.webots import Driver\n' + textwrap.dedent(body),
                      encoding='utf-8')
    path = tmp_path / 'scenario.yaml'
    path.write_text('world: {vehicles: [{name: ego}]}\nduration: 0.5\n'
                    'driver: {controller: controller.py}\n'
                    'criteria: [{kind: max_speed, limit: 10.0}]\n', encoding='utf-8')
    return path


def test_runner_controller_that_ignores_the_end_is_stopped(tmp_path):
    path = _controller_scenario(tmp_path, """\
        driver = Driver()
        driver.setCruisingSpeed(5.0)
        while True:
            driver.step()
        """)
    result = run_scenario(path)
    assert result.error is None and result.passed
    assert result.sim_time_s == pytest.approx(0.5, abs=1e-9)


def test_runner_controller_exception_is_the_runs_error(tmp_path):
    path = _controller_scenario(tmp_path, """\
        driver = Driver()
        driver.step()
        raise RuntimeError('controller bug')
        """)
    result = run_scenario(path)
    assert not result.passed
    assert 'controller bug' in result.error
    assert result.sim_time_s == pytest.approx(0.5, abs=1e-9)   # the world stepped on


def test_runner_controller_sees_the_seed(tmp_path):
    path = _controller_scenario(tmp_path, """\
        import os
        import random
        driver = Driver()
        assert os.environ['VEHICLE_SIM_SEED'] == '7'
        assert random.random() == random.Random(7).random()
        """)
    assert run_scenario(path, seed=7).passed


def test_junit_has_pytests_shape_and_one_testcase_per_criterion(blind_result, tmp_path):
    out = tmp_path / 'out.xml'
    write_junit(blind_result, out)
    root = ElementTree.parse(out).getroot()
    assert root.tag == 'testsuites'
    suite, = root.findall('testsuite')
    for attribute in ('name', 'tests', 'failures', 'errors', 'skipped', 'time', 'timestamp',
                      'hostname'):
        assert suite.get(attribute), attribute
    assert suite.get('name') == 'drive_into_obstacle'
    assert (suite.get('tests'), suite.get('failures'), suite.get('errors')) == ('3', '1', '0')
    cases = suite.findall('testcase')
    assert [c.get('name') for c in cases] == ['no_collision', 'reach_goal', 'max_speed']
    assert {c.get('classname') for c in cases} == {'scenario.drive_into_obstacle'}
    assert all(float(c.get('time')) >= 0.0 for c in cases)
    failed = [c for c in cases if c.find('failure') is not None]
    assert [c.get('name') for c in failed] == ['no_collision']
    assert 'wall' in failed[0].find('failure').get('message')
    assert 'm/s' in cases[2].find('system-out').text
    properties = {p.get('name'): p.get('value') for p in suite.find('properties')}
    assert properties['odometry_sha256'] == blind_result.odometry_sha256
    assert properties['seed'] == '0'


def test_junit_run_error_is_an_error_testcase(tmp_path):
    path = _controller_scenario(tmp_path, 'raise ValueError("broken")\n')
    result = run_scenario(path)
    out = tmp_path / 'out.xml'
    write_junit(result, out)
    suite = ElementTree.parse(out).getroot().find('testsuite')
    assert (suite.get('tests'), suite.get('errors')) == ('2', '1')
    error = suite.find("testcase[@name='run']/error")
    assert 'broken' in error.text


def test_cli_scenario_exit_status_is_0_only_when_all_pass(tmp_path, capsys):
    junit = tmp_path / 'stop.xml'
    assert main(['scenario', str(STOP), '--junit', str(junit), '--no-progress']) == 0
    out = capsys.readouterr().out
    assert 'PASS  no_collision: 0 collisions' in out
    assert 'PASS: 4/4 criteria passed' in out
    assert ElementTree.parse(junit).getroot().find('testsuite').get('failures') == '0'
    assert main(['scenario', str(BLIND), '--no-progress']) == 1
    assert 'FAIL  no_collision: 1 collision  (1 collision: wall' in capsys.readouterr().out


def test_cli_scenario_invalid_file_exits_2_naming_the_line(tmp_path, capsys):
    path = tmp_path / 'bad.yaml'
    path.write_text('world: default\nduration: -1\n', encoding='utf-8')
    assert main(['scenario', str(path)]) == 2
    assert f'{path}:2: ' in capsys.readouterr().err


def test_cli_scenario_plot_writes_a_png(tmp_path):
    pytest.importorskip('matplotlib', reason='the plot needs matplotlib')
    out = tmp_path / 'plot.png'
    assert main(['scenario', str(COMMANDS), '--plot', str(out), '--no-progress']) == 0
    assert out.read_bytes()[:8] == b'\x89PNG\r\n\x1a\n'


def test_cli_scenario_plot_without_matplotlib_exits_2_before_running(tmp_path, capsys,
                                                                     monkeypatch):
    monkeypatch.setitem(__import__('sys').modules, 'matplotlib', None)
    assert main(['scenario', str(COMMANDS), '--plot', str(tmp_path / 'p.png')]) == 2
    captured = capsys.readouterr()
    assert "pip install 'vehicle_sim[plot]'" in captured.err
    assert 'criteria passed' not in captured.out


def test_cli_scenario_progress_is_plain_lines_off_a_terminal(capsys):
    assert main(['scenario', str(COMMANDS)]) == 0
    err = capsys.readouterr().err
    assert 'commands_and_actor: t = 6.00 / 6 s' in err
    assert '\r' not in err


def test_runner_repeated_deterministic_run_has_no_spread():
    result = run_scenario(COMMANDS, repeat=2)
    assert result.runs == 2 and result.passed
    for name, (low, high) in result.spread.items():
        assert low == high, name


def test_runner_topic_criteria_are_judged_over_the_wire():
    # A topic criterion serves the car over ROS (the automobile node in the runner's process);
    # every Float64Stamped of the 2 s (one per 10 ms step) reaches the runner's subscription.
    result = run_scenario(ROOT / 'test' / 'scenarios' / 'served_topic.yaml')
    assert result.passed, [c.detail for c in result.criteria]
    assert result.deterministic
    eventually, always, clock = result.criteria
    assert 15.0 < eventually.value < 16.0            # km/h, the first message above 15
    assert 19.0 < always.value <= 20.5               # the top speed reached, below 20.5
    assert 'all 200 messages pass' in always.detail
    # /clock is published best effort, every step: a best-effort judge reads every one.
    assert 'all 200 messages pass' in clock.detail


def test_runner_robot_sensors_are_published_by_its_node_when_served():
    # The caster robot's lidar: 10 Hz, range 12 m (config/robots/caster_robot.yaml); 1 s.
    result = run_scenario(ROOT / 'test' / 'scenarios' / 'served_robot_sensors.yaml')
    assert result.passed, [c.detail for c in result.criteria]
    (scan,) = result.criteria
    assert scan.value == pytest.approx(12.0)
    assert 'all 10 messages pass' in scan.detail


def test_runner_bridge_drives_the_caster_robot_along_the_s_curve():
    # Two processes (the S-curve commander and the ackermann_to_differential bridge) drive the
    # caster robot served over ROS, in lockstep with the commander's /clock answers.
    result = run_scenario(ROOT / 'scenarios' / 'bridge_s_curve.yaml')
    assert result.error is None
    assert result.passed, [c.detail for c in result.criteria]
    assert not result.deterministic
    assert result.criterion('stay_on_path').value < 0.15
    # The lockstep waits for the bridge's two wheel commands of each /clock period, so the robot
    # is at most one period (20 ms) behind the commands: 0.016-0.026 m measured, also with six
    # busy loops on two cores (syncing on the commander alone gave 0.02-0.19 m under load).
    assert result.criterion('stay_on_path').value < 0.05
    assert result.criterion('max_speed').value == pytest.approx(0.8, abs=0.02)


def _commander_scenario(tmp_path, sync, timeout):
    # The S-curve commander driving the caster robot in lockstep on ``sync`` (a YAML flow list);
    # ``timeout``: the driver's timeout key and value
    path = tmp_path / 'commander.yaml'
    path.write_text(textwrap.dedent(f"""\
        world: {{}}
        robots: [{{name: diff_robot, model: caster_robot}}]
        duration: 1.0
        driver:
          processes: ['python {ROOT / 'examples' / 's_curve_commander.py'}']
          clock_subscribers: 1
          sync: {sync}
          sync_period: 0.02
          {timeout}
          real_time_factor: 0.0
        criteria: [{{kind: max_speed, limit: 1.0}}]
        """), encoding='utf-8')
    return path


def test_runner_lockstep_short_of_a_sync_count_ends_the_run_naming_it(tmp_path):
    # The commander publishes one command per 20 ms of /clock: a count of 2 is never met.
    result = run_scenario(_commander_scenario(
        tmp_path, '[{topic: /control/command/control_cmd, '
        'type: autoware_control_msgs/msg/Control, count: 2}]', 'sync_timeout: 1.0'))
    assert not result.passed
    # at the first sync (0.02 s), or at the second when the command of the first /clock (0.01 s)
    # came in late enough to count for the first
    assert re.match(r'lockstep: fewer than 2 messages on /control/command/control_cmd within '
                    r'1 s \(wall\) after /clock 0\.0[24]0 s\n', result.error), result.error


def test_hosted_driver_binds_to_the_host_car_and_leaves_it_in_the_world():
    from vehicle_sim.config import load_car
    from vehicle_sim.physics.simulated_car import SimulatedCar
    from vehicle_sim.physics.world import World
    from vehicle_sim.webots import Driver
    from vehicle_sim.webots.host import ControllerHost, hosting
    with World() as world:
        car = SimulatedCar(world, load_car('Car'), (0.0, 0.0, 0.0), name='ego')
        host = ControllerHost(world, car, duration_s=0.02)
        with hosting(host):
            driver = Driver(car='TeslaModel3')          # the host's car wins, as in Webots
        assert driver.world is world and driver.logic is car.logic
        driver.setCruisingSpeed(10.0)
        assert car.logic.target_cruising_speed_kmh == 10.0
        assert (driver.step(), driver.step(), driver.step()) == (0, -1, -1)
        assert world.time_s == pytest.approx(0.02, abs=1e-12)
        driver.close()
        assert car in world.bodies and not world.closed


def test_progress_draws_a_bar_on_a_terminal():
    import io

    from vehicle_sim.tools.scenario_command import ScenarioProgress

    class Tty(io.StringIO):
        def isatty(self):
            return True

    stream = Tty()
    progress = ScenarioProgress(stream, 'demo')
    progress(5.0, 10.0)
    progress.done()
    assert stream.getvalue() == '\rdemo [' + '#' * 15 + '.' * 15 + ']    5.00 / 10 s\n'


def test_runner_in_process_controller_in_a_served_world_publishes_every_step():
    result = run_scenario(ROOT / 'test' / 'scenarios' / 'served_controller.yaml')
    assert result.passed, [c.detail for c in result.criteria]
    assert result.deterministic
    assert 5.0 < result.criteria[0].value < 6.0       # km/h, the first message above 5


def _process_scenario(tmp_path, command, extra=''):
    path = tmp_path / 'scenario.yaml'
    path.write_text(textwrap.dedent(f"""\
        world: {{vehicles: [{{name: Car}}]}}
        duration: 0.5
        driver:
          processes: ['{command}']
          clock_subscribers: 1
        {extra}
        criteria: [{{kind: no_collision}}]
        """), encoding='utf-8')
    return path


def test_runner_process_that_fails_is_the_runs_error(tmp_path):
    path = _process_scenario(tmp_path, 'python -c "import sys; print(42); sys.exit(3)"')
    result = run_scenario(path)
    assert not result.passed
    assert 'exited with status 3' in result.error
    assert '42' in result.error                        # its output is quoted


def test_runner_processes_that_do_not_come_up_time_out_and_are_stopped(tmp_path):
    path = _process_scenario(tmp_path, 'python -c "import time; time.sleep(60)"')
    text = path.read_text().replace('clock_subscribers: 1', 'clock_subscribers: 1\n'
                                    '  startup_timeout: 0.5')
    path.write_text(text)
    result = run_scenario(path)
    assert not result.passed
    assert '0 of 1 /clock subscriber(s)' in result.error


def test_runner_waits_for_the_sync_topics_publishers_before_time_starts(tmp_path):
    # The commander listens to /clock but never publishes the sync topic: time does not start
    # (an answer written before the runner matched its writer would be lost), and the start-up
    # timeout names the topic.
    result = run_scenario(_commander_scenario(
        tmp_path, '[{topic: /nobody/publishes, type: std_msgs/msg/String}]',
        'startup_timeout: 3.0'))
    assert not result.passed
    assert result.error.startswith('1 of 1 /clock subscriber(s), no publisher of '
                                   '/nobody/publishes after 3 s: the processes did not come up'
                                   ), result.error


def test_runner_odometry_stream_is_identical_across_processes(tmp_path):
    # Two separate processes (no shared interpreter or PyBullet state) give the same hash.
    import subprocess
    import sys
    digests = []
    for index in range(2):
        out = tmp_path / f'run{index}.xml'
        done = subprocess.run([sys.executable, '-m', 'vehicle_sim', 'scenario', str(STOP),
                               '--junit', str(out), '--no-progress', '--seed', '5'],
                              capture_output=True, text=True, timeout=120)
        assert done.returncode == 0, done.stdout + done.stderr
        suite = ElementTree.parse(out).getroot().find('testsuite')
        digests.append({p.get('name'): p.get('value')
                        for p in suite.find('properties')}['odometry_sha256'])
    assert digests[0] == digests[1]
    assert digests[0] == run_scenario(STOP, seed=5).odometry_sha256


def _shape(root):
    # tag -> attribute names, over every element of a JUnit tree.
    shape = {}
    for element in root.iter():
        shape.setdefault(element.tag, set()).update(element.attrib)
    return shape


def test_junit_uses_the_elements_and_attributes_pytest_junitxml_writes(blind_result, tmp_path):
    # The reference is what this pytest writes for one passing and one failing test.
    (tmp_path / 'test_ref.py').write_text('def test_ok():\n    pass\n\n\n'
                                          'def test_bad():\n    assert 1 == 2\n')
    reference = tmp_path / 'ref.xml'
    subprocess.run([sys.executable, '-m', 'pytest', '-q', '-p', 'no:cacheprovider',
                    f'--junitxml={reference}', str(tmp_path / 'test_ref.py')],
                   cwd=tmp_path, capture_output=True, timeout=120)
    pytest_shape = _shape(ElementTree.parse(reference).getroot())
    out = tmp_path / 'out.xml'
    write_junit(blind_result, out)
    ours = _shape(ElementTree.parse(out).getroot())
    for tag in ('testsuites', 'testsuite', 'testcase', 'failure'):
        assert tag in ours, tag
    # pytest 8 names the <testsuites> element; pytest 7 (Ubuntu 24.04's) does not.
    pytest_shape['testsuites'] = pytest_shape.get('testsuites', set()) | {'name'}
    for tag, attributes in ours.items():
        if tag in ('properties', 'property', 'system-out', 'system-err', 'error', 'skipped'):
            continue      # elements of pytest's format that a passing/failing pair does not show
        assert tag in pytest_shape, f"<{tag}> is not in pytest's --junitxml output"
        assert attributes <= pytest_shape[tag], (tag, attributes - pytest_shape[tag])
        assert pytest_shape[tag] <= attributes, (tag, pytest_shape[tag] - attributes)


def test_runner_sigterm_stops_its_processes_before_it_exits(tmp_path):
    # `timeout`, a CI cancel or a test harness SIGTERMs the runner: its processes (each in its
    # own session, so the signal does not reach them) are stopped before it exits with 143.
    import os
    import signal
    import time
    pid_file = tmp_path / 'child.pid'
    (tmp_path / 'child.py').write_text(
        'import os, time\n'
        f'open({str(pid_file)!r}, "w").write(str(os.getpid()))\n'
        'time.sleep(300)\n', encoding='utf-8')
    path = _process_scenario(tmp_path, 'python child.py')
    path.write_text(path.read_text().replace('clock_subscribers: 1', 'clock_subscribers: 1\n'
                                             '  startup_timeout: 300'))
    runner = subprocess.Popen([sys.executable, '-m', 'vehicle_sim', 'scenario', str(path),
                               '--no-progress'], stdout=subprocess.PIPE,
                              stderr=subprocess.STDOUT)
    try:
        deadline = time.monotonic() + 120
        while not (pid_file.exists() and pid_file.read_text()):
            assert runner.poll() is None, runner.communicate()[0]
            assert time.monotonic() < deadline, 'the child never started'
            time.sleep(0.05)
        child = int(pid_file.read_text())
        runner.send_signal(signal.SIGTERM)
        assert runner.wait(timeout=120) == 128 + signal.SIGTERM
    finally:
        if runner.poll() is None:
            runner.kill()
    deadline = time.monotonic() + 30
    while True:    # stopped by the runner, reaped by init once the runner is gone
        try:
            os.kill(child, 0)
        except ProcessLookupError:
            break
        if time.monotonic() > deadline:
            os.kill(child, signal.SIGKILL)
            raise AssertionError(f'the runner left its process {child} running')
        time.sleep(0.05)
