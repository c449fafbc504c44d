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
The radar over the wire: radar_msgs/RadarTracks on <name>/tracks and RadarScan on <name>/scan.

The automobile node runs a world with a car carrying a radar 2 m ahead of base_link, 0.75 m up,
and a crate (1 x 2 x 1.5 m, label obstacle) whose centre is 20 m ahead at the radar's height;
the test steps it through ``robot/time_step`` and reads both topics with its own DdsNode. The
car settles on its suspension (millimetres), so positions are checked to 0.05 m; the received
power follows Webots' radar equation from the range sent (float32: 1e-3 dB).
"""

import math

from automobile_helpers import automobile_fixtures, stamp_of, wait_for
import pytest

from vehicle_sim.ros.sensor_interfaces import QOS_SENSOR

pytestmark = pytest.mark.transport

NAMESPACE = 'radar_ns'
WORLD = """
vehicles:
  - name: Car
    namespace: radar_ns
    sensors:
      - {type: radar, name: front_radar, pose: {x: 2.0, z: 0.75}, rate_hz: 10.0}
obstacles:
  - {name: crate, shape: box, size: [1.0, 2.0, 1.5], position: [22.0, 0.0, 0.75]}
"""


@pytest.fixture(scope='module')
def radar_world(tmp_path_factory):
    path = tmp_path_factory.mktemp('radar') / 'radar_world.yaml'
    path.write_text(WORLD)
    return str(path)


sim, tester, car = automobile_fixtures(
    'radar_tester', lambda request: [
        '--ros-args', '-p', f'world:={request.getfixturevalue("radar_world")}',
        '-p', 'synchronous:=true'], ['/clock'], NAMESPACE)


def webots_power_dbm(distance_m, rcs_m2):
    """Webots' radar equation with its Radar defaults (20 dBm, 20 dBi, 24 GHz), in dBm."""
    received_w = (0.1 * 100.0 ** 2 * (0.299792458 / 24.0) ** 2 * rcs_m2
                  / ((4.0 * math.pi) ** 3 * distance_m ** 4))
    return 10.0 * math.log10(received_w / 1e-3)


def test_radar_tracks_and_scan_over_the_wire(car, tester):
    received = {'tracks': [], 'scan': []}
    subs = [tester.create_subscription(
        ros_type, f'/{NAMESPACE}/front_radar/{topic}',
        lambda msg, key=topic: received[key].append(msg), QOS_SENSOR)
        for topic, ros_type in (('tracks', 'radar_msgs/msg/RadarTracks'),
                                ('scan', 'radar_msgs/msg/RadarScan'))]
    assert wait_for(lambda: all(s.get_publisher_count() for s in subs), spin=tester)
    assert car.call('robot/time_step', 200).success
    assert wait_for(lambda: len(received['tracks']) >= 2 and len(received['scan']) >= 2,
                    spin=tester)
    tracks, scan = received['tracks'][1], received['scan'][1]
    assert stamp_of(tracks) == stamp_of(scan) == pytest.approx(0.2, abs=1e-9)
    assert tracks.header.frame_id == scan.header.frame_id == f'{NAMESPACE}/front_radar'
    track, = tracks.tracks
    assert (track.position.x, track.position.y, track.position.z) == pytest.approx(
        (20.0, 0.0, 0.0), abs=0.05)
    assert (track.size.x, track.size.y, track.size.z) == pytest.approx((1.0, 2.0, 1.5),
                                                                       abs=1e-3)
    assert abs(track.velocity.x) < 0.05
    assert track.classification == 32000         # obstacle: Autoware's UNKNOWN
    assert bytes(track.uuid.uuid)[:14] == bytes(14)    # an instance id 0 .. 65535
    back, = scan.returns
    assert back.range == pytest.approx(20.0, abs=0.05)
    assert back.azimuth == pytest.approx(0.0, abs=1e-3)
    assert abs(back.doppler_velocity) < 0.05
    rcs = 0.30 * 2.0 * 1.5       # obstacle reflectivity x width x height
    assert back.amplitude == pytest.approx(webots_power_dbm(back.range, rcs), abs=1e-3)
