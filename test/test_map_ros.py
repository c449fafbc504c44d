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
A world with an occupancy map over the wire: /map, /map_metadata, map -> world, collisions.

The automobile node runs the room of test/map_helpers.py (its grid turned by 0.05 rad, the
world placed in the map by ``world_in_map``) in a subprocess, synchronous. The test node
subscribes only once the node is ready: a late subscriber, which gets /map because the topic is
transient-local, as nav2 map_server's.
"""

import math

from automobile_helpers import automobile_fixtures, stamp_of, wait_for
from map_helpers import (
    ORIGIN,
    RESOLUTION_M,
    ROOM_HEIGHT,
    room_pixels,
    ROOM_WIDTH,
    world_data,
    write_map,
)
import numpy as np
import pytest
import yaml

from vehicle_sim.ros import automobile_interfaces as itf
from vehicle_sim.ros.map_interfaces import MAP, MAP_METADATA
from vehicle_sim.transport.dds.graph import GraphView
from vehicle_sim.transport.qos import QOS_TF_STATIC_LISTENER

pytestmark = pytest.mark.transport

NAMESPACE = 'mapped'
GRID_YAW = 0.05
WORLD_IN_MAP = {'x': 1.0, 'y': 0.5, 'yaw': 0.1}


@pytest.fixture(scope='module')
def world_file(tmp_path_factory):
    folder = tmp_path_factory.mktemp('map_world')
    write_map(folder, origin=[ORIGIN[0], ORIGIN[1], GRID_YAW])
    data = world_data('room.yaml', world_in_map=WORLD_IN_MAP)
    data['vehicles'][0]['name'] = 'Car'
    path = folder / 'world.yaml'
    path.write_text(yaml.safe_dump(data), encoding='utf-8')
    return path


# The car's client: the node is up once /clock comes (/map was published before).
node, tester, car = automobile_fixtures(
    'map_tester', lambda request: ['--ros-args', '-r', f'__ns:=/{NAMESPACE}', '-p',
                                   f'world:={request.getfixturevalue("world_file")}',
                                   '-p', 'synchronous:=true'],
    ['/clock'], NAMESPACE, names=('node', 'tester', 'car'))


def _latched(car, row):
    received = []
    car.node.create_subscription(row.ros_type, row.name, received.append,
                                 row.qos)
    assert wait_for(lambda: received, spin=car.node), f'no {row.name}'
    return received


def test_a_late_subscriber_gets_map_equal_to_the_thresholded_image(car):
    received = _latched(car, MAP)
    grid = received[0]
    assert len(received) == 1
    assert grid.header.frame_id == 'map'
    info = grid.info
    assert (info.width, info.height) == (ROOM_WIDTH, ROOM_HEIGHT)
    assert info.resolution == pytest.approx(RESOLUTION_M)
    assert (info.origin.position.x, info.origin.position.y) == pytest.approx(ORIGIN[:2])
    q = info.origin.orientation
    assert 2.0 * math.atan2(q.z, q.w) == pytest.approx(GRID_YAW)
    # black (0) -> 100, white (254) -> 0; rows from the bottom of the image
    expected = np.where(room_pixels()[::-1] == 0, 100, 0).astype(np.int8).ravel()
    assert np.array_equal(np.asarray(grid.data, dtype=np.int8), expected)
    assert stamp_of(grid) == info.map_load_time.sec + info.map_load_time.nanosec * 1e-9


def test_map_metadata_matches_map(car):
    info = _latched(car, MAP_METADATA)[0]
    assert (info.width, info.height) == (ROOM_WIDTH, ROOM_HEIGHT)
    assert info.resolution == pytest.approx(RESOLUTION_M)


def test_map_is_reliable_transient_local_of_the_occupancy_grid_type(car):
    with GraphView() as graph:
        assert graph.wait_until(lambda: graph.publishers('/map'), 30.0)
        found = {(e.ros_type, e.reliable, e.transient_local)
                 for name in ('map', 'map_metadata')
                 for e in graph.publishers(f'/{name}')}
    assert found == {('nav_msgs/msg/OccupancyGrid', True, True),
                     ('nav_msgs/msg/MapMetaData', True, True)}
    assert MAP.qos.depth == 1 and MAP_METADATA.qos.depth == 1


def test_tf_static_has_map_to_world_from_world_in_map(car):
    transforms = []
    car.node.create_subscription(itf.TF_STATIC.ros_type, '/tf_static',
                                 lambda msg: transforms.extend(msg.transforms),
                                 QOS_TF_STATIC_LISTENER)
    assert wait_for(lambda: transforms, spin=car.node)
    found = [t for t in transforms if t.header.frame_id == 'map']
    assert [t.child_frame_id for t in found] == ['world']
    translation, rotation = found[0].transform.translation, found[0].transform.rotation
    assert (translation.x, translation.y) == pytest.approx((WORLD_IN_MAP['x'],
                                                            WORLD_IN_MAP['y']))
    assert 2.0 * math.atan2(rotation.z, rotation.w) == pytest.approx(WORLD_IN_MAP['yaw'])


def test_driving_at_a_wall_of_the_map_gives_exactly_one_collision_message(car):
    collisions = []
    sub = car.node.create_subscription(itf.COLLISION.ros_type, car.name('collision'),
                                       collisions.append, itf.COLLISION.qos)
    assert wait_for(lambda: sub.get_publisher_count(), spin=car.node)
    car.wait_node_matched()
    assert car.call('automobile/set_cruising_speed', 20.0).success
    for _ in range(16):     # 8 s at 20 km/h: the nose reaches the east wall after about 5 m
        assert car.call('robot/time_step', 500).success
    assert wait_for(lambda: collisions, spin=car.node)
    assert not wait_for(lambda: len(collisions) > 1, timeout_s=2.0, spin=car.node)
    assert collisions[0].other == 'map' and collisions[0].normal_force > 0.0


def test_a_pose_in_the_map_frame_lands_where_world_in_map_puts_it():
    # /initialpose in frame map: the node takes it through map_in_world (ros/sim_control.py)
    from vehicle_sim.core.geometry.frames import quaternion_from_yaw
    from vehicle_sim.core.map.kinds import map_from_dict
    from vehicle_sim.core.world.placement import ground_pose
    from vehicle_sim.ros.map_interfaces import map_in_world
    spec = map_from_dict({'type': 'occupancy_grid', 'file': 'm.yaml',
                          'world_in_map': WORLD_IN_MAP}, 'w.yaml: map')
    place = ground_pose((3.0, -2.0, 0.0), quaternion_from_yaw(0.4), *map_in_world(spec))
    assert (place.x_m, place.y_m) == pytest.approx(spec.world_in_map.to_world(3.0, -2.0))
    assert place.yaw_rad == pytest.approx(0.4 - WORLD_IN_MAP['yaw'])
