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
The nodes' ``gui`` parameter: a clear refusal without a display, a window under Xvfb.

The Xvfb run needs ``xvfb-run`` (Debian/Ubuntu package ``xvfb``) and is skipped with the
reason printed where it is missing.
"""

import json
import math
import os
import shutil
import subprocess
import sys

from conftest import peer_env
import pytest
from xvfb_helpers import require_xvfb, xvfb_run

from vehicle_sim.physics.gui import GuiUnavailableError

linux_only = pytest.mark.skipif(not sys.platform.startswith('linux'),
                                reason='the X display check applies on Linux only')
RUN_TIMEOUT_S = 180
REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


@linux_only
def test_automobile_node_with_gui_and_no_display_is_refused_at_start(monkeypatch):
    from vehicle_sim.ros.automobile_node import AutomobileNode
    monkeypatch.delenv('DISPLAY', raising=False)
    with pytest.raises(GuiUnavailableError, match='DISPLAY is not set.*xvfb-run'):
        AutomobileNode(['x', '--ros-args', '-r', '__ns:=/gui_refused', '-p', 'gui:=true',
                        '-p', 'synchronous:=true'], transport='dds')


@linux_only
def test_diff_robot_node_with_gui_and_no_display_is_refused_at_start(monkeypatch):
    from vehicle_sim.ros.diff_robot_node import DiffRobotNode
    monkeypatch.delenv('DISPLAY', raising=False)
    with pytest.raises(GuiUnavailableError, match='DISPLAY is not set'):
        DiffRobotNode(['x', '--ros-args', '-p', 'gui:=true', '-p', 'synchronous:=true'],
                      transport='dds', namespace='/gui_refused')


@linux_only
def test_automobile_node_main_without_display_exits_2_with_the_reason():
    env = peer_env()
    env.pop('DISPLAY', None)
    result = subprocess.run(
        [sys.executable, '-m', 'vehicle_sim.ros.automobile_node', '--ros-args', '-r',
         '__ns:=/gui_refused_main', '-p', 'gui:=true'], env=env, capture_output=True, text=True,
        timeout=RUN_TIMEOUT_S)
    assert result.returncode == 2, result.stderr
    assert 'automobile: DISPLAY is not set' in result.stderr


def test_run_gui_under_xvfb_opens_the_window_and_steps(tmp_path):
    require_xvfb()
    result = xvfb_run([sys.executable, '-m', 'vehicle_sim', 'run', '--gui', '--duration', '4',
                       '--', '--ros-args', '-r', '__ns:=/gui_run'], RUN_TIMEOUT_S, tmp_path)
    assert result.returncode == 0, result.stderr[-3000:]
    assert "PyBullet window open; keys: 'f' chase camera on/off" in result.stderr
    times = [float(line.split()[1]) for line in result.stdout.splitlines()
             if line.startswith('t ')]
    assert times and times[-1] > 0.0, result.stdout[-3000:]   # the world steps
    # Only our status lines: none of PyBullet's OpenGL and thread notices ('ven = Mesa/X.org',
    # 'destroy semaphore', ...), which it prints with printf.
    assert [line for line in result.stdout.splitlines() if not line.startswith('t ')] == []


def _require_tool(name, why, package):
    require_xvfb()
    if shutil.which(name) is None:
        pytest.skip(f'{name} not found: {why} (Debian/Ubuntu: apt-get install {package})')


def _once_ready(namespace, log, then):
    # `vehicle-sim run --gui` in the background, then the shell commands `then` once it is ready
    # ($node is its pid; a window closed during start-up is refused differently).
    return (f'"{sys.executable}" -m vehicle_sim run --gui --no-status -- --ros-args '
            f'-r __ns:={namespace} 2> {log} & node=$!; '
            f'for i in $(seq 600); do grep -q "automobile ready" {log} && break; sleep 0.2; '
            f'done; {then}')


def test_run_gui_window_fits_a_1280_by_720_screen(tmp_path):
    _require_tool('xwininfo', 'the window size cannot be read', 'x11-utils')
    log = tmp_path / 'node.log'
    script = _once_ready('/gui_fit', log, 'xwininfo -root -tree | grep "Bullet Physics"; '
                                          'kill -INT $node; wait $node')
    result = xvfb_run(['sh', '-c', script], RUN_TIMEOUT_S, tmp_path,
                      screen='-screen 0 1280x720x24 -nolisten tcp')
    assert result.returncode == 0, result.stderr[-3000:]
    # e.g. '0x200002 "Bullet Physics ExampleBrowser ...": ()  1024x620+0+0  +0+0'
    size = [word for word in result.stdout.split() if 'x' in word and '+' in word][0]
    width, height = (int(part) for part in size.split('+')[0].split('x'))
    assert (width, height) == (1024, 720 - 100)     # PyBullet's width; the height fits


def test_a_closed_window_shuts_the_node_down_instead_of_raising(monkeypatch):
    # The window's Esc (or close button) disconnects PyBullet: World.step raises GuiClosedError;
    # the node logs it, asks its spin to end, and steps no more.
    from vehicle_sim.physics.gui import GuiClosedError
    from vehicle_sim.ros.automobile_node import AutomobileNode
    app = AutomobileNode(['x', '--ros-args', '-r', '__ns:=/gui_closed', '-p',
                          'synchronous:=true'], transport='dds')
    try:
        calls = []

        def closed():
            calls.append('step')
            raise GuiClosedError('the PyBullet window was closed')

        monkeypatch.setattr(app.world, 'step', closed)
        monkeypatch.setattr(type(app.world), 'gui_closed', property(lambda world: True))
        monkeypatch.setattr(app.node, 'request_shutdown', lambda: calls.append('shutdown'))
        assert app.step_once() == 0.0
        assert app.step_once() == 0.0
        assert calls == ['step', 'shutdown']
    finally:
        monkeypatch.undo()
        app.close()


def test_an_error_with_the_window_still_open_is_raised(monkeypatch):
    from vehicle_sim.ros.automobile_node import AutomobileNode
    app = AutomobileNode(['x', '--ros-args', '-r', '__ns:=/gui_other_error', '-p',
                          'synchronous:=true'], transport='dds')
    try:
        def broken():
            raise RuntimeError('something else')

        monkeypatch.setattr(app.world, 'step', broken)
        with pytest.raises(RuntimeError, match='something else'):
            app.step_once()
    finally:
        monkeypatch.undo()
        app.close()


def test_escape_in_the_window_ends_vehicle_sim_run_with_status_0(tmp_path):
    _require_tool('xdotool', 'no key can be sent to the window', 'xdotool')
    log = tmp_path / 'node.log'
    script = _once_ready('/gui_escape', log,
                         'xdotool search --sync --name "Bullet Physics" windowfocus --sync; '
                         f'xdotool key Escape; wait $node; status=$?; cat {log} >&2; '
                         'exit $status')
    result = xvfb_run(['sh', '-c', script], RUN_TIMEOUT_S, tmp_path)
    assert result.returncode == 0, result.stderr[-3000:]
    assert 'the PyBullet window was closed: shutting down' in result.stderr


_SCENARIO_CAMERA_PROBE = """
import json, sys
import pybullet
from vehicle_sim.scenarios.runner import run_scenario
from vehicle_sim.scenarios.sim import LocalSim

