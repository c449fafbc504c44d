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
Every frame a message of the automobile node names is a frame of its tree, over the wire.

The node runs in a subprocess (synchronous) on a world with ``roads:`` and no ``map:`` (so no
``map`` frame, docs/maps.md), traffic, an obstacle and a namespaced car with every default
sensor mounted. The test finds the node's topics on the graph, subscribes to each with its
writer's QoS, steps the world and collects every ``frame_id`` and ``child_frame_id`` of every
message received; each must reach the root of the tree that ``/tf_static`` and ``/tf`` make.
"""

import copy
import dataclasses

from automobile_helpers import client_node, NodeProcess, wait_for
import pytest
import yaml

from vehicle_sim.config import read_yaml, world_path
from vehicle_sim.transport.dds.graph import GraphView
from vehicle_sim.transport.qos import (
    BEST_EFFORT,
    QosProfile,
    RELIABLE,
    TRANSIENT_LOCAL,
    VOLATILE,
)

pytestmark = pytest.mark.transport

NAMESPACE = 'framed'
FRAME_FIELDS = ('frame_id', 'child_frame_id')


def frames_of(msg):
    """Yield every frame_id and child_frame_id of a message, nested fields included."""
    for field in dataclasses.fields(msg):
        value = getattr(msg, field.name)
        if field.name in FRAME_FIELDS:
            yield value
        elif dataclasses.is_dataclass(value):
            yield from frames_of(value)
        elif isinstance(value, (list, tuple)) and value and dataclasses.is_dataclass(value[0]):
            for item in value:
                yield from frames_of(item)


def root_of(frame, parents):
    """Return the root a frame reaches through ``parents`` ({child: parent}), or None."""
    seen = set()
    while frame in parents:
        if frame in seen:
            return None
        seen.add(frame)
        frame = parents[frame]
    return frame


@pytest.fixture(scope='module')
def world(tmp_path_factory):
    data = copy.deepcopy(read_yaml(world_path('highway_traffic')))
    data['vehicles'][0]['namespace'] = 'ego'
    data['traffic']['vehicles'] = 5
    data['obstacles'] = [{'name': 'cone', 'shape': 'cylinder', 'radius': 0.2, 'height': 0.7,
                          'position': [50.0, -14.0, 0.35]}]
    assert 'map' not in data and data['roads']
    path = tmp_path_factory.mktemp('framed') / 'roads_traffic.yaml'
    path.write_text(yaml.safe_dump(data), encoding='utf-8')
    return path


def test_every_frame_a_topic_names_resolves_through_tf_static_and_tf(world):
    with NodeProcess('--ros-args', '-r', f'__ns:=/{NAMESPACE}', '-p', f'world:={world}',
                     '-p', 'synchronous:=true', '-p', "sensors:=['all']") as process, \
            GraphView() as graph, client_node('frame_checker') as client:
        step_service = f'/{NAMESPACE}/ego/robot/time_step'
        assert graph.wait_until(lambda: graph.service_servers(step_service)
                                and graph.publishers('/perception/object_recognition/objects'),
                                60.0), process.text()
        graph.wait(1.0)      # every writer of the node announced
        writers = {}
        for topic in graph.topics():
            for endpoint in graph.publishers(topic):
                writers[topic] = endpoint
        received = {topic: [] for topic in writers}
        subs = []
        for topic, endpoint in writers.items():
            qos = QosProfile(depth=100, reliability=RELIABLE if endpoint.reliable else BEST_EFFORT,
                             durability=TRANSIENT_LOCAL if endpoint.transient_local else
                             VOLATILE)
            subs.append(client.create_subscription(
                endpoint.ros_type, topic, received[topic].append, qos))
        assert wait_for(lambda: all(s.get_publisher_count() for s in subs), spin=client)
        caller = client.create_client('vehicle_msgs/srv/SetInt', step_service)
        assert caller.wait_for_service(60.0)
        request = client.srv('vehicle_msgs/srv/SetInt').Request()
        request.value = 500      # ms: every periodic topic publishes, the objects at 10 Hz
        assert caller.call(request, 60.0).success
        must = ('/tf', '/tf_static', '/perception/object_recognition/objects',
                '/sim/traffic/markers', '/map/lanes', f'/{NAMESPACE}/ego/odom',
                f'/{NAMESPACE}/ego/scan', f'/{NAMESPACE}/ego/camera/image_raw')
        assert wait_for(lambda: all(received[name] for name in must), spin=client), \
            [name for name in must if not received[name]]
        client.spin_once(0.5)
    parents = {}
    for msg in received['/tf_static'] + received['/tf']:
        for transform in msg.transforms:
            parents[transform.child_frame_id] = transform.header.frame_id
    roots = {root_of(frame, parents) for frame in parents}
    assert roots == {'world'}, parents
    named = {}
    for topic, messages in received.items():
        for msg in messages:
            for frame in frames_of(msg):
                named.setdefault(frame, set()).add(topic)
    named.pop('', None)       # no frame (a message about no place, e.g. /parameter_events)
    # the objects, the markers and the lanes in world (no map frame), the car and its sensors
    assert {'world', 'ego/odom', 'ego/base_link', 'ego/lidar', 'ego/camera_optical',
            'ego/imu', 'ego/gnss'} <= set(named)
    assert named['world'] >= {'/perception/object_recognition/objects', '/sim/traffic/markers',
                              '/map/lanes', '/tf_static'}
    unresolved = {frame: sorted(topics) for frame, topics in named.items()
                  if root_of(frame, parents) != 'world'}
    assert unresolved == {}
