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
The Webots RangeFinder device: Webots' row-major range image, its getters, saveImage.

And a Webots-style controller (examples/range_finder_stop_controller.py), unchanged but its
import.

test/data/depth_course.yaml mounts a 64 x 48 range finder 1.5 m ahead of base_link, 1.3 m up;
the wall's face is 18 m ahead of it.
"""

import math
import os
from pathlib import Path
import subprocess
import sys
import warnings

import numpy as np
import pytest

from vehicle_sim.webots import Driver, WebotsWarning

REPO = Path(__file__).resolve().parent.parent
DEPTH_COURSE = str(REPO / 'test' / 'data' / 'depth_course.yaml')

@pytest.fixture
def driver():
    with Driver(world_file=DEPTH_COURSE) as instance:
        yield instance


def test_range_image_is_webots_row_major_layout_of_the_depth(driver):
    device = driver.getDevice('depth_cam')
    assert type(device).__name__ == 'RangeFinder'
    assert (device.getWidth(), device.getHeight(), device.getFov(), device.getMinRange(),
            device.getMaxRange()) == (64, 48, 1.0, 0.05, 50.0)
    device.enable(20)
    assert device.getSamplingPeriod() == 20
    driver.step()
    assert device.getRangeImage() is None                # the first image after one period
    driver.step()
    image = device.getRangeImage()
    assert isinstance(image, list) and len(image) == 64 * 48
    rows = device.getRangeImageArray()
    assert len(rows) == 48 and all(len(row) == 64 for row in rows)
    for x, y in ((0, 0), (31, 24), (63, 47), (10, 30)):
        assert image[y * 64 + x] == rows[y][x] == device.rangeImageGetDepth(image, 64, x, y) \
            == device.imageGetDepth(image, 64, x, y)
    assert math.isinf(image[0]) and image[0] > 0                  # the sky, top left
    assert rows[24][32] == pytest.approx(18.0, abs=0.02)          # the wall face, 18 m ahead
    assert rows[47][32] < rows[24][32]                      # below: the ground or the car, nearer
    buffer = device.getRangeImage(data_type='buffer')
    assert np.frombuffer(buffer, np.float32).tolist() == image


def test_save_image_writes_webots_grey_levels(driver, tmp_path):
    image_module = pytest.importorskip('PIL.Image', reason="saveImage needs Pillow ('maps')")
    device = driver.getDevice('depth_cam')
    device.enable(10)
    driver.step()
    path = tmp_path / 'depth.png'
    assert device.saveImage(str(path), 100) == 0
    grey = np.asarray(image_module.open(path))
    assert grey.shape == (48, 64, 3) and (grey[..., 0] == grey[..., 2]).all()
    rows = np.array(device.getRangeImageArray())
    expected = (np.clip((rows - 0.05) / 50.0, 0.0, 1.0) * 255.0).astype(np.uint8)
    assert (grey[..., 0] == expected).all()
    assert grey[0, 0, 0] == 255 and grey[24, 32, 0] == int((18.0 - 0.05) / 50.0 * 255.0)
    with warnings.catch_warnings():
        warnings.simplefilter('ignore', WebotsWarning)
        assert device.saveImage(str(tmp_path / 'depth.tiff'), 100) == -1
        assert device.saveImage(str(path), 0) == -1


def test_webots_style_range_finder_controller_stops_before_the_wall():
    env = dict(os.environ, VEHICLE_SIM_WORLD=DEPTH_COURSE)
    result = subprocess.run(
        [sys.executable, str(REPO / 'examples' / 'range_finder_stop_controller.py')],
        capture_output=True, text=True, env=env, timeout=300)
    assert result.returncode == 0, result.stderr
    lines = result.stdout.strip().splitlines()
    assert lines[0] == 'range finder 64 x 48, fov 1.00 rad, 0.05 .. 50.0 m'
    assert 'stopped' in lines[-1], result.stdout
    gap_m = float(lines[-1].split('m ahead of the range finder, ')[1].split(' m')[0])
    assert 0.5 < gap_m < 5.0          # stopped before the wall, without touching it
