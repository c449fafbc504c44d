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
radar_msgs (ros-perception/radar_msgs 0.2.2) for the radar, and its message builders.

The definitions' fields are upstream's; the builders (ros/radar_messages.py) turn a radar
reading into RadarTracks (uuid from the instance id, Autoware's classes) and RadarScan.
"""

import numpy as np
import pytest

import vehicle_msgs_py
from vehicle_sim.core.sensors.labels import LABEL_IDS
from vehicle_sim.core.sensors.readings import RadarDetection, RadarReading
from vehicle_sim.physics.body_labels import instance_uuid
from vehicle_sim.ros import radar_messages as rm

msg = vehicle_msgs_py.message_type
STAMP = msg('builtin_interfaces/msg/Time')(sec=3, nanosec=5)


def _fields(ros_type):
    own = vehicle_msgs_py.message_definition(ros_type).split('=' * 80)[0]
    return [tuple(line.split()[:2]) for line in own.splitlines()
            if line.strip() and '=' not in line]


def test_the_definitions_have_upstreams_fields():
    assert _fields(rm.RADAR_TRACKS) == [('std_msgs/Header', 'header'),
                                        ('radar_msgs/RadarTrack[]', 'tracks')]
    assert _fields(rm.RADAR_TRACK) == [
        ('unique_identifier_msgs/UUID', 'uuid'), ('geometry_msgs/Point', 'position'),
        ('geometry_msgs/Vector3', 'velocity'), ('geometry_msgs/Vector3', 'acceleration'),
        ('geometry_msgs/Vector3', 'size'), ('uint16', 'classification'),
        ('float32[6]', 'position_covariance'), ('float32[6]', 'velocity_covariance'),
        ('float32[6]', 'acceleration_covariance'), ('float32[6]', 'size_covariance')]
    assert _fields(rm.RADAR_SCAN) == [('std_msgs/Header', 'header'),
                                      ('radar_msgs/RadarReturn[]', 'returns')]
    assert _fields(rm.RADAR_RETURN) == [('float32', 'range'), ('float32', 'azimuth'),
                                        ('float32', 'elevation'), ('float32', 'doppler_velocity'),
                                        ('float32', 'amplitude')]
    track = msg(rm.RADAR_TRACK)
    assert (track.NO_CLASSIFICATION, track.STATIC, track.DYNAMIC) == (0, 1, 2)


READING = RadarReading('front', 3.0, (
    RadarDetection(20.5, -60.25, -4.5, 0.1, 0.02, (20.4, 2.0, 0.4), (-4.5, 0.25, 0.0),
                   (4.5, 1.8, 1.5), LABEL_IDS['car'], 17),
    RadarDetection(30.0, -70.5, 1.5, -0.2, 0.0, (29.4, -5.9, 0.0), (1.5, 0.0, 0.0),
                   (0.6, 0.6, 1.8), LABEL_IDS['pedestrian'], 4),
    RadarDetection(40.0, -80.0, 0.0, 0.0, 0.0, (40.0, 0.0, 0.0), (0.0, 0.0, 0.0),
                   (1.0, 2.0, 1.5), LABEL_IDS['obstacle'], 9)))


def test_tracks_carry_the_instance_uuid_autowares_class_and_the_radar_frame_values():
    tracks = rm.radar_tracks_builder(msg, 'car/front')(STAMP, READING)
    assert tracks.header.frame_id == 'car/front' and tracks.header.stamp.sec == 3
    assert [bytes(t.uuid.uuid) for t in tracks.tracks] == [instance_uuid(17), instance_uuid(4),
                                                           instance_uuid(9)]
    # radar_tracks_msgs_converter: 32001 car, 32007 pedestrian, 32000 unknown
    assert [t.classification for t in tracks.tracks] == [32001, 32007, 32000]
    car = tracks.tracks[0]
    assert (car.position.x, car.position.y, car.position.z) == (20.4, 2.0, 0.4)
    assert (car.velocity.x, car.velocity.y, car.velocity.z) == (-4.5, 0.25, 0.0)
    assert (car.size.x, car.size.y, car.size.z) == (4.5, 1.8, 1.5)
    assert list(car.position_covariance) == [0.0] * 6


def test_the_track_uuid_is_given_as_rclpy_takes_it():
    # rclpy's generated UUID stores numpy.array(uuid, dtype=uint8), which refuses bytes
    # (ValueError: invalid literal for int()); the embedded types take either.
    def as_rclpy(ros_type):
        if ros_type != rm.UUID:
            return msg(ros_type)

        class Uuid:
            def __init__(self, uuid):
                self.uuid = np.array(uuid, dtype=np.uint8)
                assert self.uuid.shape == (16,)
        return Uuid

    tracks = rm.radar_tracks_builder(as_rclpy, 'car/front')(STAMP, READING)
    assert bytes(tracks.tracks[0].uuid.uuid) == instance_uuid(17)


def test_scan_returns_are_webots_targets_with_rep_103_azimuths():
    scan = rm.radar_scan_builder(msg, 'car/front')(STAMP, READING)
    first = scan.returns[0]
    assert [first.range, first.azimuth, first.doppler_velocity, first.amplitude] == \
        pytest.approx([20.5, 0.1, -4.5, -60.25])
    assert first.elevation == pytest.approx(0.02)
    assert len(scan.returns) == 3
