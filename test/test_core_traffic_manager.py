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


"""The traffic manager on the shipped highway and on small lane maps (core/traffic/manager.py)."""

import math

import numpy as np
import pytest

from vehicle_sim.config import load_world, world_from_data
from vehicle_sim.core.map.lane_graph import Boundary, Lane, LaneGraph
from vehicle_sim.core.map.road_segments import lane_graph_from_roads
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.traffic.manager import OurVehicle, TrafficManager
from vehicle_sim.core.traffic.params import traffic_from_dict

DT = 0.05
DIMS = {'Car': (4.5, 1.8), 'Truck': (8.0, 2.4)}
HIGHWAY = lane_graph_from_roads(load_world('highway').roads)
# forward lanes of the highway's first segment (600 m straight along +x): 0 = fast lane
FAST, MIDDLE, SLOW = 100001, 100002, 100003


def manager(data, graph=HIGHWAY, ours=()):
    return TrafficManager(graph, traffic_from_dict(data, 'w.yaml: traffic'), DIMS, ours)


def corners(x, y, yaw, length, width):
    c, s = math.cos(yaw), math.sin(yaw)
    local = np.array([[1, 1], [1, -1], [-1, -1], [-1, 1]]) * [length / 2, width / 2]
    return np.c_[x + c * local[:, 0] - s * local[:, 1], y + s * local[:, 0] + c * local[:, 1]]


def rectangles_overlap(a, b):
    """Separating-axis test of two rectangles given as (4, 2) corner arrays."""
    for poly in (a, b):
        for i in range(4):
            edge = poly[(i + 1) % 4] - poly[i]
            axis = np.array([-edge[1], edge[0]])
            pa, pb = a @ axis, b @ axis
            if pa.max() <= pb.min() or pb.max() <= pa.min():
                return False
    return True


def overlaps(boxes):
    """Return the index pairs of overlapping boxes (x, y, yaw, length, width) [(n, 5) array]."""
    boxes = np.asarray(boxes)
    xy = boxes[:, :2]
    reach = 0.5 * np.hypot(boxes[:, 3], boxes[:, 4])
    dist = np.hypot(*(xy[:, None, :] - xy[None, :, :]).transpose(2, 0, 1))
    near = np.argwhere(np.triu(dist < reach[:, None] + reach[None, :], 1))
    return [(i, j) for i, j in near
            if rectangles_overlap(corners(*boxes[i]), corners(*boxes[j]))]


def traffic_boxes(m):
    return [(*m.pose(v), v.length_m, v.width_m) for v in m.vehicles if v.active]


@pytest.mark.parametrize('dt', [0.05, 0.1])          # 0.1 s: the default update period
def test_fifty_vehicles_drive_the_highway_for_120_s_without_a_collision(dt):
    m = manager({'vehicles': 50, 'seed': 11, 'models': ['Car', 'Truck'],
                 'speed_factor': {'mean': 0.85, 'std': 0.1}})
    assert len(m.vehicles) == 50
    changing_seen = 0
    for _ in range(int(round(120.0 / dt))):
        m.step(dt)
        assert overlaps(traffic_boxes(m)) == []
        for v in m.vehicles:
            if not v.active:
                continue
            assert v.speed_mps <= m.desired_speed(v) * 1.01
            x, y, _ = m.pose(v)
            position, on_lane = HIGHWAY.locate_on(v.lane, x, y, near_s_m=v.s_m)
            if v.changing:
                changing_seen += 1
                assert abs(v.offset_m) <= 3.75 + 1e-9
            else:
                assert on_lane and abs(position.offset_m) < 1e-6, (v.index, v.lane, position)
    assert m.lane_changes > 0 and changing_seen > 0
    assert sum(v.active for v in m.vehicles) >= 45     # at the ends, they re-enter
    assert m.time_s == pytest.approx(120.0)


def trajectory(seed, seconds=30.0):
    m = manager({'vehicles': 40, 'seed': seed, 'models': ['Car', 'Truck']})
    rows = []
    for _ in range(int(seconds / DT)):
        m.step(DT)
        rows.append(tuple((v.lane, v.s_m, v.speed_mps, v.offset_m) for v in m.vehicles))
    return rows, m.lane_changes


def test_the_same_seed_gives_the_same_trajectories_bit_for_bit():
    first, changes = trajectory(5)
    second, _ = trajectory(5)
    assert changes > 0
    assert first == second                    # floats compared exactly
    other, _ = trajectory(6)
    assert other != first


def ours_on(lane_id, s_m, speed_mps=0.0, name='Car'):
    x, y, yaw = HIGHWAY.pose_at(lane_id, s_m)
    return OurVehicle(name, x, y, yaw, speed_mps, 4.6, 1.9)


