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


"""Traffic vehicles as bodies of the physics world (physics/traffic_bodies.py)."""

import copy
import math

import numpy as np
import pytest

from vehicle_sim.config import load_world, read_yaml, world_from_data, world_path
from vehicle_sim.core.map.lane_rules import LaneRules, StopLine, TrafficLightGroup
from vehicle_sim.core.map.signal_plan import SignalController
from vehicle_sim.core.specs.errors import InvalidParameterError, InvalidPoseError
from vehicle_sim.core.traffic.footprints import overlapping
from vehicle_sim.maps.lane_maps import with_lanes
from vehicle_sim.physics.scene import build_scene, mount_suite
from vehicle_sim.physics.sensors import CollisionMonitor
from vehicle_sim.physics.traffic_bodies import model_dimensions

HIGHWAY = read_yaml(world_path('highway'))
MIDDLE = 100002             # the ego's lane: y = -5.625 m, along +x from x = 0
LIDAR = {'name': 'lidar', 'type': 'lidar', 'pose': {'x': 1.0, 'z': 0.5}}


def highway(traffic, sensors=(LIDAR,), x=20.0):
    data = copy.deepcopy(HIGHWAY)
    data['vehicles'][0].update(model='Car', sensors=list(sensors),
                               pose={'x': x, 'y': -5.625, 'yaw': 0.0})
    data['traffic'] = traffic
    return world_from_data(data, 'highway_test.yaml')


@pytest.fixture
def scenes():
    built = []

    def make(spec, **kwargs):
        built.append(build_scene(spec, mount=mount_suite, **kwargs))
        return built[-1]
    yield make
    for scene in built:
        scene.world.close()


def ray_at_zero(scene):
    scan = scene.vehicles['Car'].sensors.sample('lidar')
    angles = scan.angle_min_rad + scan.angle_increment_rad * np.arange(scan.scan.size)
    return float(scan.scan[int(np.argmin(np.abs(angles)))])


def lidar_x(scene):
    # base_link x plus the 1 m mount along the heading (the car stands level within 1e-3 rad)
    return scene.vehicles['Car'].body.pose()[0] + 1.0


def test_the_lidar_ray_at_zero_reads_the_gap_to_the_traffic_car_ahead(scenes):
    scene = scenes(highway({'update_period': 0.01,
                            'placed': [{'model': 'ToyotaPrius', 'lanelet': MIDDLE, 's': 60.0,
                                        'speed': 0.0, 'route': [100102]}]}))
    traffic = scene.parts['traffic']
    manager = traffic.manager
    car = manager.vehicles[0]
    length = model_dimensions('ToyotaPrius')[0]
    manager.stop(0)                        # standing: the gap is fixed
    for _ in range(100):
        scene.world.step()
    expected = manager.pose(car)[0] - length / 2 - lidar_x(scene)
    assert ray_at_zero(scene) == pytest.approx(expected, abs=0.05)
    assert expected == pytest.approx(60.0 - length / 2 - 21.0, abs=0.05)


def test_the_lidar_follows_a_traffic_car_driving_away(scenes):
    scene = scenes(highway({'update_period': 0.05,
                            'placed': [{'model': 'ToyotaPrius', 'lanelet': MIDDLE, 's': 40.0,
                                        'speed': 5.0, 'route': [100102]}]}))
    manager = scene.parts['traffic'].manager
    car = manager.vehicles[0]
    length = model_dimensions('ToyotaPrius')[0]
    readings = []
    for _ in range(300):
        scene.world.step()
        # between the manager's updates (every 5 steps) the box moves on at the car's speed
        since = scene.world.time_s - manager.time_s
        assert 0.0 < since <= 0.05 + 1e-9
        ahead = manager.pose(car)[0] + car.speed_mps * since
        expected = ahead - length / 2 - lidar_x(scene)
        reading = ray_at_zero(scene)
        readings.append(reading)
        assert reading == pytest.approx(expected, abs=0.05)
    assert readings[-1] > readings[0] + 20.0       # it drove away