seen = {}
original_close = LocalSim.close


def close(self):
    # Just before the window goes: where the camera looks and where the car is.
    camera = pybullet.getDebugVisualizerCamera(physicsClientId=self.world.client_id)
    car = next(iter(self.vehicles.values())).car
    seen['target'] = list(camera[11])
    seen['car'] = list(pybullet.getBasePositionAndOrientation(  # its centre of mass
        car.body.body_id, physicsClientId=self.world.client_id)[0])
    original_close(self)


LocalSim.close = close
result = run_scenario(sys.argv[1], gui=True)
print(json.dumps({'passed': result.passed, **seen}))
"""


def test_scenario_gui_under_xvfb_follows_the_vehicle_under_test(tmp_path):
    require_xvfb()
    result = xvfb_run([sys.executable, '-c', _SCENARIO_CAMERA_PROBE,
                       os.path.join(REPO_ROOT, 'scenarios', 'stop_before_obstacle.yaml')],
                      RUN_TIMEOUT_S, tmp_path)
    assert result.returncode == 0, result.stdout + result.stderr
    seen = json.loads(result.stdout.strip().splitlines()[-1])
    assert seen['passed']
    # The car drove ~10 m; the camera looks at its centre of mass (from above), not at the start.
    assert seen['car'][0] > 5.0
    assert math.hypot(seen['target'][0] - seen['car'][0],
                      seen['target'][1] - seen['car'][1]) < 0.5
