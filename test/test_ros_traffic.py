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
The traffic topics of the automobile node (ros/traffic_interfaces.py) over the wire.

The node runs the shipped highway_traffic world in this process (synchronous, embedded DDS); a
client node subscribes to /perception/object_recognition/objects and /sim/traffic/markers. Each
message holds one object / marker per traffic vehicle on the map, with the types, frames and
QoS of the rows; the objects are where the world's traffic vehicles are.
"""

import math

from automobile_helpers import client_node, wait_for
import pytest

from vehicle_sim.physics.body_labels import instance_uuid
from vehicle_sim.ros.traffic_interfaces import (
    PREDICTED_OBJECTS_TOPIC,
    QOS_OBJECTS,
    TRAFFIC_MARKERS,
    TRAFFIC_TOPICS,
)
from vehicle_sim.transport.qos import QosProfile

pytestmark = pytest.mark.transport

# A subscription keeping every message of a burst of steps (the rows' own depth is 1).
KEEP_ALL = QosProfile(depth=1000)


@pytest.fixture(scope='module')
def app():
    from vehicle_sim.ros.automobile_node import AutomobileNode
    node = AutomobileNode(['x', '--ros-args', '-r', '__ns:=/traffic_test'], transport='dds',
                          parameter_overrides={'synchronous': True,
                                               'world': 'highway_traffic'})
    node.initial_traffic = [(v.lane, v.s_m, v.speed_mps)
                            for v in node.scene.parts['traffic'].manager.vehicles]
    yield node
    node.close()


def test_the_traffic_rows_are_wired_with_their_types_and_qos(app):
    publishers = app._traffic_outputs.publishers
    assert tuple(publishers) == TRAFFIC_TOPICS
    assert PREDICTED_OBJECTS_TOPIC.ros_type == \
        'autoware_perception_msgs/msg/PredictedObjects'
    assert TRAFFIC_MARKERS.ros_type == 'visualization_msgs/msg/MarkerArray'
    assert {row.qos for row in publishers} == {QOS_OBJECTS}
    assert QOS_OBJECTS.depth == 1


def test_objects_and_markers_over_the_wire_match_the_world(app):
    received = {row.name: [] for row in TRAFFIC_TOPICS}
    with client_node('traffic_listener') as client:
        subs = [client.create_subscription(row.ros_type, row.name,
                                           lambda msg, key=row.name: received[key].append(msg),
                                           QOS_OBJECTS) for row in TRAFFIC_TOPICS]
        assert wait_for(lambda: all(s.get_publisher_count() for s in subs), spin=client)
        app.step(10)
        assert wait_for(lambda: all(received.values()), spin=client)
        objects = received[PREDICTED_OBJECTS_TOPIC.name][-1]
        markers = received[TRAFFIC_MARKERS.name][-1]
    manager = app.scene.parts['traffic'].manager
    on_map = [v for v in manager.vehicles if v.active]
    assert len(objects.objects) == len(on_map) == 60
    assert objects.header.frame_id == 'world'     # roads:, no map: (test_ros_frames.py)
    assert objects.header.stamp.nanosec == 100_000_000     # 10 steps of 10 ms
    first = objects.objects[0]
    v = on_map[0]
    assert bytes(first.object_id.uuid) == instance_uuid(
        app.world.labels.of(app.scene.parts['traffic'].body_of(v.name))[1])
    assert [(c.label, c.probability) for c in first.classification] == [(1, 1.0)]   # CAR
    pose = first.kinematics.initial_pose_with_covariance.pose
    # where it is at the stamp: the manager's last update (at 0 s) gone on straight 0.1 s
    assert app.scene.parts['traffic'].since_update_s == pytest.approx(0.1)
    x, y, yaw = manager.pose(v)
    gone = v.speed_mps * 0.1
    assert gone > 1.0
    assert (pose.position.x, pose.position.y) == pytest.approx(
        (x + gone * math.cos(yaw), y + gone * math.sin(yaw)), abs=1e-9)
    assert first.kinematics.initial_twist_with_covariance.twist.linear.x == \
        pytest.approx(v.speed_mps)
    assert first.shape.type == 0                       # BOUNDING_BOX
    assert first.shape.dimensions.x == pytest.approx(v.length_m)
    path = first.kinematics.predicted_paths[0]
    assert len(path.path) == 10 and path.time_step.nanosec == 500_000_000
    assert markers.markers[0].header.frame_id == 'world'
    assert len(markers.markers) == 60
    assert {m.ns for m in markers.markers} == {'traffic'}
    assert sorted(m.id for m in markers.markers) == [v.index for v in on_map]


CONE = {'name': 'cone', 'shape': 'cylinder', 'radius': 0.2, 'height': 0.7,
        'position': [50.0, -14.0, 0.35]}


def run_highway(tmp_path, name, steps, parameters=None, **keys):
    """
    Run the highway with ``keys`` added to its world file ``steps`` steps.

    :return: (the node's object rows (its publishers), {row name: the messages a client node
        received}, its World, closed).
    """
    import copy

    import yaml

    from vehicle_sim.config import read_yaml, world_path
    from vehicle_sim.ros.automobile_node import AutomobileNode
    data = copy.deepcopy(read_yaml(world_path('highway')))
    data.update(keys)
    path = tmp_path / f'{name}.yaml'
    path.write_text(yaml.safe_dump(data), encoding='utf-8')
    node = AutomobileNode(['x', '--ros-args', '-r', f'__ns:=/{name}'], transport='dds',
                          parameter_overrides={'synchronous': True, 'world': str(path),
                                               **(parameters or {})})
    try:
        rows = tuple(node._traffic_outputs.publishers)
        received = {row.name: [] for row in rows}
        with client_node(f'{name}_listener') as client:
            subs = [client.create_subscription(row.ros_type, row.name, received[row.name].append,
                                               KEEP_ALL) for row in rows]
            assert wait_for(lambda: all(s.get_publisher_count() for s in subs), spin=client)
            node.step(steps)
            assert wait_for(lambda: all(received.values()), spin=client)
            client.spin_once(0.2)      # the last ones, if any
        return rows, received, node.world
    finally:
        node.close()


def objects_of_highway(tmp_path, name, **keys):
    """Run the highway with ``keys`` added to its world file; return (rows, objects, world)."""
    rows, received, world = run_highway(tmp_path, name, 10, **keys)
    return rows, received[PREDICTED_OBJECTS_TOPIC.name][-1].objects, world


def stamps(messages):
    """Return the stamps [s] of PredictedObjects or of MarkerArrays (their first marker's)."""
    headers = [m.markers[0].header if hasattr(m, 'markers') else m.header for m in messages]
    return [h.stamp.sec + h.stamp.nanosec * 1e-9 for h in headers]


def test_objects_and_markers_come_every_0_1_s_of_simulated_time_by_default(app):
    received = {row.name: [] for row in TRAFFIC_TOPICS}
    with client_node('traffic_rate') as client:
        subs = [client.create_subscription(row.ros_type, row.name,
                                           lambda msg, key=row.name: received[key].append(msg),
                                           KEEP_ALL) for row in TRAFFIC_TOPICS]
        assert wait_for(lambda: all(s.get_publisher_count() for s in subs), spin=client)
        start_s = app.world.time_s
        app.step(45)                   # 10 ms steps: 0.45 s, 4 or 5 objects at 10 Hz
        assert wait_for(lambda: all(len(v) >= 4 for v in received.values()), spin=client)
        client.spin_once(0.2)
    for name, messages in received.items():
        times = stamps(messages)
        assert len(times) == 4 + (round(start_s * 100) % 10 >= 5), (name, times)
        assert [b - a for a, b in zip(times, times[1:])] == pytest.approx(
            [0.1] * (len(times) - 1), abs=1e-9), name
        # on the grid of 0.1 s of simulated time from the node's start
        assert [t * 10.0 for t in times] == pytest.approx([round(t * 10.0) for t in times],
                                                          abs=1e-6)


@pytest.mark.parametrize('parameters, traffic, period_s', [
    ({'objects_rate': 4.0}, {}, 0.25),                                # the node's parameter
    ({'objects_rate': 4.0}, {'objects_rate': 20.0}, 0.05),            # the world's wins
])
def test_the_objects_rate_sets_the_period_of_objects_and_markers(tmp_path, parameters,
                                                                  traffic, period_s):
    name = f'rate_{int(1 / period_s)}'
    _, received, _ = run_highway(tmp_path, name, 100, parameters,
                              traffic={'vehicles': 3, 'seed': 2, **traffic})
    for topic, messages in received.items():
        times = stamps(messages)
        assert len(times) == round(1.0 / period_s), (topic, times)
        assert times == pytest.approx([period_s * (k + 1) for k in range(len(times))],
                                      abs=1e-9), topic


def test_a_world_with_obstacles_and_no_traffic_publishes_its_obstacles_as_objects(tmp_path):
    rows, objects, world = objects_of_highway(tmp_path, 'cone_only', obstacles=[CONE])
    assert rows == (PREDICTED_OBJECTS_TOPIC,)          # the objects, not the traffic markers
    cone = world.labels.of(world.obstacles['cone'])         # (label, instance) of its body
    assert [bytes(o.object_id.uuid) for o in objects] == [instance_uuid(cone[1])]
    assert cone[1] > 0
    assert [o.classification[0].label for o in objects] == [0]          # UNKNOWN


def test_docs_hold_the_traffic_topic_table():
    from pathlib import Path

    from vehicle_sim.ros.traffic_interfaces import traffic_topic_table_markdown
    text = (Path(__file__).resolve().parent.parent / 'docs' / 'traffic.md').read_text('utf-8')
    assert traffic_topic_table_markdown() in text


def test_sim_reset_starts_the_traffic_again(app):
    app.step(20)
    traffic = app.scene.parts['traffic']
    assert [(v.lane, v.s_m) for v in traffic.manager.vehicles] != \
        [(lane, s) for lane, s, _ in app.initial_traffic]
    message = app.reset()
    assert 'traffic: its 60 vehicles back at their start' in message
    assert [(v.lane, v.s_m, v.speed_mps) for v in traffic.manager.vehicles] == \
        app.initial_traffic
    # the boxes are back too
    import pybullet
    v = traffic.manager.vehicles[0]
    position, _ = pybullet.getBasePositionAndOrientation(
        traffic.body_ids[0], physicsClientId=app.world.client_id)
    assert position[:2] == pytest.approx(traffic.manager.pose(v)[:2], abs=1e-9)


def test_obstacles_of_a_traffic_world_are_objects_too(tmp_path):
    rows, objects, world = objects_of_highway(tmp_path, 'traffic_cone', obstacles=[CONE],
                                       traffic={'vehicles': 3, 'seed': 2})
    assert rows == TRAFFIC_TOPICS
    assert [o.classification[0].label for o in objects] == [1, 1, 1, 0]
    cone = objects[-1]
    # the UUID of the cone's instance id, that of the cone's body (its lidar points, pixels)
    assert bytes(cone.object_id.uuid) == instance_uuid(
        world.labels.of(world.obstacles['cone'])[1])
    assert len({bytes(o.object_id.uuid) for o in objects}) == 4
    position = cone.kinematics.initial_pose_with_covariance.pose.position
    assert (position.x, position.y, position.z) == (50.0, -14.0, 0.35)
    assert (cone.shape.type, cone.shape.dimensions.z) == (1, 0.7)
