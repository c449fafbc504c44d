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
Traffic objects of every class over the wire: their ObjectClassification labels and shapes.

The node runs the highway with a traffic engine registered by the test (test/traffic_helpers.py:
the builtin bodies, each vehicle of a given object class); a client node reads
/perception/object_recognition/objects and /sim/traffic/markers: each object carries its class's
label (autoware_perception_msgs/ObjectClassification), a pedestrian an upright CYLINDER of its
diameter and height, the rest a BOUNDING_BOX; the markers are CYLINDERs and CUBEs alike.
"""

import copy
import math

from automobile_helpers import client_node, wait_for
import pytest
from traffic_helpers import register_classes_engine, WALKER_M
import yaml

from vehicle_msgs_py import message_type
from vehicle_sim.config import read_yaml, world_path
from vehicle_sim.core.traffic.objects import CLASS_SHAPES, OBJECT_CLASSES, TrafficObject
from vehicle_sim.physics.body_labels import instance_uuid
from vehicle_sim.ros import traffic_messages as tm
from vehicle_sim.ros.traffic_interfaces import PREDICTED_OBJECTS_TOPIC, TRAFFIC_MARKERS
from vehicle_sim.transport.qos import QosProfile

pytestmark = pytest.mark.transport

CLASSES = ['car', 'pedestrian', 'truck', 'bus', 'trailer', 'motorcycle', 'bicycle']
# autoware_perception_msgs/ObjectClassification's labels, as the .msg defines them
LABELS = {'car': 1, 'truck': 2, 'bus': 3, 'trailer': 4, 'motorcycle': 5, 'bicycle': 6,
          'pedestrian': 7}


def test_each_class_has_the_label_of_its_name_in_object_classification():
    classification = message_type(tm.OBJECT_CLASSIFICATION)
    assert tuple(tm.LABEL_OF_CLASS) == OBJECT_CLASSES == tuple(CLASS_SHAPES)
    for name, label in tm.LABEL_OF_CLASS.items():
        assert label == getattr(classification, name.upper()) == LABELS[name], name
    assert CLASS_SHAPES == {**{name: 'box' for name in OBJECT_CLASSES},
                            'pedestrian': 'cylinder'}


def test_an_object_of_an_unknown_class_is_refused_naming_it():
    with pytest.raises(ValueError, match=r"object_class 'horse' of 'traffic_0': unknown; "
                                         r'valid: car, truck, bus, trailer, motorcycle, '
                                         r'bicycle, pedestrian'):
        TrafficObject(0, 'traffic_0', 0.0, 0.0, 0.0, 0.0, 4.0, 2.0, 1.5, (), 0.5, 'horse')


def test_a_cylinder_objects_size_is_its_diameter_twice_and_its_height():
    walker = TrafficObject(0, 'p', 0.0, 0.0, 0.0, 1.0, 0.3, 0.6, 1.7, (), 0.5, 'pedestrian')
    car = TrafficObject(1, 'c', 0.0, 0.0, 0.0, 1.0, 4.5, 1.8, 1.5, (), 0.5)
    assert (walker.shape, walker.size_m) == ('cylinder', (0.6, 0.6, 1.7))
    assert (car.shape, car.size_m) == ('box', (4.5, 1.8, 1.5))


def test_objects_and_markers_carry_each_vehicles_class_over_the_wire(tmp_path, monkeypatch):
    from vehicle_sim.ros.automobile_node import AutomobileNode
    register_classes_engine(monkeypatch)
    data = copy.deepcopy(read_yaml(world_path('highway')))
    data['traffic'] = {'engine': 'classes', 'vehicles': len(CLASSES), 'seed': 2,
                       'classes': CLASSES}
    path = tmp_path / 'classes.yaml'
    path.write_text(yaml.safe_dump(data), encoding='utf-8')
    node = AutomobileNode(['x', '--ros-args', '-r', '__ns:=/classes'], transport='dds',
                          parameter_overrides={'synchronous': True, 'world': str(path)})
    received = {PREDICTED_OBJECTS_TOPIC.name: [], TRAFFIC_MARKERS.name: []}
    try:
        with client_node('classes_listener') as client:
            subs = [client.create_subscription(row.ros_type, row.name, received[row.name].append,
                                               QosProfile(depth=100))
                    for row in (PREDICTED_OBJECTS_TOPIC, TRAFFIC_MARKERS)]
            assert wait_for(lambda: all(s.get_publisher_count() for s in subs), spin=client)
            node.step(10)
            assert wait_for(lambda: all(received.values()), spin=client)
        manager = node.scene.parts['traffic'].manager
        vehicles = [v for v in manager.vehicles if v.active]
    finally:
        node.close()
    objects = received[PREDICTED_OBJECTS_TOPIC.name][-1].objects
    markers = received[TRAFFIC_MARKERS.name][-1].markers
    assert len(objects) == len(markers) == len(vehicles) == len(CLASSES)
    diameter, height = WALKER_M
    for v, item, marker in zip(vehicles, objects, markers):
        name = CLASSES[v.index % len(CLASSES)]
        assert bytes(item.object_id.uuid) == instance_uuid(node.world.labels.instance(v.name))
        assert [(c.label, c.probability) for c in item.classification] == \
            [(LABELS[name], 1.0)], name
        dimensions = item.shape.dimensions
        z = item.kinematics.initial_pose_with_covariance.pose.position.z
        assert marker.id == v.index
        if name == 'pedestrian':
            assert item.shape.type == 1                                      # CYLINDER
            assert (dimensions.x, dimensions.y, dimensions.z) == (diameter, diameter, height)
            assert marker.type == 3                                          # CYLINDER
            assert (marker.scale.x, marker.scale.y, marker.scale.z) == \
                (diameter, diameter, height)
            assert z == marker.pose.position.z == 0.5 * height
        else:
            assert item.shape.type == 0                                      # BOUNDING_BOX
            assert (dimensions.x, dimensions.y) == pytest.approx((v.length_m, v.width_m))
            assert marker.type == 1                                          # CUBE
            assert (marker.scale.x, marker.scale.y) == pytest.approx((v.length_m, v.width_m))
        assert math.isclose(marker.pose.position.x, item.kinematics
                            .initial_pose_with_covariance.pose.position.x, abs_tol=1e-9)
