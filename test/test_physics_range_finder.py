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
The range finder's physics: golden depths, a render shared with a camera, noise, bad input.

Golden geometry: a range finder 1.5 m above the ground at the origin looks along +x at a box
whose near face is at x = 8 m (y 0..2, z 0..2) in front of a wall whose face is at x = 20 m
(y -10..10, z 0..4). Depth is planar (along the optical axis), so every pixel of a face
reads the face's x, the ground 1.5 m fy / (v - cy) (a ray through the pixel's centre); the
sky above the wall reads +inf. The tolerance is two steps of the float32 depth buffer d
(2^-24 each) at that depth, dz = z^2 (far - near) / (far near) dd, on the faces, and four on
the ground, whose depth the renderer interpolates across triangles tens of metres long.
"""

import math

import numpy as np
import pytest

from vehicle_sim.core.sensors.params import sensor_from_dict
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.world.params import obstacle_from_dict
from vehicle_sim.physics import World
from vehicle_sim.physics.sensors import render
from vehicle_sim.physics.sensors.camera import CameraSensor
from vehicle_sim.physics.sensors.range_finder import RangeFinderSensor

NEAR_M, FAR_M = 0.05, 50.0
HEIGHT_M = 1.5
BOX_X, BOX_Y, BOX_Z = 8.0, (0.0, 2.0), (0.0, 2.0)
WALL_X, WALL_Y, WALL_Z = 20.0, (-10.0, 10.0), (0.0, 4.0)


def depth_step_m(z_m, near_m=NEAR_M, far_m=FAR_M):
    """One step of the float32 depth buffer (2^-24) at depth z, in metres."""
    return z_m * z_m * (far_m - near_m) / (far_m * near_m) * 2.0 ** -24


class Tripod:
    """A fixed stand for a sensor (no body of its own to see): base_link at ``xyz``, level."""

    def __init__(self, xyz=(0.0, 0.0, 0.0)):
        self.xyz = tuple(xyz)

    def pose(self):
        return self.xyz + (0.0, 0.0, 0.0, 1.0)

    def velocity(self):
        return (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)


def _spec(**keys):
    data = {'type': 'range_finder', 'name': 'depth', 'width': 160, 'height': 120, 'fov': 1.0,
            'min_range': NEAR_M, 'max_range': FAR_M, 'pose': {'z': HEIGHT_M}}
    data.update(keys)
    return sensor_from_dict(data, 'test')


@pytest.fixture
def world():
    made = World()
    made.add_obstacle(obstacle_from_dict({'name': 'wall', 'shape': 'box', 'size': [1, 20, 4],
                                          'position': [WALL_X + 0.5, 0, 2]}, 'test'))
    made.add_obstacle(obstacle_from_dict({'name': 'box', 'shape': 'box', 'size': [1, 2, 2],
                                          'position': [BOX_X + 0.5, 1, 1]}, 'test'))
    yield made
    made.close()


def _first_hit(a, b):
    """Return the planar depth of the ray (1, a, b) (sensor frame, from HEIGHT_M) and its face."""
    for name, x, (y0, y1), (z0, z1) in (('box', BOX_X, BOX_Y, BOX_Z),
                                        ('wall', WALL_X, WALL_Y, WALL_Z)):
        if b < 0.0 and HEIGHT_M / -b < x:
            break                                   # the ground comes first
        if y0 <= a * x <= y1 and z0 <= HEIGHT_M + b * x <= z1:
            return x, name
    if b < 0.0 and HEIGHT_M / -b <= FAR_M:
        return HEIGHT_M / -b, 'ground'
    return math.inf, 'sky'


def _expected(spec):
    """Per pixel: the face the whole pixel sees (corners, centre) or None; the centre's depth."""
    fx, _, cx, cy = spec.intrinsics
    faces = np.empty((spec.height, spec.width), dtype=object)
    depths = np.full((spec.height, spec.width), np.nan)
    for v in range(spec.height):
        for u in range(spec.width):
            seen = {_first_hit(-(u + du - cx) / fx, -(v + dv - cy) / fx)
                    for du in (-0.5, 0.0, 0.5) for dv in (-0.5, 0.0, 0.5)}
            names = {name for _, name in seen}
            if len(names) == 1:
                faces[v, u] = names.pop()
                depths[v, u] = _first_hit(-(u - cx) / fx, -(v - cy) / fx)[0]
    return faces, depths


