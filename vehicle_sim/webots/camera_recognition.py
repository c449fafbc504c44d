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
The recognition part of the Webots Camera (camera.md, "camera recognition functions").

A camera whose configuration has ``recognition: true`` has Webots' Recognition node
(``hasRecognition()``); with ``segmentation: true`` too, its segmentation
(``hasRecognitionSegmentation()``). As in Webots, recognition has its own sampling period
(``recognitionEnable``), independent of the camera's ``enable``; the segmentation image is made
only while recognition is on and ``enableRecognitionSegmentation()`` was called.

Objects (:class:`CameraRecognitionObject`) carry Webots' fields: ``id`` (the object's instance
id, the id of PredictedObjects and the instance image), ``position`` and ``orientation`` (axis,
angle) in the camera frame (x forward, y left, z up), ``size`` (the object's extent across the
view and upwards [m]), ``position_on_image`` and ``size_on_image`` (the visible part's box [px]),
``colors`` (its label colour) and ``model`` (its label name). The segmentation image is BGRA
bytes like ``getImage()``, each pixel its label's colour (the label table of docs/sensors.md):
unlike Webots, where only Solids with recognition colours are coloured, the road, walls and the
rest are coloured too, and nothing (the sky) is black.
"""

import math
import numbers

import numpy as np

from vehicle_sim.core.sensors.labels import LABELS
from vehicle_sim.webots.webots_warning import warn

LABEL_COLOURS = np.array([label.colour for label in LABELS], dtype=np.uint8)


def _warn(message):
    warn(message, stacklevel=3)


def axis_angle(x, y, z, w):
    """Return Webots' orientation [axis x, y, z, angle] of a unit quaternion (x, y, z, w)."""
    w = max(-1.0, min(1.0, w))
    angle = 2.0 * math.acos(w)
    s = math.sqrt(max(0.0, 1.0 - w * w))
    if s < 1e-9:
        return [0.0, 0.0, 1.0, 0.0]
    return [x / s, y / s, z / s, angle]


class CameraRecognitionObject:
    """Webots CameraRecognitionObject: the fields as attributes and Webots' getters."""

    __slots__ = ('id', 'position', 'orientation', 'size', 'position_on_image',
                 'size_on_image', 'number_of_colors', 'colors', 'model')

    def __init__(self, recognised):
        """Make one from a core RecognitionObject."""
        self.id = recognised.id
        self.position = list(recognised.position_m)
        self.orientation = axis_angle(*recognised.orientation_xyzw)
        self.size = list(recognised.size_m)
        self.position_on_image = list(recognised.position_on_image)
        self.size_on_image = list(recognised.size_on_image)
        self.number_of_colors = 1
        self.colors = list(recognised.colour)
        self.model = recognised.model

    def getId(self):
        return self.id

    def getPosition(self):
        return self.position

    def getOrientation(self):
        return self.orientation

    def getSize(self):
        return self.size

    def getPositionOnImage(self):
        return self.position_on_image

    def getSizeOnImage(self):
        return self.size_on_image

    def getNumberOfColors(self):
        return self.number_of_colors

    def getColors(self):
        return self.colors

    def getModel(self):
        return self.model

    def __repr__(self):
        return (f'CameraRecognitionObject(id={self.id}, model={self.model!r}, '
                f'position={self.position})')


class CameraRecognition:
    """The recognition methods of webots/devices.py Camera (a Device with _suite and _spec)."""

    def _recognition_key(self):
        return f'{self._name}/recognition'

    def hasRecognition(self):
        """Return whether the camera has a Recognition node (``recognition: true``)."""
        return bool(self._spec.recognition)

    def recognitionEnable(self, samplingPeriod):
        """Recognise objects every ``samplingPeriod`` ms (the first result after one period)."""
        if isinstance(samplingPeriod, bool) or not isinstance(samplingPeriod, numbers.Integral):
            raise TypeError(f'recognitionEnable() expects a sampling period in ms (int), '
                            f'got {samplingPeriod!r}')
        if not self.hasRecognition():
            _warn(f'{self._name}: recognitionEnable() called on a camera without recognition '
                  "(set 'recognition: true' on the camera)")
            return
        if samplingPeriod < 0:
            _warn(f'{self._name}: recognitionEnable() called with negative sampling period '
                  f'({samplingPeriod}); ignored')
            return
        if samplingPeriod == 0:
            self.recognitionDisable()
            return
        self._recognition_ms = int(samplingPeriod)
        self._recognition_since_s = self._suite.world.time_s
        self._suite.set_period_ms(self._spec.name, self._recognition_ms,
                                  key=self._recognition_key())

    def recognitionDisable(self):
        """Stop recognising (and segmenting)."""
        if getattr(self, '_recognition_ms', 0):
            self._suite.stop(self._recognition_key())
        self._recognition_ms = 0
        self._recognition_since_s = None

    def getRecognitionSamplingPeriod(self):
        """Return the recognition period [ms], 0 when disabled."""
        return getattr(self, '_recognition_ms', 0)

    def _recognition_reading(self, function):
        if not self.getRecognitionSamplingPeriod():
            _warn(f'{function}() called for {self._name!r} with recognition disabled! Please '
                  'use: recognitionEnable()')
            return None
        reading = self._suite.latest(self._recognition_key())
        if reading is None or reading.time_s <= self._recognition_since_s:
            return None
        return reading

    def getRecognitionNumberOfObjects(self):
        """Return the number of objects recognised at the last recognition sample."""
        return len(self.getRecognitionObjects())

    def getRecognitionObjects(self):
        """Return the objects of the last recognition sample ([] before the first)."""
        reading = self._recognition_reading('getRecognitionObjects')
        if reading is None or reading.objects is None:
            return []
        return [CameraRecognitionObject(found) for found in reading.objects]

    def hasRecognitionSegmentation(self):
        """Return whether the Recognition node segments (``segmentation: true`` too)."""
        return self.hasRecognition() and bool(self._spec.segmentation)

    def enableRecognitionSegmentation(self):
        """Make the segmentation image at each recognition sample (recognition must be on)."""
        if not self.hasRecognitionSegmentation():
            _warn(f'{self._name}: enableRecognitionSegmentation(): the camera has no '
                  "segmentation (set 'recognition: true' and 'segmentation: true')")
            return
        if not self.getRecognitionSamplingPeriod():
            _warn(f'{self._name}: enableRecognitionSegmentation(): recognition is disabled; '
                  'use recognitionEnable() first')
            return
        self._segmentation = True

    def disableRecognitionSegmentation(self):
        """Stop making the segmentation image."""
        self._segmentation = False

    def isRecognitionSegmentationEnabled(self):
        """Return whether the segmentation image is made (recognition on and enabled)."""
        return bool(getattr(self, '_segmentation', False)) and \
            bool(self.getRecognitionSamplingPeriod())

    def _segmentation_rgb(self, function):
        if not self.isRecognitionSegmentationEnabled():
            _warn(f'{function}() called for {self._name!r} with the segmentation disabled! '
                  'Please use: enableRecognitionSegmentation()')
            return None
        reading = self._recognition_reading(function)
        return None if reading is None else LABEL_COLOURS[reading.semantic]

    def getRecognitionSegmentationImage(self):
        """Return the last segmentation image as BGRA bytes (None before the first)."""
        rgb = self._segmentation_rgb('getRecognitionSegmentationImage')
        if rgb is None:
            return None
        height, width = rgb.shape[:2]
        bgra = np.empty((height, width, 4), dtype=np.uint8)
        bgra[:, :, :3] = rgb[:, :, ::-1]
        bgra[:, :, 3] = 255
        return bgra.tobytes()

    def getRecognitionSegmentationImageArray(self):
        """Return the segmentation image as image[x][y] = [red, green, blue] (Webots' layout)."""
        rgb = self._segmentation_rgb('getRecognitionSegmentationImageArray')
        return None if rgb is None else rgb.transpose(1, 0, 2).tolist()

    def saveRecognitionSegmentationImage(self, filename, quality):
        """
        Save the last segmentation image as PNG or JPEG (by the file's extension; Pillow).

        :return: 0 on success, -1 on failure (no image yet, another extension, no Pillow, a
            file that cannot be written), as Webots.
        """
        rgb = self._segmentation_rgb('saveRecognitionSegmentationImage')
        lower = str(filename).lower()
        if rgb is None or not lower.endswith(('.png', '.jpg', '.jpeg')):
            return -1
        try:
            from PIL import Image
        except ImportError:
            _warn('saveRecognitionSegmentationImage() needs Pillow: pip install Pillow')
            return -1
        try:
            Image.fromarray(rgb).save(filename, quality=int(quality))
        except (OSError, ValueError):
            return -1
        return 0
