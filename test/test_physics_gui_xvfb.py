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
PyBullet's window under Xvfb: the chase camera shows the car (test/gui_probe.py looks).

Needs ``xvfb-run`` (Debian/Ubuntu package ``xvfb``); the screenshot test also needs ``xwd``
(package ``x11-apps``). Where they are missing the tests are skipped and pytest prints the reason
(``-ra``); ``make test`` does not need them.
"""

import json
import math
import os
import sys

from conftest import REPO_ROOT
import pytest
from xvfb_helpers import require_xvfb, xvfb_run

PROBE = os.path.join(REPO_ROOT, 'test', 'gui_probe.py')
PROBE_TIMEOUT_S = 240


@pytest.fixture(scope='module')
def seen(tmp_path_factory):
    require_xvfb()
    out_dir = tmp_path_factory.mktemp('gui')
    proc = xvfb_run([sys.executable, PROBE, str(out_dir)], PROBE_TIMEOUT_S, out_dir)
    lines = [line for line in proc.stdout.splitlines() if line.startswith('{')]
    assert proc.returncode == 0 and lines, (proc.returncode, proc.stdout[-3000:],
                                            proc.stderr[-3000:])
    result = json.loads(lines[-1])
    result['out_dir'] = str(out_dir)
    return result


def test_window_camera_is_behind_the_car_looking_along_its_heading(seen):
    # The window reports the view the chase camera sent: default distance and pitch, yaw =
    # heading - 90 deg (PyBullet's convention), the target above the car.
    window, view = seen['window_camera'], seen['view']
    assert window['distance_m'] == pytest.approx(8.0, abs=1e-4)
    assert window['pitch_deg'] == pytest.approx(-20.0, abs=1e-4)
    expected_yaw = math.degrees(seen['car_yaw']) - 90.0
    assert math.remainder(window['yaw_deg'] - expected_yaw, 360.0) == pytest.approx(0.0,
                                                                                    abs=0.5)
    assert window['target_m'] == pytest.approx(view['target_m'], abs=1e-3)
    # The target is the car's centre of mass, ahead of base_link (rear axle), 1 m up; the car
    # drove from (3, -2) along yaw 0.7.
    car_x, car_y = seen['car_xy']
    assert math.hypot(view['target_m'][0] - car_x, view['target_m'][1] - car_y) < 3.0
    assert math.hypot(car_x - 3.0, car_y + 2.0) > 1.0


def test_window_view_shows_the_car_at_the_centre(seen):
    # Rendered through the window camera's matrices (in the window's OpenGL context): the car's
    # body id covers a good part of the central box; teleported 200 m away, none of it.
    assert seen['car_pixels_centre'] > 0.05 * seen['centre_pixels']
    assert seen['car_pixels_centre_away'] == 0
    # Colour: the centre changes when the car goes, the sky at the top does not.
    assert seen['render_centre_change'] > 5.0
    assert seen['render_border_change'] < 1.0


def test_screenshot_of_the_display_shows_the_car(seen):
    if seen['screenshot'] is None:
        pytest.skip('xwd not found: no screenshot of the X display '
                    '(Debian/Ubuntu: apt-get install x11-apps)')
    shot = seen['screenshot']
    assert shot['window_size'] == [1024, 768]
    assert shot['centre_changed_fraction'] > 0.05
    assert shot['top_rows_changed_fraction'] < 0.01


def test_a_closed_window_stops_the_world_with_a_clear_error(seen):
    assert seen['step_after_close'] == 'GuiClosedError: the PyBullet window was closed'
