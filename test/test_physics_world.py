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

"""World: fixed step, explicit stepping, sub-steps, several worlds, determinism, lifecycle."""

import math
import os
import subprocess
import sys
import time

from conftest import peer_env
import pytest

from vehicle_sim.config import load_car
from vehicle_sim.core.car.vehicle_io import Actuation, WheelMode
from vehicle_sim.physics import CarBody, World


def _drive_script(world, car):
    """Drive a fixed command sequence for 3 s and return the base_link trajectory."""
    actuation = Actuation()
    trajectory = []
    for step in range(300):
        t = step * world.time_step_s
        actuation.steer_right_rad = actuation.steer_left_rad = 0.3 * math.sin(t)
        for index in (0, 1):
            actuation.wheel_mode[index] = WheelMode.VELOCITY
            actuation.wheel_velocity_radps[index] = 3.0 * t
        actuation.wheel_mode[2] = WheelMode.TORQUE
        actuation.wheel_torque_nm[2] = 50.0
        car.apply(actuation)
        world.step()
        trajectory.append(car.pose() + car.velocity()[0])
    return trajectory


def test_world_step_advances_time_by_the_basic_step():
    with World(time_step_s=0.016) as world:
        assert world.time_s == 0.0
        for _ in range(10):
            world.step()
        assert world.step_count == 10
        assert world.time_s == pytest.approx(0.16, abs=1e-12)


@pytest.mark.parametrize('kwargs', [{'time_step_s': 0.0}, {'time_step_s': -0.01},
                                    {'substeps': 0}, {'substeps': 1.5}, {'friction': 0.0}])
def test_world_invalid_arguments_raise(kwargs):
    with pytest.raises(ValueError):
        World(**kwargs)


def test_world_close_is_idempotent_and_stepping_after_close_raises():
    world = World()
    world.close()
    world.close()
    assert world.closed
    with pytest.raises(RuntimeError):
        world.step()


def test_world_calls_hooks_once_per_step_and_per_extra_substep():
    class Counter:
        def __init__(self):
            self.steps = 0
            self.substeps = 0

        def pre_step(self):
            self.steps += 1

        def pre_substep(self):
            self.substeps += 1

    with World(substeps=3) as world:
        counter = world.add_body(Counter())
        world.add_body(counter)                     # registering twice is harmless
        for _ in range(5):
            world.step()
        assert (counter.steps, counter.substeps) == (5, 10)
        world.remove(counter)
        world.step()
        assert counter.steps == 5


def test_every_read_of_the_world_between_steps_syncs_the_placed_bodies_first():
    # A placed body (traffic) moves only when put: rays, overlap checks and body states run
    # the before_query hooks first, which put it where it is now.
    import pybullet

    from vehicle_sim.core.world.params import ObstacleSpec
    from vehicle_sim.physics.sensors.rays import cast_rays

    class Placer:
        def __init__(self, world, body_id):
            self.world, self.body_id, self.calls, self.x = world, body_id, 0, 10.0

        def before_query(self):
            self.calls += 1
            pybullet.resetBasePositionAndOrientation(
                self.body_id, (self.x, 0.0, 0.5), (0.0, 0.0, 0.0, 1.0),
                physicsClientId=self.world.client_id)
            self.world.mark_moved()

    with World() as world:
        spec = ObstacleSpec('box', 'box', (10.0, 0.0, 0.5), 0.0, 0.0, 0.0, 0.0,
                            (1.0, 0.0, 0.0, 1.0), (1.0, 1.0, 1.0))
        body_id = world.add_obstacle(spec, placed=True)
        placer = world.add_body(Placer(world, body_id))
        world.step()
        placer.x = 20.0                    # where it is now; Bullet still has it at 10 m
        hit = cast_rays(world, (0.0, 0.0, 0.5), [(100.0, 0.0, 0.5)], -1)[0]
        assert placer.calls == 1 and hit * 100.0 == pytest.approx(19.5, abs=1e-6)
        placer.x = 30.0
        (position, _), *_ = world.body_state(body_id)
        assert placer.calls == 2 and position[0] == pytest.approx(30.0)
        world.overlaps(body_id)
        assert placer.calls == 3
        before = placer.calls
        for _ in range(20):                # nothing reads: the body is not put
            world.step()
        assert placer.calls == before