def test_golden_depth_reads_each_face_per_pixel_within_the_depth_buffer_resolution(world):
    spec = _spec()
    depth = RangeFinderSensor(world, Tripod(), spec).sample(0.0).depth_m
    assert depth.shape == (120, 160) and depth.dtype == np.float32
    faces, expected = _expected(spec)
    # the ground: interpolated in float32 across its large triangles, a few steps more
    for face, steps in (('box', 2.0), ('wall', 2.0), ('ground', 4.0)):
        on = faces == face
        assert on.sum() > 300, face
        error = np.abs(depth[on] - expected[on]) / depth_step_m(expected[on])
        assert error.max() <= steps, (face, error.max())
    sky = faces == 'sky'
    assert sky.sum() > 1000 and np.isposinf(depth[sky]).all()        # +inf over the horizon
    assert np.isposinf(depth[0]).all()                                # the top row: sky only


def test_nothing_drawn_reads_plus_inf_whatever_the_clip_planes(world):
    # the cleared depth buffer is 1 less float32 rounding: judged there, not as metres to far
    for near_m, far_m in ((0.05, 50.0), (0.1, 100.0), (0.01, 1000.0), (0.5, 5.0)):
        spec = _spec(min_range=near_m, max_range=far_m, pose={'z': HEIGHT_M, 'pitch': -0.5})
        depth = RangeFinderSensor(world, Tripod(), spec).sample(0.0).depth_m
        assert np.isposinf(depth[0]).all(), (near_m, far_m, depth[0].min())


def test_camera_and_range_finder_with_one_view_share_one_render(world, monkeypatch):
    renders = []
    real = render.Renderer._render

    def counted(self, *args):
        renders.append(args[0])
        return real(self, *args)
    monkeypatch.setattr(render.Renderer, '_render', counted)
    camera_spec = sensor_from_dict({'type': 'camera', 'name': 'camera', 'width': 160,
                                    'height': 120, 'fov': 1.0, 'near': NEAR_M, 'far': FAR_M,
                                    'pose': {'z': HEIGHT_M}}, 'test')
    stand = Tripod()
    camera = CameraSensor(world, stand, camera_spec)
    depth = RangeFinderSensor(world, stand, _spec())
    colour, reading = camera.sample(0.0), depth.sample(0.0)
    assert len(renders) == 1 and colour.rgb.shape == (120, 160, 3)
    assert reading.depth_m[60, 150] == pytest.approx(WALL_X, abs=0.01)
    world.step()
    depth.sample(world.time_s)
    assert len(renders) == 2                   # a new step renders again


def test_noise_is_seeded_off_by_default_and_keeps_the_sky_inf(world):
    stand = Tripod()
    exact = RangeFinderSensor(world, stand, _spec()).sample(0.0).depth_m
    noisy = [RangeFinderSensor(world, stand, _spec(noise=0.05, seed=3)).sample(0.0).depth_m
             for _ in range(2)]
    assert np.array_equal(noisy[0], noisy[1], equal_nan=True)     # the same seed repeats
    finite = np.isfinite(exact)
    both = finite & np.isfinite(noisy[0])
    assert both.sum() > 0.99 * finite.sum()
    error = noisy[0][both] - exact[both]
    assert 0.04 < error.std() < 0.06 and abs(error.mean()) < 0.01
    assert np.isposinf(noisy[0][~finite]).all()


def test_points_are_depth_image_proc_s_cloud_in_the_optical_frame(world):
    reading = RangeFinderSensor(world, Tripod(), _spec()).sample(0.0)
    points = reading.points()
    assert points.shape == (120, 160, 3) and points.dtype == np.float32
    fx, _, cx, cy = _spec().intrinsics
    v, u = 50, 150                                        # on the wall, right of the box
    z = reading.depth_m[v, u]
    assert tuple(points[v, u]) == pytest.approx(((u - cx) * z / fx, (v - cy) * z / fx, z))
    assert np.isnan(points[0]).all()                      # the sky: NaN points
    assert (reading.step, len(reading.data), reading.encoding) == (640, 160 * 120 * 4, '32FC1')
    assert np.frombuffer(reading.data, '<f4').reshape(120, 160)[v, u] == z


@pytest.mark.parametrize('keys, field', [
    ({'width': 1921, 'height': 1080}, "'height'"),
    ({'width': 3841}, "'width'"),
    ({'min_range': 5.0, 'max_range': 5.0}, "'min_range'"),
    ({'min_range': 0.0}, "'min_range'"),
    ({'fov': 3.2}, "'fov'"),
    ({'noise': -0.1}, "'noise'"),
    ({'point_cloud': 'yes'}, "'point_cloud'"),
])
def test_bad_range_finder_keys_are_refused_naming_the_field(keys, field):
    with pytest.raises(InvalidParameterError, match=f'w.yaml: sensors.0.: field {field}'):
        sensor_from_dict(dict({'type': 'range_finder', 'name': 'd'}, **keys), 'w.yaml: sensors[0]')
