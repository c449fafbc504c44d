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
ROS-free sensor math: geodesy, sample scheduling, noise, lookup tables, collision debounce, frames.

Values are checked against closed forms; each derivation is in the comment above the assert.
"""

from fractions import Fraction
import math

import numpy as np
import pytest

from vehicle_sim.core.geometry.frames import (
    OPTICAL_QUATERNION,
    quaternion_from_rpy,
    rotation_matrix,
    rpy_from_quaternion,
)
from vehicle_sim.core.geometry.geodesy import (
    ecef_to_geodetic,
    geodetic_to_ecef,
    GeodeticOrigin,
    LocalTangentPlane,
    WGS84_A_M,
    WGS84_B_M,
    WGS84_E2,
)
from vehicle_sim.core.sensors.lookup_table import LookupTable
from vehicle_sim.core.sensors.noise import GaussianNoise
from vehicle_sim.core.sensors.sampling import due_steps, exact, SampleSchedule, Scheduler
from vehicle_sim.core.world.collision import CollisionDebouncer

ORIGIN = GeodeticOrigin(48.0, 11.0, 500.0)

# ------------------------------------------------------------------------------- geodesy


def test_geodetic_to_ecef_on_the_equator_and_at_the_pole_are_the_semi_axes():
    assert geodetic_to_ecef(0.0, 0.0, 0.0) == pytest.approx((WGS84_A_M, 0.0, 0.0), abs=1e-9)
    assert geodetic_to_ecef(90.0, 0.0, 0.0) == pytest.approx((0.0, 0.0, WGS84_B_M), abs=1e-9)
    # at longitude 90 the equatorial point lies on +y
    assert geodetic_to_ecef(0.0, 90.0, 10.0) == pytest.approx((0.0, WGS84_A_M + 10.0, 0.0),
                                                              abs=1e-8)


def test_geodetic_to_ecef_matches_the_prime_vertical_radius_formula():
    # N = a / sqrt(1 - e^2 sin^2(lat)); z = (N (1 - e^2) + h) sin(lat)
    lat = math.radians(48.0)
    n = WGS84_A_M / math.sqrt(1.0 - WGS84_E2 * math.sin(lat) ** 2)
    x, y, z = geodetic_to_ecef(48.0, 0.0, 500.0)
    assert x == pytest.approx((n + 500.0) * math.cos(lat), abs=1e-8)
    assert z == pytest.approx((n * (1.0 - WGS84_E2) + 500.0) * math.sin(lat), abs=1e-8)


@pytest.mark.parametrize('lat, lon, alt', [
    (48.0, 11.0, 500.0), (-33.9, 151.2, 58.0), (89.9999, -45.0, 10.0), (-90.0, 0.0, 0.0),
    (0.0, 180.0, -100.0), (27.98, 86.92, 8848.0), (45.0, 7.0, 400000.0), (1e-9, -1e-9, 0.0)])
def test_ecef_to_geodetic_inverts_geodetic_to_ecef_to_1e_12_deg(lat, lon, alt):
    back = ecef_to_geodetic(*geodetic_to_ecef(lat, lon, alt))
    assert back[0] == pytest.approx(lat, abs=1e-12)
    if abs(lat) < 90.0:
        assert math.remainder(back[1] - lon, 360.0) == pytest.approx(0.0, abs=1e-12)
    assert back[2] == pytest.approx(alt, abs=1e-6)


def test_local_plane_origin_reads_the_origin():
    plane = LocalTangentPlane(ORIGIN)
    lat, lon, alt = plane.to_geodetic(0.0, 0.0, 0.0)
    assert (lat, lon) == pytest.approx((48.0, 11.0), abs=1e-12)
    assert alt == pytest.approx(500.0, abs=1e-6)


def test_local_plane_100_m_east_changes_longitude_by_the_exact_value():
    # Issue 8 golden value: ENU (100, 0, 1.5) at (48 N, 11 E, 500 m) -> dlon = 0.00133992 deg.
    # First order: dlon = 100 / ((N + h) cos(lat)) rad = 0.0013399 deg (N = 6388838 m).
    plane = LocalTangentPlane(ORIGIN)
    _, lon0, _ = plane.to_geodetic(0.0, 0.0, 1.5)
    lat, lon, alt = plane.to_geodetic(100.0, 0.0, 1.5)
    assert lon - lon0 == pytest.approx(0.00133992, abs=1e-8)
    n = WGS84_A_M / math.sqrt(1.0 - WGS84_E2 * math.sin(math.radians(48.0)) ** 2)
    assert math.radians(lon - lon0) == pytest.approx(
        100.0 / ((n + 501.5) * math.cos(math.radians(48.0))), rel=1e-6)
    # the plane leaves the curved Earth: 100 m away it is d^2 / (2 R) = 0.78 mm higher
    assert alt - 501.5 == pytest.approx(100.0 ** 2 / (2.0 * 6.39e6), rel=0.01)
    assert lat < 48.0    # and slightly south (the plane's east leaves the parallel)


def test_local_plane_north_and_up_move_latitude_and_altitude():
    plane = LocalTangentPlane(ORIGIN)
    lat, lon, alt = plane.to_geodetic(0.0, 1000.0, 0.0)
    # one degree of latitude at 48 deg is 111.2 km
    assert (lat - 48.0) * 111_200.0 == pytest.approx(1000.0, rel=2e-3)
    assert lon == pytest.approx(11.0, abs=1e-12)
    assert plane.to_geodetic(0.0, 0.0, 25.0)[2] == pytest.approx(525.0, abs=1e-6)


def test_local_plane_round_trip_of_a_world_position():
    plane = LocalTangentPlane(ORIGIN)
    assert plane.from_geodetic(*plane.to_geodetic(123.4, -56.7, 8.9)) == pytest.approx(
        (123.4, -56.7, 8.9), abs=1e-6)


# ------------------------------------------------------------------------------- scheduling

def test_schedule_40_hz_on_a_10_ms_step_alternates_3_and_2_steps():
    # k / 40 s = 2.5 k steps; first step at or after: 3, 5, 8, 10, 13, ...
    steps = due_steps(40.0, 0.010, 8)
    assert steps == (3, 5, 8, 10, 13, 15, 18, 20)
    assert set(np.diff((0,) + steps)) == {2, 3}


@pytest.mark.parametrize('rate_hz, step_s, period_steps', [
    (10.0, 0.010, 10), (100.0, 0.010, 1), (20.0, 0.005, 10), (0.1, 0.010, 1000),
    (3.0, 0.001, None)])
def test_schedule_has_no_drift_over_a_long_run(rate_hz, step_s, period_steps):
    # Sample k is due at ceil(k / (rate * dt)) exactly, even after 100000 samples; 0.01 s is not
    # a binary fraction, so float arithmetic would drift by a step here and there.
    schedule = SampleSchedule.from_rate(rate_hz, step_s)
    count = 100_000
    fired = []
    step = 0
    while len(fired) < count:
        step = schedule.next_step
        assert schedule.due(step)
        fired.append(step)
    ratio = exact(rate_hz) * exact(step_s)
    assert fired[-1] == math.ceil(Fraction(count) / ratio)
    if period_steps:
        assert set(np.diff(fired)) == {period_steps}


def test_schedule_is_due_once_per_step_and_not_between():
    schedule = SampleSchedule.from_rate(40.0, 0.010)
    assert [n for n in range(0, 11) if schedule.due(n)] == [3, 5, 8, 10]


def test_schedule_faster_than_the_step_samples_every_step():
    schedule = SampleSchedule.from_rate(250.0, 0.010)
    assert [n for n in range(1, 6) if schedule.due(n)] == [1, 2, 3, 4, 5]


def test_schedule_started_later_counts_from_its_start():
    # Webots: the first sample is one sampling period after enable()
    schedule = SampleSchedule.from_period_ms(50, 10, start_step=7)
    assert [n for n in range(40) if schedule.due(n)] == [12, 17, 22, 27, 32, 37]


def test_schedule_skipped_steps_do_not_queue_samples():
    schedule = SampleSchedule.from_rate(10.0, 0.010)
    assert schedule.due(35)       # samples 1..3 all fell before step 35: one reading
    assert schedule.next_step == 40


@pytest.mark.parametrize('bad', [0.0, -1.0])
def test_schedule_rejects_a_non_positive_rate(bad):
    with pytest.raises(ValueError):
        SampleSchedule.from_rate(bad, 0.01)


def test_scheduler_returns_the_due_sensors_in_order():
    scheduler = Scheduler()
    scheduler.set('lidar', SampleSchedule.from_rate(40.0, 0.01))
    scheduler.set('gnss', SampleSchedule.from_rate(10.0, 0.01))
    scheduler.set('imu', SampleSchedule.from_rate(100.0, 0.01))
    due = {n: scheduler.due(n) for n in range(1, 11)}
    assert due[1] == ['imu'] and due[3] == ['lidar', 'imu']
    assert due[10] == ['lidar', 'gnss', 'imu']
    scheduler.set('imu', None)
    assert scheduler.due(11) == [] and scheduler.next_step() == 13


# ------------------------------------------------------------------------------- noise

def test_noise_off_returns_the_values_untouched():
    noise = GaussianNoise(0.0, seed=3, stream='lidar')
    values = np.arange(5.0)
    assert noise.add(values) is values
    assert not noise


def test_noise_is_reproducible_per_seed_and_stream_and_has_its_sigma():
    a = GaussianNoise(0.5, seed=7, stream='lidar').add(np.zeros(20000))
    b = GaussianNoise(0.5, seed=7, stream='lidar').add(np.zeros(20000))
    c = GaussianNoise(0.5, seed=7, stream='gnss').add(np.zeros(20000))
    assert np.array_equal(a, b) and not np.array_equal(a, c)
    # standard error of the sample std of 20000 normals: sigma / sqrt(2 n) = 0.0025
    assert np.std(a) == pytest.approx(0.5, abs=0.01)
    assert np.mean(a) == pytest.approx(0.0, abs=0.015)


def test_noise_rejects_a_negative_sigma():
    with pytest.raises(ValueError):
        GaussianNoise(-0.1)


# ------------------------------------------------------------------------------- lookup table

WEBOTS_EXAMPLE = ((0.0, 1000.0, 0.0), (0.1, 1000.0, 0.1), (0.2, 400.0, 0.1), (0.3, 50.0, 0.1),
                  (0.37, 30.0, 0.0))


def test_lookup_table_interpolates_linearly_between_rows():
    table = LookupTable(WEBOTS_EXAMPLE)
    assert table.value(0.15) == pytest.approx(700.0)       # halfway between 1000 and 400
    assert table.value(0.25) == pytest.approx(225.0)       # halfway between 400 and 50
    assert table.relative_noise(0.335) == pytest.approx(0.05)


def test_lookup_table_saturates_outside_its_rows():
    table = LookupTable(WEBOTS_EXAMPLE)
    assert table.value(5.0) == 30.0 and table.value(-1.0) == 1000.0


def test_lookup_table_min_and_max_value_come_from_the_second_column():
    table = LookupTable(WEBOTS_EXAMPLE)
    assert (table.min_value, table.max_value, table.max_distance_m) == (30.0, 1000.0, 0.37)


def test_lookup_table_identity_returns_the_distance():
    table = LookupTable.identity(20.0)
    assert table.value(12.5) == 12.5 and table.max_value == 20.0 and not table.has_noise


@pytest.mark.parametrize('rows', [
    [(0.0, 0.0, 0.0)], [(0.2, 1.0, 0.0), (0.1, 2.0, 0.0)], [(-0.1, 1.0, 0.0), (0.1, 2.0, 0.0)],
    [(0.0, 1.0, -0.1), (0.1, 2.0, 0.0)], [(0.0, float('nan'), 0.0), (1.0, 1.0, 0.0)]])
def test_lookup_table_rejects_bad_rows(rows):
    with pytest.raises(ValueError):
        LookupTable(rows)


# ------------------------------------------------------------------------------- collisions

def test_debouncer_reports_the_first_contact_once_with_its_force():
    debounce = CollisionDebouncer()
    events = debounce.update(1.00, {'wall': 1234.5})
    assert [(e.time_s, e.other, e.normal_force_n) for e in events] == [(1.0, 'wall', 1234.5)]
    assert debounce.update(1.01, {'wall': 99.0}) == []


def test_debouncer_ignores_flicker_shorter_than_0_1_s():
    debounce = CollisionDebouncer()
    dt = 0.01
    debounce.update(0.0, {'wall': 1.0})
    # apart for 9 steps (0.09 s), then touching again: the same collision
    for step in range(1, 10):
        assert debounce.update(step * dt, {}) == []
    assert debounce.update(10 * dt, {'wall': 1.0}) == []


def test_debouncer_reports_again_after_0_1_s_apart():
    debounce = CollisionDebouncer()
    dt = 0.01
    debounce.update(0.0, {'wall': 1.0})
    for step in range(1, 11):       # apart at steps 1..10: 10 steps = 0.1 s
        debounce.update(step * dt, {})
    events = debounce.update(11 * dt, {'wall': 2.0})
    assert [e.other for e in events] == ['wall']


def test_debouncer_tracks_each_other_body_separately():
    debounce = CollisionDebouncer()
    assert [e.other for e in debounce.update(0.0, {'wall': 1.0})] == ['wall']
    assert [e.other for e in debounce.update(0.01, {'wall': 1.0, 'car2': 5.0})] == ['car2']


# ------------------------------------------------------------------------------- frames

def test_quaternion_from_rpy_round_trips_and_matches_the_rotation_matrix():
    q = quaternion_from_rpy(0.3, -0.4, 1.2)
    assert rpy_from_quaternion(q) == pytest.approx((0.3, -0.4, 1.2), abs=1e-12)
    # R = Rz(yaw) Ry(pitch) Rx(roll) (URDF fixed-axis rpy)
    cr, sr, cp, sp, cy, sy = (math.cos(0.3), math.sin(0.3), math.cos(-0.4), math.sin(-0.4),
                              math.cos(1.2), math.sin(1.2))
    rz = np.array([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]])
    ry = np.array([[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]])
    rx = np.array([[1, 0, 0], [0, cr, -sr], [0, sr, cr]])
    assert np.allclose(rotation_matrix(q), rz @ ry @ rx, atol=1e-12)


def test_optical_frame_looks_along_x_with_x_right_and_y_down():
    axes = rotation_matrix(OPTICAL_QUATERNION)      # columns: optical x, y, z in the body frame
    assert np.allclose(axes[:, 0], (0.0, -1.0, 0.0), atol=1e-12)     # right
    assert np.allclose(axes[:, 1], (0.0, 0.0, -1.0), atol=1e-12)     # down
    assert np.allclose(axes[:, 2], (1.0, 0.0, 0.0), atol=1e-12)      # forward
