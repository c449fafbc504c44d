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
A range finder over the wire: the 32FC1 depth image, its camera_info and the organized cloud.

The automobile node runs test/data/depth_course.yaml (a range finder and a camera of the same
view 1.5 m ahead of base_link, 1.3 m up, the wall's face 18 m ahead) in a subprocess,
synchronous; the test steps it and reads the topics with its own DdsNode.
"""

from pathlib import Path

from automobile_helpers import automobile_fixtures, stamp_of
import numpy as np
import pytest
from test_ros_sensors import Listener

pytestmark = pytest.mark.transport

NAMESPACE = 'deep'
WORLD = str(Path(__file__).resolve().parent / 'data' / 'depth_course.yaml')
TOPICS = {
    'depth_cam/depth/image_raw': ('sensor_msgs/msg/Image',),
    'depth_cam/depth/camera_info': ('sensor_msgs/msg/CameraInfo',),
    'depth_cam/depth/points': ('sensor_msgs/msg/PointCloud2',),
    'camera/image_raw': ('sensor_msgs/msg/Image',),
}

course, tester, car = automobile_fixtures(
    'depth_tester', ['--ros-args', '-r', f'__ns:=/{NAMESPACE}', '-p', f'world:={WORLD}',
                     '-p', 'synchronous:=true'],
    ['/clock'], NAMESPACE, names=('course', 'tester', 'car'))


@pytest.fixture(scope='module')
def received(car, tester):
    listener = Listener(tester, f'/{NAMESPACE}', TOPICS)
    listener.wait_matched()
    assert car.call('robot/time_step', 200).success          # 5 Hz: one sample at 0.2 s
    assert listener.wait_counts({topic: 1 for topic in TOPICS})
    return {topic: messages[-1] for topic, messages in listener.received.items()}


def test_depth_image_is_32fc1_metres_with_rep_118_inf_for_the_sky(received):
    image = received['depth_cam/depth/image_raw']
    assert (image.width, image.height, image.encoding, image.is_bigendian, image.step) == \
        (64, 48, '32FC1', 0, 4 * 64)
    assert image.header.frame_id == 'depth_cam_optical' and stamp_of(image) == 0.2
    depth = np.frombuffer(bytes(image.data), '<f4').reshape(48, 64)
    assert depth[24, 32] == pytest.approx(18.0, abs=0.02)           # the wall's face
    assert np.isposinf(depth[0]).all()                               # the sky: +inf
    assert np.isfinite(depth[-1]).all()                              # the ground, the bonnet


def test_depth_camera_info_and_points_match_the_image(received):
    image, info = received['depth_cam/depth/image_raw'], received['depth_cam/depth/camera_info']
    cloud = received['depth_cam/depth/points']
    focal = 32.0 / np.tan(0.5)
    assert list(info.k) == pytest.approx([focal, 0, 31.5, 0, focal, 23.5, 0, 0, 1])
    assert (info.width, info.height, info.header.frame_id) == (64, 48, 'depth_cam_optical')
    assert (cloud.height, cloud.width, cloud.point_step, cloud.row_step, cloud.is_dense) == \
        (48, 64, 12, 12 * 64, False)
    assert [(f.name, f.offset) for f in cloud.fields] == [('x', 0), ('y', 4), ('z', 8)]
    assert cloud.header.frame_id == 'depth_cam_optical'
    points = np.frombuffer(bytes(cloud.data), '<f4').reshape(48, 64, 3)
    depth = np.frombuffer(bytes(image.data), '<f4').reshape(48, 64)
    assert points[24, 40, 2] == depth[24, 40]
    assert points[24, 40, 0] == pytest.approx((40 - 31.5) * depth[24, 40] / focal, rel=1e-5)
    assert np.isnan(points[0]).all()


def test_the_camera_of_the_same_view_publishes_its_frame_at_the_same_stamp(received):
    colour = received['camera/image_raw']
    assert stamp_of(colour) == stamp_of(received['depth_cam/depth/image_raw'])
    assert (colour.width, colour.height, colour.encoding) == (64, 48, 'rgb8')
