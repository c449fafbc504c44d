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
Traffic lights in the physics world: the camera sees the lamps in the state of their group.

The world: lane_helpers.signal_crossing (lane 1 runs east to a crossing; its stop line at x = -2
is governed by group 11, whose light stands at the kerb south of the lane at (0, -2.6): red at
3.0 m, yellow at 2.6 m, green at 2.2 m, facing the traffic (west); group 12 governs lane 3). The
car stands on lane 1 at x = -10, looking east with a camera 1.5 m ahead of it.
"""

from dataclasses import replace
import math

from lane_helpers import BULB_Z, LIGHT_XY, signal_crossing, StandInSignals
import numpy as np
import pybullet
import pytest

from vehicle_sim.config import read_yaml, world_from_data, world_path
from vehicle_sim.core.map.signal_lamps import DARK_LAMP_COLOR, HOUSING_DEPTH_M, LAMP_COLORS
from vehicle_sim.core.map.signal_plan import FixedTimePlan, SignalController
from vehicle_sim.core.sensors.labels import LABEL_IDS
from vehicle_sim.physics import World
from vehicle_sim.physics.scene import build_scene, mount_suite
from vehicle_sim.physics.signal_lamps import LAMPS_BODY_NAME, SignalLamps, SignalLampsPart

CAR_X = -10.0
CAMERA = {'type': 'camera', 'name': 'camera', 'pose': {'x': 1.5, 'y': 0.0, 'z': 1.3},
          'width': 320, 'height': 240, 'fov': 1.1, 'rate_hz': 5.0}


def crossing_spec(sensors=(CAMERA,), x=CAR_X, y=0.0):
    spec = world_from_data({'vehicles': [{'name': 'car', 'model': 'Car', 'sensors': list(sensors),
                                          'pose': {'x': x, 'y': y, 'yaw': 0.0}}]}, 'lamps.yaml')
    return replace(spec, lanes=signal_crossing(areas=False))


@pytest.fixture
def scene():
    built = []

    def make(parts=(StandInSignals(), SignalLampsPart()), **kwargs):
        built.append(build_scene(crossing_spec(**kwargs), mount=mount_suite, parts=parts))
        return built[-1]
    yield make
    for one in built:
        one.world.close()


def _pixel(scene, bulb_z, offset_m=0.0):
    """Return the (row, column) where the camera sees the front of a bulb of the light."""
    frame = scene.vehicles['car'].sensors.sample('camera')
    fx, cx, fy, cy = frame.k[0], frame.k[2], frame.k[4], frame.k[5]
    base = scene.vehicles['car'].body.pose()
    camera = (base[0] + 1.5, base[1], base[2] + 1.3)
    depth = LIGHT_XY[0] - camera[0]
    u = cx + fx * -(LIGHT_XY[1] + offset_m - camera[1]) / depth
    v = cy + fy * -(bulb_z - camera[2]) / depth
    return frame.rgb, int(round(v)), int(round(u))


def _lamp_rgb(scene, color):
    """Return the mean colour [0, 1] of the 3 x 3 pixels at the middle of a bulb of group 11."""
    rgb, row, col = _pixel(scene, BULB_Z[color])
    return rgb[row - 1:row + 2, col - 1:col + 2].reshape(-1, 3).mean(axis=0) / 255.0


def _is_lit(rgb, color):
    """Lit: the chromaticity of the lamp's colour (shaded: 30 .. 100 % brightness)."""
    want = np.array(LAMP_COLORS[color][:3])
    scale = rgb.sum() / want.sum()
    return scale > 0.3 and np.abs(rgb - scale * want).max() < 0.08


def _is_dark(rgb):
    """Dark: grey (equal channels), no brighter than the dark lamp's grey."""
    return np.ptp(rgb) < 0.04 and rgb.max() <= DARK_LAMP_COLOR[0] + 0.02