def test_a_collision_with_our_car_stops_the_traffic_car_and_names_it(scenes):
    # a slow traffic car 15 m ahead; ours drives into it at full throttle
    scene = scenes(highway({'placed': [{'model': 'Car', 'lanelet': MIDDLE, 's': 40.0,
                                        'speed': 1.0, 'speed_factor': 0.05,
                                        'route': [100102]}]}, sensors=()))
    manager = scene.parts['traffic'].manager
    monitor = CollisionMonitor(scene.world, scene.vehicles['Car'].body)
    scene.vehicles['Car'].car.logic.set_gear(1)
    scene.vehicles['Car'].car.logic.set_throttle(1.0)
    events = []
    for _ in range(800):
        scene.world.step()
        events += monitor.fresh
        if manager.vehicles[0].stopped:
            break
    assert manager.vehicles[0].stopped and manager.vehicles[0].speed_mps == 0.0
    assert [e.other for e in events] == ['traffic_0']
    s = manager.vehicles[0].s_m
    traffic = scene.parts['traffic']
    (where, _), *_ = scene.world.body_state(traffic.body_ids[0])
    # its box stands where the manager has it (where it was when it was hit)
    assert where[:2] == pytest.approx(manager.pose(manager.vehicles[0])[:2], abs=1e-9)
    for _ in range(100):
        scene.world.step()
    assert manager.vehicles[0].s_m == s         # it stays, an obstacle
    (after, _), *_ = scene.world.body_state(traffic.body_ids[0])
    assert after == pytest.approx(where, abs=1e-9)      # no jump at the next updates


def test_a_traffic_box_far_from_ours_waits_under_the_ground_until_the_world_is_read(scenes):
    # An update puts the boxes near our vehicles; the far ones wait under the ground (putting
    # every box cost more than the rest of the update), until something reads the world:
    # rays, cameras and body states find each where its vehicle is, moving or standing.
    import pybullet
    scene = scenes(highway({'update_period': 0.1, 'placed': [
        {'model': 'ToyotaPrius', 'lanelet': MIDDLE, 's': 40.0, 'speed': 20.0,
         'route': [100102]},
        {'model': 'ToyotaPrius', 'lanelet': MIDDLE, 's': 400.0, 'speed': 20.0,
         'route': [100102]},
        {'model': 'ToyotaPrius', 'lanelet': MIDDLE, 's': 600.0, 'speed': 0.0,
         'route': [100102]}]}, sensors=()))
    traffic = scene.parts['traffic']
    manager, bodies, cid = traffic.manager, traffic.body_ids, scene.world.client_id
    manager.stop(2)                        # standing: only a read puts it
    for _ in range(25):                    # two updates
        scene.world.step()

    def put_at(index):                     # where Bullet has the box, nothing synced
        return pybullet.getBasePositionAndOrientation(bodies[index], physicsClientId=cid)[0]
    assert put_at(0)[2] > 0.0                              # near ours: put
    assert put_at(1)[2] < -40.0 and put_at(2)[2] < -40.0   # far: under the ground
    for index in (1, 2):
        v = manager.vehicles[index]
        x, y, _ = manager.pose(v)          # along +x: on at its speed since the update
        (where, _), *_ = scene.world.body_state(bodies[index])
        assert where[:2] == pytest.approx((x + v.speed_mps * traffic.since_update_s, y),
                                          abs=1e-9)
        assert where[2] > 0.0
    since = traffic.since_update_s
    while traffic.since_update_s >= since:     # on to the next update
        since = traffic.since_update_s
        scene.world.step()
    assert put_at(1)[2] < -40.0 and put_at(2)[2] < -40.0   # down again