def test_traffic_stops_behind_our_stopped_car():
    ego = ours_on(MIDDLE, 300.0)
    m = manager({'placed': [{'lanelet': MIDDLE, 's': 50.0, 'speed': 30.0,
                             'route': [100102]}]}, ours=[ego])
    v = m.vehicles[0]
    m.set_ours([ego])
    for _ in range(int(40.0 / DT)):
        m.step(DT)
        assert v.s_m + v.length_m / 2 < 300.0 - 4.6 / 2
    assert v.speed_mps == 0.0
    gap = 300.0 - 4.6 / 2 - (v.s_m + v.length_m / 2)
    assert gap == pytest.approx(m.idm.min_gap_m, abs=0.3)


def test_a_leader_on_the_next_lane_counts():
    # ours stands 30 m into the next segment's middle lane; the traffic car comes from 400 m
    # before the segment's end at 30 m/s and must stop behind it across the lane boundary
    ego = ours_on(100102, 30.0)
    m = manager({'placed': [{'lanelet': MIDDLE, 's': 200.0, 'speed': 30.0,
                             'route': [100102, 100202]}]}, ours=[ego])
    v = m.vehicles[0]
    m.set_ours([ego])
    for _ in range(int(60.0 / DT)):
        m.step(DT)
        assert v.lane == MIDDLE or v.s_m + v.length_m / 2 < 30.0 - 4.6 / 2
    assert v.lane == 100102 and v.speed_mps == 0.0
    assert 30.0 - 4.6 / 2 - (v.s_m + v.length_m / 2) == pytest.approx(m.idm.min_gap_m, abs=0.3)


def run_blocked(ours_lanes):
    """Run a car behind a slow truck on the middle lane, ours beside it on ``ours_lanes``."""
    m = manager({'placed': [{'model': 'Car', 'lanelet': MIDDLE, 's': 100.0, 'speed': 30.0},
                            {'model': 'Truck', 'lanelet': MIDDLE, 's': 160.0, 'speed': 10.0,
                             'speed_factor': 0.3, 'route': [100102]}]},
                ours=[ours_on(lane, 90.0, 30.0) for lane in ours_lanes])
    car = m.vehicles[0]
    for _ in range(int(3.0 / DT)):
        # ours keep pace with the car, 10 m (centre to centre) behind it
        m.set_ours([ours_on(lane, car.s_m - 10.0, car.speed_mps, f'ours{k}')
                    for k, lane in enumerate(ours_lanes)])
        m.step(DT)
    return m, car


def test_traffic_changes_lanes_to_pass_a_slow_truck_but_never_cuts_in_front_of_ours():
    free, car = run_blocked([])
    assert free.lane_changes == 1 and car.lane in (100001, 100003)
    blocked, car = run_blocked([FAST, SLOW])
    assert blocked.lane_changes == 0 and car.lane == MIDDLE
    assert car.acc_mps2 < -1.0                 # it brakes behind the truck instead


def test_a_scripted_lane_change_starts_at_its_time_and_is_the_only_one():
    m = manager({'placed': [{'lanelet': FAST, 's': 100.0, 'speed': 25.0,
                             'change_lane': 'right', 'change_at': 2.0},
                            {'model': 'Truck', 'lanelet': FAST, 's': 140.0, 'speed': 10.0,
                             'speed_factor': 0.3, 'route': [100101]}]})
    car = m.vehicles[0]
    lanes = []
    for _ in range(int(8.0 / DT)):
        m.step(DT)
        lanes.append((round(m.time_s, 6), car.lane, car.changing))
    # behind a slow truck, yet no MOBIL change before 2 s; then the scripted one, to the right
    assert all(lane == FAST for t, lane, _ in lanes if t <= 2.0)
    started = next(t for t, lane, _ in lanes if lane == MIDDLE)
    assert started == pytest.approx(2.0 + DT)
    assert lanes[-1] == (pytest.approx(8.0), MIDDLE, False)
    starts = sum(1 for (_, _, now), (_, _, before) in zip(lanes[1:], lanes) if now and not before)
    assert starts == 1
    with pytest.raises(InvalidParameterError, match=r"placed\[0\]: field 'change_lane' = "
                                                    r"'left': a vehicle with a route"):
        manager({'placed': [{'lanelet': MIDDLE, 'route': [100102], 'change_lane': 'left'}]})