def test_the_camera_sees_the_red_lamp_lit_when_the_group_is_forced_red_then_green(scene):
    world = scene()
    controller = world.parts['signals'].controller
    controller.force(11, 'red')
    lamps = {color: _lamp_rgb(world, color) for color in BULB_Z}
    assert _is_lit(lamps['red'], 'red'), lamps
    assert _is_dark(lamps['yellow']) and _is_dark(lamps['green']), lamps
    controller.force(11, 'green')       # no step: the camera shows the state published now
    lamps = {color: _lamp_rgb(world, color) for color in BULB_Z}
    assert _is_lit(lamps['green'], 'green'), lamps
    assert _is_dark(lamps['red']) and _is_dark(lamps['yellow']), lamps
    controller.force(11, 'off')
    assert all(_is_dark(_lamp_rgb(world, color)) for color in BULB_Z)


def test_the_lamps_follow_the_plan_and_change_colour_only_when_a_state_changes(scene):
    world = scene()
    lamps, controller = world.parts['signal_lamps'], world.parts['signals'].controller
    assert lamps.shown == controller.states() == {11: 'green', 12: 'red'}
    changes = lamps.changes
    for _ in range(150):                # 1.5 s: both groups hold their state
        world.world.step()
        world.world.sync_bodies()
    assert lamps.changes == changes
    seen = []
    for _ in range(700):                # 7 s: green 2 s, yellow 1 s, all red 1 s, then group 12
        world.world.step()
        world.world.sync_bodies()       # what any reader of the world does first (a camera)
        if lamps.shown != (seen[-1] if seen else None):
            seen.append(dict(lamps.shown))
        assert lamps.shown == controller.states()
    assert [s[11] for s in seen][:3] == ['green', 'yellow', 'red']
    assert {'green'} == {s[12] for s in seen} - {'red', 'yellow'}
    # three bulbs per group, two of them change colour per state change (one goes dark, one on)
    transitions = sum(1 for a, b in zip(seen, seen[1:]) for g in (11, 12) if a[g] != b[g])
    assert lamps.changes - changes == 3 * transitions


def test_with_a_gui_window_the_lamps_follow_each_step_without_a_reader():
    graph = signal_crossing(areas=False)
    controller = SignalController(graph, FixedTimePlan(green_s=2.0, yellow_s=1.0,
                                                       all_red_s=1.0))
    for gui in (False, True):
        with World() as world:
            world.gui = gui                 # as a window's world (no window needed here)
            lamps = SignalLamps(world, graph, controller)
            controller.force(11, 'red')
            world.step()
            assert lamps.shown[11] == ('red' if gui else 'green')
            world.sync_bodies()
            assert lamps.shown[11] == 'red'
            controller.release()


def test_the_pole_is_solid_and_named_the_housings_and_lamps_are_not(scene):
    world = scene(sensors=())
    lamps = world.parts['signal_lamps']
    # a pole per light, the housings one mesh; a lamp per bulb once the world is drawn
    assert len(lamps.lamp_ids) == 0 and len(lamps.pole_ids) == 2 and len(lamps.housing_ids) == 1
    world.world.prepare_render()
    assert len(lamps.lamp_ids) == 6 and lamps.visual_shape_count == 9
    cid = world.world.client_id
    pole = lamps.poles[0]
    assert (pole.x_m, pole.y_m) == pytest.approx(
        (LIGHT_XY[0] + HOUSING_DEPTH_M + 0.075, LIGHT_XY[1]))
    hit = pybullet.rayTest((pole.x_m - 5.0, pole.y_m, 1.0), (pole.x_m + 5.0, pole.y_m, 1.0),
                           physicsClientId=cid)[0]
    assert world.world.body_name(hit[0]) == LAMPS_BODY_NAME
    assert hit[3][0] == pytest.approx(pole.x_m - 0.075, abs=1e-3)
    car = world.vehicles['car'].body.body_id
    for body_id in lamps.lamp_ids + lamps.housing_ids:    # nothing to be near: no shape
        assert pybullet.getClosestPoints(body_id, car, 100.0, physicsClientId=cid) == ()
    assert pybullet.getClosestPoints(lamps.pole_ids[0], car, 100.0, physicsClientId=cid) != ()
    # the lamps face the traffic of lane 1 (west), the pole stands behind them
    assert {round(lamp.yaw_rad, 6) for lamp in lamps.lamps if lamp.group_id == 11} == {
        round(math.pi, 6)}


