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

"""The clearance criterion: fed by hand against closed-form distances, and in the shipped run."""

import math
from pathlib import Path
import re

import pytest
import yaml

from vehicle_sim.config import load_car
from vehicle_sim.core.geometry.footprint import (
    car_outline,
    circle_footprint,
    Outline,
    polygon_footprint,
)
from vehicle_sim.core.specs.errors import InvalidParameterError
from vehicle_sim.core.world.collision import CollisionEvent
from vehicle_sim.scenarios.criteria import CRITERIA, Sample, validate_criterion
from vehicle_sim.scenarios.runner import run_scenario
from vehicle_sim.scenarios.scene import CriteriaScene

ROOT = Path(__file__).resolve().parent.parent
STOP = ROOT / 'scenarios' / 'stop_before_obstacle.yaml'
# config/cars/Car.yaml seen from above: base_link at the rear axle, bumper 4.5 m ahead of it.
CAR = Outline(-0.5, 4.5, -1.0, 1.0)
# config/worlds/obstacle_course.yaml: the wall's near face and the pole.
WALL = polygon_footprint('wall', ((19.5, -3.0), (20.5, -3.0), (20.5, 3.0), (19.5, 3.0)))
POLE = circle_footprint('pole', (10.0, 5.0), 0.2)


def _clearance(min_m, fixed=(WALL, POLE), moving=None):
    criterion = CRITERIA['clearance']('clearance', 'ego', validate_criterion(
        'clearance', {'min': min_m}), 10.0)
    criterion.bind(CriteriaScene({'ego': CAR}, fixed, moving))
    return criterion


def _drive(criterion, xs, dt_s=0.5, yaw_rad=0.0):
    for index, x in enumerate(xs):
        criterion.observe(Sample(index * dt_s, x, 0.0, yaw_rad, 1.0))
    return criterion.result()


def test_clearance_is_the_smallest_gap_to_the_nearest_obstacle_with_its_name_and_time():
    # the bumper reaches x = 11 + 4.5 = 15.5: 4.0 m from the wall's face; passing the pole its
    # left side (y = 1) is 5 - 0.2 - 1 = 3.8 m from it, first when the car spans x = 10 (t = 1)
    result = _drive(_clearance(2.0), [5.0, 6.0, 8.0, 11.0, 11.0])
    assert result.passed and result.unit == 'm'
    assert result.value == pytest.approx(3.8, abs=1e-9)
    assert 'closest 3.800 m to pole at 0.50 s (bound 2 m); wall 4.000 m at 1.50 s' \
        == result.detail
    # the closest points, per obstacle, nearest first: the car's side and the pole's surface
    assert result.points_m[0] == pytest.approx((10.0, 1.0)) and \
        result.points_m[1] == pytest.approx((10.0, 4.8))
    assert result.points_m[2][0] == pytest.approx(15.5) and \
        result.points_m[3][0] == pytest.approx(19.5)


def test_clearance_below_the_bound_fails_with_the_value():
    result = _drive(_clearance(2.0, fixed=(WALL,)), [10.0, 13.0, 14.0])    # bumper 18.5
    assert not result.passed
    assert result.value == pytest.approx(1.0, abs=1e-9)
    assert result.detail == 'closest 1.000 m to wall at 1.00 s (bound 2 m)'


def test_clearance_touching_is_zero_and_fails_any_positive_bound():
    result = _drive(_clearance(0.5, fixed=(WALL,)), [14.0, 15.5])          # bumper in the wall
    assert (result.passed, result.value, result.points_m) == (False, 0.0, ())
    assert _drive(_clearance(0.0, fixed=(WALL,)), [15.5]).passed


def test_clearance_turns_the_footprint_with_the_yaw():
    # heading +y at (19, -10): the car's right side (y = -1 in base_link) is at x = 20;
    # a pole at (23, -8) is 3 - 0.2 = 2.8 m from it
    criterion = _clearance(1.0, fixed=(circle_footprint('p', (23.0, -8.0), 0.2),))
    criterion.observe(Sample(0.0, 19.0, -10.0, math.pi / 2, 0.0))
    assert criterion.result().value == pytest.approx(2.8, abs=1e-9)


def test_clearance_reads_the_movable_obstacles_at_every_step():
    positions = iter([(30.0, 0.0), (16.5, 0.0)])    # a ball rolling towards the car
    criterion = _clearance(2.0, fixed=(), moving=lambda: [
        circle_footprint('ball', next(positions), 0.5)])
    result = _drive(criterion, [10.0, 10.0])
    assert result.value == pytest.approx(16.5 - 0.5 - 14.5, abs=1e-9)
    assert not result.passed


