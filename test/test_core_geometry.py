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

"""Plane geometry written once: yaw from a quaternion, angle wrapping."""

import math
from pathlib import Path
import re

import pytest

from vehicle_sim.core.geometry.angles import wrap_angle_rad, yaw_from_quaternion

PACKAGE = Path(__file__).resolve().parent.parent / 'vehicle_sim'


@pytest.mark.parametrize('theta', [0.0, 0.3, -1.2, math.pi / 2, 3.0, -3.0])
def test_yaw_from_quaternion_of_a_rotation_about_z_is_its_angle(theta):
    # q = (0, 0, sin θ/2, cos θ/2): atan2(2 sin θ/2 cos θ/2, 1 - 2 sin² θ/2) = atan2(sin θ, cos θ)
    assert yaw_from_quaternion(0.0, 0.0, math.sin(theta / 2), math.cos(theta / 2)) == \
        pytest.approx(theta, abs=1e-12)


def test_yaw_from_quaternion_ignores_roll_and_pitch():
    # yaw 0.7 after roll 0.2 and pitch -0.1 (z-y-x): q = qz(0.7) ⊗ qy(-0.1) ⊗ qx(0.2)
    def mul(a, b):
        ax, ay, az, aw = a
        bx, by, bz, bw = b
        return (aw * bx + ax * bw + ay * bz - az * by, aw * by - ax * bz + ay * bw + az * bx,
                aw * bz + ax * by - ay * bx + az * bw, aw * bw - ax * bx - ay * by - az * bz)
    q = mul(mul((0.0, 0.0, math.sin(0.35), math.cos(0.35)),
                (0.0, math.sin(-0.05), 0.0, math.cos(-0.05))),
            (math.sin(0.1), 0.0, 0.0, math.cos(0.1)))
    assert yaw_from_quaternion(*q) == pytest.approx(0.7, abs=1e-12)


@pytest.mark.parametrize('angle, wrapped', [
    (0.0, 0.0), (3 * math.pi / 2, -math.pi / 2), (-3 * math.pi / 2, math.pi / 2),
    (7.0, 7.0 - 2 * math.pi)])
def test_wrap_angle_rad_brings_an_angle_into_minus_pi_pi(angle, wrapped):
    assert wrap_angle_rad(angle) == pytest.approx(wrapped, abs=1e-12)


@pytest.mark.parametrize('angle', [math.pi, -math.pi])
def test_wrap_angle_rad_is_half_open_at_minus_pi_as_ros_angles_normalize_angle(angle):
    # ROS's angles::normalize_angle: (-pi, pi]; a half turn either way is +pi, never -pi.
    assert wrap_angle_rad(angle) == math.pi


@pytest.mark.parametrize('angle', [0.3, -3.0, 1e-300, -math.pi + 1e-15])
def test_wrap_angle_rad_returns_an_angle_in_the_interval_unchanged(angle):
    assert wrap_angle_rad(angle) == angle


def test_the_angle_wrap_is_written_once_in_the_package():
    # atan2(sin a, cos a), (a + pi) % 2pi - pi and remainder(a, 2pi): wraps, with other ends.
    wrap = re.compile(r'atan2\(\s*math\.sin\(|%\s*\(?2(\.0)?\s*\*\s*math\.pi|%\s*math\.tau|'
                      r'remainder\(')
    found = sorted(str(path.relative_to(PACKAGE)) for path in PACKAGE.rglob('*.py')
                   if wrap.search(path.read_text(encoding='utf-8')))
    assert found == ['core/geometry/angles.py']


def test_the_yaw_formula_is_written_once_in_the_package():
    formula = re.compile(r'atan2\(\s*2(\.0)?\s*\*\s*\(\s*q?w\s*\*\s*q?z')
    found = [str(path.relative_to(PACKAGE)) for path in PACKAGE.rglob('*.py')
             if formula.search(path.read_text(encoding='utf-8'))]
    assert found == ['core/geometry/angles.py']