def test_at_a_fork_each_vehicle_takes_a_seeded_random_branch():
    def lane(lane_id, points, successors=()):
        pts = np.asarray(points, dtype=float)
        normal = np.array([[0.0, 1.75]])
        return Lane(lane_id, pts, Boundary(lane_id * 10, pts + normal, 'solid'),
                    Boundary(lane_id * 10 + 1, pts - normal, 'solid'), 20.0, successors)
    graph = LaneGraph([lane(1, [[0, 0], [100, 0]], (2, 3)),
                       lane(2, [[100, 0], [200, 20]]), lane(3, [[100, 0], [200, -20]])])

    def branches(seed):
        m = manager({'vehicles': 3, 'seed': seed, 'spawn': {'lanes': [1], 'spacing': 30.0}},
                    graph)
        taken = []
        for _ in range(int(60.0 / DT)):
            before = [v.lane for v in m.vehicles]
            m.step(DT)
            taken += [v.lane for v, lane_id in zip(m.vehicles, before)
                      if lane_id == 1 and v.lane != 1]
        return taken
    first = branches(1)
    assert len(first) >= 10 and set(first) == {2, 3}
    assert branches(1) == first


@pytest.mark.parametrize('traffic, message', [
    ({'density': -1.0}, r"w\.yaml: traffic: field 'density' = -1\.0: must be >= 0"),
    ({'vehicles': 500}, r"w\.yaml: traffic: field 'vehicles' = 500: more than fit: 456 "
                        r"places"),
    ({'density': 20.0, 'spawn': {'spacing': 60.0}},
     r"w\.yaml: traffic: field 'density' = 20 \(\d+ vehicles\): more than fit"),
    ({'placed': [{'lanelet': 100001, 'route': [100101, 999]}]},
     r"w\.yaml: traffic: placed\[0\]: field 'route': lane 999 is not in the map"),
    ({'placed': [{'lanelet': 100001, 'route': [100201]}]},
     r"w\.yaml: traffic: placed\[0\]: field 'route': lane 100201 does not follow lane "
     r"100001"),
    ({'placed': [{'lanelet': 7}]}, r"placed\[0\]: field 'lanelet' = 7: lane 7 is not in the "
                                   r"map"),
    ({'placed': [{'lanelet': 100001, 's': 601.0}]}, r"placed\[0\]: field 's' = 601: not on "
                                                    r"lane 100001"),
    ({'placed': [{'lanelet': 100001, 's': 10.0}, {'lanelet': 100001, 's': 13.0}]},
     r"placed\[1\]: field 's' = 13: overlaps another vehicle"),
    ({'spawn': {'lanes': [100001, 5]}}, r"traffic: spawn: field 'lanes': lane 5 is not in "
                                        r"the map"),
    ({'objects_rate': 0.0}, r"w\.yaml: traffic: field 'objects_rate' = 0\.0: must be > 0"),
    ({'objects_rate': float('nan')}, r"traffic: field 'objects_rate' = nan: must be finite"),
    ({'objects_rate': -10.0}, r"traffic: field 'objects_rate' = -10\.0: must be > 0"),
])
def test_bad_traffic_is_refused_naming_the_file_and_field(traffic, message):
    with pytest.raises(InvalidParameterError, match=message):
        manager(traffic)


def test_an_unknown_model_is_refused_when_the_world_file_is_read():
    with pytest.raises(InvalidParameterError,
                       match=r"highway_x\.yaml: traffic: field 'models': unknown model "
                             r"'Bus'.*known: BmwX5"):
        world_from_data({'vehicles': [{'name': 'Car'}], 'traffic': {'models': ['Car', 'Bus']}},
                        'highway_x.yaml')
    with pytest.raises(InvalidParameterError, match=r"placed\[0\]: field 'model': unknown model"):
        world_from_data({'vehicles': [{'name': 'Car'}],
                         'traffic': {'placed': [{'model': 'Bus', 'lanelet': 1}]}}, 'w.yaml')


def test_a_world_file_with_traffic_reads_into_the_world_spec():
    spec = world_from_data({'vehicles': [{'name': 'Car'}], 'traffic': {'vehicles': 3, 'seed': 2}},
                           'w.yaml')
    assert spec.traffic.vehicles == 3 and spec.traffic.seed == 2
    assert spec.traffic.source == 'w.yaml: traffic'
    assert world_from_data({'vehicles': [{'name': 'Car'}]}, 'w.yaml').traffic is None


def test_no_vehicle_is_spawned_on_our_car_and_the_step_refuses_a_bad_dt():
    ego = ours_on(MIDDLE, 300.0)
    m = manager({'vehicles': 400, 'seed': 1}, ours=[ego])
    for v in m.vehicles:
        if v.lane == MIDDLE:
            assert abs(v.s_m - 300.0) >= 15.0 + 2.3
    with pytest.raises(ValueError, match='dt_s'):
        m.step(float('nan'))


