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
Message builders of a camera's segmentation and recognition (the rows: ros/sensor_interfaces.py).

- the semantic and instance images: sensor_msgs/Image ``mono16`` (little-endian): label ids
  (core/sensors/labels.py) and object ids (0 = none);
- the detections: vision_msgs/Detection2DArray, one Detection2D per recognised object: ``id``
  its object id as text, ``bbox`` the box of its visible pixels (centre in pixel coordinates,
  integers at pixel centres; size in pixels; theta 0), one result with ``class_id`` its label
  name, ``score`` 1.0 and the pose of its box's centre in the image's optical frame;
- the label table: vision_msgs/LabelInfo, ``class_map`` every label's id and name, published
  once, latched; ``threshold`` 0 (every score is 1.0: ground truth). The table's ``none`` is id
  0, not vision_msgs' 65535 "unlabeled" convention.
"""

from array import array

from vehicle_sim.core.geometry.frames import quaternion_multiply, rotate
from vehicle_sim.ros.messages import HEADER, IMAGE

DETECTION_2D_ARRAY = 'vision_msgs/msg/Detection2DArray'
DETECTION_2D = 'vision_msgs/msg/Detection2D'
OBJECT_HYPOTHESIS_WITH_POSE = 'vision_msgs/msg/ObjectHypothesisWithPose'
LABEL_INFO = 'vision_msgs/msg/LabelInfo'
VISION_CLASS = 'vision_msgs/msg/VisionClass'
# The camera frame (x forward, y left, z up) seen from the optical one (z forward, x right,
# y down): v_optical = rotate(CAMERA_TO_OPTICAL, v_camera).
CAMERA_TO_OPTICAL = (0.5, -0.5, 0.5, 0.5)


def _mono16_builder(msg, frame_id, attr):
    header_type, image_type = msg(HEADER), msg(IMAGE)

    def build(stamp, reading):
        image = getattr(reading, attr)
        height, width = image.shape
        data = image.astype('<u2', copy=False).tobytes()
        return image_type(header=header_type(stamp=stamp, frame_id=frame_id), height=height,
                          width=width, encoding='mono16', is_bigendian=0, step=2 * width,
                          data=array('B', data))
    return build


def semantic_image_builder(msg, frame_id: str):
    """Return ``build(stamp, reading)``: sensor_msgs/Image mono16 of a reading's label ids."""
    return _mono16_builder(msg, frame_id, 'semantic')


def instance_image_builder(msg, frame_id: str):
    """Return ``build(stamp, reading)``: sensor_msgs/Image mono16 of a reading's object ids."""
    return _mono16_builder(msg, frame_id, 'instance')


def detection_2d_array_builder(msg, frame_id: str):
    """Return ``build(stamp, reading)``: vision_msgs/Detection2DArray of a reading's objects."""
    header_type, array_type = msg(HEADER), msg(DETECTION_2D_ARRAY)
    detection_type, result_type = msg(DETECTION_2D), msg(OBJECT_HYPOTHESIS_WITH_POSE)

    def build(stamp, reading):
        detections = []
        for found in reading.objects:
            result = result_type()
            result.hypothesis.class_id = found.model
            result.hypothesis.score = 1.0
            pose = result.pose.pose
            (pose.position.x, pose.position.y, pose.position.z) = (
                float(v) for v in rotate(CAMERA_TO_OPTICAL, found.position_m))
            (pose.orientation.x, pose.orientation.y, pose.orientation.z,
             pose.orientation.w) = quaternion_multiply(CAMERA_TO_OPTICAL,
                                                       found.orientation_xyzw)
            detection = detection_type(header=header_type(stamp=stamp, frame_id=frame_id),
                                       results=[result], id=str(found.id))
            u, v = found.centre_px
            width, height = found.size_on_image
            detection.bbox.center.position.x, detection.bbox.center.position.y = u, v
            detection.bbox.size_x, detection.bbox.size_y = float(width), float(height)
            detections.append(detection)
        return array_type(header=header_type(stamp=stamp, frame_id=frame_id),
                          detections=detections)
    return build


def label_info_builder(msg, frame_id: str):
    """Return ``build(stamp, labels)``: vision_msgs/LabelInfo of the label table."""
    header_type, info_type, class_type = msg(HEADER), msg(LABEL_INFO), msg(VISION_CLASS)

    def build(stamp, labels):
        return info_type(header=header_type(stamp=stamp, frame_id=frame_id),
                         class_map=[class_type(class_id=label.id, class_name=label.name)
                                    for label in labels], threshold=0.0)
    return build