def test_clearance_without_obstacles_passes_and_says_so():
    result = _drive(_clearance(1.0, fixed=()), [0.0, 1.0])
    assert (result.passed, result.value) == (True, None)
    assert 'no obstacle' in result.detail


@pytest.mark.parametrize('data, match', [
    ({'min': -1.0}, 'min'),
    ({}, 'min'),
    ({'min': 1.0, 'max': 2.0}, 'max'),
])
def test_clearance_bad_bound_is_refused_naming_the_key(data, match):
    with pytest.raises(InvalidParameterError, match=match):
        validate_criterion('clearance', data)


def test_stop_before_obstacle_keeps_its_clearance_from_the_pole_and_the_wall():
    result = run_scenario(STOP)
    clearance = result.criterion('clearance')
    assert clearance.passed
    # passing the pole (y = 5, r = 0.2) with its side at y = 1: 3.8 m, driving straight
    assert clearance.value == pytest.approx(3.8, abs=0.01)
    assert 'to pole' in clearance.detail
    # the wall: the bumper (4.5 m ahead of base_link) stopped 3.9 m short of its face (19.5 m)
    wall_m = 19.5 - (result.tracks['Car'].x_m[-1] + 4.5)
    assert wall_m == pytest.approx(3.9, abs=0.1)
    reported = re.search(r'wall (\d+\.\d+) m', clearance.detail)
    assert float(reported.group(1)) == pytest.approx(wall_m, abs=0.01)


def _race_track_run(tmp_path, steering_rad, duration_s):
    # config/worlds/race_track.yaml: an occupancy map's walls, no obstacle; the car starts on
    # the straight heading +x, between the walls' faces at y = 3.5 and (the cells' raster)
    # y = -3.4 m
    data = {'name': 'race_track_clearance', 'world': 'race_track', 'duration': duration_s,
            'driver': {'commands': [{'t': 0.0, 'cruising_speed': 20.0,
                                     'steering_angle': steering_rad}]},
            'criteria': [{'kind': 'no_collision'}, {'kind': 'clearance', 'min': 0.5}]}
    path = tmp_path / 'race_track_clearance.yaml'
    path.write_text(yaml.safe_dump(data), encoding='utf-8')
    return run_scenario(path)


def test_clearance_measures_the_map_walls(tmp_path):
    result = _race_track_run(tmp_path, 0.0, 2.0)           # straight on along y = 0
    assert result.criterion('no_collision').passed
    clearance = result.criterion('clearance')
    half_width_m = car_outline(load_car('CitroenCZero')).y_max_m
    assert clearance.passed
    assert clearance.value == pytest.approx(3.4 - half_width_m, abs=0.01)
    assert 'to map at' in clearance.detail
    # the car's right side and the right wall's face
    assert clearance.points_m[0][1] == pytest.approx(-half_width_m, abs=0.01)
    assert clearance.points_m[1][1] == pytest.approx(-3.4, abs=1e-6)


def test_clearance_fails_when_the_car_hits_a_map_wall(tmp_path):
    # steering left on the straight: the car drives into the wall at y = 3.5 m
    result = _race_track_run(tmp_path, -0.3, 4.0)
    hit = result.criterion('no_collision')
    assert not hit.passed and hit.detail.startswith('3 collisions: map at 2.57 s')
    clearance = result.criterion('clearance')
    assert not clearance.passed
    assert clearance.value == 0.0
    assert clearance.detail.startswith('touched map at 2.57 s (a collision: distance 0')
    # the contact point, twice (vehicle and wall): on the wall's face
    assert clearance.points_m[0] == clearance.points_m[1]
    assert clearance.points_m[0][1] == pytest.approx(3.5, abs=0.15)


def test_clearance_fails_on_a_collision_with_an_obstacle_whatever_the_bound():
    criterion = _clearance(0.0, fixed=(WALL,))
    criterion.observe(Sample(0.0, 14.99, 0.0, 0.0, 1.0))        # 0.01 m from the wall's face
    criterion.collision(CollisionEvent(0.1, 'wall', 500.0, (19.5, 0.2, 0.4)))
    criterion.collision(CollisionEvent(0.2, 'other_car', 500.0, (1.0, 1.0, 0.4)))  # not one
    result = criterion.result()
    assert (result.passed, result.value) == (False, 0.0)
    assert result.detail == 'touched wall at 0.10 s (a collision: distance 0; bound 0 m)'
    assert result.points_m == ((19.5, 0.2), (19.5, 0.2))
