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
PyBullet's window without a display, and the chase camera's logic in a DIRECT world.

The window itself is tested under Xvfb in test_physics_gui_xvfb.py.
"""

import math
import sys

import pytest

from vehicle_sim.config import load_car, load_world
from vehicle_sim.core.geometry.chase_camera import eye_position
from vehicle_sim.core.specs.errors import InvalidPoseError
from vehicle_sim.physics import SimulatedCar, World
from vehicle_sim.physics._pybullet import pybullet
from vehicle_sim.physics.gui import (
    ChaseCamera,
    FRAME_PERIOD_S,
    gui_unavailable_reason,
    GuiUnavailableError,
    KEY_CLOSER,
    KEY_FARTHER,
    KEY_FOLLOW,
    KEY_NEXT,
)
from vehicle_sim.physics.scene import build_scene

linux_only = pytest.mark.skipif(not sys.platform.startswith('linux'),
                                reason='the X display check applies on Linux only')


def press(camera, key):
    camera.handle_keys({ord(key): pybullet.KEY_WAS_TRIGGERED | pybullet.KEY_IS_DOWN})


def com_of(world, car):
    return pybullet.getBasePositionAndOrientation(car.body.body_id,
                                                  physicsClientId=world.client_id)[0]


@linux_only
def test_no_display_is_reported_with_the_way_out():
    reason = gui_unavailable_reason({})
    assert reason.startswith('DISPLAY is not set')
    assert 'xvfb-run' in reason


@linux_only
def test_a_display_without_server_is_reported():
    reason = gui_unavailable_reason({'DISPLAY': ':917'})
    assert reason is not None and 'xvfb-run' in reason
    assert ':917' in reason or 'libX11' in reason


@linux_only
def test_gui_world_without_display_raises_instead_of_ending_the_process(monkeypatch):
    # PyBullet's own GUI connect calls exit(1) when no X server answers; World checks first.
    monkeypatch.delenv('DISPLAY', raising=False)
    with pytest.raises(GuiUnavailableError, match='DISPLAY is not set'):
        World(gui=True)


@pytest.fixture
def two_cars():
    world = World()
    first = SimulatedCar(world, load_car('Car'), (0.0, 0.0, 0.0))
    second = SimulatedCar(world, load_car('Car'), (0.0, 20.0, math.pi / 2))
    yield world, first, second
    world.close()



def test_a_gui_world_holds_an_x_connection_until_pybullet_has_its_own(monkeypatch):
    # An X server started without -noreset (Xvfb under xvfb-run) resets when its last client
    # leaves; PyBullet, connecting during that reset, ended the process ('cannot connect to X
    # server'; seen under load after the availability probe had closed its connection).
    from contextlib import contextmanager

    from vehicle_sim.physics import gui
    held = []
    seen = []

    @contextmanager
    def fake_display(display):
        held.append(display)
        try:
            yield None, None, None
        finally:
            held.pop()

    class Connected(Exception):
        pass

    def fake_connect(*args, **kwargs):
        seen.append(list(held))
        raise Connected

    monkeypatch.setenv('DISPLAY', ':99')
    monkeypatch.setattr(gui, '_x_display', fake_display)
    monkeypatch.setattr(gui, 'screen_size', lambda environ=None: None)
    monkeypatch.setattr(pybullet, 'connect', fake_connect)
    with pytest.raises(Connected):
        World(gui=True)
    assert seen == [[':99']]
    assert held == []

def test_chase_camera_follows_the_first_vehicle_from_behind(two_cars):
    world, first, second = two_cars
    camera = ChaseCamera(world, [first, second], period_s=0.0)
    first.logic.set_cruising_speed_kmh(30.0)
    for _ in range(200):
        world.step()
    x, y = first.body.pose()[:2]
    assert x > 2.0
    view = camera.view
    # Target 1 m above the car's centre of mass (PyBullet's base position).
    com = com_of(world, first)
    assert view.target_m == pytest.approx((com[0], com[1], com[2] + 1.0), abs=1e-9)
    assert com[0] > x and view.target_m[1] == pytest.approx(y, abs=0.1)
    eye = eye_position(view)
    assert eye[0] < x and eye[2] > view.target_m[2]           # behind and above
    assert view.yaw_deg == pytest.approx(-90.0, abs=1.0)      # heading 0 -> yaw -90 deg


def test_camera_moves_once_per_period(two_cars):
    world, first, _ = two_cars
    camera = ChaseCamera(world, [first])        # 0.03 s: every third 10 ms step
    first.logic.set_cruising_speed_kmh(30.0)
    views = []
    for _ in range(12):
        world.step()
        views.append(camera.view)
    changed = [index + 1 for index in range(1, 12) if views[index] is not views[index - 1]]
    assert changed == [3, 6, 9, 12]
    with pytest.raises(ValueError, match='period_s'):
        ChaseCamera(world, [first], period_s=-1.0)


def test_keys_toggle_follow_cycle_vehicles_and_zoom(two_cars):
    world, first, second = two_cars
    camera = ChaseCamera(world, [first, second])
    press(camera, KEY_CLOSER)
    assert camera.view.distance_m == pytest.approx(8.0 / 1.25)
    press(camera, KEY_FARTHER)
    press(camera, KEY_FARTHER)
    assert camera.view.distance_m == pytest.approx(8.0 * 1.25)
    press(camera, KEY_NEXT)
    assert camera.target_id == second.body.body_id
    com = com_of(world, second)
    assert camera.view.target_m == pytest.approx((com[0], com[1], com[2] + 1.0), abs=1e-9)
    assert camera.view.yaw_deg == pytest.approx(0.0, abs=1.0)   # heading 90 deg, snapped
    press(camera, KEY_FOLLOW)
    assert not camera.following
    view = camera.view
    second.logic.set_cruising_speed_kmh(30.0)
    for _ in range(100):
        world.step()
    assert camera.view is view                                  # the mouse has the camera
    press(camera, KEY_FOLLOW)
    assert camera.following and camera.view.target_m[1] > view.target_m[1] + 0.5
    press(camera, KEY_NEXT)
    assert camera.target_id == first.body.body_id


def test_a_key_released_without_a_new_press_does_nothing(two_cars):
    world, first, _ = two_cars
    camera = ChaseCamera(world, [first])
    camera.handle_keys({ord(KEY_CLOSER): pybullet.KEY_WAS_RELEASED,
                        ord(KEY_FOLLOW): pybullet.KEY_IS_DOWN})
    assert camera.following and camera.view.distance_m == pytest.approx(8.0)


def test_chase_camera_needs_a_target(two_cars):
    with pytest.raises(ValueError, match='at least one target'):
        ChaseCamera(two_cars[0], [])


# ----------------------------------------------------------------------- building, drawing

def _gui_flagged_world():
    # A DIRECT world that takes itself for a GUI one: what the scene builder and the traffic
    # decide from ``world.gui`` runs, and nothing is drawn (rendering switches are no-ops).
    world = World()
    world.gui = True
    return world


def _spy(monkeypatch, calls, name, label):
    real = getattr(pybullet, name)

    def spy(*args, **kwargs):
        calls.append(label(*args))
        return real(*args, **kwargs)
    monkeypatch.setattr(pybullet, name, spy)


def test_a_gui_scene_is_built_with_rendering_off_then_on_again(monkeypatch):
    world = _gui_flagged_world()
    calls = []
    _spy(monkeypatch, calls, 'configureDebugVisualizer',
         lambda flag, enable, *rest: ('rendering', enable)
         if flag == pybullet.COV_ENABLE_RENDERING else ('other', flag))
    _spy(monkeypatch, calls, 'createMultiBody', lambda *args: 'body')
    try:
        build_scene(load_world('highway_traffic', 'ToyotaPrius'), world=world)
    finally:
        world.close()
    bodies = [i for i, call in enumerate(calls) if call == 'body']
    switches = [(i, call[1]) for i, call in enumerate(calls) if call[0] == 'rendering']
    assert len(bodies) > 50                     # roads, car, 50 traffic boxes
    assert [enable for _, enable in switches] == [0, 1]
    assert switches[0][0] < bodies[0] and bodies[-1] < switches[1][0]


def test_a_refused_gui_scene_turns_rendering_on_again_and_a_direct_one_never_switches(
        monkeypatch, tmp_path):
    calls = []
    _spy(monkeypatch, calls, 'configureDebugVisualizer',
         lambda flag, enable, *rest: ('rendering', enable)
         if flag == pybullet.COV_ENABLE_RENDERING else ('other', flag))
    world = _gui_flagged_world()
    inside = tmp_path / 'inside.yaml'
    inside.write_text('vehicles:\n  - {name: Car}\nobstacles:\n  - {name: crate, shape: box, '
                      'size: [2, 2, 2], position: [1.5, 0, 1]}\n', encoding='utf-8')
    try:
        with pytest.raises(InvalidPoseError):
            build_scene(load_world(str(inside), 'Car'), world=world)
    finally:
        world.close()
    assert calls == [('rendering', 0), ('rendering', 1)]
    calls.clear()
    build_scene(load_world('highway', 'ToyotaPrius')).world.close()
    assert calls == []


def test_traffic_boxes_are_placed_for_the_window_once_a_frame_not_every_step(monkeypatch):
    world = _gui_flagged_world()
    try:
        traffic = build_scene(load_world('highway_traffic', 'ToyotaPrius'),
                              world=world).parts['traffic']
        everyone = list(range(len(traffic.body_ids)))
        placed_at = []
        real_move = traffic._move

        def move(indices, standing=()):
            if list(indices) == everyone:           # every box: for the window (or a query)
                placed_at.append(world.time_s)
            real_move(indices, standing)
        monkeypatch.setattr(traffic, '_move', move)
        for _ in range(60):                      # 0.6 s, no sensor or other query
            world.step()
    finally:
        world.close()
    gaps = [b - a for a, b in zip(placed_at, placed_at[1:])]
    assert len(placed_at) >= 10 and min(gaps) >= FRAME_PERIOD_S - 1e-9, placed_at
