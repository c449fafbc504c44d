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
End to end on simulated time: one Autoware command stream drives the robots and the car.

The scenario (vehicle_sim/tools/end_to_end.py, docs/end_to_end.md): straight, left arc, S-curve,
silence, stop. The caster and skid-steer robots go through the Ackermann -> differential bridge in
ONE shared World; the car goes through the autoware_automobile node. Paths are compared with the
kinematic bicycle integrated from the commands as applied. Everything is driven in-process with sim
time as receipt time, so the run is deterministic.
"""

import math
import struct

import pytest

from vehicle_sim.tools import end_to_end
from vehicle_sim.tools.end_to_end import (
    BRIDGE_CONTROL_RATE_HZ,
    COMMAND_TIMEOUT_S,
    constant_stream,
    DT_S,
    run_robots,
)

# |p_gt(t) − p_ref(t)| <= max(5 % of the distance travelled up to t, 5 cm): the floor covers
# t near 0, where the distance is tiny and the wheels' spin-up slip dominates.
ROBOT_FRACTION, ROBOT_FLOOR_M = 0.05, 0.05
CAR_FRACTION = 0.10


@pytest.fixture(scope='module')
def result():
    return end_to_end.run_scenario()


def test_bicycle_reference_of_a_constant_command_is_the_closed_form_circle():
    # R = L / tan δ; after a quarter turn (t = (π/2)·R/v) the pose is (R, R, π/2)
    wheel_base, steer, speed = 2.0, 0.3, 1.5
    radius = wheel_base / math.tan(steer)
    steps = 1000
    dt = (math.pi / 2) * radius / speed / steps
    x, y, yaw = end_to_end.bicycle_reference([(speed, steer)] * steps, wheel_base, dt)[-1]
    assert (x, y, yaw) == pytest.approx((radius, radius, math.pi / 2), abs=1e-9)


def test_stream_segments_follow_each_other_and_silence_sends_nothing():
    stream = end_to_end.autoware_stream(1.0, 0.3)
    assert [s.name for s in stream.segments] == ['straight', 'arc', 's_curve', 'silence', 'stop']
    assert stream.command_at(0.0) == (1.0, 0.0)
    assert stream.command_at(3.5) == (1.0, 0.3)
    assert stream.command_at(13.5) is None
    assert stream.command_at(15.0) == (0.0, 0.0)
    assert stream.command_at(stream.duration_s + 0.1) is None


def test_caster_robot_path_stays_within_5_percent_of_the_distance_from_the_bicycle(result):
    track = result.robots['caster_robot']
    ratio = track.error_ratio(ROBOT_FRACTION, ROBOT_FLOOR_M)
    print(f'caster: travelled {track.distance_m()[-1]:.2f} m, max error '
          f'{max(track.errors_m()):.3f} m, error / allowed {ratio:.3f}')
    assert track.distance_m()[-1] > 8.0
    assert ratio <= 1.0


def test_skid_steer_robot_yaw_efficiency_and_path_error_are_measured(result, record_property):
    track = result.robots['skid_steer_robot']
    efficiency = track.yaw_efficiency(*result.robot_stream.bounds('arc'))
    error = max(track.errors_m())
    distance = track.distance_m()[-1]
    print(f'skid-steer: yaw efficiency on the arc {efficiency:.3f} (measured / commanded '
          f'heading change), max path error {error:.3f} m over {distance:.2f} m, end error '
          f'{track.end_error_m():.3f} m')
    record_property('skid_steer_yaw_efficiency', round(efficiency, 4))
    record_property('skid_steer_max_path_error_m', round(error, 4))
    assert math.isfinite(efficiency) and math.isfinite(error)
    x0, y0, _ = track.pose[0]
    x1, y1, _ = track.pose[-1]
    assert math.hypot(x1 - x0, y1 - y0) > 1.0        # it moved
    assert efficiency > 0.0                          # and turned the commanded way


def test_car_end_position_lies_within_10_percent_of_the_distance_from_the_bicycle(result):
    track = result.car
    distance = track.distance_m()[-1]
    print(f'car ({track.name}): travelled {distance:.2f} m, end error '
          f'{track.end_error_m():.3f} m ({track.end_error_m() / distance:.2%}), max error '
          f'{max(track.errors_m()):.3f} m')
    assert distance > 40.0
    assert track.end_error_m() <= CAR_FRACTION * distance
    assert track.pose[-1][1] - track.pose[0][1] > 10.0       # turned left (REP 103)


@pytest.mark.parametrize('vehicle', ['caster_robot', 'skid_steer_robot', 'car'])
def test_commands_stop_zero_within_timeout_plus_one_control_period(result, vehicle):
    track = result.car if vehicle == 'car' else result.robots[vehicle]
    delay = track.watchdog_delay_s()
    print(f'{vehicle}: zero command {delay:.3f} s after the last command')
    # the robots' bridges tick at BRIDGE_CONTROL_RATE_HZ; the car's node checks every step
    period = DT_S if vehicle == 'car' else 1.0 / BRIDGE_CONTROL_RATE_HZ
    assert COMMAND_TIMEOUT_S < delay <= COMMAND_TIMEOUT_S + period + 1e-6


def test_saturated_wheels_still_follow_the_commanded_curvature():
    # 2 m/s with δ = 0.35 asks for wheel speeds beyond max_wheel_speed_mps = 1 m/s: both wheels
    # scale, v drops, the circle R = L / tan δ stays.
    steer, duration = 0.35, 6.0
    track = run_robots(constant_stream(2.0, steer, duration), robots=('caster_robot',),
                       bridge_overrides={'max_wheel_speed_mps': 1.0})['caster_robot']
    speeds = [v for v, _ in track.applied[-100:]]
    assert max(speeds) < 1.0                         # saturated: slower than commanded
    # measured curvature over the last 3 s: heading change / path length
    i0 = len(track.pose) - int(round(3.0 / DT_S)) - 1
    heading = track.pose[-1][2] - track.pose[i0][2]
    heading = math.atan2(math.sin(heading), math.cos(heading))
    length = sum(math.hypot(b[0] - a[0], b[1] - a[1])
                 for a, b in zip(track.pose[i0:], track.pose[i0 + 1:]))
    curvature = heading / length
    print(f'saturated: applied v {speeds[-1]:.3f} m/s, curvature {curvature:.4f} 1/m, '
          f'commanded {math.tan(steer) / track.wheel_base_m:.4f} 1/m')
    assert curvature == pytest.approx(math.tan(steer) / track.wheel_base_m, rel=0.05)


def test_demo_writes_a_readable_png(tmp_path):
    from matplotlib import image

    from vehicle_sim.tools import demo
    out = tmp_path / 'demo.png'
    demo.run_demo(str(out), short=True)
    data = out.read_bytes()
    assert data[:8] == b'\x89PNG\r\n\x1a\n'
    width, height = struct.unpack('>II', data[16:24])
    assert width >= 800 and height >= 600
    pixels = image.imread(str(out))
    assert pixels.shape[:2] == (height, width)
