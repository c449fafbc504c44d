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
Fast serializers of the traffic topics: the CDR bytes of :mod:`.traffic_messages`' messages.

Each ``<type>_serializer`` takes the constants of its builder and returns ``serialize(*values)``
taking the builder's values, and gives the bytes the builder's message serializes to (tests
compare them with cyclonedds-python's and rosbags'), packed with ``struct`` through
:class:`~vehicle_sim.transport.fast_cdr.CdrWriter`: no message object is built. A traffic
world's PredictedObjects (60 vehicles, each with its predicted path: ~100 kB) cost some 40 ms
through cyclonedds-python's generic serializer, several times a 10 ms step; these, about 1 ms.
The builders name them (``builder.serializer``), so a row's converter publishes the bytes
(``endpoints.MessageKit``).
"""

import math
import struct

from vehicle_sim.core.geometry.frames import quaternion_from_yaw
from vehicle_sim.physics.body_labels import instance_uuid
from vehicle_sim.ros import traffic_messages as tm
from vehicle_sim.transport.fast_cdr import cdr_string, CdrWriter

_U32 = CdrWriter.U32
_STAMP = struct.Struct('<iI')
# existence_probability, classification count 1, its label and probability
_EXISTENCE_CLASS = struct.Struct('<fIB3xf')
# Pose and 36 zero covariances; Twist (x forward) and 36 zeros
_POSE_COVARIANCE = struct.Struct('<7d288x')
_TWIST_COVARIANCE = struct.Struct('<6d288x')
_ZERO_ACCELERATION = bytes(42 * 8)
_PATH_END = struct.Struct('<iIf')        # time_step (sec, nanosec), confidence
_SHAPE_HEAD = struct.Struct('<B3xI')     # type, footprint point count (0)
_VECTOR3 = struct.Struct('<3d')
_IDS = struct.Struct('<3i')             # Marker id, type, action
# Marker pose, scale, color, lifetime (0 s), frame_locked (false)
_MARKER_BODY = struct.Struct('<7d3d4fiI?')
_GROUP_HEAD = struct.Struct('<qI')      # traffic_light_group_id, element count
_ELEMENT = struct.Struct('<3Bxf')       # color, shape, status, confidence (4-aligned start)


def _time_step(step_s):
    seconds = math.floor(step_s)
    return int(seconds), int(round((step_s - seconds) * 1e9))


def predicted_objects_serializer(frame_id: str):
    """Return ``serialize(stamp, objects, obstacles=())``: the PredictedObjects' bytes."""
    frame = cdr_string(frame_id)
    uuids = {}
    poses = {}
    labels, shapes = tm.LABEL_OF_CLASS, tm.OBJECT_SHAPE_OF_OBSTACLE

    def uuid_of(instance_id):
        found = uuids.get(instance_id)
        if found is None:
            found = uuids[instance_id] = instance_uuid(instance_id)
        return found

    def path_layout(count):
        found = poses.get(count)
        if found is None:
            found = poses[count] = struct.Struct(f'<{7 * count}d')
        return found

    def serialize(stamp, objects, obstacles=()):
        out = CdrWriter()
        pack, raw = out.pack, out.raw
        pack(4, _STAMP, stamp.sec, stamp.nanosec)
        raw(4, frame)
        pack(4, _U32, len(objects) + len(obstacles))
        for o in objects:
            raw(1, uuid_of(o.instance_id))
            pack(4, _EXISTENCE_CLASS, 1.0, 1, labels[o.object_class], 1.0)
            z = 0.5 * o.height_m
            qx, qy, qz, qw = quaternion_from_yaw(o.yaw_rad)
            pack(8, _POSE_COVARIANCE, o.x_m, o.y_m, z, qx, qy, qz, qw)
            pack(8, _TWIST_COVARIANCE, o.speed_mps, 0.0, 0.0, 0.0, 0.0, 0.0)
            raw(8, _ZERO_ACCELERATION)
            pack(4, _U32, 1)                   # one predicted path
            values = []
            for x, y, yaw in o.path:
                values += (x, y, z, *quaternion_from_yaw(yaw))
            pack(4, _U32, len(o.path))
            if o.path:
                pack(8, path_layout(len(o.path)), *values)
            pack(4, _PATH_END, *_time_step(o.step_s), 1.0)
            pack(4, _SHAPE_HEAD, shapes[o.shape], 0)
            pack(8, _VECTOR3, *o.size_m)
        for o in obstacles:
            raw(1, uuid_of(o.instance_id))
            pack(4, _EXISTENCE_CLASS, 1.0, 1, tm.UNKNOWN, 1.0)
            pack(8, _POSE_COVARIANCE, o.x_m, o.y_m, o.z_m, *quaternion_from_yaw(o.yaw_rad))
            pack(8, _TWIST_COVARIANCE, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
            raw(8, _ZERO_ACCELERATION)
            pack(4, _U32, 0)                   # no predicted path
            pack(4, _SHAPE_HEAD, tm.OBJECT_SHAPE_OF_OBSTACLE[o.shape], 0)
            pack(8, _VECTOR3, *o.size_m)
        return out.data()
    return serialize


def marker_tail() -> bytes:
    """
    Return what follows frame_locked in a Marker without points, texture, text or mesh.

    Constant bytes from a 4-aligned offset (every field in it is 4-aligned or a byte): the
    points' count, the colours' count, and the empty rest.
    """
    out = CdrWriter()
    empty = cdr_string('')
    for part in (_U32.pack(0), _U32.pack(0), empty,          # points, colors, texture_resource
                 _STAMP.pack(0, 0), empty, empty, _U32.pack(0),  # texture: header, format, data
                 _U32.pack(0), empty, empty,               # uv_coordinates, text, mesh_resource
                 empty, _U32.pack(0)):                      # mesh_file: filename, data
        out.raw(4, part)
    out.raw(1, b'\0')                                       # mesh_use_embedded_materials
    return out.data()[4:]


def traffic_markers_serializer(frame_id: str, colours=()):
    """Return ``serialize(stamp, objects)``: the traffic MarkerArray's bytes (see its builder)."""
    frame, ns, tail = cdr_string(frame_id), cdr_string('traffic'), marker_tail()
    shown = set()
    markers = tm.MARKER_OF_SHAPE

    def serialize(stamp, objects):
        out = CdrWriter()
        pack, raw = out.pack, out.raw
        present = {o.index for o in objects}
        deleted = sorted(shown - present)
        pack(4, _U32, len(objects) + len(deleted))
        sec, nanosec = stamp.sec, stamp.nanosec
        for o in objects:
            r, g, b, a = colours[o.index % len(colours)] if colours else (0.6, 0.6, 0.6, 1.0)
            pack(4, _STAMP, sec, nanosec)
            raw(4, frame)
            raw(4, ns)
            pack(4, _IDS, o.index, markers[o.shape], tm.ADD)
            pack(8, _MARKER_BODY, o.x_m, o.y_m, 0.5 * o.height_m,
                 *quaternion_from_yaw(o.yaw_rad), *o.size_m, r, g, b, a, 0, 0, False)
            raw(4, tail)
        for index in deleted:
            pack(4, _STAMP, sec, nanosec)
            raw(4, frame)
            raw(4, ns)
            pack(4, _IDS, index, 0, tm.DELETE)
            pack(8, _MARKER_BODY, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0,
                 0.0, 0.0, 0.0, 0.0, 0, 0, False)
            raw(4, tail)
        shown.clear()
        shown.update(present)
        return out.data()
    return serialize


def traffic_signals_serializer():
    """Return ``serialize(stamp, groups)``: the TrafficLightGroupArray's bytes (its builder's)."""
    elements_bytes = {}

    def elements_of(elements):
        # each group's elements, then its empty predictions: constant bytes per Elements, from
        # the 4-aligned offset after the element count (an element is 8 bytes, 4-aligned)
        found = elements_bytes.get(elements)
        if found is None:
            found = elements_bytes[elements] = b''.join(
                _ELEMENT.pack(color, shape, status, 1.0)
                for color, shape, status in elements) + _U32.pack(0)
        return found

    def serialize(stamp, groups):
        out = CdrWriter()
        pack, raw = out.pack, out.raw
        pack(4, _STAMP, stamp.sec, stamp.nanosec)
        pack(4, _U32, len(groups))
        for group_id, elements in groups:
            pack(8, _GROUP_HEAD, group_id, len(elements))
            raw(4, elements_of(elements))
        return out.data()
    return serialize
