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

"""Footprints and distances on the ground plane, against closed-form values."""

import math

import pytest

from vehicle_sim.config import load_car, load_robot
from vehicle_sim.core.geometry.footprint import (
    band_polygon,
    car_outline,
    circle_footprint,
    clearance,
    convex_hull,
    distance_to_polyline,
    obstacle_footprint,
    Outline,
    polygon_footprint,
    RIM_POINTS,
    robot_outline,
)
from vehicle_sim.core.world.params import obstacle_from_dict

TOL = 1e-9


def _square(cx, cy, half):
    return ((cx - half, cy - half), (cx + half, cy - half), (cx + half, cy + half),
            (cx - half, cy + half))


def test_car_outline_of_the_default_car_is_its_body_box():
    # config/cars/Car.yaml: box 5.0 x 1.7 centred 2.0 m ahead of the rear axle; tyres 0.3 wide
    # at track 1.7: y reaches 1.7/2 + 0.3/2 = 1.0, beyond the box's 0.85
    assert car_outline(load_car('Car')) == Outline(-0.5, 4.5, -1.0, 1.0)


def test_car_outline_of_the_prius_includes_its_tyres_and_pitched_boxes():
    params = load_car('ToyotaPrius')
    outline = car_outline(params)
    half_y = params.track_front_m / 2 + params.front_tire_width_m / 2
    assert outline.y_max_m == pytest.approx(max(half_y, max(
        b.position_m[1] + b.size_m[1] / 2 for b in params.collision_boxes)), abs=TOL)
    for box in params.collision_boxes:      # every box lies inside, seen from above
        reach = (box.size_m[0] * abs(math.cos(box.pitch_rad))
                 + box.size_m[2] * abs(math.sin(box.pitch_rad))) / 2
        assert outline.x_min_m <= box.position_m[0] - reach + TOL
        assert outline.x_max_m >= box.position_m[0] + reach - TOL


def test_robot_outline_of_the_caster_robot_spans_body_wheels_and_caster():
    params = load_robot('caster_robot')
    outline = robot_outline(params)
    length, width, _ = params.body_size_m
    assert outline.x_min_m == pytest.approx(min(
        params.body_offset_m - length / 2, params.caster_offset_m - params.caster_radius_m,
        -params.wheel_radius_m), abs=TOL)
    assert outline.x_max_m == pytest.approx(max(
        params.body_offset_m + length / 2, params.wheel_radius_m), abs=TOL)
    assert outline.y_max_m == pytest.approx(max(
        width / 2, params.wheel_tread_m / 2 + params.wheel_width_m / 2), abs=TOL)
    assert outline.y_min_m == -outline.y_max_m


def test_outline_corners_turn_with_the_yaw_about_base_link():
    # a quarter turn left: forward (x) becomes +y, left (y) becomes -x
    corners = Outline(-1.0, 3.0, -0.5, 0.5).corners(10.0, 20.0, math.pi / 2)
    expected = ((10.5, 19.0), (10.5, 23.0), (9.5, 23.0), (9.5, 19.0))
    for got, want in zip(corners, expected):
        assert got == pytest.approx(want, abs=TOL)


def test_clearance_between_separated_squares_is_the_gap_and_its_points():
    # squares of side 2 centred 5 m apart on x: faces at x = 1 and x = 4
    distance, on_a, on_b = clearance(_square(0, 0, 1), polygon_footprint('b', _square(5, 0, 1)))
    assert distance == pytest.approx(3.0, abs=TOL)
    assert on_a[0] == pytest.approx(1.0) and on_b[0] == pytest.approx(4.0)
    assert math.dist(on_a, on_b) == pytest.approx(3.0, abs=TOL)


def test_clearance_to_a_corner_turned_towards_the_vehicle_is_the_corner_distance():
    # a square of side 2 turned 45 degrees at x = 5 points a corner at x = 5 - sqrt(2)
    c = math.sqrt(2)          # half its diagonal
    diamond = ((5 - c, 0), (5, -c), (5 + c, 0), (5, c))
    distance, _, on_b = clearance(_square(0, 0, 1), polygon_footprint('d', diamond))
    assert distance == pytest.approx(4.0 - math.sqrt(2), abs=TOL)
    assert on_b == pytest.approx((5 - math.sqrt(2), 0.0), abs=TOL)


def test_clearance_of_overlapping_footprints_is_zero_without_points():
    assert clearance(_square(0, 0, 1), polygon_footprint('o', _square(1.5, 0.5, 1))) == \
        (0.0, None, None)
    assert clearance(_square(0, 0, 1), circle_footprint('c', (1.2, 0), 0.5)) == \
        (0.0, None, None)
    assert clearance(_square(0, 0, 1), circle_footprint('in', (0, 0), 0.1))[0] == 0.0


