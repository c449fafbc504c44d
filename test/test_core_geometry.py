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

"""yaw_from_quaternion: the one closed form of a quaternion's heading, and its only copy."""

import math
from pathlib import Path
import re

import pytest

from vehicle_sim.core.frames import quaternion_from_rpy
from vehicle_sim.core.geometry import yaw_from_quaternion

ROOT = Path(__file__).resolve().parent.parent


@pytest.mark.parametrize('yaw', [0.0, 0.3, -1.2, math.pi / 2, -math.pi / 2, 3.0, -3.0])
def test_pure_yaw_is_the_half_angle_closed_form(yaw):
    # A rotation by yaw about z is (0, 0, sin(yaw/2), cos(yaw/2)).
    q = (0.0, 0.0, math.sin(yaw / 2.0), math.cos(yaw / 2.0))
    assert yaw_from_quaternion(q) == pytest.approx(yaw, abs=1e-12)


def test_values_from_the_formula():
    # atan2(2 (w z + x y), 1 - 2 (y^2 + z^2)) on hand-picked values.
    assert yaw_from_quaternion((0.0, 0.0, 0.0, 1.0)) == 0.0
    assert yaw_from_quaternion((0.0, 0.0, 1.0, 0.0)) == pytest.approx(math.pi)
    half = math.sqrt(0.5)
    assert yaw_from_quaternion((0.0, 0.0, half, half)) == pytest.approx(math.pi / 2)
    assert yaw_from_quaternion((0.0, 0.0, -half, half)) == pytest.approx(-math.pi / 2)


@pytest.mark.parametrize('roll, pitch, yaw', [(0.2, -0.3, 1.0), (-0.5, 0.4, -2.5),
                                              (0.1, 0.1, 3.1)])
def test_yaw_survives_roll_and_pitch(roll, pitch, yaw):
    assert yaw_from_quaternion(quaternion_from_rpy(roll, pitch, yaw)) == pytest.approx(yaw)


def test_the_formula_is_written_once():
    pattern = re.compile(r'atan2\(\s*2(\.0)?\s*\*\s*\(?\s*\w+(\[\d\])?\s*\*\s*\w+(\[\d\])?\s*\+')
    copies = []
    for package in ('vehicle_sim', 'vehicle_msgs_py', 'test'):
        for path in sorted((ROOT / package).rglob('*.py')):
            for number, line in enumerate(path.read_text(encoding='utf-8').splitlines(), 1):
                if pattern.search(line) and 'w * x' not in line:     # roll has its own formula
                    copies.append(f'{path.relative_to(ROOT)}:{number}')
    assert copies == ['vehicle_sim/core/geometry.py:36']
