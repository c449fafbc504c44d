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
The fast serializer of ``/map/lanes``: the CDR bytes of ``lane_markers_builder``'s message.

The lane map's markers (:func:`~vehicle_sim.ros.lane_messages.lane_marker_parts`) hold every
point of the map's surface, lines and areas: about 47 000 points (1.6 MB) for the shipped SUMO
city, ten times that for a city of 12 x 12 blocks. cyclonedds-python's generic serializer and
one Point object a point took about 0.45 s for the shipped city and 5.4 s for the larger one,
at the node's start; here each marker's points go out as one array's bytes (numpy), and the
rest with ``struct`` through :class:`~vehicle_sim.transport.fast_cdr.CdrWriter`.
test/test_ros_lane_cdr.py checks the bytes equal to cyclonedds-python's and rosbags' CDR of the
builder's message; benchmarks/bench_maps.py times both.
"""

import struct

import numpy as np

from vehicle_sim.ros.lane_messages import lane_marker_parts
from vehicle_sim.ros.traffic_cdr import marker_tail
from vehicle_sim.transport.fast_cdr import cdr_string, CdrWriter

_U32 = CdrWriter.U32
_STAMP = struct.Struct('<iI')
_IDS = struct.Struct('<3i')             # Marker id, type, action (ADD)
# Marker pose (identity), scale, color, lifetime (0 s), frame_locked (false), the point count
_MARKER_BODY = struct.Struct('<7d3d4fiI?3xI')
_POINTS_DTYPE = np.dtype('<f8')


def lane_markers_serializer(frame_id: str):
    """Return ``serialize(stamp, graph)``: the bytes of ``lane_markers_builder(frame_id)``'s."""
    frame = cdr_string(frame_id)
    # what follows the points: the colours' count (0), then the marker's constant end
    tail = marker_tail()[4:]
    names = {}

    def serialize(stamp, graph):
        out = CdrWriter()
        pack, raw = out.pack, out.raw
        parts = lane_marker_parts(graph)
        pack(4, _U32, len(parts))
        sec, nanosec = stamp.sec, stamp.nanosec
        for part in parts:
            ns = names.get(part.ns)
            if ns is None:
                ns = names[part.ns] = cdr_string(part.ns)
            pack(4, _STAMP, sec, nanosec)
            raw(4, frame)
            raw(4, ns)
            pack(4, _IDS, part.marker_id, part.kind, 0)
            points = part.points
            pack(8, _MARKER_BODY, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, *part.scale, *part.rgba,
                 0, 0, False, len(points))
            if len(points):
                raw(8, np.ascontiguousarray(points, dtype=_POINTS_DTYPE).tobytes())
            raw(4, tail)
        return out.data()
    return serialize