def lamp_rgba(world, body_id):
    """Return the colour a lamp body is drawn in (PyBullet's visual shape data)."""
    (shape,) = pybullet.getVisualShapeData(body_id, physicsClientId=world.client_id)
    return tuple(round(c, 6) for c in shape[7])


def test_the_lamps_are_made_when_the_world_is_first_drawn_in_the_states_of_then(scene):
    # A world nothing draws has no lamp body (Bullet's step walks over every body it has); the
    # first image makes them, lit as the groups are then, each labelled as its group's light.
    world = scene()
    lamps, controller = world.parts['signal_lamps'], world.parts['signals'].controller
    bodies = pybullet.getNumBodies(physicsClientId=world.world.client_id)
    for _ in range(250):                # 2.5 s: group 11 goes from green to yellow
        world.world.step()
        world.world.sync_bodies()       # rays and overlap checks read the world: no lamps made
    assert lamps.lamp_ids == () and lamps.shown == controller.states() == {11: 'yellow',
                                                                           12: 'red'}
    assert pybullet.getNumBodies(physicsClientId=world.world.client_id) == bodies
    assert _is_lit(_lamp_rgb(world, 'yellow'), 'yellow')      # a camera image makes them
    assert _is_dark(_lamp_rgb(world, 'green')) and _is_dark(_lamp_rgb(world, 'red'))
    assert len(lamps.lamp_ids) == 6
    assert pybullet.getNumBodies(physicsClientId=world.world.client_id) == bodies + 6
    drawn = {(lamp.group_id, lamp.bulb.color): lamp_rgba(world.world, body)
             for lamp, body in zip(lamps.lamps, lamps.lamp_ids)}
    assert drawn == {(group, color): tuple(round(c, 6) for c in (
        LAMP_COLORS[color] if color == state else DARK_LAMP_COLOR))
        for group, state in controller.states().items() for color in BULB_Z}
    labels = world.world.labels
    instances = {lamp.group_id: labels.instance(f'traffic_light_{lamp.group_id}')
                 for lamp in lamps.lamps}
    assert [labels.of(body) for body in lamps.lamp_ids] == [
        (LABEL_IDS['traffic_light'], instances[lamp.group_id]) for lamp in lamps.lamps]
    ids = lamps.lamp_ids
    world.world.prepare_render()        # made once
    assert lamps.lamp_ids == ids


def test_a_car_pushed_into_a_pole_touches_it_and_is_stopped(scene):
    # The car 4 m west of the pole, pushed east at 5 m/s: it hits the pole and stays west of it.
    pole_x = LIGHT_XY[0] + HOUSING_DEPTH_M + 0.075
    world = scene(sensors=(), x=pole_x - 6.0, y=LIGHT_XY[1])
    lamps, cid = world.parts['signal_lamps'], world.world.client_id
    car = world.vehicles['car'].body.body_id
    pybullet.resetBaseVelocity(car, (5.0, 0.0, 0.0), physicsClientId=cid)
    touched = False
    for _ in range(300):
        world.world.step()
        touched = touched or bool(pybullet.getContactPoints(car, lamps.pole_ids[0],
                                                            physicsClientId=cid))
    assert touched
    assert world.vehicles['car'].body.pose()[0] < pole_x


def test_a_vehicle_that_starts_inside_a_pole_is_refused_naming_it(scene):
    pole_x = LIGHT_XY[0] + HOUSING_DEPTH_M + 0.075
    with pytest.raises(Exception, match=LAMPS_BODY_NAME):
        scene(sensors=(), x=pole_x - 2.0, y=LIGHT_XY[1])


class NoSignals:
    """A 'signals' part that builds nothing: the world has no SignalController."""

    name = 'signals'

    def build(self, world, spec):
        return None


