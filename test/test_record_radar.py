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
A radar's topics (radar_msgs RadarTracks and RadarScan) recorded in process, read by rosbags.

rosbags is an independent reader and CDR decoder, its types built from the file's own schemas.

The world is test_ros_radar.py's: a car with a radar and a crate 20 m ahead of it.
"""

import pytest

pytest.importorskip('mcap', reason="recording needs the mcap package (the 'record' extra)")

from record_helpers import record_automobile, typestore  # noqa: E402
from rosbags.rosbag2 import Reader  # noqa: E402
from test_ros_radar import WORLD  # noqa: E402

STEPS = 50                  # 0.5 s at 10 ms: five radar readings at 10 Hz


def test_radar_topics_record_and_read_back_with_rosbags(tmp_path):
    world = tmp_path / 'radar_world.yaml'
    world.write_text(WORLD)
    path = str(tmp_path / 'radar.mcap')

    def drive(app):
        for _ in range(STEPS):
            app.step_once()
    _, _, error = record_automobile(path, '/rec_radar', drive,
                                    parameters=(f'world:={world}',))
    assert error is None
    found = {}
    with Reader(path) as reader:
        store = typestore(reader.connections)
        for connection, timestamp, raw in reader.messages():
            if connection.topic.startswith('/rec_radar/radar_ns/front_radar/'):
                msg = store.deserialize_cdr(raw, connection.msgtype)
                found.setdefault(connection.topic, []).append((connection.msgtype, msg))
    tracks = found['/rec_radar/radar_ns/front_radar/tracks']
    scans = found['/rec_radar/radar_ns/front_radar/scan']
    assert len(tracks) == len(scans) == 5
    assert {t for t, _ in tracks} == {'radar_msgs/msg/RadarTracks'}
    assert {t for t, _ in scans} == {'radar_msgs/msg/RadarScan'}
    last_track, = tracks[-1][1].tracks
    last_return, = scans[-1][1].returns
    assert last_track.position.x == pytest.approx(20.0, abs=0.05)
    assert last_return.range == pytest.approx(20.0, abs=0.05)
    assert last_track.classification == 32000
    assert tracks[-1][1].header.frame_id == 'radar_ns/front_radar'
