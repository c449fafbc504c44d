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
vision_msgs (vision_msgs 4.1.1) for a camera's recognition, and its message builders.

The definitions' fields are upstream's; the builders (ros/perception_messages.py) turn a camera
reading into the mono16 images, the Detection2DArray in the optical frame, and the LabelInfo.
"""

import math
from types import SimpleNamespace

import numpy as np
import pytest

import vehicle_msgs_py
from vehicle_sim.core.geometry.frames import rotate
from vehicle_sim.core.sensors.labels import LABELS
from vehicle_sim.core.sensors.recognition import RecognitionObject
from vehicle_sim.ros import perception_messages as pm

msg = vehicle_msgs_py.message_type
STAMP = msg('builtin_interfaces/msg/Time')(sec=3, nanosec=5)


def _fields(ros_type):
    own = vehicle_msgs_py.message_definition(ros_type).split('=' * 80)[0]
    return [tuple(line.split()[:2]) for line in own.splitlines() if line.strip()]


def test_the_definitions_have_upstreams_fields():
    assert _fields(pm.DETECTION_2D_ARRAY) == [('std_msgs/Header', 'header'),
                                              ('vision_msgs/Detection2D[]', 'detections')]
    assert _fields(pm.DETECTION_2D) == [
        ('std_msgs/Header', 'header'), ('vision_msgs/ObjectHypothesisWithPose[]', 'results'),
        ('vision_msgs/BoundingBox2D', 'bbox'), ('string', 'id')]
    assert _fields('vision_msgs/msg/BoundingBox2D') == [
        ('vision_msgs/Pose2D', 'center'), ('float64', 'size_x'), ('float64', 'size_y')]
    assert _fields(pm.LABEL_INFO) == [('std_msgs/Header', 'header'),
                                      ('vision_msgs/VisionClass[]', 'class_map'),
                                      ('float32', 'threshold')]
    assert _fields(pm.VISION_CLASS) == [('uint16', 'class_id'), ('string', 'class_name')]


def test_the_camera_frame_seen_from_the_optical_one():
    # x forward -> z, y left -> -x, z up -> -y
    assert rotate(pm.CAMERA_TO_OPTICAL, (1.0, 2.0, 3.0)) == pytest.approx((-2.0, -3.0, 1.0))


def test_a_detection_carries_the_object_id_class_visible_box_and_optical_pose():
    yaw = 0.3                        # the object turned left about the camera's z (up)
    found = RecognitionObject(
        7, 7, 'car', (10.0, 1.0, -0.5), (0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2)),
        (4.0, 1.8, 1.5), (1.8, 1.5), (100, 40, 139, 69), 900, (0.0, 0.0, 0.5))
    reading = SimpleNamespace(objects=(found,))
    message = pm.detection_2d_array_builder(msg, 'cam_optical')(STAMP, reading)
    assert message.header.frame_id == 'cam_optical' and message.header.stamp.sec == 3
    (detection,) = message.detections
    assert detection.id == '7' and detection.header.frame_id == 'cam_optical'
    assert (detection.bbox.center.position.x, detection.bbox.center.position.y,
            detection.bbox.center.theta) == (119.5, 54.5, 0.0)
    assert (detection.bbox.size_x, detection.bbox.size_y) == (40.0, 30.0)
    (result,) = detection.results
    assert (result.hypothesis.class_id, result.hypothesis.score) == ('car', 1.0)
    pose = result.pose.pose
    assert (pose.position.x, pose.position.y, pose.position.z) == pytest.approx(
        (-1.0, 0.5, 10.0))
    # the object's forward axis: in the camera frame (cos yaw, sin yaw, 0); in the optical frame
    # (-sin yaw, 0, cos yaw)
    q = (pose.orientation.x, pose.orientation.y, pose.orientation.z, pose.orientation.w)
    assert rotate(q, (1.0, 0.0, 0.0)) == pytest.approx((-math.sin(yaw), 0.0, math.cos(yaw)))


def test_images_are_mono16_little_endian_and_the_label_table_complete():
    semantic = np.array([[0, 7], [15, 14]], dtype=np.uint8)
    instance = np.array([[0, 513], [0, 0]], dtype=np.uint16)
    reading = SimpleNamespace(semantic=semantic, instance=instance)
    image = pm.instance_image_builder(msg, 'o')(STAMP, reading)
    assert (image.encoding, image.is_bigendian, image.step, image.width, image.height) == (
        'mono16', 0, 4, 2, 2)
    assert bytes(image.data) == bytes([0, 0, 1, 2, 0, 0, 0, 0])
    labels = pm.semantic_image_builder(msg, 'o')(STAMP, reading)
    assert np.frombuffer(bytes(labels.data), '<u2').tolist() == [0, 7, 15, 14]
    table = pm.label_info_builder(msg, 'o')(STAMP, LABELS)
    assert [(c.class_id, c.class_name) for c in table.class_map] == [
        (label.id, label.name) for label in LABELS]
    assert table.threshold == 0.0
