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
A labelled lidar's PointCloud2 over the wire: fields intensity, label and instance.

The node runs the obstacle course with a 4-layer lidar with ``labels: true``; a client node
reads ``/labelled/points``: the rays at 0 rad meet the wall's near face head on (x = 19.5 m):
label ``obstacle``, the wall's instance id, intensity its reflectivity (cos 0 = 1).
"""

import copy

from automobile_helpers import client_node, wait_for
import numpy as np
import pytest
import yaml

from vehicle_sim.config import read_yaml, world_path
from vehicle_sim.core.sensors.labels import LABEL_IDS, LABELS
from vehicle_sim.ros.messages import LABELLED_POINT
from vehicle_sim.ros.sensor_interfaces import QOS_SENSOR

pytestmark = pytest.mark.transport

LIDAR = {'type': 'lidar', 'name': 'lidar', 'pose': {'x': 1.0, 'y': 0.0, 'z': 1.0},
         'fov': 0.4, 'horizontal_resolution': 41, 'layers': 4, 'vertical_fov': 0.06,
         'max_range': 50.0, 'rate_hz': 10.0, 'labels': True}


def test_the_labelled_cloud_carries_the_walls_label_instance_and_intensity(tmp_path):
    from vehicle_sim.ros.automobile_node import AutomobileNode
    data = copy.deepcopy(read_yaml(world_path('obstacle_course')))
    data['vehicles'][0]['sensors'] = [LIDAR]
    path = tmp_path / 'labelled.yaml'
    path.write_text(yaml.safe_dump(data), encoding='utf-8')
    node = AutomobileNode(['x', '--ros-args', '-r', '__ns:=/labelled'], transport='dds',
                          parameter_overrides={'synchronous': True, 'world': str(path)})
    received = []
    try:
        with client_node('labelled_listener') as client:
            sub = client.create_subscription('sensor_msgs/msg/PointCloud2', '/labelled/points',
                                             received.append, QOS_SENSOR)
            assert wait_for(lambda: sub.get_publisher_count(), spin=client)
            node.step(10)
            assert wait_for(lambda: received, spin=client)
        wall = node.world.labels.instance('wall')
    finally:
        node.close()
    cloud = received[-1]
    assert [(f.name, f.offset, f.datatype) for f in cloud.fields] == [
        ('x', 0, 7), ('y', 4, 7), ('z', 8, 7), ('intensity', 12, 7), ('label', 16, 4),
        ('instance', 18, 4)]                          # FLOAT32 = 7, UINT16 = 4
    assert (cloud.height, cloud.width, cloud.point_step) == (4, 41, 20)
    points = np.frombuffer(bytes(cloud.data), dtype=LABELLED_POINT).reshape(4, 41)
    middle = points[:, 20]                              # azimuth 0 rad, every layer
    assert middle['x'] == pytest.approx(np.full(4, 18.5), rel=1e-3)
    assert middle['label'].tolist() == [LABEL_IDS['obstacle']] * 4
    assert middle['instance'].tolist() == [wall] * 4 and wall > 0
    reflectivity = LABELS[LABEL_IDS['obstacle']].reflectivity
    assert middle['intensity'] == pytest.approx(np.full(4, reflectivity), rel=1e-3)