def test_clearance_to_a_circle_beside_an_edge_and_off_a_corner():
    distance, on_a, on_b = clearance(_square(0, 0, 1), circle_footprint('c', (0, 5), 0.5))
    assert distance == pytest.approx(3.5, abs=TOL)
    assert on_a == pytest.approx((0.0, 1.0)) and on_b == pytest.approx((0.0, 4.5))
    distance, on_a, _ = clearance(_square(0, 0, 1), circle_footprint('c', (4, 5), 1.0))
    assert distance == pytest.approx(5.0 - 1.0, abs=TOL)        # (1, 1) to (4, 5): 3-4-5
    assert on_a == pytest.approx((1.0, 1.0))


def test_obstacle_footprint_of_a_yawed_box_is_its_rotated_rectangle():
    spec = obstacle_from_dict({'name': 'crate', 'shape': 'box', 'size': [4.0, 2.0, 1.0],
                               'position': [10.0, 5.0, 0.5], 'yaw': math.pi / 6}, 'test')
    c, s = math.cos(math.pi / 6), math.sin(math.pi / 6)
    expected = {(round(10 + c * u - s * v, 9), round(5 + s * u + c * v, 9))
                for u in (-2, 2) for v in (-1, 1)}
    got = obstacle_footprint(spec)
    assert not got.is_circle and got.name == 'crate'
    assert {(round(x, 9), round(y, 9)) for x, y in got.vertices} == expected


def test_obstacle_footprint_of_round_shapes_upright_and_lying():
    pole = obstacle_from_dict({'name': 'pole', 'shape': 'cylinder', 'radius': 0.2,
                               'height': 2.0, 'position': [10.0, 5.0, 1.0]}, 'test')
    ball = obstacle_from_dict({'name': 'ball', 'shape': 'sphere', 'radius': 0.5,
                               'position': [1.0, 2.0, 0.5]}, 'test')
    log = obstacle_from_dict({'name': 'log', 'shape': 'cylinder', 'radius': 0.3,
                              'height': 4.0, 'position': [0.0, 0.0, 0.3],
                              'roll': math.pi / 2}, 'test')
    assert obstacle_footprint(pole) == circle_footprint('pole', (10.0, 5.0), 0.2)
    assert obstacle_footprint(ball) == circle_footprint('ball', (1.0, 2.0), 0.5)
    # lying along y: 4 m long, 0.6 m wide (its rims sampled at RIM_POINTS: exact at the ends)
    xs, ys = zip(*obstacle_footprint(log).vertices)
    assert (min(ys), max(ys)) == pytest.approx((-2.0, 2.0), abs=TOL)
    assert max(xs) == pytest.approx(0.3, abs=TOL) and RIM_POINTS % 4 == 0
    # and at a pose given now (a movable obstacle that rolled away)
    moved = obstacle_footprint(ball, (7.0, -1.0, 0.5), (0.0, 0.0, 0.0, 1.0))
    assert moved.center_m == (7.0, -1.0)


def test_convex_hull_drops_inner_points_and_turns_counter_clockwise():
    hull = convex_hull([(0, 0), (2, 0), (1, 1), (2, 2), (0, 2), (1, 0)])
    assert hull == ((0.0, 0.0), (2.0, 0.0), (2.0, 2.0), (0.0, 2.0))


@pytest.mark.parametrize('path', [
    [(0.0, 0.0), (10.0, 0.0)],
    [(0.0, 0.0), (3.0, 0.0), (5.0, 2.0), (5.0, 6.0), (2.0, 8.0)],      # left and right bends
    [(0.0, 0.0), (1.0, 0.0), (1.0, 0.0), (2.0, 0.5)],                  # a repeated point
], ids=['straight', 'bends', 'repeated'])
def test_band_polygon_vertices_lie_at_the_half_width_from_the_path(path):
    band = band_polygon(path, 0.5)
    for x, y in band:
        assert distance_to_polyline(x, y, path) == pytest.approx(0.5, abs=1e-9)
    # round ends: the points straight behind the start and ahead of the end are on it
    assert any(p == pytest.approx((-0.5, 0.0), abs=1e-9) for p in band)


def test_band_polygon_of_a_single_point_is_refused():
    with pytest.raises(ValueError, match='2 distinct points'):
        band_polygon([(1.0, 1.0), (1.0, 1.0)], 0.5)