def test_without_a_signal_controller_every_lamp_is_dark(scene):
    world = scene(parts=(NoSignals(),), sensors=(CAMERA,))
    lamps = world.parts['signal_lamps']
    assert all(_is_dark(_lamp_rgb(world, color)) for color in BULB_Z)
    assert lamps.controller is None and lamps.changes == 0
    with World() as alone:              # no controller, no parts: drawn dark, never recoloured
        lamps = SignalLamps(alone, signal_crossing())
        assert lamps.lamp_ids == () and lamps.refresh() == 0
        alone.prepare_render()
        assert len(lamps.lamp_ids) == 6 and lamps.changes == 0
        assert {lamp_rgba(alone, body) for body in lamps.lamp_ids} == {DARK_LAMP_COLOR}


def test_the_lamps_row_shows_the_world_signals_part_or_a_callers_own(scene):
    world = scene(parts=())             # the rows: signals, then the lamps
    assert world.parts['signal_lamps'].controller is world.parts['signals'].controller
    world = scene(parts=(StandInSignals(),))    # built after the lamps row: found when looked
    controller = world.parts['signals'].controller
    controller.force(11, 'red')
    assert _is_lit(_lamp_rgb(world, 'red'), 'red')
    assert world.parts['signal_lamps'].controller is controller


# ------------------------------------------------------------------------------ the shipped world

def test_in_city_block_signals_the_camera_shows_each_state_the_controller_publishes():
    # The car waits 20 m before the ring's southern intersection, looking east with a narrow
    # camera; over one 100 s cycle of the plan, at every change of the state of the group
    # governing its lane, the image shows that state's bulb lit and the others dark.
    data = read_yaml(world_path('city_block_signals'))
    data.pop('traffic')
    camera = dict(CAMERA, fov=0.5)
    data['vehicles'] = [{'name': 'car', 'model': 'Car', 'sensors': [camera],
                         'pose': {'x': -25.0, 'y': -101.75, 'yaw': 0.0}}]
    scene = build_scene(world_from_data(data, 'city_block_signals.yaml'), mount=mount_suite)
    try:
        lamps, controller = scene.parts['signal_lamps'], scene.parts['signals'].controller
        assert lamps.controller is controller
        graph = scene.lanes
        here = graph.locate(-25.0, -101.75, 0.0)
        line, _ = graph.rules.next_stop_line(graph, here.lane_id, here.s_m, 50.0)
        group = graph.rules.group(line.group_id)
        assert {bulb.color for bulb in group.bulbs} == set(BULB_Z)
        camera_sensor = scene.vehicles['car'].sensors
        seen, last = [], None
        for _ in range(10001):                                  # 100 s: one cycle
            state = controller.state(group.id)
            if state != last:
                frame = camera_sensor.sample('camera')
                rgb = {bulb.color: _bulb_rgb(scene, frame, bulb) for bulb in group.bulbs}
                assert _is_lit(rgb[state], state), (scene.world.time_s, state, rgb)
                assert all(_is_dark(rgb[c]) for c in rgb if c != state), (state, rgb)
                seen.append(state)
                last = state
            scene.world.step()
        assert set(seen) == {'red', 'yellow', 'green'}
    finally:
        scene.world.close()


def _bulb_rgb(scene, frame, bulb):
    """Return the mean colour [0, 1] of the 3 x 3 pixels where the camera sees a bulb's front."""
    fx, cx, fy, cy = frame.k[0], frame.k[2], frame.k[4], frame.k[5]
    base = scene.vehicles['car'].body.pose()            # the car faces +x (yaw 0)
    camera = (base[0] + 1.5, base[1], base[2] + 1.3)
    depth = bulb.x_m - camera[0]
    col = int(round(cx + fx * -(bulb.y_m - camera[1]) / depth))
    row = int(round(cy + fy * -(bulb.z_m - camera[2]) / depth))
    return frame.rgb[row - 1:row + 2, col - 1:col + 2].reshape(-1, 3).mean(axis=0) / 255.0