def test_traffic_bodies_are_seen_by_the_teleport_check(scenes):
    scene = scenes(highway({'placed': [{'lanelet': MIDDLE, 's': 60.0, 'speed': 0.0,
                                        'route': [100102]}]}, sensors=()))
    scene.parts['traffic'].manager.stop(0)
    scene.world.step()
    with pytest.raises(InvalidPoseError, match='traffic_0'):
        scene.vehicles['Car'].car.teleport((60.0, -5.625, 0.0))


def test_fifty_traffic_cars_drive_among_the_bodies(scenes):
    scene = scenes(highway({'vehicles': 50, 'seed': 4, 'models': ['ToyotaPrius', 'BmwX5']},
                           sensors=()))
    traffic = scene.parts['traffic']
    assert len(traffic.body_ids) == 50
    assert len(set(scene.world.obstacles) & {f'traffic_{i}' for i in range(50)}) == 50
    start = [v.s_m for v in traffic.manager.vehicles]
    for _ in range(200):
        scene.world.step()
    moved = [v.s_m != s for v, s in zip(traffic.manager.vehicles, start)]
    assert all(moved)
    # updated (to the world's time then) before the physics of the steps that start at
    # 0.1, 0.2, ..., 1.9 s (update_period 0.1 s)
    assert traffic.manager.time_s == pytest.approx(1.9, abs=1e-9)
    assert scene.world.time_s == pytest.approx(2.0)


def test_traffic_without_a_lane_map_or_with_an_odd_update_period_is_refused(scenes):
    data = {'vehicles': [{'name': 'Car'}], 'traffic': {'vehicles': 1}}
    with pytest.raises(InvalidParameterError,
                       match=r'w\.yaml: traffic: traffic needs a lane map \(roads:'):
        scenes(world_from_data(data, 'w.yaml'))
    with pytest.raises(InvalidParameterError,
                       match=r"highway_test\.yaml: traffic: field 'update_period' = 0\.015: "
                             r'must be a multiple of the world step'):
        scenes(highway({'vehicles': 1, 'update_period': 0.015}))


def test_no_traffic_key_no_traffic_part(scenes):
    scene = scenes(highway(None, sensors=()))
    assert 'traffic' not in scene.parts
    assert not any(name.startswith('traffic_') for name in scene.world.obstacles)
    assert math.isfinite(scene.world.step())


def test_the_shipped_highway_traffic_world_builds_and_drives(scenes):
    from vehicle_sim.config import load_world
    scene = scenes(load_world('highway_traffic'))
    traffic = scene.parts['traffic']
    assert len(traffic.body_ids) == 60
    for _ in range(100):
        scene.world.step()
    assert traffic.manager.time_s == pytest.approx(0.9)
    assert not any(v.stopped for v in traffic.manager.vehicles)


def test_a_car_at_a_dead_end_re_enters_at_the_start_of_an_entry_lane(scenes):
    scene = scenes(highway({'placed': [{'lanelet': 100402, 's': 590.0, 'speed': 20.0}]},
                           sensors=()))
    traffic = scene.parts['traffic']
    car = traffic.manager.vehicles[0]
    for _ in range(200):
        scene.world.step()
    # the highway's entry lanes: forward lanes of its first segment, backward of its last
    assert car.active and car.lane in (100001, 100002, 100003, 100451, 100452, 100453)
    assert car.s_m < 100.0
    (position, _), *_ = scene.world.body_state(traffic.body_ids[0])
    # the box, as anything reading the world sees it: the manager's pose moved on at the
    # car's velocity since its last update
    x, y, yaw = traffic.manager.pose(car)
    since = scene.world.time_s - traffic.manager.time_s
    assert position[:2] == pytest.approx((x + car.speed_mps * since * math.cos(yaw),
                                          y + car.speed_mps * since * math.sin(yaw)), abs=0.01)
    assert position[2] > 0.0


