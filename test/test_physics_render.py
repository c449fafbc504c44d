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


"""The shared renderer (physics/sensors/render.py): metric depth, body mask, one render a step."""

import math

import numpy as np
import pytest

from vehicle_sim.core.world.params import ObstacleSpec
from vehicle_sim.physics.sensors.render import metric_depth, View
from vehicle_sim.physics.world import World

VIEW = View(64, 48, math.radians(45.0), 0.1, 50.0)
LOOK_ALONG_X = np.eye(3)      # columns: x forward, y left, z up


def _wall(world, x_m):
    spec = ObstacleSpec('wall', 'box', (x_m + 0.5, 0.0, 2.0), 0.0, 0.0, 0.0, 0.0,
                        (1.0, 1.0, 1.0, 1.0), (1.0, 40.0, 4.0))
    return world.add_obstacle(spec)


def test_metric_depth_inverts_the_perspective_depth_buffer():
    near, far = 0.1, 50.0
    z = np.array([0.1, 1.0, 7.5, 49.0])
    buffer = (far + near) / (far - near) * 0.5 + 0.5 - far * near / ((far - near) * z)
    assert metric_depth(buffer, near, far) == pytest.approx(z, rel=1e-5)
    assert metric_depth([1.0], near, far)[0] == np.inf


def test_a_wall_7_m_ahead_reads_7_m_and_its_body_in_the_mask():
    world = World()
    try:
        body = _wall(world, 7.0)
        frame = world.renderer.render(VIEW, (0.0, 0.0, 1.0), LOOK_ALONG_X, mask=True)
        centre = frame.depth_m[VIEW.height // 2, VIEW.width // 2]
        assert centre == pytest.approx(7.0, abs=0.01)
        assert frame.bodies[VIEW.height // 2, VIEW.width // 2] == body
        assert frame.links[VIEW.height // 2, VIEW.width // 2] == -1
        again = world.renderer.render(VIEW, (0.0, 0.0, 1.0), LOOK_ALONG_X)
        assert again is frame                   # one render per step and pose
        world.step()
        assert world.renderer.render(VIEW, (0.0, 0.0, 1.0), LOOK_ALONG_X) is not frame
    finally:
        world.close()


def test_nothing_drawn_reads_inf_and_no_body():
    world = World()
    try:
        up = np.array([[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]]).T   # look at +z
        frame = world.renderer.render(VIEW, (0.0, 0.0, 1.0), up, mask=True)
        assert np.isinf(frame.depth_m).all()
        assert (frame.bodies == -1).all()
    finally:
        world.close()


def test_a_body_moved_between_steps_is_rendered_where_it_is_now():
    world = World()
    try:
        body = _wall(world, 7.0)
        centre = (VIEW.height // 2, VIEW.width // 2)
        assert world.renderer.render(VIEW, (0.0, 0.0, 1.0), LOOK_ALONG_X).depth_m[centre] == \
            pytest.approx(7.0, abs=0.01)
        (_, orientation), velocity, joints = world.body_state(body)
        world.restore_body_state(body, (((12.5, 0.0, 2.0), orientation), velocity, joints))
        assert world.renderer.render(VIEW, (0.0, 0.0, 1.0), LOOK_ALONG_X).depth_m[centre] == \
            pytest.approx(12.0, abs=0.02)
    finally:
        world.close()


def test_a_view_once_asked_with_the_mask_renders_with_it_so_a_plain_sensor_first_costs_none():
    # a range finder sampled before a segmenting camera of its view: one render per step
    world = World()
    renders = []
    real = world.renderer._render
    world.renderer._render = lambda *args: renders.append(args) or real(*args)
    try:
        _wall(world, 7.0)
        world.renderer.render(VIEW, (0.0, 0.0, 1.0), LOOK_ALONG_X, mask=True)
        for _ in range(3):
            world.step()
            plain = world.renderer.render(VIEW, (0.0, 0.0, 1.0), LOOK_ALONG_X)
            masked = world.renderer.render(VIEW, (0.0, 0.0, 1.0), LOOK_ALONG_X, mask=True)
            assert masked is plain and plain.bodies is not None
        assert len(renders) == 4
        other = View(32, 24, VIEW.vertical_fov_rad, 0.1, 50.0)   # another view: no mask
        assert world.renderer.render(other, (0.0, 0.0, 1.0), LOOK_ALONG_X).bodies is None
    finally:
        world.close()