def test_no_vehicle_starts_on_ours_across_two_lanes_or_off_every_lane():
    # One of ours straddles the middle and fast lanes at an angle (located on one lane, it
    # reaches into the other); a long one stands across the slow lane's edge, its centre off
    # every lane. No traffic vehicle starts on either, for any seed; each keeps CLEARANCE_M.
    from vehicle_sim.core.traffic.spawn import CLEARANCE_M
    x, y, yaw = HIGHWAY.pose_at(MIDDLE, 315.0)        # a spawn place (spacing 30 m)
    across = OurVehicle('across', x, y + 1.875, yaw + 0.5, 0.0, 4.6, 1.9)
    x, y, _ = HIGHWAY.pose_at(SLOW, 525.0)
    edge = OurVehicle('edge', x, y - 3.5, math.pi / 2, 0.0, 8.0, 2.5)
    assert HIGHWAY.locate(edge.x_m, edge.y_m) is None
    near = 0
    for seed in range(10):
        m = manager({'vehicles': 300, 'seed': seed}, ours=[across, edge])
        for o in (across, edge):
            box = corners(o.x_m, o.y_m, o.yaw_rad, o.length_m, o.width_m)
            grown = corners(o.x_m, o.y_m, o.yaw_rad, o.length_m + 2 * CLEARANCE_M - 0.01,
                            o.width_m + 2 * CLEARANCE_M - 0.01)
            for b in traffic_boxes(m):
                assert not rectangles_overlap(box, corners(*b)), (seed, o.name, b)
                near += rectangles_overlap(grown, corners(*b))
    assert near == 0


def test_docs_hold_the_generated_key_tables():
    from pathlib import Path

    from vehicle_sim.core.traffic.params import traffic_markdown
    text = (Path(__file__).resolve().parent.parent / 'docs' / 'traffic.md').read_text('utf-8')
    assert traffic_markdown() in text


def test_the_shipped_highway_traffic_world_spawns_its_vehicles():
    spec = load_world('highway_traffic')
    sizes = {'ToyotaPrius': (4.3, 1.8), 'BmwX5': (4.6, 1.9), 'TeslaModel3': (4.7, 1.9),
             'CitroenCZero': (3.5, 1.5), 'LincolnMKZ': (4.9, 1.9)}
    m = TrafficManager(lane_graph_from_roads(spec.roads), spec.traffic, sizes)
    assert len(m.vehicles) == 60
    speeds_kmh = [m.desired_speed(v) * 3.6 for v in m.vehicles]
    assert 59.9 <= min(speeds_kmh) and max(speeds_kmh) <= 100.1


def test_a_stopped_vehicle_stands_where_it_was_hit_between_steps():
    m = manager({'placed': [{'lanelet': MIDDLE, 's': 100.0, 'speed': 20.0,
                             'route': [100102]}]})
    car = m.vehicles[0]
    m.step(DT)
    s = car.s_m
    m.stop(0, 0.7)                   # it went on 0.7 m since the step before it was hit
    assert car.stopped and car.speed_mps == 0.0 and car.s_m == pytest.approx(s + 0.7)
    for _ in range(20):
        m.step(DT)
    assert car.s_m == pytest.approx(s + 0.7)
    with pytest.raises(ValueError, match='travelled_m = nan'):
        m.stop(0, float('nan'))
    with pytest.raises(ValueError, match='travelled_m = -1'):
        m.stop(0, -1.0)
    assert car.s_m == pytest.approx(s + 0.7)


def test_objects_are_where_the_vehicles_are_at_the_stamp():
    from vehicle_sim.core.traffic.objects import traffic_objects
    m = manager({'placed': [{'lanelet': MIDDLE, 's': 100.0, 'speed': 20.0,
                             'route': [100102]}]})
    heights = {'Car': 1.5, 'Truck': 3.0}
    now = traffic_objects(m, heights)[0]
    later = traffic_objects(m, heights, since_s=0.05)[0]
    car = m.vehicles[0]
    x, y, yaw = m.pose(car)
    assert (now.x_m, now.y_m) == (x, y)
    # 0.05 s on at 20 m/s along the straight lane (+x): 1 m, and the path from there
    assert (later.x_m - x, later.y_m - y) == pytest.approx((1.0, 0.0), abs=1e-9)
    assert later.path[0][0] - now.path[0][0] == pytest.approx(1.0, abs=1e-9)
    with pytest.raises(ValueError, match='since_s = -0.1'):
        traffic_objects(m, heights, since_s=-0.1)


def test_objects_without_paths_are_the_same_objects_with_empty_paths():
    from dataclasses import replace

    from vehicle_sim.core.traffic.objects import traffic_objects
    m = manager({'placed': [{'lanelet': MIDDLE, 's': 100.0, 'speed': 20.0,
                             'route': [100102]},
                            {'lanelet': MIDDLE, 's': 160.0, 'speed': 15.0}]})
    heights = {'Car': 1.5, 'Truck': 3.0}
    full = traffic_objects(m, heights, since_s=0.05)
    bare = traffic_objects(m, heights, since_s=0.05, paths=False)
    assert len(full) == 2 and all(len(o.path) == 10 for o in full)
    assert bare == tuple(replace(o, path=()) for o in full)