def test_world_same_inputs_give_the_same_trajectory_run_after_run():
    params = load_car('BmwX5')
    runs = []
    for _ in range(2):
        with World() as world:
            runs.append(_drive_script(world, CarBody(world, params)))
    assert runs[0] == runs[1]          # bit-identical
    assert runs[0][-1][0] > 2.0        # and the car did move


def test_world_two_worlds_in_one_process_are_independent_and_identical():
    params = load_car('Car')
    with World() as first, World() as second:
        assert first.client_id != second.client_id
        car_a, car_b = CarBody(first, params), CarBody(second, params)
        actuation = Actuation()
        actuation.wheel_mode[0] = actuation.wheel_mode[1] = WheelMode.VELOCITY
        actuation.wheel_velocity_radps[:2] = 10.0
        for _ in range(100):
            car_a.apply(actuation)
            first.step()
        assert second.time_s == 0.0
        assert car_b.pose()[0] == pytest.approx(0.0, abs=1e-3)
        for _ in range(100):
            car_b.apply(actuation)
            second.step()
        assert car_a.pose() == car_b.pose()


def test_world_torques_act_on_every_substep():
    # PyBullet clears applied torques after each internal sub-step; the world loops sub-steps
    # and the body re-applies them, so the speed gained does not depend on the sub-steps.
    params = load_car('TeslaModel3')
    speeds = []
    for substeps in (1, 4):
        with World(substeps=substeps) as world:
            car = CarBody(world, params)
            actuation = Actuation()
            for index in params.driven_wheels:
                actuation.wheel_mode[index] = WheelMode.TORQUE
                actuation.wheel_torque_nm[index] = 400.0
            car.apply(actuation)
            for _ in range(100):
                world.step()
            speeds.append(car.forward_speed_mps())
    assert speeds[0] > 0.5
    assert speeds[1] == pytest.approx(speeds[0], rel=0.02)


# Generous bound for an interpreter importing numpy and pybullet.
IMPORT_TIMEOUT_S = 120.0


@pytest.mark.parametrize('module', ['vehicle_sim.physics', 'vehicle_sim.physics.world'])
def test_importing_the_physics_prints_nothing_not_even_the_pybullet_banner(module):
    # Piped output is fully buffered in C: the banner would appear at exit if left in the buffer.
    code = f'import {module}; import sys; sys.stdout.write("after import\\n")'
    env = peer_env()
    env.pop('PYTHONUNBUFFERED')   # as a node started by ros2 run (C's stdout buffered)
    result = subprocess.run([sys.executable, '-c', code], env=env, capture_output=True,
                            text=True, timeout=IMPORT_TIMEOUT_S)
    assert result.returncode == 0, result.stderr
    assert (result.stdout, result.stderr) == ('after import\n', '')


def test_output_written_before_the_quiet_import_is_kept_and_in_order():
    code = ('import sys; sys.stdout.write("before\\n"); sys.stderr.write("err before\\n"); '
            'import vehicle_sim.physics; print("after")')
    result = subprocess.run([sys.executable, '-c', code], env=peer_env(), capture_output=True,
                            text=True, timeout=IMPORT_TIMEOUT_S)
    assert (result.stdout, result.stderr) == ('before\nafter\n', 'err before\n')


def test_quiet_import_drops_a_banner_left_in_the_c_stdout_buffer(tmp_path):
    # Builds of pybullet that printf the banner to stdout: piped, it waits in C's buffer.
    (tmp_path / 'noisy_extension.py').write_text(
        'import ctypes\nctypes.CDLL(None).printf(b"banner on C stdout\\n")\n')
    code = ('from vehicle_sim.physics._pybullet import import_quietly; '
            'import_quietly("noisy_extension"); print("after")')
    env = peer_env()
    env['PYTHONPATH'] = str(tmp_path) + os.pathsep + env['PYTHONPATH']
    env.pop('PYTHONUNBUFFERED')   # python -u makes C's stdout unbuffered too
    result = subprocess.run([sys.executable, '-c', code], env=env, capture_output=True,
                            text=True, timeout=IMPORT_TIMEOUT_S)
    assert (result.stdout, result.stderr) == ('after\n', '')


