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
The Webots Camera's recognition API (camera.md, "camera recognition functions") on our camera.

A wall stands 20 m ahead of the car; a small box 10 m ahead, left of the centre line. The camera
has ``segmentation`` and ``recognition``; a second one has neither.
"""

import warnings

import numpy as np
import pytest

from vehicle_sim.core.sensors.labels import LABEL_IDS, LABELS
from vehicle_sim.webots import Driver, WebotsWarning
from vehicle_sim.webots.devices import CameraRecognitionObject

WORLD = """
vehicles:
  - name: ego
    sensors:
      - {name: camera, pose: {x: 1.5, z: 1.3}, width: 96, height: 64, segmentation: true,
         recognition: true}
      - {type: camera, name: plain, topic: plain, pose: {x: 1.5, z: 1.3}, width: 32, height: 24}
obstacles:
  - {name: wall, shape: box, size: [1.0, 6.0, 2.0], position: [20.0, 0.0, 1.0]}
  - {name: crate, shape: box, size: [1.0, 1.0, 1.0], position: [10.0, 2.0, 0.5]}
"""
OBSTACLE = LABEL_IDS['obstacle']


@pytest.fixture
def driver(tmp_path):
    path = tmp_path / 'recognition.yaml'
    path.write_text(WORLD)
    with Driver(world_file=str(path)) as instance:
        yield instance


def _quiet(function, *args):
    with warnings.catch_warnings():
        warnings.simplefilter('ignore', WebotsWarning)
        return function(*args)


def test_recognition_objects_carry_webots_fields_from_the_camera(driver):
    camera = driver.getDevice('camera')
    assert camera.hasRecognition() and camera.hasRecognitionSegmentation()
    assert camera.getRecognitionSamplingPeriod() == 0
    camera.recognitionEnable(20)            # the camera itself need not be enabled
    assert camera.getRecognitionSamplingPeriod() == 20 and camera.getSamplingPeriod() == 0
    assert camera.getRecognitionObjects() == [] and camera.getRecognitionNumberOfObjects() == 0
    driver.step()
    driver.step()
    objects = camera.getRecognitionObjects()
    assert camera.getRecognitionNumberOfObjects() == len(objects) == 2
    assert all(isinstance(o, CameraRecognitionObject) for o in objects)
    reading = driver.sensors.latest('camera/recognition')
    labels = driver.world.labels
    wall, crate = sorted(objects, key=lambda o: o.getId() != labels.instance('wall'))
    assert (wall.getId(), crate.getId()) == (labels.instance('wall'), labels.instance('crate'))
    core = {o.id: o for o in reading.objects}[wall.getId()]
    assert wall.getModel() == crate.getModel() == 'obstacle'
    # the wall's centre in the camera frame (x forward, y left, z up), no rotation
    assert wall.getPosition() == pytest.approx(list(core.position_m))
    assert wall.getPosition()[0] == pytest.approx(20.0 - 1.5, abs=0.01)
    assert wall.getOrientation() == pytest.approx([0.0, 0.0, 1.0, 0.0], abs=1e-6)
    assert wall.getSize() == pytest.approx([6.0, 2.0], abs=1e-6)
    assert crate.getSize() == pytest.approx([1.0, 1.0], abs=1e-6)
    assert wall.getPositionOnImage() == list(core.position_on_image)
    assert wall.getSizeOnImage() == list(core.size_on_image)
    assert wall.getNumberOfColors() == 1
    assert wall.getColors() == pytest.approx([c / 255 for c in LABELS[OBSTACLE].colour])
    # the attributes are the getters' values, as in Webots' ctypes structure
    assert (wall.id, wall.model, wall.size_on_image) == (wall.getId(), 'obstacle',
                                                         wall.getSizeOnImage())
    # the crate is left of the image centre and nearer
    assert crate.getPositionOnImage()[0] < 48 and crate.getPosition()[1] > 0


def test_the_segmentation_image_is_bgra_in_the_label_colours(driver, tmp_path):
    camera = driver.getDevice('camera')
    assert not camera.isRecognitionSegmentationEnabled()
    with pytest.warns(WebotsWarning, match='recognition is disabled'):
        camera.enableRecognitionSegmentation()
    assert not camera.isRecognitionSegmentationEnabled()
    camera.recognitionEnable(10)
    camera.enableRecognitionSegmentation()
    assert camera.isRecognitionSegmentationEnabled()
    driver.step()
    image = camera.getRecognitionSegmentationImage()
    semantic = driver.sensors.latest('camera/recognition').semantic
    width, height = camera.getWidth(), camera.getHeight()
    assert len(image) == width * height * 4
    x, y = 48, 30                                 # the wall at the image centre
    assert semantic[y, x] == OBSTACLE
    red, green, blue = LABELS[OBSTACLE].colour
    assert [camera.imageGetRed(image, width, x, y), camera.imageGetGreen(image, width, x, y),
            camera.imageGetBlue(image, width, x, y)] == [red, green, blue]
    assert image[4 * (y * width + x) + 3] == 255
    assert camera.getRecognitionSegmentationImageArray()[x][y] == [red, green, blue]
    assert camera.getRecognitionSegmentationImageArray()[x][0] == [0, 0, 0]    # the sky
    pytest.importorskip('PIL')
    from PIL import Image
    path = tmp_path / 'segmentation.png'
    assert camera.saveRecognitionSegmentationImage(str(path), 100) == 0
    saved = np.asarray(Image.open(path).convert('RGB'))
    assert saved.shape == (height, width, 3) and saved[y, x].tolist() == [red, green, blue]
    assert camera.saveRecognitionSegmentationImage(str(tmp_path / 'x.bmp'), 100) == -1


def test_disabling_recognition_stops_objects_and_segmentation(driver):
    camera = driver.getDevice('camera')
    camera.recognitionEnable(10)
    camera.enableRecognitionSegmentation()
    driver.step()
    assert camera.getRecognitionNumberOfObjects() == 2
    camera.recognitionDisable()
    assert camera.getRecognitionSamplingPeriod() == 0
    assert not camera.isRecognitionSegmentationEnabled()
    with pytest.warns(WebotsWarning, match='recognition disabled'):
        assert camera.getRecognitionObjects() == []
    assert _quiet(camera.getRecognitionSegmentationImage) is None
    camera.recognitionEnable(0)
    assert camera.getRecognitionSamplingPeriod() == 0


def test_a_camera_without_recognition_says_so_and_bad_periods_are_refused(driver):
    plain = driver.getDevice('plain')
    assert not plain.hasRecognition() and not plain.hasRecognitionSegmentation()
    with pytest.warns(WebotsWarning, match='without recognition'):
        plain.recognitionEnable(10)
    assert plain.getRecognitionSamplingPeriod() == 0
    camera = driver.getDevice('camera')
    with pytest.raises(TypeError, match='sampling period'):
        camera.recognitionEnable('10')
    with pytest.warns(WebotsWarning, match='negative'):
        camera.recognitionEnable(-5)
    assert camera.getRecognitionSamplingPeriod() == 0
