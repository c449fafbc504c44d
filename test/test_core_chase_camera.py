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

"""Tests of the chase camera math (vehicle_sim.core.geometry.chase_camera)."""

import math

import numpy as np
import pytest

from vehicle_sim.core.geometry.chase_camera import (
    bullet_yaw_deg,
    camera_forward,
    chase_view,
    ChaseSettings,
    ChaseView,
    eye_position,
    follow_heading,
    MAX_DISTANCE_M,
    MIN_DISTANCE_M,
)
from vehicle_sim.core.specs.errors import InvalidParameterError


@pytest.mark.parametrize('heading_deg', [0.0, 30.0, 90.0, 179.0, -120.0])
def test_the_eye_is_behind_and_above_the_vehicle_looking_along_its_heading(heading_deg):
    # Eye = target - d * (cos p cos h, cos p sin h, sin p) with p = pitch < 0: behind the car by
    # d cos|p| along the heading, above the target by d sin|p|.
    settings = ChaseSettings(distance_m=10.0, pitch_deg=-30.0, target_height_m=1.0)
    heading = math.radians(heading_deg)
    view = chase_view((5.0, -3.0, 0.2), heading, settings)
    assert view.target_m == (5.0, -3.0, 1.2)
    eye = eye_position(view)
    horizontal = 10.0 * math.cos(math.radians(30.0))
    assert eye[0] == pytest.approx(5.0 - horizontal * math.cos(heading), abs=1e-9)
    assert eye[1] == pytest.approx(-3.0 - horizontal * math.sin(heading), abs=1e-9)
    assert eye[2] == pytest.approx(1.2 + 10.0 * math.sin(math.radians(30.0)), abs=1e-9)
    forward = camera_forward(view)
    assert math.atan2(forward[1], forward[0]) == pytest.approx(heading, abs=1e-9)


def test_bullet_yaw_is_the_heading_minus_a_quarter_turn():
    # PyBullet's camera at yaw 0 looks along +y (heading 90 deg).
    assert bullet_yaw_deg(math.pi / 2) == pytest.approx(0.0)
    assert bullet_yaw_deg(0.0) == pytest.approx(-90.0)
    assert bullet_yaw_deg(math.pi) == pytest.approx(90.0)
    assert bullet_yaw_deg(-math.pi / 2) == pytest.approx(180.0)     # (-180, 180]


def test_eye_matches_pybullet_view_matrix():
    # The view matrix PyBullet builds from the same yaw/pitch/distance/target (z up) puts the
    # eye where eye_position says (the window's camera uses the same construction).
    pybullet = pytest.importorskip('vehicle_sim.physics._pybullet').pybullet
    for yaw, pitch in ((0.0, -30.0), (30.0, -20.0), (-135.0, -60.0)):
        view = ChaseView(7.0, yaw, pitch, (1.0, 2.0, 3.0))
        matrix = np.array(pybullet.computeViewMatrixFromYawPitchRoll(
            view.target_m, view.distance_m, yaw, pitch, 0.0, 2)).reshape(4, 4).T
        rotation, translation = matrix[:3, :3], matrix[:3, 3]
        np.testing.assert_allclose(-rotation.T @ translation, eye_position(view), atol=1e-5)


def test_follow_heading_is_a_first_order_lag_the_short_way_round():
    # One step of dt = lag closes 1 - 1/e of the gap.
    assert follow_heading(0.0, 1.0, 0.1, 0.1) == pytest.approx(1.0 - math.exp(-1.0))
    # From 170 deg to -170 deg the gap is +20 deg through 180, not -340 deg.
    new = follow_heading(math.radians(170), math.radians(-170), 0.1, 0.1)
    gained = math.radians(20) * (1.0 - math.exp(-1.0))
    assert new == pytest.approx(math.remainder(math.radians(170) + gained, 2 * math.pi))
    assert follow_heading(0.3, 2.0, 0.01, 0.0) == pytest.approx(2.0)


@pytest.mark.parametrize('heading', [math.pi, -math.pi])
def test_the_camera_heading_is_wrapped_into_minus_pi_pi_as_every_angle(heading):
    # One wrap in the package (core/geometry/angles.py, ROS's normalize_angle): a half turn
    # either way is +pi.
    assert follow_heading(0.0, heading, 0.01, 0.0) == math.pi
    assert follow_heading(-math.pi, heading, 0.01, 0.01) == math.pi


def test_zoom_scales_the_distance_within_its_range():
    settings = ChaseSettings(distance_m=8.0)
    assert settings.zoomed(1).distance_m == pytest.approx(10.0)
    assert settings.zoomed(-1).distance_m == pytest.approx(6.4)
    assert settings.zoomed(-100).distance_m == MIN_DISTANCE_M
    assert settings.zoomed(100).distance_m == MAX_DISTANCE_M


@pytest.mark.parametrize('field, value', [
    ('distance_m', 0.5), ('distance_m', float('nan')), ('pitch_deg', 10.0),
    ('pitch_deg', -91.0), ('target_height_m', float('inf')), ('heading_lag_s', -1.0)])
def test_settings_refuse_values_out_of_range(field, value):
    with pytest.raises(InvalidParameterError, match=field):
        ChaseSettings(**{field: value})