def test_quieting_pybullet_stdout_waits_only_for_an_awaited_notice(monkeypatch):
    # A DIRECT world silences one printf notice: drain what is there, never wait for more (a
    # settle wait on every World cost 0.2 s each); only the GUI waits for its window's notices.
    from vehicle_sim.physics import pybullet_stdout
    timeouts = []
    real_select = pybullet_stdout.select.select

    def spy(read, write, error, timeout):
        timeouts.append(timeout)
        return real_select(read, write, error, timeout)

    monkeypatch.setattr(pybullet_stdout.select, 'select', spy)
    with pybullet_stdout.quiet_stdout():
        pass
    assert timeouts and set(timeouts) == {0.0}


# Generous bound on the quieting's wait for the notices: one that waits it out missed them.
NOTICE_WAIT_S = 60.0


def _printf_later(parts):
    # Another thread printing with the C library's printf, as PyBullet's window thread does:
    # ``parts`` are (delay [s], bytes), printed in turn.
    import ctypes
    import threading
    libc = ctypes.CDLL(None)

    def run():
        for delay_s, text in parts:
            time.sleep(delay_s)
            libc.printf(b'%s', text)
    thread = threading.Thread(target=run)
    thread.start()
    return thread, libc


def test_quieting_waits_for_every_awaited_notice_and_keeps_them_all_out(capfd):
    # PyBullet's X11 window prints 'ven = <vendor>' twice (two render targets), the second
    # some 0.1-0.5 s after connect returns: stdout stays silenced until both came, even though
    # the C library holds the second in its buffer (stdout is not a terminal here).
    from vehicle_sim.physics import pybullet_stdout
    start = time.monotonic()
    with pybullet_stdout.quiet_stdout(settle_on=b'ven = ', settle_count=2,
                                      max_wait_s=NOTICE_WAIT_S):
        thread, libc = _printf_later([(0.05, b'ven = First\n'), (0.4, b'ven = Second\n')])
    waited_s = time.monotonic() - start
    thread.join()
    libc.fflush(None)
    out = capfd.readouterr().out
    assert 'ven = ' not in out
    assert 0.4 < waited_s < NOTICE_WAIT_S   # until the second came and 0.2 s of quiet


def test_quieting_sees_a_notice_split_over_two_reads(capfd):
    import ctypes

    from vehicle_sim.physics import pybullet_stdout
    libc = ctypes.CDLL(None)
    start = time.monotonic()
    with pybullet_stdout.quiet_stdout(settle_on=b'ven = ', max_wait_s=NOTICE_WAIT_S):
        libc.printf(b'%s', b'noise ve')
        libc.fflush(None)
        thread, _ = _printf_later([(0.2, b'n = Split\n')])
    thread.join()
    assert time.monotonic() - start < NOTICE_WAIT_S     # seen, not waited out
    libc.fflush(None)
    assert 'ven = ' not in capfd.readouterr().out


def test_contact_points_are_read_once_per_body_while_the_post_step_hooks_run(monkeypatch):
    # A collision monitor and the traffic's contact check both ask for our car's contacts
    # after each step: one getContactPoints read serves both, until a hook moves a body.
    import pybullet

    reads = []
    real = pybullet.getContactPoints

    def counted(*args, **kwargs):
        reads.append(args[0] if args else kwargs.get('bodyA'))    # (bodyA, by position or not)
        return real(*args, **kwargs)

    class Reader:
        def __init__(self, world, body_id, moves=False):
            self.world, self.body_id, self.moves, self.seen = world, body_id, moves, []

        def post_step(self):
            self.seen.append(self.world.contact_points(self.body_id))
            if self.moves:
                self.world.mark_moved()

    with World() as world:
        car = CarBody(world, load_car('Car'))
        for _ in range(50):                 # settled on its wheels: four points on the ground
            world.step()
        first = world.add_body(Reader(world, car.body_id))
        second = world.add_body(Reader(world, car.body_id))
        monkeypatch.setattr(pybullet, 'getContactPoints', counted)
        world.step()
        assert reads == [car.body_id]
        assert second.seen[-1] is first.seen[-1]
        assert len(first.seen[-1]) == 4 and {p[2] for p in first.seen[-1]} == {world.ground_id}
        first.moves = True                  # a hook moved a body: the next one reads again
        world.step()
        assert reads == [car.body_id] * 3 and second.seen[-1] == first.seen[-1]
        world.remove(first)
        world.remove(second)
        assert world.contact_points(car.body_id) == real(bodyA=car.body_id,
                                                         physicsClientId=world.client_id)
        world.contact_points(car.body_id)   # between steps: every call reads
        assert reads == [car.body_id] * 5