def test_the_camera_shows_the_traffic_car_ahead_in_its_colour(scenes):
    from vehicle_sim.physics.traffic_bodies import COLOURS
    camera = {'name': 'camera', 'type': 'camera', 'pose': {'x': 1.5, 'z': 0.6}, 'width': 160,
              'height': 120, 'fov': 1.0, 'rate_hz': 10.0}
    scene = scenes(highway({'placed': [{'model': 'BmwX5', 'lanelet': MIDDLE, 's': 35.0,
                                        'speed': 0.0, 'route': [100102]}]}, sensors=(camera,)))
    scene.parts['traffic'].manager.stop(0)
    scene.world.step()
    frame = scene.vehicles['Car'].sensors.sample('camera')
    colour = np.array(COLOURS[0][:3])                    # traffic_0's body: red
    pixels = frame.rgb[56:64, 76:84].astype(float) / 255.0
    # shaded red: the same chromaticity as the body colour, not the grey road or the sky
    scale = pixels.sum(axis=-1, keepdims=True) / colour.sum()
    assert (np.abs(pixels - scale * colour).max(axis=-1) < 0.05).all()
    # without the car, the centre is not red
    scene.parts['traffic'].manager.vehicles[0].active = False
    scene.parts['traffic']._place()
    scene.world.step()
    empty = scene.vehicles['Car'].sensors.sample('camera').rgb[56:64, 76:84].astype(float)
    assert not (np.abs(empty / 255.0 - (empty.sum(axis=-1, keepdims=True) / 255.0 /
                                         colour.sum()) * colour).max(axis=-1) < 0.05).all()


def box_x(scene, body):
    return scene.world.body_state(body)[0][0][0]


class SignalsPart:
    """A stand-in for the world's signals part: its controller, built before the traffic."""

    name = 'signals'

    def __init__(self, controller):
        self.controller = controller

    def build(self, world, spec):
        return self


def test_the_traffic_part_obeys_the_signals_part_controller(scenes):
    spec = with_lanes(highway({'placed': [{'model': 'ToyotaPrius', 'lanelet': MIDDLE,
                                           's': 60.0, 'speed': 15.0, 'route': [100102]}]}))
    x, y, _ = spec.lanes.pose_at(MIDDLE, 150.0)
    line = StopLine(7, MIDDLE, 150.0, [(x, y - 1.5), (x, y + 1.5)], 'traffic_light', 70)
    spec.lanes.set_rules(LaneRules(stop_lines=(line,),
                                   groups=(TrafficLightGroup(70, (MIDDLE,), (7,)),)))
    signals = SignalController(spec.lanes)
    signals.force(70, 'red')
    scene = scenes(spec, parts=[SignalsPart(signals)])
    traffic = scene.parts['traffic']
    assert traffic.manager.signals is signals
    half = model_dimensions('ToyotaPrius')[0] / 2
    body = traffic.body_ids[0]
    for _ in range(1500):                        # 15 s: it stops before the line
        scene.world.step()
        assert box_x(scene, body) + half < x
    assert traffic.manager.vehicles[0].speed_mps < 0.01
    signals.force(70, 'green')
    for _ in range(500):
        scene.world.step()
    assert box_x(scene, body) - half > x


def test_the_shipped_city_block_signals_traffic_stops_at_red_and_never_overlaps(scenes):
    scene = scenes(load_world('city_block_signals'))
    controller = scene.parts['signals'].controller
    manager = scene.parts['traffic'].manager
    assert manager.signals is controller
    lines = {line.lane_id: line for line in scene.lanes.rules.stop_lines}
    at_red = set()
    for step in range(3000):                    # 30 s of the world
        scene.world.step()
        if step % 10 == 9:                      # after each traffic update
            assert overlapping([(*manager.pose(v), v.length_m, v.width_m)
                                for v in manager.vehicles if v.active]) == []
            for v in manager.vehicles:
                line = lines.get(v.lane)
                if line is not None and v.speed_mps < 0.01 and \
                        controller.state(line.group_id) == 'red' and \
                        0.0 < line.s_m - (v.s_m + 0.5 * v.length_m) < 3.0:
                    at_red.add(v.index)
    assert len(at_red) >= 5                     # the first of each queue, at its line
