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
The radar's messages: radar_msgs/RadarTracks (what Autoware's radar pipeline reads) and RadarScan.

RadarTracks (``<name>/tracks``): one track per target, in the radar frame ``<p><name>``: its
``uuid`` the target's instance id as a UUID (physics/body_labels.py instance_uuid, the
PredictedObjects object id of the same object), ``position`` the body's centre, ``velocity`` its
velocity relative to the radar, ``size`` its extents along the radar's axes, ``acceleration``
and the covariances zero (unknown), ``classification`` Autoware's vendor classes
(radar_tracks_msgs_converter: 32000 unknown, 32001 car, 32002 truck, 32003 bus, 32004 trailer,
32005 motorcycle, 32006 bicycle, 32007 pedestrian) from the target's label.

RadarScan (``<name>/scan``): one return per target as Webots reads it: ``range`` its distance,
``azimuth`` (REP 103, > 0 to the left), ``elevation``, ``doppler_velocity`` its radial speed
(> 0 moving away), ``amplitude`` its received power in dBm.
"""

from vehicle_sim.core.sensors.labels import LABEL_IDS
from vehicle_sim.physics.body_labels import instance_uuid
from vehicle_sim.ros.messages import HEADER

RADAR_TRACKS = 'radar_msgs/msg/RadarTracks'
RADAR_TRACK = 'radar_msgs/msg/RadarTrack'
RADAR_SCAN = 'radar_msgs/msg/RadarScan'
RADAR_RETURN = 'radar_msgs/msg/RadarReturn'
UUID = 'unique_identifier_msgs/msg/UUID'

UNKNOWN_CLASS = 32000
# label id -> Autoware's RadarTrack classification (radar_tracks_msgs_converter)
CLASSIFICATION = {LABEL_IDS[name]: 32000 + offset for offset, name in enumerate(
    ('obstacle', 'car', 'truck', 'bus', None, 'motorcycle', 'bicycle', 'pedestrian')) if name}
ZERO6 = [0.0] * 6


def radar_tracks_builder(msg, frame_id: str):
    """Return ``build(stamp, reading)``: radar_msgs/RadarTracks of a RadarReading."""
    header_type, tracks_type, track_type, uuid_type = (
        msg(HEADER), msg(RADAR_TRACKS), msg(RADAR_TRACK), msg(UUID))
    point_type = type(track_type().position)
    vector_type = type(track_type().velocity)

    def build(stamp, reading):
        tracks = []
        for t in reading.targets:
            (px, py, pz), (vx, vy, vz), (sx, sy, sz) = t.position_m, t.velocity_mps, t.size_m
            tracks.append(track_type(
                uuid=uuid_type(uuid=list(instance_uuid(t.instance_id))),
                position=point_type(x=px, y=py, z=pz),
                velocity=vector_type(x=vx, y=vy, z=vz),
                acceleration=vector_type(),
                size=vector_type(x=sx, y=sy, z=sz),
                classification=CLASSIFICATION.get(t.label, UNKNOWN_CLASS),
                position_covariance=ZERO6, velocity_covariance=ZERO6,
                acceleration_covariance=ZERO6, size_covariance=ZERO6))
        return tracks_type(header=header_type(stamp=stamp, frame_id=frame_id), tracks=tracks)
    return build


def radar_scan_builder(msg, frame_id: str):
    """Return ``build(stamp, reading)``: radar_msgs/RadarScan of a RadarReading."""
    header_type, scan_type, return_type = msg(HEADER), msg(RADAR_SCAN), msg(RADAR_RETURN)

    def build(stamp, reading):
        returns = [return_type(range=t.distance_m, azimuth=t.azimuth_rad,
                               elevation=t.elevation_rad, doppler_velocity=t.speed_mps,
                               amplitude=t.received_power_dbm) for t in reading.targets]
        return scan_type(header=header_type(stamp=stamp, frame_id=frame_id), returns=returns)
    return build
